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
    const ControlInterval own = detail::known_state_controls(c, from, x);
    if (own.empty()) return own;  // the second query cannot make it less empty
    return intersect(own, admissible_controls(c, to, x, 2.0 * length, lo, hi));
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

constexpr std::size_t kNoStation = static_cast<std::size_t>(-1);

void mark_infeasible(TimeOptimalProfile& out, std::size_t station, Constraint binding,
                     std::string message) {
  out.status = ProfileStatus::kInfeasible;
  out.infeasible_station = station;
  out.infeasible_binding = binding;
  out.message = std::move(message);
}

/// Resets `out` in place for `limits`' stations: a reused result keeps its
/// vectors' storage (no allocation once it has held a profile this long).
void reset(const VelocityLimits& limits, TimeOptimalProfile& out) {
  const std::size_t n = limits.size();
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
}

/// The stations kept: those closer than kMergeDistance to the previous kept
/// one collapse into it (the last station replaces the kept one before it).
void keep_distinct_stations(const std::vector<double>& s, std::vector<std::size_t>& kept) {
  kept.clear();
  kept.push_back(0);
  for (std::size_t k = 1; k < s.size(); ++k) {
    if (s[k] - s[kept.back()] >= kMergeDistance) {
      kept.push_back(k);
    } else if (k + 1 == s.size()) {
      kept.back() = k;
    }
  }
}

/// InputError when `speed` at `station` lies outside its [v_min, v_max].
void check_end_speed(const VelocityLimits& limits, const std::vector<double>& s, const char* which,
                     double speed, std::size_t station) {
  const SpeedLimits& l = limits.limits(station);
  if (speed > l.v_max * (1.0 + 1e-9) + 1e-12) {
    std::ostringstream msg;
    msg << which << " speed " << speed << " m/s is above the speed limit " << l.v_max << " m/s ("
        << to_string(l.upper_binding) << ") at " << station_text(station, s[station]);
    throw InputError(msg.str());
  }
  if (speed < l.v_min * (1.0 - 1e-9) - 1e-12) {
    std::ostringstream msg;
    msg << which << " speed " << speed << " m/s is below the minimum speed " << l.v_min << " m/s ("
        << to_string(l.lower_binding) << ") at " << station_text(station, s[station]);
    throw InputError(msg.str());
  }
}

/// One backward step: the states [x_min, x_max] of its start (the station's
/// speed limits) from which the next controllable set [next_lo, next_hi] is
/// reachable.
struct BackwardStep {
  const Step& step;
  double x_min, x_max, next_lo, next_hi;

  bool feasible(double x) const { return step.feasible(x, next_lo, next_hi); }

  /// The closed-form braking state that lands on `target`; false when none.
  bool braking_state(double target, double& candidate) const {
    const ControlInterval u = step.backward(target, x_min, x_max);
    if (u.empty() || !std::isfinite(u.lower)) return false;
    candidate = std::max(target - 2.0 * step.length * u.lower, x_min);
    return true;
  }

  /// From a feasible closed-form candidate: the largest feasible state.
  double settle_upper(double candidate) const {
    const auto is_feasible = [this](double x) { return feasible(x); };
    const double probe = candidate * (1.0 + 1e-9) + 1e-12;
    if (probe < x_max && feasible(probe)) {
      if (std::isfinite(x_max) && feasible(x_max)) return x_max;
      double top = std::isfinite(x_max) ? x_max : 2.0 * probe + 1.0;
      while (!std::isfinite(x_max) && feasible(top)) top *= 2.0;
      return bisect_boundary(probe, top, is_feasible);
    }
    return candidate;
  }

  /// The closed-form state sits on the boundary: it, or nudged inside if rounding put it
  /// out; false when neither is feasible. (Each feasibility test is two admissible-set
  /// queries, the solve's main cost: none is repeated.)
  bool feasible_near(double& candidate) const {
    if (feasible(candidate)) return true;
    candidate = std::max(candidate * (1.0 - 1e-9) - 1e-12, x_min);
    return feasible(candidate);
  }

