#include "talus/optimal/profile_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void require_sizes(const TimeOptimalProfile& p, std::size_t n, const char* what) {
  if (p.s.size() != n || p.v.size() != n || p.a.size() != n || p.v_max.size() != n ||
      p.binding.size() != n) {
    std::ostringstream msg;
    msg << "analyze_profile: the profile's arrays must have " << n << " entries (" << what
        << "), got s " << p.s.size() << ", v " << p.v.size() << ", a " << p.a.size() << ", v_max "
        << p.v_max.size() << ", binding " << p.binding.size();
    throw InputError(msg.str());
  }
}

}  // namespace

void ProfileAnalysisOptions::validate() const {
  if (!(touch_tolerance >= 0.0 && touch_tolerance < 1.0)) {
    std::ostringstream msg;
    msg << "ProfileAnalysisOptions.touch_tolerance must be in [0, 1), got " << touch_tolerance;
    throw InputError(msg.str());
  }
  if (!(acceleration_tolerance >= 0.0 && std::isfinite(acceleration_tolerance))) {
    std::ostringstream msg;
    msg << "ProfileAnalysisOptions.acceleration_tolerance must be finite and >= 0, got "
        << acceleration_tolerance;
    throw InputError(msg.str());
  }
}

bool on_limit(double v, double v_max, double touch_tolerance) {
  return std::isfinite(v_max) && v >= (1.0 - touch_tolerance) * v_max;
}

std::vector<StepClass> classify_steps(const TimeOptimalProfile& p,
                                      const std::vector<AccelerationBounds>& bounds,
                                      const ProfileAnalysisOptions& options) {
  options.validate();
  const std::size_t n = bounds.size();
  if (n < 2) throw InputError("classify_steps: a profile needs at least 2 stations");
  require_sizes(p, n, "one per acceleration bound");
  std::vector<StepClass> steps(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    StepClass& step = steps[k];
    const bool on0 = on_limit(p.v[k], p.v_max[k], options.touch_tolerance);
    const bool on1 = on_limit(p.v[k + 1], p.v_max[k + 1], options.touch_tolerance);
    if (on0 && on1) {
      step.binding = p.binding[k + 1];
      continue;
    }
    // The tighter end of each bound; an end with no admissible s̈ (the speed
    // exactly on a sliding limit, up to rounding) does not count.
    double a_max = kInf, a_min = -kInf;
    Constraint upper = Constraint::kNone, lower = Constraint::kNone;
    for (const std::size_t end : {k, k + 1}) {
      const AccelerationBounds& b = bounds[end];
      if (!b.feasible) continue;
      if (b.a_max < a_max) {
        a_max = b.a_max;
        upper = b.upper_binding;
      }
      if (b.a_min > a_min) {
        a_min = b.a_min;
        lower = b.lower_binding;
      }
    }
    const double a = p.a[k], tolerance = options.acceleration_tolerance * (1.0 + std::abs(a));
    if (a >= a_max - tolerance) {
      step.kind = ControlKind::kAccelerate;
      step.binding = upper;
    } else if (a <= a_min + tolerance) {
      step.kind = ControlKind::kDecelerate;
      step.binding = lower;
    } else {
      step.inside = true;
    }
  }
  return steps;
}

std::vector<SwitchingPoint> switching_points(const std::vector<StepClass>& steps,
                                             const std::vector<double>& s) {
  if (s.size() != steps.size() + 1) {
    throw InputError("switching_points: need one arc length per station (steps + 1), got " +
                     std::to_string(s.size()) + " for " + std::to_string(steps.size()) + " steps");
  }
  std::vector<SwitchingPoint> switches;
  if (steps.empty()) return switches;
  ControlKind current = steps[0].kind;
  for (std::size_t k = 1; k < steps.size(); ++k) {
    const StepClass& step = steps[k];
    if (step.kind == current) continue;
    if (step.inside && k + 1 < steps.size() && !steps[k + 1].inside) {
      const ControlKind next = steps[k + 1].kind;
      if (next != current) switches.push_back({k, s[k], current, next});
      current = next;
      ++k;
      continue;
    }
    switches.push_back({k, s[k], current, step.kind});
    current = step.kind;
  }
  return switches;
}

