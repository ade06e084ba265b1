#include "talus/planners/talus_planner.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <utility>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/core/termination.hpp"
#include "talus/dynamics/admissible_set.hpp"
#include "talus/dynamics/wheel_contact.hpp"
#include "talus/kinematic/baseline_options.hpp"
#include "talus/optimal/planner.hpp"

namespace talus {
namespace {

std::shared_ptr<const BPatch> fit(const RuledTerrain& terrain, double smoothing) {
  return std::make_shared<const BPatch>(smoothing > 0.0
                                            ? BPatch::fit_smoothing(terrain.grid(), smoothing)
                                            : BPatch::interpolate(terrain.grid()));
}

/// The vehicle can stand at `pose` and move off along its heading: a straight pass (no planar
/// curvature, as the traversability map judges a node) whose admissible set holds some
/// acceleration at rest. Not "at some speed": a flank too steep to stand on can be admissible
/// at speed, held by the path's geodesic curvature like a wall of death, and a start or goal
/// at rest could not be there.
ConfigurationCheck pass_check(const RuledTerrain& terrain, const BPatch& surface,
                              const AdmissibleSet& set, double max_speed, const SE2Pose& pose) {
  const Vec2 p = pose.position();
  if (!std::isfinite(pose.theta) || !terrain.has_data(p) || !surface.contains(p)) return {};
  try {
    const PathFrame frame = lift_to_surface(
        p, surface.evaluate(p), Vec2(std::cos(pose.theta), std::sin(pose.theta)), Vec2::Zero());
    const StationGeometry g = station_geometry(frame, surface, set.wheels());
    const SpeedLimits limits = set.speed_limits(g);
    if (!limits.traversable || !(limits.v_max > 0.0) || limits.v_min > 0.0 ||
        !set.acceleration_bounds(g, 0.0).feasible)
      return {};
    return {true, std::isfinite(max_speed) ? std::min(1.0, limits.v_max / max_speed) : 1.0, 1};
  } catch (const InputError&) {  // a wheel off the surface's domain
    return {};
  }
}

BaselineStatus status_of(PlannerStatus status) {
  switch (status) {
    case PlannerStatus::kOk:
      return BaselineStatus::kFound;
    case PlannerStatus::kStopped:
    case PlannerStatus::kTimeLimit:
      return BaselineStatus::kBudgetExceeded;
    case PlannerStatus::kUnreachable:
    case PlannerStatus::kInfeasible:
      break;
  }
  return BaselineStatus::kNoPath;
}

/// The best trajectory's stations as poses (heading = the planar tangent), the query's own
/// poses at the ends (the local stage pins the positions and headings; the stations' tangents
/// agree to rounding), and their planar length.
void fill_path(const Trajectory& best, const SE2Pose& start, const SE2Pose& goal,
               BaselineResult& r) {
  const VelocityLimits& limits = *best.limits;
  for (std::size_t k = 0; k < limits.size(); ++k) {
    const PathFrame& f = limits.frame(k);
    r.path.push_back({f.point.x(), f.point.y(), std::atan2(f.tangent.y(), f.tangent.x())});
  }
  r.path.front() = start;
  r.path.back() = goal;
  for (std::size_t k = 1; k < r.path.size(); ++k)
    r.length_m += (r.path[k].position() - r.path[k - 1].position()).norm();
}

std::vector<BaselineOptionSpec> option_specs() {
  const TalusPlannerOptions d;
  return {
      {"robot", "",
       "vehicle YAML with a finite max_speed (data/vehicles/README.md), e.g. "
       "data/vehicles/iagnemma_ugv.yaml",
       false, true},
      {"smoothing", "0", "lambda of the smoothing fit of the grid (>= 0; 0 = interpolating fit)"},
      {"candidates", std::to_string(d.candidates), "global candidates refined (>= 1)"},
      {"budget", std::to_string(d.budget),
       "work budget (>= 1): polls of the plan's termination, one per 1024 lattice nodes sampled "
       "or expanded and one per solver iteration or evaluation; the query stops with status "
       "budget_exceeded once spent"},
  };
}

std::unique_ptr<BaselinePlanner> make(const BaselineOptions& text) {
  const BaselineOptionReader reader(option_specs(), text);
  TalusPlannerOptions o;
  o.smoothing = reader.number("smoothing", 0.0, 1e12);
  o.candidates = reader.count("candidates", 1);
  o.budget = reader.count("budget", 1);
  const std::string& file = reader.text("robot");
  return std::make_unique<TalusPlanner>(load_vehicle(file), o, file);
}

}  // namespace

void TalusPlannerOptions::validate() const {
  if (!(smoothing >= 0.0) || !std::isfinite(smoothing))
    throw InputError("TalusPlannerOptions.smoothing must be finite and >= 0");
  if (candidates < 1) throw InputError("TalusPlannerOptions.candidates must be >= 1");
  if (budget < 1) throw InputError("TalusPlannerOptions.budget must be >= 1");
}

TalusPlanner::TalusPlanner(Vehicle vehicle, TalusPlannerOptions options, std::string vehicle_file)
    : vehicle_(std::move(vehicle)), options_(options), vehicle_file_(std::move(vehicle_file)) {
  options_.validate();
  vehicle_.validate();
  if (!std::isfinite(vehicle_.max_speed))
    throw InputError("the talus planner needs a vehicle with a finite max_speed");
}

std::vector<BaselineSetting> TalusPlanner::settings() const {
  return {
      {"options", "smoothing", options_.smoothing},
      {"options", "candidates", static_cast<long long>(options_.candidates)},
      {"options", "budget", static_cast<long long>(options_.budget)},
      {"robot", "file", vehicle_file_},
      {"robot", "kind", std::string("vehicle")},
      {"robot", "model",
       std::string(vehicle_.model == VehicleModel::kRigidBody ? "rigid_body" : "point_mass")},
      {"robot", "friction", vehicle_.friction},
      {"robot", "max_speed", vehicle_.max_speed},
  };
}

ValidityFunction TalusPlanner::validity(const RuledTerrain& terrain) const {
  auto surface = fit(terrain, options_.smoothing);
  auto set = std::make_shared<const AdmissibleSet>(vehicle_);
  return [&terrain, surface, set, max_speed = vehicle_.max_speed](const SE2Pose& pose) {
    return pass_check(terrain, *surface, *set, max_speed, pose);
  };
}

BaselineResult TalusPlanner::solve(const RuledTerrain& terrain, const SE2Pose& start,
                                   const SE2Pose& goal) const {
  BaselineResult r;
  const auto started = std::chrono::steady_clock::now();
  const std::shared_ptr<const BPatch> surface = fit(terrain, options_.smoothing);
  const AdmissibleSet set(vehicle_);
  r.preprocessing_seconds = seconds_since(started);
  const auto searched = std::chrono::steady_clock::now();
  const auto finish = [&](BaselineStatus status, std::string message) {
    r.status = status;
    r.message = std::move(message);
    r.search_seconds = seconds_since(searched);
    return r;
  };
  if (!pass_check(terrain, *surface, set, vehicle_.max_speed, start).valid)
    return finish(BaselineStatus::kStartInvalid, "the vehicle cannot pass the start's pose");
  if (!pass_check(terrain, *surface, set, vehicle_.max_speed, goal).valid)
    return finish(BaselineStatus::kGoalInvalid, "the vehicle cannot pass the goal's pose");

  PlanningProblem problem(surface, vehicle_, start.position(), goal.position());
  problem.start_heading = start.theta;
  problem.goal_heading = goal.theta;
  PlannerOptions options;
  options.global.candidates = options_.candidates;
  options.global.threads = 1;  // plan() may run on several threads at once
  std::size_t polls = 0;
  options.termination =
      Termination::when([&polls, budget = options_.budget] { return ++polls > budget; });
  const PlannerResult planned = talus::plan(problem, options);

  r.counters = {{"nodes_expanded", planned.global.expanded},
                {"edges_evaluated", planned.global.edges_evaluated},
                {"candidates", planned.global.candidates.size()},
                {"termination_polls", polls}};
  r.stage_seconds = {{"global", planned.seconds.global}, {"local", planned.seconds.local}};
  const BaselineStatus status = status_of(planned.status);
  if (status != BaselineStatus::kFound) {
    return finish(status, std::string(to_string(planned.status)) + ": " + planned.message);
  }
  fill_path(*planned.best(), start, goal, r);
  return finish(status, "travel time " + std::to_string(planned.travel_time()) + " s");
}

BaselineEntry talus_planner_entry() {
  return {"talus",
          "Talus's two-stage time-optimal planner (talus::plan): a global search whose edge cost "
          "is the travel time at the vehicle's velocity limit, then the B-spline optimiser; the "
          "path is the best trajectory's stations",
          option_specs(), make};
}

}  // namespace talus