  /// The top of the controllable set, or −inf when no state is feasible. The
  /// speed limit itself if it can reach the next set; otherwise the closed-form
  /// braking state from the top (or bottom) of the next set. The braking state
  /// from the top is computed first because it decides most steps alone: when
  /// it lies below the speed limit and nothing above it is feasible it is the
  /// answer, and the speed limit need not be tried.
  double upper_end() const {
    double top_candidate = kInfinity;
    const bool from_top = braking_state(next_hi, top_candidate);
    // Tried first below the speed limit; then it is known to fail and not tried again.
    bool top_tried = false;
    if (from_top && top_candidate < x_max * (1.0 - 1e-12)) {
      top_tried = true;
      double candidate = top_candidate;
      if (feasible_near(candidate)) return settle_upper(candidate);
    }
    if (std::isfinite(x_max) && feasible(x_max)) return x_max;
    for (const double target : {next_hi, next_lo}) {
      double candidate = 0.0;
      if (target == next_hi) {
        if (!from_top || top_tried) continue;
        candidate = top_candidate;
      } else if (!braking_state(target, candidate)) {
        continue;
      }
      if (!feasible_near(candidate)) continue;
      return settle_upper(candidate);
    }
    // Last resort: the feasible states form an interval; if its bottom is
    // feasible, bisect up to its top.
    if (feasible(x_min)) {
      const auto is_feasible = [this](double x) { return feasible(x); };
      double top = std::isfinite(x_max) ? x_max : 2.0 * x_min + 1.0;
      while (!std::isfinite(x_max) && feasible(top)) top *= 2.0;
      return bisect_boundary(x_min, top, is_feasible);
    }
    return -kInfinity;
  }

  /// The bottom of the controllable set given its top `hi` (+inf when none):
  /// symmetrically, the speed's lower limit or the closed-form accelerating
  /// state; `standing` when rest at both ends is admissible and the next set
  /// reaches down to rest.
  double lower_end(double hi, bool standing) const {
    if (standing) return 0.0;
    if (feasible(x_min)) return x_min;
    if (!(hi > -kInfinity)) return kInfinity;
    const auto is_feasible = [this](double x) { return feasible(x); };
    for (const double target : {next_lo, next_hi}) {
      const ControlInterval u = step.backward(target, x_min, x_max);
      if (u.empty() || !std::isfinite(u.upper)) continue;
      double candidate = std::min(std::max(target - 2.0 * step.length * u.upper, x_min), x_max);
      if (!feasible(candidate)) candidate = std::min(candidate * (1.0 + 1e-9) + 1e-12, x_max);
      if (!feasible(candidate)) continue;
      const double probe = candidate * (1.0 - 1e-9) - 1e-12;
      if (probe > x_min && feasible(probe)) return bisect_boundary(probe, x_min, is_feasible);
      return candidate;
    }
    return bisect_boundary(hi, x_min, is_feasible);
  }
};

/// Whether the vehicle can stand still at a station (u = 0 admissible at rest).
bool can_stand(const AdmissibleSet& constants, const StationGeometry& g) {
  const ControlInterval u = detail::known_state_controls(constants, g, 0.0);
  return u.lower <= 0.0 && u.upper >= 0.0;
}

/// The backward pass: the controllable sets K_j = [lower_j, upper_j] in x = ṡ²
/// of the kept stations, from the end state back. False (and `out` marked
/// infeasible) where a set is empty.
bool controllable_sets(const VelocityLimits& limits, const std::vector<std::size_t>& kept,
                       double x_end, std::vector<double>& lower, std::vector<double>& upper,
                       TimeOptimalProfile& out) {
  const AdmissibleSet& constants = limits.admissible_set();
  const std::size_t m = kept.size();
  lower.assign(m, 0.0);
  upper.assign(m, 0.0);
  lower[m - 1] = upper[m - 1] = x_end;
  // Standing still at the later station is known from the previous step.
  std::size_t stand_station = kNoStation;
  bool stand_value = false;
  for (std::size_t jj = m - 1; jj-- > 0;) {
    const std::size_t i0 = kept[jj], i1 = kept[jj + 1];
    const Step step{constants, limits.geometry(i0), limits.geometry(i1), out.s[i1] - out.s[i0]};
    const SpeedLimits& here = limits.limits(i0);
    const BackwardStep backward{step, here.v_min * here.v_min, here.v_max * here.v_max,
                                lower[jj + 1], upper[jj + 1]};
    const double hi = backward.upper_end();
    // Common case first: standing still at both ends is admissible and K_{j+1}
    // reaches down to rest, so u = 0 from rest stays at rest (two cheap checks).
    bool standing = false;
    if (backward.x_min == 0.0 && backward.next_lo == 0.0) {
      const bool stand_to = (stand_station == i1) ? stand_value : can_stand(constants, step.to);
      standing = stand_to && can_stand(constants, step.from);
      stand_station = stand_to ? i0 : kNoStation;
      stand_value = standing;
    }
    const double lo = backward.lower_end(hi, standing);
    if (!(lo <= hi)) {
      mark_infeasible(out, i0, here.upper_binding,
                      "from " + station_text(i0, out.s[i0]) +
                          " no admissible speed reaches the end: the vehicle cannot brake (or "
                          "accelerate) enough over the rest of the path");
      return false;
    }
    lower[jj] = lo;
    upper[jj] = hi;
  }
  return true;
}

