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

/// The default station spacing [m] of a profile on `surface` for `vehicle`:
///     max(h, b) / kStationsPerFeature,   kStationsPerFeature = 10,
/// with h the surface's knot spacing (the grid's cell size) and b the
/// vehicle's half-track (centre of mass to the wheel line, its smallest
/// length). The profile's discretisation error is first order in the
/// spacing relative to the length over which the limits change, and on a
/// grid that length is the cell (or the vehicle, on grids finer than it):
/// scaling a terrain's x, y and z by λ scales v² by λ and the profile's
/// time by √λ, so a spacing proportional to h gives the same relative error
/// at any scale, where an absolute one gives the 15 km Mars grids 10⁷
/// stations. Evidence: at 1 m cells with the rover (b = 0.6 m) this is the
/// former absolute default, 0.1 m, about 0.1 % (optimal-profile experiment:
/// +0.50 % at 0.5 m, +0.11 % at 0.1 m); the scale test
/// (TrajectoryDefaults.SameRelativeErrorOnAOneMetreAndAFifteenKilometreGrid)
/// measures equal relative errors, within a factor 2, on a 1 m and a 15 km
/// copy of one terrain.
double default_station_spacing(const BPatch& surface, const Vehicle& vehicle);
/// Stations per max(cell size, half-track) of default_station_spacing().
inline constexpr double kStationsPerFeature = 10.0;
/// The finest station spacing an option may ask for [m]: a millimetre, 24 times
/// finer than the default on the battery's 0.24 m cells; below it a plan's
/// paths would need tens of thousands of stations per metre and only hit the
/// memory budget.
inline constexpr double kMinStationSpacing = 1e-3;
/// InputError unless `spacing` is 0 (the default) or a finite number >=
/// kMinStationSpacing; `field` names the option in the message.
void require_station_spacing(double spacing, const char* field);
/// `requested` when > 0, else default_station_spacing(surface, vehicle).
double resolve_station_spacing(double requested, const BPatch& surface, const Vehicle& vehicle);

/// How evaluate_trajectory() samples and drives a path.
struct TrajectoryOptions {
  ProfileOptions speeds;  ///< start and end speeds [m/s]
  /// [m] (0 or >= kMinStationSpacing), see station_count(); 0 =
  /// default_station_spacing(surface, vehicle).
  double station_spacing = 0.0;
  /// Throws InputError naming the field.
  void validate() const;
};

/// A path on the surface with its speed limits and time-optimal profile.
/// Copies share the (immutable) path and limits. The path holds the surface
/// it was evaluated on (a BPatch copy shares its coefficients): nothing has
/// to outlive it.
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
/// station_count(length, spacing) stations (spacing: options.station_spacing,
/// or default_station_spacing() when it is 0) (equally spaced
/// in the curve parameter) and solves the time-optimal profile. A curve that
/// leaves the surface's data, or has no admissible profile, gives an
/// infeasible trajectory with a message (not an exception); invalid options
/// or vehicle throw InputError. `workspace` (optional) is reused between calls.
Trajectory evaluate_trajectory(const BPatch& surface, const Vehicle& vehicle, const Curve2& curve,
                               const TrajectoryOptions& options,
                               TimeOptimalProfileSolver* workspace = nullptr);

}  // namespace talus
