#include "talus/optimal/verify_profile.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "talus/core/error.hpp"

namespace talus {
namespace {

void require_nonnegative(const char* field, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    std::ostringstream msg;
    msg << "ProfileVerificationOptions." << field << " must be finite and >= 0, got " << value;
    throw InputError(msg.str());
  }
}

void record(WorstViolation& worst, std::size_t station, double amount) {
  if (amount > worst.amount) worst = {station, amount};
}

/// How far the contact force per unit mass that state x = ṡ² and s̈ = u need
/// at a station lies outside the vehicle's admissible force set [m/s²]: the
/// largest Euclidean distance in (f_t, f_q, R) to one of the set's pieces,
/// the friction cone (the lighter axle's, for the rigid body) and each linear condition; 0
/// inside. Evaluated from the
/// force model itself (admissible_set.hpp), not from the set's intervals.
/// Measured in force, not in s̈, because at the tip of the admissible set (a
/// speed on the sliding limit) the s̈ interval is sqrt(v_max − v) wide: a
/// force 1e-11 m/s² outside the cone there sits 1e-5 m/s² outside the interval.
double force_excess(const AdmissibleSet& set, const StationGeometry& s, double x, double u) {
  const double g = set.gravity(), mu = set.friction();
  const double f_t = u + g * s.k_t, f_q = g * s.k_q + s.kappa_g * x, R = g * s.k_r + s.kappa_n * x;
  // The friction cone, or the lighter axle's (AdmissibleSet::friction_coupling):
  // sqrt(f_t² + 2 beta |f_t f_q| + f_q²) <= μ R.
  const double beta = set.friction_coupling();
  const double magnitude =
      beta == 0.0 ? std::hypot(f_t, f_q)
                  : std::sqrt(f_t * f_t + 2.0 * beta * std::abs(f_t * f_q) + f_q * f_q);
  double excess = (magnitude - mu * R) / std::sqrt(1.0 + mu * mu);
  for (const ForceCondition& c : set.conditions()) {
    const double norm = std::sqrt(c.t * c.t + c.q * c.q + c.r * c.r);
    if (norm > 0.0) excess = std::max(excess, -(c.t * f_t + c.q * f_q + c.r * R + c.c) / norm);
  }
  return std::max(excess, 0.0);
}

}  // namespace

void ProfileVerificationOptions::validate() const {
  require_nonnegative("speed_relative", speed_relative);
  require_nonnegative("speed_absolute", speed_absolute);
  require_nonnegative("acceleration_tolerance", acceleration_tolerance);
  require_nonnegative("time_relative", time_relative);
  require_nonnegative("time_absolute", time_absolute);
  require_nonnegative("merge_distance", merge_distance);
}

std::string_view to_string(VerificationStatus status) {
  switch (status) {
    case VerificationStatus::kPass:
      return "pass";
    case VerificationStatus::kNoProfile:
      return "no_profile";
    case VerificationStatus::kSpeedAboveLimit:
      return "speed_above_limit";
    case VerificationStatus::kInadmissibleState:
      return "inadmissible_state";
    case VerificationStatus::kAccelerationOutOfBounds:
      return "acceleration_out_of_bounds";
    case VerificationStatus::kInconsistent:
      return "inconsistent";
  }
  return "unknown";
}

