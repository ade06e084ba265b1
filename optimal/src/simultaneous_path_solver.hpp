#pragma once
// The simultaneous (direct-transcription) local stage: one smooth NLP in the
// path's interior control points and the squared speed b_k = ṡ² at every
// station, solved by Ipopt (MUMPS; forward-difference Hessian of the exact
// gradient, or limited-memory quasi-Newton).
//
// Variables: z = (x_1, y_1, ..., x_{M-2}, y_{M-2}) of a clamped cubic with
// uniform breakpoints on σ ∈ [0, 1] (the nested formulation's, so both
// optimise over the same paths), held as offsets from the initial control
// points (map coordinates can be 1e6 m), and b_0 .. b_{N-1} at N stations
// equally spaced in σ; b_0 and b_{N-1} are fixed by the start and end speeds.
// Arc length per step: the Hermite-corrected trapezoid rule of the nested
// objective, Δs_j = h (s'_j + s'_{j+1}) / 2 + h² (s''_j − s''_{j+1}) / 12.
//
// Objective: T = Σ_j 2 Δs_j / (√b_j + √b_{j+1}), smooth for b >= kMinSquaredSpeed > 0.
// Constraints: the profile solver's discrete model (each step's control
// u_j = (b_{j+1} − b_j) / (2 Δs_j) admissible at both of its ends). At
// each end, with the station's geometry and x = b there, the force per unit
// mass f_t = u + g k_t, f_q = g k_q + κ_g x, R = g k_r + κ_n x must satisfy
// every ForceCondition of the vehicle's AdmissibleSet (contact, the model's
// tip-over conditions, drive, brake: linear, so a new vehicle model works
// unchanged) and the friction cone (μ² R² − f_t² − f_q²) / (2 g) >= 0;
// b <= max_speed² is a bound. Jacobian: exact and sparse, from the B-spline
// basis and station_derivatives().
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/core/termination.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus::detail {

/// Lower bound of every b_k [m²/s²] (ṡ >= 1 cm/s) keeping √b smooth; a start
/// or end speed below 1 cm/s is modelled as 1 cm/s inside the NLP only.
inline constexpr double kMinSquaredSpeed = 1e-4;

struct SimultaneousProblem {
  const BPatch* terrain = nullptr;
  Vehicle vehicle;
  /// The initial path: clamped cubic, uniform breakpoints on [0, 1], M >= 4.
  const Curve2* initial = nullptr;
  std::size_t stations = 0;  ///< N >= 2
  ProfileOptions speeds;
  /// Box of z [m] (2 (M − 2) entries each).
  Eigen::VectorXd lower, upper;
  /// Starting b_k (N entries), or empty for a slow uniform start.
  std::vector<double> initial_squared_speeds;
  std::size_t max_iterations = 1000;
  /// Each interior control point moves only along its lateral direction
  /// (normal to the chord of its neighbours in the initial control
  /// polygon): M − 2 offsets instead of 2 (M − 2) coordinates.
  bool lateral_offsets = true;
  /// Ipopt's L-BFGS approximation instead of the finite-difference Hessian.
  bool limited_memory_hessian = false;
  double tolerance = 1e-6;  ///< Ipopt's tol
  /// Start near a point believed close to the optimum (warm start).
  bool warm_start = false;
  /// Polled every iteration, armed: once it holds Ipopt stops (status
  /// "time_limit"). Default: never.
  Termination termination;
};

struct SimultaneousRun {
  std::string status;      ///< ipopt_status_text()
  bool failed = false;     ///< an error return (not a stop on a limit)
  bool converged = false;  ///< Solve_Succeeded or Solved_To_Acceptable_Level
  std::size_t iterations = 0;
  std::size_t evaluations = 0;           ///< geometry evaluations at new points
  std::size_t gradient_evaluations = 0;  ///< objective-gradient evaluations
  Eigen::VectorXd variables;             ///< z of Ipopt's final iterate
  std::vector<double> squared_speeds;    ///< b of Ipopt's final iterate
  double nlp_time = std::numeric_limits<double>::quiet_NaN();  ///< its objective [s]
};

/// Solves the NLP from `problem.initial`. Ipopt's restoration phase lets it
/// start where the initial b (or the path itself) violates the constraints.
SimultaneousRun run_simultaneous(const SimultaneousProblem& problem);

}  // namespace talus::detail
