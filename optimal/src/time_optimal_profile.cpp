#include "talus/optimal/time_optimal_profile.hpp"

#include <cmath>
#include <sstream>

#include "step_controls.hpp"
#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kMergeDistance = 1e-9;  // [m]: stations closer than this are one station

using detail::admissible_controls;
using detail::ControlInterval;

ControlInterval intersect(ControlInterval a, const ControlInterval& b) {
  a.intersect(b.lower, b.upper);
  return a;
}

/// One step between kept stations j and j+1, with its constant geometry.
struct Step {
  const AdmissibleSet& c;
  const StationGeometry& from;
  const StationGeometry& to;
  double length;

  /// Controls admissible at the start (state x) that land in [lo, hi] at the end.
  ControlInterval forward(double x, double lo, double hi) const {
    return intersect(detail::known_state_controls(c, from, x),
                     admissible_controls(c, to, x, 2.0 * length, lo, hi));
  }
  /// Controls admissible at the end (state x_end) reached from a start state in [lo, hi].
  ControlInterval backward(double x_end, double lo, double hi) const {
    return intersect(detail::known_state_controls(c, to, x_end),
                     admissible_controls(c, from, x_end, -2.0 * length, lo, hi));
  }
  bool feasible(double x, double lo, double hi) const { return !forward(x, lo, hi).empty(); }
};

/// Largest (or smallest) x in [a, b] with feasible(x), given feasible(a) and
/// not feasible(b): bisection on the convex set's boundary, used in the steps
/// where the closed-form candidate is not the extreme (the limit curve tangent
/// to the braking curve, or the rounding slack of the admissible set past it).
/// The boundary usually lies within 1e-8 (relative) of a, so steps growing
/// from 1e-10 bracket it first: about 20 feasibility tests instead of 45.
template <typename Feasible>
double bisect_boundary(double a, double b, Feasible&& feasible) {
  const double tolerance = 1e-13 * (1.0 + std::abs(a));
  for (double step = 1e-10 * (1.0 + std::abs(a)); 8.0 * step < std::abs(b - a); step *= 8.0) {
    const double probe = a + std::copysign(step, b - a);
    if (!feasible(probe)) {
      b = probe;
      break;
    }
    a = probe;
  }
  for (int iteration = 0; iteration < 200 && std::abs(b - a) > tolerance; ++iteration) {
    const double mid = 0.5 * (a + b);
    (feasible(mid) ? a : b) = mid;
  }
  return a;
}

std::string station_text(std::size_t station, double s) {
  std::ostringstream out;
  out << "station " << station << " (s = " << s << " m)";
  return out.str();
}

}  // namespace

void ProfileOptions::validate() const {
  if (!(start_speed >= 0.0) || !std::isfinite(start_speed)) {
    throw InputError("ProfileOptions.start_speed must be finite and >= 0, got " +
                     std::to_string(start_speed));
  }
  if (!(end_speed >= 0.0) || !std::isfinite(end_speed)) {
    throw InputError("ProfileOptions.end_speed must be finite and >= 0, got " +
                     std::to_string(end_speed));
  }
}

std::string_view to_string(ControlKind kind) {
  switch (kind) {
    case ControlKind::kAccelerate:
      return "accelerate";
    case ControlKind::kDecelerate:
      return "decelerate";
    case ControlKind::kLimit:
      return "limit";
  }
  return "unknown";
}

TimeOptimalProfile TimeOptimalProfileSolver::solve(const VelocityLimits& limits,
                                                   const ProfileOptions& options) {
  TimeOptimalProfile out;
  solve(limits, options, out);
  return out;
}

