#pragma once
/// @file
/// analyze_profile: what a solved time-optimal profile does along its path.
/// For every step between two stations it says whether the vehicle
/// accelerates at the upper bound a_max, brakes at the lower bound a_min or
/// rides the limit curve v_max(s), and which constraint sets that bound; from
/// that it derives the switching points of the control, the path length each
/// constraint limits, and where the profile touches v_max(s).
///
/// Why not the solver's own labels (TimeOptimalProfile::control and
/// switching_points): the solver holds a step's constant s̈ admissible at
/// **both** of its ends, but labels the step by comparing s̈ with the bounds
/// at its start only. Where a bound tightens along the path, a full-drive step
/// sits on the end station's a_max and the solver calls it `limit`, so a
/// bang-bang arc alternates between `accelerate` and `limit` every few
/// stations. analyze_profile compares s̈ with the tighter end of each bound.
///
/// profile_difference compares two profiles along the same stations (e.g.
/// two vehicle models). describe_infeasibility explains a kInfeasible result: where it fails and
/// whether the verdict is provably wrong (standing still is admissible from
/// there to the end).
///
/// Admissibility itself (v <= v_max, s̈ in its bounds) is verify_profile's
/// job (verify_profile.hpp); analyze_profile assumes an admissible profile.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/velocity_limits.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus {

/// Tolerances of analyze_profile.
struct ProfileAnalysisOptions {
  /// A station is on the limit curve if v >= (1 − touch_tolerance) v_max
  /// (dimensionless, in [0, 1)).
  double touch_tolerance = 1e-3;
  /// A step's s̈ is on a bound if within acceleration_tolerance (1 + |s̈|)
  /// [m/s²] of it (>= 0, finite). The solver widens its bounds by about
  /// 1e-12 so that states exactly on the limit curve stay admissible.
  double acceleration_tolerance = 1e-6;
  /// Throws InputError naming the field.
  void validate() const;
};

/// True if `v` is on the limit curve `v_max` [m/s]: v_max is finite and
/// v >= (1 − touch_tolerance) v_max.
bool on_limit(double v, double v_max, double touch_tolerance = 1e-3);

/// What one step (station k to k + 1) does, judged against the bounds at
/// both of its ends at their profile speeds.
struct StepClass {
  /// kAccelerate: s̈ on the tighter a_max; kDecelerate: s̈ on the tighter
  /// a_min; kLimit: both ends on v_max (riding the limit curve) or s̈
  /// strictly inside both bounds (see `inside`).
  ControlKind kind = ControlKind::kLimit;
  /// kAccelerate / kDecelerate: what sets the bound s̈ sits on (drive,
  /// brake, sliding or pitch-over); kLimit on the limit curve: what sets
  /// v_max at the step's end; kLimit inside: kNone.
  Constraint binding = Constraint::kNone;
  /// kLimit with an end off the limit curve: s̈ strictly inside both bounds
  /// (a switching step, or a boundary of the controllable set).
  bool inside = false;
};

/// Path length [m] of the steps in each class (they add up to the path's
/// length between the first and last station).
struct LimitingLengths {
  double accelerate_drive = 0.0;    ///< s̈ on a_max set by the drive limit
  double accelerate_sliding = 0.0;  ///< s̈ on a_max set by friction
  double accelerate_pitch = 0.0;    ///< s̈ on a_max set by pitch-over
  double decelerate_brake = 0.0;    ///< s̈ on a_min set by the brake limit
  double decelerate_sliding = 0.0;  ///< s̈ on a_min set by friction
  double decelerate_pitch = 0.0;    ///< s̈ on a_min set by pitch-over
  double limit = 0.0;               ///< kLimit steps: riding v_max or a controllable-set boundary
  double other = 0.0;               ///< on a bound set by anything else (0 for the bundled models)

  double accelerating() const { return accelerate_drive + accelerate_sliding + accelerate_pitch; }
  double decelerating() const { return decelerate_brake + decelerate_sliding + decelerate_pitch; }
};

/// Classifies every step of `profile` (steps = stations − 1) given the
/// acceleration bounds at each station's profile speed (`bounds[k]` =
/// limits.acceleration_bounds(k, profile.v[k])). A step with both ends on
/// the limit curve rides it; otherwise s̈ is compared with the tighter end of
/// each bound (an end with no admissible s̈, the speed on a sliding limit up
/// to rounding, does not count). Throws InputError if the sizes disagree or
/// the profile has fewer than 2 stations.
std::vector<StepClass> classify_steps(const TimeOptimalProfile& profile,
                                      const std::vector<AccelerationBounds>& bounds,
                                      const ProfileAnalysisOptions& options = {});

