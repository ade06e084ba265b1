#pragma once
/// @file
/// Velocity-limit studies along a path: each station's limits broken down by
/// constraint, acceleration bounds of a group of vehicles at one common
/// speed, and a summary of a whole path (extremes, medians, the share of the
/// path limited by each constraint). What `talus experiment velocity-limits`
/// reports, as a library.
///
/// Units: arc length s [m], speeds [m/s], accelerations [m/s²], curvatures [1/m].
#include <array>
#include <cstddef>
#include <vector>

#include "talus/bspline/surface_path.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"

namespace talus {

/// Number of enumerators of talus::Constraint (kNone … kSteering).
inline constexpr std::size_t kConstraintCount = 9;

/// Index of `constraint` in arrays of kConstraintCount entries.
constexpr std::size_t constraint_index(Constraint constraint) {
  return static_cast<std::size_t>(constraint);
}

/// √upper of one constraint's interval of ṡ² [m/s]: ∞ where the constraint
/// does not bound the speed, 0 where the interval is empty (no speed
/// satisfies the constraint).
double upper_speed(const SquaredSpeedInterval& interval);
/// √lower of one constraint's interval of ṡ² [m/s]: 0 where the interval is
/// empty.
double lower_speed(const SquaredSpeedInterval& interval);

/// One station of a limit study.
struct LimitStation {
  double s = 0.0;             ///< 3-D arc length [m]
  Vec3 point = Vec3::Zero();  ///< on the surface [m]
  StationGeometry geometry;
  SpeedLimits limits;  ///< of all constraints together
  /// Each constraint's own speed limits, upper_speed / lower_speed of its interval [m/s].
  double v_sliding = 0.0, v_tipover = 0.0, v_contact = 0.0;
  double v_sliding_min = 0.0, v_tipover_min = 0.0;
  /// Set by evaluate_common_accelerations: the speed the bounds were
  /// evaluated at [m/s], and the bounds (feasible = false until then).
  double accel_speed = 0.0;
  AccelerationBounds accel;
};

/// One vehicle's stations along one path.
struct LimitProfile {
  Vehicle vehicle;
  std::vector<LimitStation> stations;
};

/// The stations of `limits` (a VelocityLimits already computed), with each
/// constraint's own limits; accelerations not evaluated.
LimitProfile limit_profile(const VelocityLimits& limits);
/// Computes the limits of `vehicle` at `stations` (>= 2) stations of `path`,
/// equally spaced in the curve parameter (VelocityLimits), then as above.
LimitProfile limit_profile(const Vehicle& vehicle, const SurfacePath& path, std::size_t stations);

/// Acceleration bounds of every profile in `group` (the same stations of the
/// same path) at one common speed per station: `speed_fraction` × the
/// smallest v_max of the group there, raised to the largest v_min (but not
/// above that smallest v_max). At a common speed the lateral load, and with
/// it the friction left for s̈, is the same for all vehicles, so the bounds
/// differ only through the acceleration constraints themselves (pitch-over,
/// drive, brake). Where some vehicle cannot pass (v_max = 0) the bounds are
/// those at standstill. Throws InputError if `speed_fraction` is not in
/// [0, 1] or the profiles' station counts differ; an empty group is a no-op.
void evaluate_common_accelerations(const std::vector<LimitProfile*>& group, double speed_fraction);

/// A summary of one profile.
struct LimitSummary {
  std::size_t stations = 0;
  double min_v_max = 0.0;     ///< ∞ for no station [m/s]
  std::size_t min_index = 0;  ///< first station where v_max is smallest
  double median_v_max = 0.0;  ///< upper_median (sample_statistics.hpp) of v_max [m/s]
  /// Stations by the constraint that sets v_max (an untraversable station
  /// counts under the constraint that fails), indexed by constraint_index.
  std::array<std::size_t, kConstraintCount> upper_counts{};
  std::size_t untraversable = 0;
  std::size_t lower_bound_stations = 0;  ///< v_min > 0
  double max_v_min = 0.0;                ///< [m/s]
  /// Strict local minima of v_max(s) at interior stations (v_max below both
  /// neighbours): the "dips" of the limit curve.
  std::size_t dips = 0;
  std::size_t sliding_on_crest = 0;  ///< v_max set by sliding where κ_n < 0
  /// Smallest of each constraint's own upper limit over the path [m/s].
  double min_v_sliding = 0.0, min_v_tipover = 0.0, min_v_contact = 0.0;
  /// Acceleration bounds (evaluate_common_accelerations): stations where no
  /// s̈ is admissible (or the bounds were not evaluated), the feasible
  /// stations where a constraint sets a_min or a_max (indexed by
  /// constraint_index; a station counts once per constraint), and the
  /// medians of a_min and a_max over the feasible stations [m/s²].
  std::size_t accel_infeasible = 0;
  std::array<std::size_t, kConstraintCount> accel_bound_counts{};
  double median_a_min = 0.0, median_a_max = 0.0;

  /// Stations whose v_max is set by `constraint`.
  std::size_t upper_count(Constraint constraint) const {
    return upper_counts[constraint_index(constraint)];
  }
  /// Fraction of the stations whose v_max is set by `constraint` (0 for none).
  double upper_share(Constraint constraint) const;
  /// Feasible stations where `constraint` sets a_min or a_max.
  std::size_t accel_bound_stations(Constraint constraint) const {
    return accel_bound_counts[constraint_index(constraint)];
  }
};

/// Summary of `stations` (in order along the path).
LimitSummary summarise_limits(const std::vector<LimitStation>& stations);
/// Summary of the stations of `limits` without copying them (no
/// acceleration bounds: every station counts in accel_infeasible); the same
/// speed-limit figures as summarise_limits(limit_profile(limits).stations).
LimitSummary summarise_limits(const VelocityLimits& limits);

/// Whether two profiles of the same stations have exactly equal v_max and
/// v_min at every station (false if the station counts differ).
bool same_speed_limits(const LimitProfile& a, const LimitProfile& b);
/// Whether they have exactly equal a_min and a_max at every station.
bool same_acceleration_bounds(const LimitProfile& a, const LimitProfile& b);

}  // namespace talus
