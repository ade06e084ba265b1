#pragma once
/// @file
/// verify_profile: an independent check that a velocity profile along a path
/// is admissible for the vehicle of a VelocityLimits table. It trusts
/// nothing the solver reports about itself (v_max, bindings, controls): it
/// re-evaluates the vehicle's AdmissibleSet at every station.
///
/// Checks, each with its documented tolerance (ProfileVerificationOptions):
///   speed          v_k <= v_max,k (1 + speed_relative) + speed_absolute, v_max from the limits
///   admissible     some s̈ is admissible at (station k, v_k): acceleration_bounds is feasible
///                  (this also rejects v_k < v_min, a NaN or a negative speed)
///   acceleration   the step's s̈ a_k is admissible at **both** of its ends, at their speeds:
///                  the contact force per unit mass it needs there lies within
///                  acceleration_tolerance (1 + |a_k|) [m/s²] of the vehicle's admissible force
///                  set (friction cone and linear conditions, from the force model itself).
///                  Measured in force because the s̈ interval [a_min, a_max] is ill-conditioned
///                  at its tip: on a sliding limit it is sqrt(v_max − v) wide, so rounding of
///                  1e-11 m/s² in force moves its ends by 1e-5 m/s².
///   consistency    a_k = (v_{k+1}² − v_k²) / (2 Δs) within acceleration_tolerance (1 + |a_k|);
///                  t_0 = 0, t_{k+1} = t_k + 2 Δs / (v_k + v_{k+1}) accumulated, within
///                  time_relative t + time_absolute; travel_time = t at the last station
/// Stations closer than merge_distance to the previous checked station are
/// skipped, as the solver merges them (the last station replaces the one
/// before it); the steps are those between the checked stations.
#include <cstddef>
#include <string>
#include <string_view>

#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus {

/// Tolerances of verify_profile. The defaults accept the solver's rounding
/// (it widens its bounds by 1e-10 relative) and nothing physical.
struct ProfileVerificationOptions {
  double speed_relative = 1e-9;          ///< of v_max (>= 0)
  double speed_absolute = 1e-12;         ///< [m/s] (>= 0)
  double acceleration_tolerance = 1e-6;  ///< [m/s²] per (1 + |s̈|) (>= 0)
  double time_relative = 1e-9;           ///< of the arrival time (>= 0)
  double time_absolute = 1e-12;          ///< [s] (>= 0)
  double merge_distance = 1e-9;          ///< [m] (>= 0): shorter steps are merged stations
  /// Throws InputError naming the field.
  void validate() const;
};

/// The verdict: the first failing check in the order of the enum.
enum class VerificationStatus {
  kPass,                     ///< every check holds
  kNoProfile,                ///< the profile's status is not kOk: nothing to verify
  kSpeedAboveLimit,          ///< some v > v_max
  kInadmissibleState,        ///< some (station, v) admits no s̈ at all
  kAccelerationOutOfBounds,  ///< some step's s̈ needs an inadmissible force at an end
  kInconsistent,             ///< accelerations or times do not follow from the speeds
};
/// Lower-case name: pass, no_profile, speed_above_limit, inadmissible_state,
/// acceleration_out_of_bounds, inconsistent.
std::string_view to_string(VerificationStatus status);

/// The worst violation of one check: where, and by how much (0 if none).
struct WorstViolation {
  std::size_t station = 0;
  double amount = 0.0;  ///< in the check's unit: m/s, m/s² or s
};

/// Result of verify_profile.
struct ProfileVerification {
  VerificationStatus status = VerificationStatus::kNoProfile;
  std::string message = "verify_profile was not called";
  bool passed() const { return status == VerificationStatus::kPass; }

  std::size_t speed_violations = 0;     ///< stations with v above the tolerance band
  WorstViolation worst_speed;           ///< largest v − v_max [m/s] over all stations
  std::size_t inadmissible_states = 0;  ///< stations where no s̈ is admissible at v
  std::size_t first_inadmissible = 0;   ///< the first such station
  Constraint inadmissible_constraint = Constraint::kNone;  ///< what it violates
  std::size_t acceleration_violations = 0;  ///< step ends whose s̈ needs a force outside the band
  /// Largest distance of a step end's contact force per unit mass outside the
  /// admissible force set [m/s²] (the end's station).
  WorstViolation worst_acceleration;
  /// Steps whose s̈ or arrival time disagrees with the speeds (+1 each for a
  /// nonzero t_0 and a travel_time other than the last arrival time).
  std::size_t inconsistencies = 0;
  WorstViolation worst_time;         ///< largest |t − Σ 2 Δs / (v_k + v_{k+1})| [s]
  WorstViolation worst_consistency;  ///< largest |a_k − Δ(v²) / (2 Δs)| [m/s²]
};

/// Verifies `profile` against `limits`. Throws InputError if the options
/// are invalid or the profile's arrays do not have limits.size() entries; a
/// failed check is a status, not an error. O(stations).
ProfileVerification verify_profile(const VelocityLimits& limits, const TimeOptimalProfile& profile,
                                   const ProfileVerificationOptions& options = {});

}  // namespace talus
