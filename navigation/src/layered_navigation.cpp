#include "talus/navigation/layered_navigation.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <utility>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/grid_window.hpp"
#include "talus/optimal/closed_loop_check.hpp"

namespace talus {

void LayeredNavigationOptions::validate() const {
  if (coarse_factor < 1) throw InputError("LayeredNavigationOptions.coarse_factor must be >= 1");
  if (!(waypoint_spacing >= 0.0) || !std::isfinite(waypoint_spacing))
    throw InputError("LayeredNavigationOptions.waypoint_spacing must be >= 0 [m] (0 = default)");
  planner.validate();
  navigation.validate();
}

std::string_view to_string(LayeredNavigationStatus status) {
  switch (status) {
    case LayeredNavigationStatus::kReachedGoal:
      return "reached";
    case LayeredNavigationStatus::kFailed:
      return "failed";
    case LayeredNavigationStatus::kTimeout:
      return "timeout";
    case LayeredNavigationStatus::kNoPlan:
      return "no_plan";
  }
  return "unknown";
}

double LayeredNavigationResult::time_increase() const {
  if (status != LayeredNavigationStatus::kReachedGoal || !navigation)
    return std::numeric_limits<double>::quiet_NaN();
  return navigation->navigation_time / optimal_time - 1.0;
}

std::string LayeredNavigationResult::brief_report() const {
  char line[300];
  std::snprintf(line, sizeof line,
                "layered navigation: %s; plan %s (%.4g s optimal, planned in %.3g s), %zu "
                "waypoints%s%s\n",
                std::string(to_string(status)).c_str(), std::string(to_string(plan_status)).c_str(),
                optimal_time, plan_seconds, waypoints.points.size(), message.empty() ? "" : "; ",
                message.c_str());
  return line + (navigation ? navigation->brief_report() : std::string());
}

ReferenceTrajectory plan_waypoints(const ReferenceTrajectory& reference, double spacing) {
  if (reference.points.size() < 2 || reference.speed.size() != reference.points.size())
    throw InputError("plan_waypoints: the reference needs two or more points with speeds");
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw InputError("plan_waypoints: the spacing must be > 0 [m]");
  ReferenceTrajectory out;
  double since = 0.0;
  for (std::size_t k = 1; k < reference.points.size(); ++k) {
    since += (reference.points[k] - reference.points[k - 1]).norm();
    if (since >= spacing || k + 1 == reference.points.size()) {
      out.points.push_back(reference.points[k]);
      out.speed.push_back(reference.speed[k]);
      since = 0.0;
    }
  }
  if (out.speed.size() >= 2) out.speed.back() = out.speed[out.speed.size() - 2];
  return out;
}

LayeredNavigationResult navigate_layered(const ElevationGrid& fine, const Vehicle& vehicle,
                                         const Vec2& start, const Vec2& goal,
                                         const LayeredNavigationOptions& options) {
  options.validate();
  vehicle.validate();
  if (!vehicle.body) throw InputError("navigate_layered: the vehicle has no body (mass, ...)");
  const BPatch fine_surface = BPatch::interpolate(fine);
  const auto coarse = std::make_shared<const BPatch>(
      BPatch::interpolate(decimate_grid(fine, options.coarse_factor)));
  const BPatch& coarse_surface = *coarse;
  LayeredNavigationResult result;
  const auto started = std::chrono::steady_clock::now();
  const PlannerResult plan_result =
      plan(PlanningProblem(coarse, vehicle, start, goal), options.planner);
  result.plan_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  result.plan_status = plan_result.status;
  const Trajectory* best = plan_result.best();
  if (best == nullptr) {
    result.status = LayeredNavigationStatus::kNoPlan;
    result.optimal_time = std::numeric_limits<double>::quiet_NaN();
    result.message = "no high-level plan: " + plan_result.message;
    return result;
  }
  result.optimal_time = best->travel_time();
  const double spacing =
      options.waypoint_spacing > 0.0 ? options.waypoint_spacing : 4.0 * coarse_surface.cellsize();
  result.waypoints = plan_waypoints(reference_trajectory(*best), spacing);
  const Vec2 first = result.waypoints.points.front() - start;
  const double yaw = std::atan2(first.y(), first.x());
  result.navigation.emplace(navigate_potential_field(fine_surface, vehicle, start, yaw,
                                                     result.waypoints, {}, options.navigation));
  switch (result.navigation->status) {
    case TrackingStatus::kReachedGoal:
      result.status = LayeredNavigationStatus::kReachedGoal;
      break;
    case TrackingStatus::kTimeout:
      result.status = LayeredNavigationStatus::kTimeout;
      break;
    default:
      result.status = LayeredNavigationStatus::kFailed;
      break;
  }
  result.message = result.navigation->message;
  return result;
}

}  // namespace talus