/// The forward pass from x_start: at each step the largest control that keeps
/// the state controllable, with its kind, speed and time. False (and `out`
/// marked infeasible) on a numerical failure or a standstill inside the path.
bool forward_pass(const VelocityLimits& limits, const std::vector<std::size_t>& kept,
                  double x_start, const std::vector<double>& lower,
                  const std::vector<double>& upper, TimeOptimalProfile& out) {
  const AdmissibleSet& constants = limits.admissible_set();
  double x = std::clamp(x_start, lower[0], upper[0]);
  out.v[kept[0]] = std::sqrt(x);
  out.t[kept[0]] = 0.0;
  // The bounds at the end of one step, at its end state, are the next step's own.
  ControlInterval own = detail::known_state_controls(constants, limits.geometry(kept[0]), x);
  for (std::size_t jj = 0; jj + 1 < kept.size(); ++jj) {
    const std::size_t i0 = kept[jj], i1 = kept[jj + 1];
    const Step step{constants, limits.geometry(i0), limits.geometry(i1), out.s[i1] - out.s[i0]};
    const ControlInterval u =
        intersect(own, admissible_controls(constants, step.to, x, 2.0 * step.length, lower[jj + 1],
                                           upper[jj + 1]));
    if (u.empty()) {
      mark_infeasible(out, i0, limits.limits(i0).upper_binding,
                      "numerical failure: no admissible control at " + station_text(i0, out.s[i0]) +
                          " although the state is controllable; please report this path");
      return false;
    }
    const double control = u.upper;
    const double x_next = std::clamp(x + 2.0 * step.length * control, lower[jj + 1], upper[jj + 1]);
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
      mark_infeasible(out, i0, limits.limits(i0).upper_binding,
                      "the vehicle comes to a standstill between " + station_text(i0, out.s[i0]) +
                          " and the next station");
      return false;
    }
    out.t[i1] = out.t[i0] + 2.0 * step.length / (v0 + v1);
    out.v[i1] = v1;
    x = x_next;
    own = next_own;
  }
  return true;
}

/// Merged stations take the values of the kept station they collapsed into;
/// then the switching points between kept stations and the travel time.
void finish(const std::vector<std::size_t>& kept, TimeOptimalProfile& out) {
  const std::size_t n = out.s.size(), m = kept.size();
  for (std::size_t jj = 0, k = 0; k < n; ++k) {
    while (jj + 1 < m && kept[jj] < k) ++jj;
    const std::size_t src = kept[jj];
    if (src == k) continue;
    out.v[k] = out.v[src];
    out.t[k] = out.t[src];
    out.a[k] = out.a[src];
    out.control[k] = out.control[src];
  }
  out.a[n - 1] = out.a[kept[m - 2]];
  out.control[n - 1] = out.control[kept[m - 2]];
  for (std::size_t jj = 1; jj + 1 < m; ++jj) {
    const ControlKind before = out.control[kept[jj - 1]], after = out.control[kept[jj]];
    if (before != after) out.switching_points.push_back({kept[jj], out.s[kept[jj]], before, after});
  }
  out.travel_time = out.t[n - 1];
  out.status = ProfileStatus::kOk;
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
  reset(limits, out);
  keep_distinct_stations(out.s, kept_);
  out.merged_stations = n - kept_.size();
  if (kept_.size() < 2) throw InputError("the path is shorter than 1e-9 m: no profile to compute");
  for (const std::size_t k : kept_) {
    const SpeedLimits& l = limits.limits(k);
    if (!l.traversable) {
      mark_infeasible(out, k, l.upper_binding,
                      "not traversable at any speed at " + station_text(k, out.s[k]) + ": " +
                          std::string(to_string(l.upper_binding)) + " limit");
      return;
    }
  }
  check_end_speed(limits, out.s, "start", options.start_speed, 0);
  check_end_speed(limits, out.s, "end", options.end_speed, n - 1);

  if (!controllable_sets(limits, kept_, options.end_speed * options.end_speed, lower_, upper_, out))
    return;
  const double x_start = options.start_speed * options.start_speed;
  if (x_start > upper_[0] * (1.0 + 1e-9) + 1e-12 || x_start < lower_[0] * (1.0 - 1e-9) - 1e-12) {
    std::ostringstream msg;
    msg << "no admissible profile from start speed " << options.start_speed
        << " m/s: the speeds from which the end state is reachable at the start are ["
        << std::sqrt(lower_[0]) << ", " << std::sqrt(upper_[0]) << "] m/s";
    mark_infeasible(out, 0, limits.limits(0).upper_binding, msg.str());
    return;
  }
  if (!forward_pass(limits, kept_, x_start, lower_, upper_, out)) return;
  finish(kept_, out);
}

}  // namespace talus
