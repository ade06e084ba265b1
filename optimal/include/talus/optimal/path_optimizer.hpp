#pragma once
/// @file
/// The local stage of the Shiller–Gwo planner (first part): the control
/// points of a clamped cubic B-spline path, start and goal fixed, optimised
/// for the travel time of its exact time-optimal velocity profile. This file
/// holds the objective and the derivative-free NLopt solver (BOBYQA); the
/// gradient-based solvers (Ipopt, NLopt LBFGS) come with the analytic
/// gradient of the travel time.
#include <cstddef>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus {

struct PathOptimizerOptions {
  std::size_t control_points = 8;     ///< of the clamped cubic path (>= 4)
  double station_spacing = 0.5;       ///< profile stations during the search [m] (> 0)
  std::size_t max_evaluations = 400;  ///< objective evaluations (>= 10)
  double relative_tolerance = 1e-5;   ///< stop when the travel time changes less than this
  ProfileOptions speeds;              ///< start and end speeds
  /// Throws InputError naming the field.
  void validate() const;
};

/// Travel time [s] of the exact time-optimal profile along the clamped cubic
/// with these control points, lifted onto `terrain`, at stations
/// `station_spacing` apart; +inf when the path leaves the map or no
/// admissible profile exists.
double path_travel_time(const BPatch& terrain, const Vehicle& vehicle,
                        const std::vector<Vec2>& control_points, double station_spacing,
                        const ProfileOptions& speeds);

struct OptimizedPath {
  Curve2 curve;                 ///< the best path found
  double travel_time = 0.0;     ///< its travel time at the search's station spacing [s]
  double initial_time = 0.0;    ///< the initial path's travel time, same spacing [s]
  std::size_t evaluations = 0;  ///< objective evaluations
  std::string solver_status;    ///< NLopt's result code, as text
};

/// Fits the initial path to `initial_polyline` (fit_clamped_cubic to the
/// polyline resampled at 10 points per control point) and
/// minimises its travel time over the interior control points with NLopt's
/// BOBYQA inside the terrain's bounding box. Never returns a path slower
/// than the initial one. Throws InputError if the initial path is off the map
/// or has no admissible profile.
OptimizedPath optimize_path_bobyqa(const BPatch& terrain, const Vehicle& vehicle,
                                   const std::vector<Vec2>& initial_polyline,
                                   const PathOptimizerOptions& options);

}  // namespace talus