LimitingLengths limiting_lengths(const std::vector<StepClass>& steps,
                                 const std::vector<double>& s) {
  if (s.size() != steps.size() + 1) {
    throw InputError("limiting_lengths: need one arc length per station (steps + 1), got " +
                     std::to_string(s.size()) + " for " + std::to_string(steps.size()) + " steps");
  }
  LimitingLengths l;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const double ds = s[k + 1] - s[k];
    const StepClass& step = steps[k];
    switch (step.kind) {
      case ControlKind::kAccelerate:
        (step.binding == Constraint::kDrive       ? l.accelerate_drive
         : step.binding == Constraint::kSliding   ? l.accelerate_sliding
         : step.binding == Constraint::kPitchover ? l.accelerate_pitch
                                                  : l.other) += ds;
        break;
      case ControlKind::kDecelerate:
        (step.binding == Constraint::kBrake       ? l.decelerate_brake
         : step.binding == Constraint::kSliding   ? l.decelerate_sliding
         : step.binding == Constraint::kPitchover ? l.decelerate_pitch
                                                  : l.other) += ds;
        break;
      case ControlKind::kLimit:
        l.limit += ds;
        break;
    }
  }
  return l;
}

ProfileAnalysis analyze_profile(const VelocityLimits& limits, const TimeOptimalProfile& p,
                                const ProfileAnalysisOptions& options) {
  options.validate();
  if (p.status != ProfileStatus::kOk) {
    throw InputError("analyze_profile: the profile is infeasible (" + p.message + ")");
  }
  const std::size_t n = limits.size();
  require_sizes(p, n, "one per station of the limits");
  ProfileAnalysis r;
  r.bounds.resize(n);
  const double max_speed = limits.vehicle().max_speed;
  bool previous_touch = false;
  for (std::size_t k = 0; k < n; ++k) {
    r.bounds[k] = limits.acceleration_bounds(k, p.v[k]);
    r.max_speed = std::max(r.max_speed, p.v[k]);
    const bool touch = on_limit(p.v[k], p.v_max[k], options.touch_tolerance);
    if (touch) {
      ++r.touching;
      if (previous_touch) {
        r.touch_length += p.s[k] - p.s[k - 1];
      } else {
        ++r.touch_segments;
      }
    }
    previous_touch = touch;
    if (p.v_max[k] < r.slowest_v_max) {
      r.slowest_v_max = p.v_max[k];
      r.slowest_station = k;
    }
    // Strict on the left, weak on the right: a flat-bottomed dip counts once.
    if (k > 0 && k + 1 < n && p.v_max[k] < (1.0 - 1e-9) * max_speed &&
        p.v_max[k] < p.v_max[k - 1] && p.v_max[k] <= p.v_max[k + 1]) {
      ++r.dips;
      if (touch) ++r.dips_touched;
    }
  }
  r.slowest_s = p.s[r.slowest_station];
  r.slowest_v = p.v[r.slowest_station];
  r.steps = classify_steps(p, r.bounds, options);
  r.switches = switching_points(r.steps, p.s);
  r.lengths = limiting_lengths(r.steps, p.s);
  return r;
}

ProfileDifference profile_difference(const TimeOptimalProfile& a, const TimeOptimalProfile& b) {
  if (a.v.size() != b.v.size() || a.v.empty()) {
    throw InputError(
        "profile_difference: the profiles must have the same, nonzero number of "
        "stations, got " +
        std::to_string(a.v.size()) + " and " + std::to_string(b.v.size()));
  }
  ProfileDifference d;
  for (std::size_t k = 0; k < a.v.size(); ++k) {
    const double gap = a.v[k] - b.v[k];
    if (gap > d.largest_gap) {
      d.largest_gap = gap;
      d.largest_gap_station = k;
    }
    d.largest_difference = std::max(d.largest_difference, std::abs(gap));
  }
  return d;
}

InfeasibilityDiagnosis describe_infeasibility(const VelocityLimits& limits,
                                              const TimeOptimalProfile& profile) {
  if (profile.status == ProfileStatus::kOk) {
    throw InputError("describe_infeasibility: the profile is feasible");
  }
  if (profile.infeasible_station >= limits.size()) {
    throw InputError("describe_infeasibility: infeasible_station " +
                     std::to_string(profile.infeasible_station) + " is not one of the " +
                     std::to_string(limits.size()) + " stations");
  }
  InfeasibilityDiagnosis d{profile.message, profile.infeasible_station,
                           limits.frame(profile.infeasible_station).s, true};
  for (std::size_t k = profile.infeasible_station; k < limits.size(); ++k) {
    const AccelerationBounds b = limits.acceleration_bounds(k, 0.0);
    d.rest_admissible &=
        limits.limits(k).v_min == 0.0 && b.feasible && b.a_min <= 0.0 && b.a_max >= 0.0;
  }
  return d;
}

}  // namespace talus
