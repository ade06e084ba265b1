#pragma once
/// @file
/// The local stage of the Shiller–Gwo planner: the control points of a
/// clamped cubic B-spline path, start and goal fixed, optimised for the
/// travel time of its exact time-optimal velocity profile
/// (PathTimeObjective), starting from a global candidate.
///
/// Solvers (PathOptimizerOptions::solver):
/// - ipopt: Ipopt 3.11 interior point, exact gradient (adjoint), L-BFGS
///   Hessian approximation; the primary solver.
/// - nlopt-lbfgs: NLopt's LD_LBFGS, exact gradient.
/// - nlopt-bobyqa: NLopt's LN_BOBYQA, derivative-free trust region.
/// The variables are bounded by the terrain's domain, which keeps the whole
/// path on the map (a B-spline lies in the convex hull of its control
/// points); paths over NODATA or without an admissible profile are
/// infeasible points the solvers step back from.
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus {

enum class PathSolver { kIpopt, kNloptLbfgs, kNloptBobyqa };
/// "ipopt", "nlopt-lbfgs", "nlopt-bobyqa".
std::string_view to_string(PathSolver solver);
/// Inverse of to_string; throws InputError listing the choices.
PathSolver parse_path_solver(std::string_view name);

struct PathOptimizerOptions {
  PathSolver solver = PathSolver::kIpopt;
  /// Of the clamped cubic path (>= 4). 8 from the control-point study of the
  /// shiller-gwo experiment: from 5 to 16 points the optimum changes by less
  /// than 1 % on its cases (not at all on West Bijou), and the local stage's
  /// time grows with M; winding candidates get more (adaptive_control_points).
  std::size_t control_points = 8;
  /// Grow M by half (up to max_control_points) while the fit to the
  /// candidate has no admissible profile: winding candidates need more.
  bool adaptive_control_points = true;
  std::size_t max_control_points = 48;
  double station_spacing = 0.5;  ///< profile stations during the search [m] (> 0)
  /// At most this many stations during the search (>= 8): long paths get a
  /// coarser search spacing; callers re-evaluate the result at their own.
  std::size_t max_search_stations = 3000;
  std::size_t max_iterations = 40;  ///< Ipopt iterations (>= 1)
  /// Objective evaluations, all solvers (>= 10). 150: on the bench_plan case
  /// 400 gained 0.05 % of travel time at 2.3x the local-stage time.
  std::size_t max_evaluations = 150;
  double relative_tolerance = 1e-5;  ///< stop when the travel time changes less than this
  ProfileOptions speeds;             ///< start and end speeds
  /// Throws InputError naming the field.
  void validate() const;
};

/// A locally optimised path with the solver's diagnostics.
struct OptimizedPath {
  explicit OptimizedPath(Curve2 path) : curve(path), initial_curve(std::move(path)) {}
  Curve2 curve;                    ///< the best path found (never slower than the initial one)
  Curve2 initial_curve;            ///< the initial fit to the candidate
  std::size_t control_points = 0;  ///< M used (more than asked when the fit needed them)
  double travel_time = 0.0;        ///< its travel time at the search's station spacing [s]
  double initial_time = 0.0;       ///< the initial path's travel time, same stations [s]
  std::string solver;              ///< to_string(PathSolver)
  std::string solver_status;       ///< the solver's return code as text (Ipopt / NLopt names)
  bool solver_failed = false;      ///< an error return; the best point seen is still reported
  std::size_t iterations = 0;      ///< Ipopt iterations; NLopt: objective evaluations
  std::size_t evaluations = 0;     ///< objective evaluations
  std::size_t gradient_evaluations = 0;
  std::size_t finite_difference_fallbacks = 0;  ///< gradients taken by finite differences
  /// First-order optimality at the returned path: the largest component of
  /// the projected gradient (zero where a bound is active and the gradient
  /// pushes into it) [s/m]; NaN if the gradient there is unavailable.
  double optimality = 0.0;
  std::size_t stations = 0;  ///< profile stations used during the search
  double seconds = 0.0;      ///< wall time of this optimisation
};

/// Fits the initial path to `initial_polyline` (fit_clamped_cubic to the
/// polyline resampled at 10 points per control point, ends exact) and
/// minimises its travel time with the chosen solver. Throws InputError if the
/// initial path is off the data or has no admissible profile; a solver
/// failure is reported in the result (status, best point), not thrown.
OptimizedPath optimize_path(const BPatch& terrain, const Vehicle& vehicle,
                            const std::vector<Vec2>& initial_polyline,
                            const PathOptimizerOptions& options);

}  // namespace talus
