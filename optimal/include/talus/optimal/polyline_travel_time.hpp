#pragma once
/// @file
/// The time-optimal travel time along a planar polyline on a terrain (a path
/// from a kinematic planner, or one piece of it between cusps): the polyline
/// is replaced by a clamped cubic B-spline fitted to it and driven from rest
/// to rest at its exact time-optimal velocity profile.
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/time_optimal_profile.hpp"
#include "talus/optimal/trajectory.hpp"

namespace talus {

/// Rest-to-rest travel time [s] of `vehicle` along `polyline` (planar
/// positions [m]) on `surface`: resample_polyline to max(10·m, n) points
/// (n the polyline's point count) and fit_clamped_cubic with m control points,
/// m = clamp(ceil(L), 4, 48) for the polyline's planar length L [m] (one per
/// metre), then evaluate_trajectory with `options` (default: rest to rest,
/// 0.1 m stations). 0 for a polyline shorter than 1 µm; ∞ if the fitted
/// curve leaves the surface's data or no profile is admissible. `solver`
/// (optional) is reused between calls.
double polyline_travel_time(const BPatch& surface, const Vehicle& vehicle,
                            const std::vector<Vec2>& polyline,
                            const TrajectoryOptions& options = {},
                            TimeOptimalProfileSolver* solver = nullptr);

}  // namespace talus
