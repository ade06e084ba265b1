#pragma once
// The NLP solvers of the local stage behind one interface: minimise the path
// travel time over a box. Each run remembers the best feasible point it
// evaluated, so the caller never gets a path slower than the best one seen
// (the start included), whatever the solver's own final iterate.
#include <cstddef>
#include <functional>
#include <limits>
#include <string>

#include <Eigen/Core>

#include "talus/core/termination.hpp"
#include "talus/optimal/path_time_objective.hpp"

namespace talus::detail {

/// The objective with best-point bookkeeping.
class TrackedObjective {
 public:
  explicit TrackedObjective(PathTimeObjective& objective) : objective_(objective) {}
  double operator()(const Eigen::VectorXd& z, Eigen::VectorXd* gradient) {
    const double t = objective_.evaluate(z, gradient);
    if (t < best_value_) {
      best_value_ = t;
      best_ = z;
    }
    return t;
  }
  const Eigen::VectorXd& best() const { return best_; }
  double best_value() const { return best_value_; }
  std::size_t dimension() const { return objective_.dimension(); }
  const PathTimeObjective& objective() const { return objective_; }
  /// Profiles solved so far (a value and a gradient at one point are one;
  /// finite-difference fallbacks count every probe).
  std::size_t evaluations() const { return objective_.evaluations(); }

 private:
  PathTimeObjective& objective_;
  Eigen::VectorXd best_;
  double best_value_ = std::numeric_limits<double>::infinity();
};

struct BoxProblem {
  Eigen::VectorXd start, lower, upper;
  std::size_t max_iterations = 100;
  std::size_t max_evaluations = 400;
  double relative_tolerance = 1e-5;
  double initial_step = 1.0;  ///< derivative-free trust-region radius [m]
  /// Polled every iteration (Ipopt) or evaluation (NLopt), armed: once it
  /// holds the solver stops with status "time_limit". Default: never.
  Termination termination;
};

struct SolverRun {
  std::string status;   ///< the solver's own return code, as text
  bool failed = false;  ///< an error return (not a stop on a limit)
  std::size_t iterations = 0;
};

SolverRun run_ipopt(TrackedObjective& objective, const BoxProblem& problem);
SolverRun run_nlopt_lbfgs(TrackedObjective& objective, const BoxProblem& problem);
SolverRun run_nlopt_bobyqa(TrackedObjective& objective, const BoxProblem& problem);

}  // namespace talus::detail
