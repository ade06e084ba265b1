#pragma once
// CvodeIntegrator: one CVODE BDF integration with a dense direct linear
// solver and root finding, its SUNDIALS objects owned (RAII) in one place.
// Private to talus::dynamics (the vehicle simulation).
#include <cvode/cvode.h>

#include <memory>
#include <string>
#include <vector>

namespace talus::detail {

/// What CVODE counted (summed over restarts: CVodeReInit zeroes its own counters).
struct CvodeCounters {
  long rhs_evaluations = 0;  ///< including the linear solver's difference quotients
  long jacobian_evaluations = 0;
  long root_evaluations = 0;
  long error_test_failures = 0;
  long nonlinear_failures = 0;
};

struct CvodeSettings {
  double relative_tolerance = 1e-6;
  double absolute_tolerance = 1e-8;
  double max_step = 0.0;  ///< 0: CVODE's own
};

class CvodeIntegrator {
 public:
  /// `states` ODE states from `initial` at t = 0, right-hand side `rhs` and
  /// `roots` root functions `root` (each found when it falls through zero),
  /// both called with `user_data`. Throws SolverError when SUNDIALS cannot be
  /// set up.
  CvodeIntegrator(int states, const double* initial, CVRhsFn rhs, int roots, CVRootFn root,
                  void* user_data, const CvodeSettings& settings);
  ~CvodeIntegrator();
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  /// The current state (CVODE's own vector: it changes with every step).
  double* state();
  /// Steps will not pass `t_stop` (until the next call).
  void set_stop_time(double t_stop);
  /// One internal step towards `t_stop` (the stop time set); `t` is the time
  /// reached. Returns CVODE's flag (< 0: failure; CV_ROOT_RETURN: a root).
  int step(double t_stop, double& t);
  /// The roots found by the last step that returned CV_ROOT_RETURN.
  void roots_found(int* found) const;
  /// The state at `t` inside the last step, by CVODE's interpolant, in the
  /// integrator's scratch vector; null when CVODE refuses.
  const double* interpolate(double t);
  /// Restarts the BDF history at (t, state()): the right-hand side jumped.
  /// Throws SolverError when CVODE refuses.
  void restart(double t);
  /// The counters, summed over restarts.
  CvodeCounters counters() const;
  /// A failure's description: CVODE's flag name and its error handler's last message.
  std::string failure(int flag) const;

 private:
  void add_counters(CvodeCounters& to) const;
  struct Sundials;
  std::unique_ptr<Sundials> sundials_;
  CvodeCounters before_restarts_;
  std::string error_message_;
};

}  // namespace talus::detail
