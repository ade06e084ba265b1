#include "talus/optimal/closed_loop_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {

ReferenceTrajectory reference_trajectory(const Trajectory& trajectory) {
  if (!trajectory.feasible() || trajectory.limits == nullptr) {
    throw InputError("reference_trajectory: the trajectory has no feasible profile (" +
                     trajectory.message + ")");
  }
  const VelocityLimits& limits = *trajectory.limits;
  ReferenceTrajectory r;
  for (std::size_t k = 0; k < limits.size(); ++k) {
    const Vec2 p(limits.frame(k).point.x(), limits.frame(k).point.y());
    const double v = trajectory.profile.v[k];
    if (!r.points.empty() && (r.points.back() - p).norm() < 1e-9) {
      r.speed.back() = std::max(r.speed.back(), v);
      continue;
    }
    r.points.push_back(p);
    r.speed.push_back(v);
  }
  return r;
}

void ClosedLoopOptions::validate() const {
  if (speed_scales.empty()) throw InputError("ClosedLoopOptions.speed_scales: none given");
  for (const double scale : speed_scales) {
    if (!(scale > 0.0) || !std::isfinite(scale)) {
      throw InputError("ClosedLoopOptions.speed_scales: each must be finite and > 0, got " +
                       std::to_string(scale));
    }
  }
  tracking.validate();
}

double ClosedLoopDrive::schedule_ratio() const {
  return reached() ? result.travel_time / result.planned_time
                   : std::numeric_limits<double>::quiet_NaN();
}

bool ClosedLoopDrive::kept_schedule(double tolerance) const {
  return reached() && result.travel_time <= (1.0 + tolerance) * result.planned_time;
}

std::size_t ClosedLoopResult::reached() const {
  return static_cast<std::size_t>(std::count_if(
      drives.begin(), drives.end(), [](const ClosedLoopDrive& d) { return d.reached(); }));
}

std::string ClosedLoopResult::brief_report() const {
  std::ostringstream out;
  out << reached() << " of " << drives.size() << " drives reached the goal";
  for (const ClosedLoopDrive& d : drives) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "\n  at %.0f %% of the profile speed: %s, progress %.1f %%, %.2f s against "
                  "%.2f s planned, peak lateral load ratio %.2f",
                  100.0 * d.speed_scale, std::string(to_string(d.result.status)).c_str(),
                  100.0 * d.result.progress, d.result.travel_time, d.result.planned_time,
                  d.result.simulation.diagnostics.peak_lateral_load_ratio);
    out << line;
  }
  return out.str();
}

ClosedLoopResult check_closed_loop(const BPatch& surface, const Vehicle& vehicle,
                                   const Trajectory& trajectory, const ClosedLoopOptions& options) {
  options.validate();
  ClosedLoopResult result;
  result.reference = reference_trajectory(trajectory);
  for (const double scale : options.speed_scales) {
    TrackingOptions tracking = options.tracking;
    tracking.speed_scale = scale;
    result.drives.push_back(
        {scale, track_trajectory(surface, vehicle, result.reference, tracking)});
  }
  return result;
}

void SpeedScaleLimitOptions::validate() const {
  if (!(lowest > 0.0) || !std::isfinite(lowest) || !(highest > lowest) || !std::isfinite(highest)) {
    throw InputError("SpeedScaleLimitOptions: need 0 < lowest < highest (finite), got lowest " +
                     std::to_string(lowest) + ", highest " + std::to_string(highest));
  }
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    throw InputError("SpeedScaleLimitOptions.tolerance: must be finite and > 0, got " +
                     std::to_string(tolerance));
  }
  if (!(schedule_tolerance >= 0.0)) {
    throw InputError("SpeedScaleLimitOptions.schedule_tolerance: must be >= 0 (+inf: off), got " +
                     std::to_string(schedule_tolerance));
  }
  tracking.validate();
}

std::string_view to_string(SpeedScaleLimitStatus status) {
  switch (status) {
    case SpeedScaleLimitStatus::kBracketed:
      return "bracketed";
    case SpeedScaleLimitStatus::kReachesHighest:
      return "reaches_highest";
    case SpeedScaleLimitStatus::kFailsLowest:
      return "fails_lowest";
  }
  return "unknown";
}

namespace {
const ClosedLoopDrive* drive_at(const std::vector<ClosedLoopDrive>& drives, double scale) {
  for (const ClosedLoopDrive& d : drives)
    if (d.speed_scale == scale) return &d;
  return nullptr;
}
}  // namespace

const ClosedLoopDrive* SpeedScaleLimit::bounding_failure() const {
  return drive_at(drives, smallest_failing_scale);
}

const ClosedLoopDrive* SpeedScaleLimit::largest_reaching_drive() const {
  return drive_at(drives, largest_reaching_scale);
}

std::string SpeedScaleLimit::bounding_reason() const {
  const ClosedLoopDrive* failure = bounding_failure();
  if (failure == nullptr) return "";
  return failure->reached() ? "behind_schedule" : std::string(to_string(failure->result.status));
}

std::string SpeedScaleLimit::brief_report() const {
  char line[256];
  const std::string reason = bounding_reason();
  std::snprintf(line, sizeof line, "s* = %.3f (%s; smallest failing scale %.3f%s%s), %zu drives",
                largest_reaching_scale, std::string(to_string(status)).c_str(),
                smallest_failing_scale, reason.empty() ? "" : ": ", reason.c_str(), drives.size());
  return line;
}

SpeedScaleLimit find_speed_scale_limit(const BPatch& surface, const Vehicle& vehicle,
                                       const Trajectory& trajectory,
                                       const SpeedScaleLimitOptions& options) {
  options.validate();
  const ReferenceTrajectory reference = reference_trajectory(trajectory);
  SpeedScaleLimit result;
  result.schedule_tolerance = options.schedule_tolerance;
  auto drive = [&](double scale) {
    TrackingOptions tracking = options.tracking;
    tracking.speed_scale = scale;
    result.drives.push_back({scale, track_trajectory(surface, vehicle, reference, tracking)});
    return result.drives.back().kept_schedule(options.schedule_tolerance);
  };
  // Invariant: every scale at or below `reach` is taken to reach, every scale at or above
  // `fail` to fail; the ends are assumptions until driven.
  double reach = options.lowest, fail = options.highest;
  bool reach_driven = false, fail_driven = false;
  while (fail - reach > options.tolerance) {
    const double mid = 0.5 * (reach + fail);
    if (drive(mid)) {
      reach = mid;
      reach_driven = true;
    } else {
      fail = mid;
      fail_driven = true;
    }
  }
  if (!fail_driven && drive(options.highest)) {
    result.status = SpeedScaleLimitStatus::kReachesHighest;
    result.largest_reaching_scale = options.highest;
    return result;
  }
  if (!reach_driven && !drive(options.lowest)) {
    result.status = SpeedScaleLimitStatus::kFailsLowest;
    result.smallest_failing_scale = options.lowest;
    return result;
  }
  result.status = SpeedScaleLimitStatus::kBracketed;
  result.largest_reaching_scale = reach;
  result.smallest_failing_scale = fail;
  return result;
}

}  // namespace talus