/// The switching points of a classification: each station where the kind of
/// the steps changes (SwitchingPoint::station is the first station of the
/// step with the new kind). An `inside` step has kind kLimit, so next to a
/// kLimit arc it is part of that arc. A single `inside` step between two
/// arcs of other kinds is where a bang-bang switch falls within one step: it
/// marks the switch (at its first station) and is no arc of its own; between
/// two arcs of the same kind it is no switch at all. Two or more `inside`
/// steps in a row are a kLimit arc. `s` holds the stations' arc lengths.
std::vector<SwitchingPoint> switching_points(const std::vector<StepClass>& steps,
                                             const std::vector<double>& s);

/// Path length of the steps of each class; `s` as above (steps.size() + 1 entries).
LimitingLengths limiting_lengths(const std::vector<StepClass>& steps, const std::vector<double>& s);

/// Everything analyze_profile finds.
struct ProfileAnalysis {
  std::vector<AccelerationBounds> bounds;  ///< at each station, at its profile speed
  std::vector<StepClass> steps;            ///< one per step (stations − 1)
  std::vector<SwitchingPoint> switches;    ///< switching_points(steps, profile.s)
  LimitingLengths lengths;                 ///< limiting_lengths(steps, profile.s)

  double max_speed = 0.0;          ///< largest v [m/s]
  std::size_t touching = 0;        ///< stations on the limit curve (on_limit)
  std::size_t touch_segments = 0;  ///< maximal runs of such stations
  double touch_length = 0.0;       ///< path length between consecutive such stations [m]
  /// Interior strict local minima of v_max below the vehicle's max speed
  /// (strict on the left, weak on the right, so a flat-bottomed dip counts once),
  /// and how many of them the profile touches.
  std::size_t dips = 0, dips_touched = 0;
  std::size_t slowest_station = 0;  ///< the (first) station of the smallest v_max
  double slowest_v_max = std::numeric_limits<double>::infinity();  ///< that v_max [m/s]
  double slowest_s = 0.0;                                          ///< its arc length [m]
  double slowest_v = 0.0;  ///< the profile's speed there [m/s]
};

/// Analyses a feasible profile solved on `limits`. Throws InputError if the
/// profile is not kOk, its arrays do not have limits.size() entries, or the
/// options are invalid. O(stations).
ProfileAnalysis analyze_profile(const VelocityLimits& limits, const TimeOptimalProfile& profile,
                                const ProfileAnalysisOptions& options = {});

/// How two profiles along the same stations differ in speed.
struct ProfileDifference {
  /// Largest a.v − b.v [m/s] (where `b` is slowest relative to `a`; may be
  /// negative if `b` is faster everywhere), and its (first) station.
  double largest_gap = -std::numeric_limits<double>::infinity();
  std::size_t largest_gap_station = 0;
  double largest_difference = 0.0;  ///< largest |a.v − b.v| [m/s]
};

/// Compares the speeds of `a` and `b` station by station. Throws InputError
/// if they have different numbers of stations or none. O(stations).
ProfileDifference profile_difference(const TimeOptimalProfile& a, const TimeOptimalProfile& b);

/// Where and why a profile is infeasible, and whether the verdict is
/// provably wrong: with the end state at rest, if standing still is
/// admissible at every station from the failing one to the end (v_min = 0
/// and 0 ∈ [a_min, a_max] at v = 0), then x = ṡ² = 0 with s̈ = 0 reaches the
/// end, so the path is feasible from there.
struct InfeasibilityDiagnosis {
  std::string message;           ///< the solver's message
  std::size_t station = 0;       ///< TimeOptimalProfile::infeasible_station
  double s = 0.0;                ///< its arc length [m]
  bool rest_admissible = false;  ///< standing still is admissible from `station` to the end
};

/// Diagnoses an infeasible `profile` solved on `limits`. Throws InputError
/// if the profile is kOk or its infeasible_station is not a station of `limits`.
InfeasibilityDiagnosis describe_infeasibility(const VelocityLimits& limits,
                                              const TimeOptimalProfile& profile);

}  // namespace talus
