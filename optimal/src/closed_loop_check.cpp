#include "talus/optimal/closed_loop_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

}  // namespace talus
