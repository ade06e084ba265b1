#include "talus/dynamics/limit_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "talus/core/error.hpp"
#include "talus/core/sample_statistics.hpp"

namespace talus {

double upper_speed(const SquaredSpeedInterval& interval) {
  return interval.empty() ? 0.0 : std::sqrt(interval.upper);  // sqrt(∞) = ∞
}

double lower_speed(const SquaredSpeedInterval& interval) {
  return interval.empty() ? 0.0 : std::sqrt(interval.lower);
}

LimitProfile limit_profile(const VelocityLimits& limits) {
  LimitProfile profile{limits.vehicle(), std::vector<LimitStation>(limits.size())};
  for (std::size_t k = 0; k < limits.size(); ++k) {
    LimitStation& st = profile.stations[k];
    st.s = limits.frame(k).s;
    st.point = limits.frame(k).point;
    st.geometry = limits.geometry(k);
    st.limits = limits.limits(k);
    st.v_sliding = upper_speed(st.limits.sliding);
    st.v_tipover = upper_speed(st.limits.tipover);
    st.v_contact = upper_speed(st.limits.contact);
    st.v_sliding_min = lower_speed(st.limits.sliding);
    st.v_tipover_min = lower_speed(st.limits.tipover);
  }
  return profile;
}

LimitProfile limit_profile(const Vehicle& vehicle, const SurfacePath& path, std::size_t stations) {
  return limit_profile(VelocityLimits(vehicle, path, stations));
}

void evaluate_common_accelerations(const std::vector<LimitProfile*>& group, double speed_fraction) {
  if (!(speed_fraction >= 0.0 && speed_fraction <= 1.0)) {
    std::ostringstream message;
    message << "evaluate_common_accelerations: speed_fraction must be in [0, 1], got "
            << speed_fraction;
    throw InputError(message.str());
  }
  if (group.empty()) return;
  const std::size_t n = group.front()->stations.size();
  for (const LimitProfile* profile : group) {
    if (profile->stations.size() != n) {
      throw InputError("evaluate_common_accelerations: the profiles have different station counts");
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    double v_max = std::numeric_limits<double>::infinity(), v_min = 0.0;
    for (const LimitProfile* profile : group) {
      v_max = std::min(v_max, profile->stations[k].limits.v_max);
      v_min = std::max(v_min, profile->stations[k].limits.v_min);
    }
    const double speed = std::max(speed_fraction * v_max, std::min(v_min, v_max));
    for (LimitProfile* profile : group) {
      LimitStation& st = profile->stations[k];
      st.accel_speed = speed;
      st.accel = acceleration_bounds(profile->vehicle, st.geometry, speed);
    }
  }
}

double LimitSummary::upper_share(Constraint constraint) const {
  return stations == 0
             ? 0.0
             : static_cast<double>(upper_count(constraint)) / static_cast<double>(stations);
}

namespace {

/// What the summary reads of one station.
struct StationView {
  const SpeedLimits& limits;
  double kappa_n;
  double v_sliding, v_tipover, v_contact;
  const AccelerationBounds* accel;  ///< null: not evaluated
};

/// The summary of `n` stations; view(k) is station k.
template <typename View>
LimitSummary summarise(std::size_t n, const View& view) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  LimitSummary sum;
  sum.stations = n;
  std::vector<double> v_max, a_max, a_min;
  v_max.reserve(n);
  sum.min_v_max = kInf;
  sum.min_v_sliding = sum.min_v_tipover = sum.min_v_contact = kInf;
  for (std::size_t k = 0; k < n; ++k) {
    const StationView st = view(k);
    const SpeedLimits& l = st.limits;
    v_max.push_back(l.v_max);
    if (l.v_max < sum.min_v_max) {
      sum.min_v_max = l.v_max;
      sum.min_index = k;
    }
    if (k > 0 && k + 1 < n && l.v_max < view(k - 1).limits.v_max &&
        l.v_max < view(k + 1).limits.v_max)
      ++sum.dips;
    ++sum.upper_counts[constraint_index(l.upper_binding)];
    if (!l.traversable) ++sum.untraversable;
    if (l.v_min > 0.0) ++sum.lower_bound_stations;
    if (l.upper_binding == Constraint::kSliding && st.kappa_n < 0.0) ++sum.sliding_on_crest;
    sum.max_v_min = std::max(sum.max_v_min, l.v_min);
    sum.min_v_sliding = std::min(sum.min_v_sliding, st.v_sliding);
    sum.min_v_tipover = std::min(sum.min_v_tipover, st.v_tipover);
    sum.min_v_contact = std::min(sum.min_v_contact, st.v_contact);
    if (st.accel == nullptr || !st.accel->feasible) {
      ++sum.accel_infeasible;
      continue;
    }
    ++sum.accel_bound_counts[constraint_index(st.accel->upper_binding)];
    if (st.accel->lower_binding != st.accel->upper_binding)
      ++sum.accel_bound_counts[constraint_index(st.accel->lower_binding)];
    a_max.push_back(st.accel->a_max);
    a_min.push_back(st.accel->a_min);
  }
  sum.median_v_max = upper_median(std::move(v_max));
  sum.median_a_max = upper_median(std::move(a_max));
  sum.median_a_min = upper_median(std::move(a_min));
  return sum;
}

}  // namespace

LimitSummary summarise_limits(const std::vector<LimitStation>& stations) {
  return summarise(stations.size(), [&](std::size_t k) {
    const LimitStation& st = stations[k];
    return StationView{st.limits,    st.geometry.kappa_n, st.v_sliding,
                       st.v_tipover, st.v_contact,        &st.accel};
  });
}

LimitSummary summarise_limits(const VelocityLimits& limits) {
  return summarise(limits.size(), [&](std::size_t k) {
    const SpeedLimits& l = limits.limits(k);
    return StationView{l,
                       limits.geometry(k).kappa_n,
                       upper_speed(l.sliding),
                       upper_speed(l.tipover),
                       upper_speed(l.contact),
                       nullptr};
  });
}

bool same_speed_limits(const LimitProfile& a, const LimitProfile& b) {
  if (a.stations.size() != b.stations.size()) return false;
  for (std::size_t k = 0; k < a.stations.size(); ++k) {
    if (!(a.stations[k].limits.v_max == b.stations[k].limits.v_max &&
          a.stations[k].limits.v_min == b.stations[k].limits.v_min))
      return false;
  }
  return true;
}

bool same_acceleration_bounds(const LimitProfile& a, const LimitProfile& b) {
  if (a.stations.size() != b.stations.size()) return false;
  for (std::size_t k = 0; k < a.stations.size(); ++k) {
    if (!(a.stations[k].accel.a_max == b.stations[k].accel.a_max &&
          a.stations[k].accel.a_min == b.stations[k].accel.a_min))
      return false;
  }
  return true;
}

}  // namespace talus