ProfileVerification verify_profile(const VelocityLimits& limits, const TimeOptimalProfile& profile,
                                   const ProfileVerificationOptions& options) {
  options.validate();
  ProfileVerification out;
  if (profile.status != ProfileStatus::kOk) {
    out.status = VerificationStatus::kNoProfile;
    out.message = "the profile's status is not ok: " + profile.message;
    return out;
  }
  const std::size_t n = limits.size();
  const auto check_size = [n](const char* name, std::size_t size) {
    if (size != n) {
      throw InputError("verify_profile: profile." + std::string(name) + " has " +
                       std::to_string(size) + " entries, the limits " + std::to_string(n) +
                       " stations");
    }
  };
  check_size("s", profile.s.size());
  check_size("v", profile.v.size());
  check_size("a", profile.a.size());
  check_size("t", profile.t.size());
  if (n < 2) throw InputError("verify_profile: a profile needs at least 2 stations");

  const AdmissibleSet& set = limits.admissible_set();
  // The stations checked: as the solver merges them, a station closer than
  // merge_distance to the previous checked one is skipped (the last station
  // replaces the previous one instead).
  std::vector<std::size_t> kept{0};
  for (std::size_t k = 1; k < n; ++k) {
    if (limits.frame(k).s - limits.frame(kept.back()).s >= options.merge_distance) {
      kept.push_back(k);
    } else if (k + 1 == n) {
      kept.back() = k;
    }
  }
  if (kept.size() < 2) throw InputError("verify_profile: the path is shorter than merge_distance");
  // Speeds, and the admissible s̈ at every station (used by both steps there).
  std::vector<AccelerationBounds> bounds(kept.size());
  for (std::size_t j = 0; j < kept.size(); ++j) {
    const std::size_t k = kept[j];
    const double v = profile.v[k], v_max = limits.limits(k).v_max;
    record(out.worst_speed, k, v - v_max);
    if (v > v_max * (1.0 + options.speed_relative) + options.speed_absolute) ++out.speed_violations;
    bounds[j] = set.acceleration_bounds(limits.geometry(k), v);
    if (!(v >= 0.0) || !bounds[j].feasible) {
      if (out.inadmissible_states++ == 0) {
        out.first_inadmissible = k;
        out.inadmissible_constraint = bounds[j].violated;
      }
    }
  }
  // Steps: s̈ admissible at both ends; s̈ and times consistent with the speeds.
  const auto time_ok = [&](double error, double time) {
    return error <= options.time_relative * time + options.time_absolute;
  };
  double t = 0.0;
  record(out.worst_time, 0, std::abs(profile.t[0]));
  if (!time_ok(std::abs(profile.t[0]), 0.0)) ++out.inconsistencies;
  for (std::size_t j = 0; j + 1 < kept.size(); ++j) {
    const std::size_t k0 = kept[j], k1 = kept[j + 1];
    const double ds = limits.frame(k1).s - limits.frame(k0).s;
    const double v0 = profile.v[k0], v1 = profile.v[k1], a = profile.a[k0];
    const double tolerance = options.acceleration_tolerance * (1.0 + std::abs(a));
    bool inconsistent = false;
    const double implied = (v1 * v1 - v0 * v0) / (2.0 * ds);
    record(out.worst_consistency, k0, std::abs(a - implied));
    if (!(std::abs(a - implied) <= tolerance)) inconsistent = true;
    for (const std::size_t end : {j, j + 1}) {
      if (!bounds[end].feasible) continue;  // counted as an inadmissible state
      const double v = profile.v[kept[end]];
      const double excess = force_excess(set, limits.geometry(kept[end]), v * v, a);
      record(out.worst_acceleration, kept[end], excess);
      if (!(excess <= tolerance)) ++out.acceleration_violations;
    }
    t += 2.0 * ds / (v0 + v1);
    const double time_error = std::abs(profile.t[k1] - t);
    record(out.worst_time, k1, time_error);
    if (!time_ok(time_error, t)) inconsistent = true;
    if (inconsistent) ++out.inconsistencies;
  }
  if (!time_ok(std::abs(profile.travel_time - t), t)) ++out.inconsistencies;

  std::ostringstream msg;
  if (out.speed_violations > 0) {
    out.status = VerificationStatus::kSpeedAboveLimit;
  } else if (out.inadmissible_states > 0) {
    out.status = VerificationStatus::kInadmissibleState;
  } else if (out.acceleration_violations > 0) {
    out.status = VerificationStatus::kAccelerationOutOfBounds;
  } else if (out.inconsistencies > 0) {
    out.status = VerificationStatus::kInconsistent;
  } else {
    out.status = VerificationStatus::kPass;
  }
  msg << to_string(out.status) << ": " << n << " stations; " << out.speed_violations
      << " above v_max (worst " << out.worst_speed.amount << " m/s at station "
      << out.worst_speed.station << "), " << out.inadmissible_states << " inadmissible states";
  if (out.inadmissible_states > 0) {
    msg << " (first at station " << out.first_inadmissible << ": "
        << to_string(out.inadmissible_constraint) << ")";
  }
  msg << ", " << out.acceleration_violations
      << " step ends whose s̈ needs an inadmissible force (worst " << out.worst_acceleration.amount
      << " m/s² outside the force set at station " << out.worst_acceleration.station << "), "
      << out.inconsistencies << " inconsistent steps (worst time error " << out.worst_time.amount
      << " s at station " << out.worst_time.station << ")";
  out.message = msg.str();
  return out;
}

}  // namespace talus