void TimeOptimalProfileSolver::solve(const VelocityLimits& limits, const ProfileOptions& options,
                                     TimeOptimalProfile& out) {
  options.validate();
  const std::size_t n = limits.size();
  if (n < 2) throw InputError("a velocity profile needs at least 2 stations");
  const AdmissibleSet& constants = limits.admissible_set();

  // Reset in place: a reused result keeps its vectors' storage (no allocation
  // once it has held a profile this long).
  out.status = ProfileStatus::kInfeasible;
  out.message.clear();
  out.travel_time = kInfinity;
  out.switching_points.clear();
  out.infeasible_station = 0;
  out.infeasible_binding = Constraint::kNone;
  out.merged_stations = 0;
  out.s.resize(n);
  out.v.assign(n, 0.0);
  out.a.assign(n, 0.0);
  out.t.assign(n, kInfinity);
  out.v_max.resize(n);
  out.binding.resize(n);
  out.control.assign(n, ControlKind::kLimit);
  for (std::size_t k = 0; k < n; ++k) {
    out.s[k] = limits.frame(k).s;
    out.v_max[k] = limits.limits(k).v_max;
    out.binding[k] = limits.limits(k).upper_binding;
  }

  const auto fail = [&out](std::size_t station, Constraint binding, const std::string& message) {
    out.status = ProfileStatus::kInfeasible;
    out.infeasible_station = station;
    out.infeasible_binding = binding;
    out.message = message;
  };

  // Stations closer than kMergeDistance collapse into one (the later one).
  kept_.clear();
  kept_.push_back(0);
  for (std::size_t k = 1; k < n; ++k) {
    if (out.s[k] - out.s[kept_.back()] >= kMergeDistance) {
      kept_.push_back(k);
    } else if (k + 1 == n) {
      kept_.back() = k;
    }
  }
  out.merged_stations = n - kept_.size();
  const std::size_t m = kept_.size();
  if (m < 2) throw InputError("the path is shorter than 1e-9 m: no profile to compute");

  for (std::size_t j = 0; j < m; ++j) {
    const SpeedLimits& l = limits.limits(kept_[j]);
    if (!l.traversable) {
      fail(kept_[j], l.upper_binding,
           "not traversable at any speed at " + station_text(kept_[j], out.s[kept_[j]]) + ": " +
               std::string(to_string(l.upper_binding)) + " limit");
      return;
    }
  }
  const auto check_speed = [&](const char* which, double speed, std::size_t station) {
    const SpeedLimits& l = limits.limits(station);
    if (speed > l.v_max * (1.0 + 1e-9) + 1e-12) {
      std::ostringstream msg;
      msg << which << " speed " << speed << " m/s is above the speed limit " << l.v_max << " m/s ("
          << to_string(l.upper_binding) << ") at " << station_text(station, out.s[station]);
      throw InputError(msg.str());
    }
    if (speed < l.v_min * (1.0 - 1e-9) - 1e-12) {
      std::ostringstream msg;
      msg << which << " speed " << speed << " m/s is below the minimum speed " << l.v_min
          << " m/s (" << to_string(l.lower_binding) << ") at "
          << station_text(station, out.s[station]);
      throw InputError(msg.str());
    }
  };
  check_speed("start", options.start_speed, 0);
  check_speed("end", options.end_speed, n - 1);

  // ---- Backward pass: controllable sets K_j = [lower_j, upper_j] in x = ṡ². ----
  lower_.assign(m, 0.0);
  upper_.assign(m, 0.0);
  lower_[m - 1] = upper_[m - 1] = options.end_speed * options.end_speed;
  constexpr std::size_t kNoStation = static_cast<std::size_t>(-1);
  std::size_t stand_station = kNoStation;  // station whose can-stand answer is kept
  bool stand_value = false;
  for (std::size_t jj = m - 1; jj-- > 0;) {
    const std::size_t i0 = kept_[jj], i1 = kept_[jj + 1];
    const Step step{constants, limits.geometry(i0), limits.geometry(i1), out.s[i1] - out.s[i0]};
    const double next_lo = lower_[jj + 1], next_hi = upper_[jj + 1];
    const SpeedLimits& here = limits.limits(i0);
    const double x_min = here.v_min * here.v_min, x_max = here.v_max * here.v_max;
    const auto feasible = [&](double x) { return step.feasible(x, next_lo, next_hi); };

    // Upper end: the speed limit itself if it can reach K_{j+1}; otherwise the
    // closed-form braking state from the top (or bottom) of K_{j+1}. The
    // braking state from the top is computed first because it decides most
    // steps alone: when it lies below the speed limit and nothing above it is
    // feasible it is the answer, and the speed limit need not be tried.
    double hi = -kInfinity;
    const auto braking_state = [&](double target, double& candidate) {
      const ControlInterval u = step.backward(target, x_min, x_max);
      if (u.empty() || !std::isfinite(u.lower)) return false;
      candidate = std::max(target - 2.0 * step.length * u.lower, x_min);
      return true;
    };
    // From a feasible closed-form candidate: the largest feasible state.
    const auto settle_upper = [&](double candidate) {
      const double probe = candidate * (1.0 + 1e-9) + 1e-12;
      if (probe < x_max && feasible(probe)) {
        if (std::isfinite(x_max) && feasible(x_max)) return x_max;
        double top = std::isfinite(x_max) ? x_max : 2.0 * probe + 1.0;
        while (!std::isfinite(x_max) && feasible(top)) top *= 2.0;
        return bisect_boundary(probe, top, feasible);
      }
      return candidate;
    };
    double top_candidate = kInfinity;
    const bool from_top = braking_state(next_hi, top_candidate);
    if (from_top && top_candidate < x_max * (1.0 - 1e-12)) {
      double candidate = top_candidate;
      // The closed-form state sits on the boundary: nudge it inside if rounding put it out.
      if (!feasible(candidate)) candidate = std::max(candidate * (1.0 - 1e-9) - 1e-12, x_min);
      if (feasible(candidate)) hi = settle_upper(candidate);
    }
    if (hi == -kInfinity) {
      if (std::isfinite(x_max) && feasible(x_max)) {
        hi = x_max;
      } else {
        for (const double target : {next_hi, next_lo}) {
          double candidate = 0.0;
          if (target == next_hi) {
            if (!from_top) continue;
            candidate = top_candidate;
          } else if (!braking_state(target, candidate)) {
            continue;
          }
          if (!feasible(candidate)) candidate = std::max(candidate * (1.0 - 1e-9) - 1e-12, x_min);
          if (!feasible(candidate)) continue;
          hi = settle_upper(candidate);
          break;
        }
        // Last resort: the feasible states form an interval; if its bottom is
        // feasible, bisect up to its top.
        if (hi == -kInfinity && feasible(x_min)) {
          double top = std::isfinite(x_max) ? x_max : 2.0 * x_min + 1.0;
          while (!std::isfinite(x_max) && feasible(top)) top *= 2.0;
          hi = bisect_boundary(x_min, top, feasible);
        }
      }
    }
    // Lower end, symmetrically.
    double lo = kInfinity;
    // Common case first: standing still at both ends is admissible and K_{j+1}
    // reaches down to rest, so u = 0 from rest stays at rest (two cheap checks).
    // (The answer at the later station is kept from the previous step.)
    const auto can_stand = [&](const StationGeometry& g) {
      const ControlInterval u = detail::known_state_controls(constants, g, 0.0);
      return u.lower <= 0.0 && u.upper >= 0.0;
    };
    bool standing = false;
    if (x_min == 0.0 && next_lo == 0.0) {
      const bool stand_to = (stand_station == i1) ? stand_value : can_stand(step.to);
      standing = stand_to && can_stand(step.from);
      stand_station = stand_to ? i0 : kNoStation;
      stand_value = standing;
    }
    if (standing) {
      lo = 0.0;
    } else if (feasible(x_min)) {
      lo = x_min;
    } else if (hi > -kInfinity) {
      for (const double target : {next_lo, next_hi}) {
        const ControlInterval u = step.backward(target, x_min, x_max);
        if (u.empty() || !std::isfinite(u.upper)) continue;
        double candidate = std::min(std::max(target - 2.0 * step.length * u.upper, x_min), x_max);
        if (!feasible(candidate)) candidate = std::min(candidate * (1.0 + 1e-9) + 1e-12, x_max);
        if (!feasible(candidate)) continue;
        lo = candidate;
        const double probe = candidate * (1.0 - 1e-9) - 1e-12;
        if (probe > x_min && feasible(probe)) lo = bisect_boundary(probe, x_min, feasible);
        break;
      }
      if (lo == kInfinity) lo = bisect_boundary(hi, x_min, feasible);
    }
    if (!(lo <= hi)) {
      fail(i0, here.upper_binding,
           "from " + station_text(i0, out.s[i0]) +
               " no admissible speed reaches the end: the vehicle cannot brake (or accelerate) "
               "enough over the rest of the path");
      return;
    }
    lower_[jj] = lo;
    upper_[jj] = hi;
  }
  const double x_start = options.start_speed * options.start_speed;
  if (x_start > upper_[0] * (1.0 + 1e-9) + 1e-12 || x_start < lower_[0] * (1.0 - 1e-9) - 1e-12) {
    std::ostringstream msg;
    msg << "no admissible profile from start speed " << options.start_speed
        << " m/s: the speeds from which the end state is reachable at the start are ["
        << std::sqrt(lower_[0]) << ", " << std::sqrt(upper_[0]) << "] m/s";
    fail(0, limits.limits(0).upper_binding, msg.str());
    return;
  }

  // ---- Forward pass: greedy largest control that stays controllable. ----
  double x = std::clamp(x_start, lower_[0], upper_[0]);
  out.v[kept_[0]] = std::sqrt(x);
  out.t[kept_[0]] = 0.0;
  // The bounds at the end of one step, at its end state, are the next step's own.
  ControlInterval own = detail::known_state_controls(constants, limits.geometry(kept_[0]), x);
  for (std::size_t jj = 0; jj + 1 < m; ++jj) {
    const std::size_t i0 = kept_[jj], i1 = kept_[jj + 1];
    const Step step{constants, limits.geometry(i0), limits.geometry(i1), out.s[i1] - out.s[i0]};
    const ControlInterval u =
        intersect(own, admissible_controls(constants, step.to, x, 2.0 * step.length, lower_[jj + 1],
                                           upper_[jj + 1]));
    if (u.empty()) {
      fail(i0, limits.limits(i0).upper_binding,
           "numerical failure: no admissible control at " + station_text(i0, out.s[i0]) +
               " although the state is controllable; please report this path");
      return;
    }
    const double control = u.upper;
    const double x_next =
        std::clamp(x + 2.0 * step.length * control, lower_[jj + 1], upper_[jj + 1]);
    // The step's own bounds are those at both of its ends.
    const ControlInterval next_own = detail::known_state_controls(constants, step.to, x_next);
    const ControlInterval bounds = intersect(own, next_own);
    const double tolerance = 1e-7 * (1.0 + std::abs(control));
    out.control[i0] = control >= bounds.upper - tolerance   ? ControlKind::kAccelerate
                      : control <= bounds.lower + tolerance ? ControlKind::kDecelerate
                                                            : ControlKind::kLimit;
    out.a[i0] = control;
    const double v0 = std::sqrt(x), v1 = std::sqrt(std::max(x_next, 0.0));
    if (!(v0 + v1 > 0.0)) {
      fail(i0, limits.limits(i0).upper_binding,
           "the vehicle comes to a standstill between " + station_text(i0, out.s[i0]) +
               " and the next station");
      return;
    }
    out.t[i1] = out.t[i0] + 2.0 * step.length / (v0 + v1);
    out.v[i1] = v1;
    x = x_next;
    own = next_own;
  }
  // Merged stations take the values of the kept station they collapsed into.
  for (std::size_t jj = 0, k = 0; k < n; ++k) {
    while (jj + 1 < m && kept_[jj] < k) ++jj;
    const std::size_t src = kept_[jj];
    if (src == k) continue;
    out.v[k] = out.v[src];
    out.t[k] = out.t[src];
    out.a[k] = out.a[src];
    out.control[k] = out.control[src];
  }
  out.a[n - 1] = out.a[kept_[m - 2]];
  out.control[n - 1] = out.control[kept_[m - 2]];
  for (std::size_t jj = 1; jj + 1 < m; ++jj) {
    const ControlKind before = out.control[kept_[jj - 1]], after = out.control[kept_[jj]];
    if (before != after)
      out.switching_points.push_back({kept_[jj], out.s[kept_[jj]], before, after});
  }
  out.travel_time = out.t[n - 1];
  out.status = ProfileStatus::kOk;
}

}  // namespace talus
