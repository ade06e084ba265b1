#pragma once
/// @file
/// The one evaluation rule of Talus: a planar curve lifted onto the terrain
/// surface, the vehicle's speed limits at stations along it and its exact
/// time-optimal velocity profile. The planner, the CLI, the experiments and
/// the benchmarks all evaluate paths through evaluate_trajectory(), so a
/// travel time means the same thing everywhere.
#include <cstddef>
#include <memory>
#include <string>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus {

/// Stations for a path of 3-D length `length` [m] with stations at most
/// `spacing` [m] apart: ceil(length / spacing) + 1, and at least 2. Throws
/// InputError for a negative or non-finite length, a spacing that is not
/// positive and finite, or a count beyond what a std::size_t holds.
std::size_t station_count(double length, double spacing = kDefaultStationSpacing);

/// How evaluate_trajectory() samples and drives a path.
struct TrajectoryOptions {
  ProfileOptions speeds;                          ///< start and end speeds [m/s]
  double station_spacing = kDefaultStationSpacing;  ///< [m] (> 0), see station_count()
  /// Throws InputError naming the field.
  void validate() const;
};

/// A path on the surface with its speed limits and time-optimal profile.
/// Copies share the (immutable) path and limits. The path refers to the
/// surface it was evaluated on, which must outlive it.
struct Trajectory {
  std::shared_ptr<const SurfacePath> path;       ///< null if the curve could not be lifted
  std::shared_ptr<const VelocityLimits> limits;  ///< null if the curve could not be lifted
  TimeOptimalProfile profile;                    ///< status kInfeasible unless solved
  std::string message;                           ///< why there is no profile; empty if feasible

  bool feasible() const { return profile.status == ProfileStatus::kOk; }
  /// The profile's travel time [s]; +inf when infeasible.
  double travel_time() const;
  /// The path's 3-D length [m]; NaN without a path.
  double length() const;
};

/// Lifts `curve` onto `surface`, computes `vehicle`'s speed limits at
/// station_count(length, options.station_spacing) stations (equally spaced
/// in the curve parameter) and solves the time-optimal profile. A curve that
/// leaves the surface's data, or has no admissible profile, gives an
/// infeasible trajectory with a message (not an exception); invalid options
/// or vehicle throw InputError. `workspace` (optional) is reused between calls.
Trajectory evaluate_trajectory(const BPatch& surface, const Vehicle& vehicle, const Curve2& curve,
                               const TrajectoryOptions& options,
                               TimeOptimalProfileSolver* workspace = nullptr);

}  // namespace talus
