#include "talus/navigation/iagnemma_baseline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>
#include <utility>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/grid_window.hpp"
#include "talus/navigation/hazard_detection.hpp"
#include "talus/navigation/hazard_route.hpp"
#include "talus/navigation/layered_navigation.hpp"
#include "talus/navigation/potential_field_navigation.hpp"
#include "talus/optimal/closed_loop_check.hpp"
#include "talus/optimal/planner.hpp"

namespace talus {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

/// The fine map's hazards as a test of a position: on the data and the
/// nearest node not a hazard.
class HazardMap {
 public:
  HazardMap(const RuledTerrain& terrain, const BPatch& surface, const Vehicle& vehicle)
      : terrain_(terrain), mask_(hazard_node_mask(surface, vehicle)) {}

  bool valid(const Vec2& p) const {
    if (!terrain_.has_data(p)) return false;
    const auto [i, j] = nearest_grid_node(terrain_.grid(), p);
    return mask_[j * terrain_.grid().ncols() + i] == 0;
  }
  std::size_t hazards() const {
    return static_cast<std::size_t>(std::count(mask_.begin(), mask_.end(), 1));
  }
  const std::vector<unsigned char>& mask() const { return mask_; }

 private:
  const RuledTerrain& terrain_;
  std::vector<unsigned char> mask_;
};

std::vector<BaselineOptionSpec> option_specs() {
  const IagnemmaOptions d;
  return {
      {"robot", "",
       "vehicle YAML with a simulation body (mass, wheels, ...; data/vehicles/README.md), e.g. "
       "data/vehicles/iagnemma_ugv.yaml",
       false, true},
      {"high-level", d.time_optimal_plan ? "plan" : "route",
       "plan: Talus's time-optimal plan on the coarse map, as the paper's section II; route: a "
       "shortest hazard-free route over the grid's nodes keeping route-clearance (the default: "
       "the navigator follows a plan that passes hazards closely poorly)"},
      {"coarse-factor", std::to_string(d.coarse_factor),
       "the high-level route's grid is every k-th node of the terrain's (>= 1; 1 = the terrain's "
       "own grid)"},
      {"waypoint-spacing", "1", "distance [m] between waypoints along the route (> 0)"},
      {"route-clearance", "1.5",
       "distance [m] from hazards the route keeps where it can: moves closer cost up to 11 times "
       "their length (>= 0; 0 = none)"},
      {"speed", "1",
       "desired speed [m/s] at every waypoint (>= 0; 0 = the vehicle's max_speed, which must then "
       "be finite)"},
      {"waypoint-radius", "0.2",
       "a waypoint, and the goal, is reached within this distance [m] (0 < r <= 1)"},
      {"sensor-radius", "1.5", "hazards on the map within this distance [m] are avoided (> 0)"},
      {"lookahead", "true",
       "true: the model-based lookahead of section IV (near-optimal navigation); false: the "
       "standard potential field of section III"},
      {"seed", std::to_string(d.seed), "seed of the potential field's descent step (>= 0)"},
      {"time-limit", "60", "most simulated time [s] (> 0)"},
      {"budget", std::to_string(d.budget),
       "most control ticks of the navigator (>= 1; one per 0.01 s of simulated time); the query "
       "stops with status budget_exceeded once spent"},
  };
}

std::unique_ptr<BaselinePlanner> make(const BaselineOptions& text) {
  const BaselineOptionReader reader(option_specs(), text);
  IagnemmaOptions o;
  const std::string& high_level = reader.text("high-level");
  if (high_level != "plan" && high_level != "route")
    throw BaselineOptionError("high-level", "must be plan or route, got '" + high_level + "'");
  o.time_optimal_plan = high_level == "plan";
  o.coarse_factor = reader.count("coarse-factor", 1);
  o.waypoint_spacing = reader.number("waypoint-spacing", 1e-6, 1e6);
  o.route_clearance = reader.number("route-clearance", 0.0, 1e6);
  o.speed = reader.number("speed", 0.0, 1e3);
  o.waypoint_radius = reader.number("waypoint-radius", 1e-6, 1.0);
  o.sensor_radius = reader.number("sensor-radius", 1e-6, 1e6);
  o.lookahead = reader.flag("lookahead");
  o.seed = reader.count("seed", 0);
  o.time_limit = reader.number("time-limit", 1e-6, 1e9);
  o.budget = reader.count("budget", 1);
  const std::string& file = reader.text("robot");
  return std::make_unique<IagnemmaBaseline>(load_vehicle(file), o, file);
}

/// The navigator's control period [s] (VehicleSimulationOptions' default).
double control_period() {
  return VehicleSimulationOptions{}.control_period;
}

}  // namespace

void IagnemmaOptions::validate() const {
  const auto require = [](bool ok, const char* what) {
    if (!ok) throw InputError(std::string("IagnemmaOptions.") + what);
  };
  require(coarse_factor >= 1, "coarse_factor must be >= 1");
  require(waypoint_spacing > 0.0 && std::isfinite(waypoint_spacing),
          "waypoint_spacing must be > 0 [m]");
  require(route_clearance >= 0.0 && std::isfinite(route_clearance),
          "route_clearance must be >= 0 [m]");
  require(speed >= 0.0 && std::isfinite(speed), "speed must be >= 0 [m/s] (0 = max_speed)");
  require(waypoint_radius > 0.0 && waypoint_radius <= 1.0, "waypoint_radius must be in (0, 1] [m]");
  require(sensor_radius > 0.0 && std::isfinite(sensor_radius), "sensor_radius must be > 0 [m]");
  require(time_limit > 0.0 && std::isfinite(time_limit), "time_limit must be > 0 [s]");
  require(budget >= 1, "budget must be >= 1 control tick");
}

IagnemmaBaseline::IagnemmaBaseline(Vehicle vehicle, IagnemmaOptions options,
                                   std::string vehicle_file)
    : vehicle_(std::move(vehicle)),
      options_(std::move(options)),
      vehicle_file_(std::move(vehicle_file)) {
  options_.validate();
  vehicle_.validate();
  const std::string who = vehicle_file_.empty() ? "the vehicle" : vehicle_file_;
  if (!vehicle_.body)
    throw InputError("iagnemma: " + who +
                     " has no simulation body (mass, wheels, ...; data/vehicles/README.md)");
  if (options_.speed == 0.0 && !std::isfinite(vehicle_.max_speed))
    throw InputError("iagnemma: " + who +
                     " has no max_speed; give the waypoints' speed (option speed)");
}

GoalTolerance IagnemmaBaseline::goal_tolerance() const {
  return {options_.waypoint_radius, std::numbers::pi};
}

std::vector<BaselineSetting> IagnemmaBaseline::settings() const {
  const VehicleBody& body = *vehicle_.body;
  return {
      {"robot", "file", vehicle_file_},
      {"robot", "kind", std::string("vehicle")},
      {"robot", "model",
       std::string(vehicle_.model == VehicleModel::kRigidBody ? "rigid_body" : "point_mass")},
      {"robot", "friction", vehicle_.friction},
      {"robot", "cg_height", vehicle_.cg_height},
      {"robot", "half_track", vehicle_.half_track},
      {"robot", "half_wheelbase", vehicle_.half_wheelbase},
      {"robot", "max_speed", vehicle_.max_speed},
      {"robot", "mass", body.mass},
      {"robot", "wheel_radius", body.wheel_radius},
      {"options", "high_level", std::string(options_.time_optimal_plan ? "plan" : "route")},
      {"options", "coarse_factor", static_cast<long long>(options_.coarse_factor)},
      {"options", "waypoint_spacing", options_.waypoint_spacing},
      {"options", "route_clearance", options_.route_clearance},
      {"options", "speed", options_.speed > 0.0 ? options_.speed : vehicle_.max_speed},
      {"options", "waypoint_radius", options_.waypoint_radius},
      {"options", "sensor_radius", options_.sensor_radius},
      {"options", "lookahead", options_.lookahead},
      {"options", "seed", static_cast<long long>(options_.seed)},
      {"options", "time_limit", options_.time_limit},
      {"options", "budget", static_cast<long long>(options_.budget)},
      {"options", "control_period", control_period()},
  };
}

ValidityFunction IagnemmaBaseline::validity(const RuledTerrain& terrain) const {
  const BPatch surface = BPatch::interpolate(terrain.grid());
  const auto map = std::make_shared<const HazardMap>(terrain, surface, vehicle_);
  return [map](const SE2Pose& q) {
    ConfigurationCheck c;
    c.valid = map->valid(q.position());
    c.margin = c.valid ? 1.0 : 0.0;
    return c;
  };
}

namespace {

double waypoint_speed(const IagnemmaOptions& options, const Vehicle& vehicle) {
  return options.speed > 0.0 ? options.speed : vehicle.max_speed;
}

/// The hazard-free route's waypoints at the constant waypoint speed; `failure` says why there
/// are none.
ReferenceTrajectory route_high_level(const IagnemmaOptions& options_, const Vehicle& vehicle_,
                                     const RuledTerrain& terrain, const HazardMap& hazards,
                                     const SE2Pose& start, const SE2Pose& goal, BaselineResult& out,
                                     std::string& failure) {
  // On the terrain's own grid the fine map's hazards are the route's.
  const HazardRoute route =
      options_.coarse_factor == 1
          ? plan_hazard_route(terrain.grid(), hazards.mask(), start.position(), goal.position(),
                              options_.route_clearance)
          : plan_hazard_route(terrain.grid(), vehicle_, start.position(), goal.position(),
                              options_.coarse_factor, options_.route_clearance);
  out.counters["route_nodes"] = route.route_nodes;
  out.counters["route_expansions"] = route.expansions;
  out.counters["route_hazard_nodes"] = route.hazard_nodes;
  if (!route.found) {
    failure = "no hazard-free route over the grid's nodes from the start to the goal";
    return {};
  }
  return route_waypoints(route.points, options_.waypoint_spacing,
                         waypoint_speed(options_, vehicle_));
}

/// The time-optimal plan's waypoints on the coarse map, the profile's speeds capped at the
/// waypoint speed; `failure` says why there are none.
ReferenceTrajectory plan_high_level(const IagnemmaOptions& options_, const Vehicle& vehicle_,
                                    const RuledTerrain& terrain,
                                    const std::shared_ptr<const BPatch>& fine, const SE2Pose& start,
                                    const SE2Pose& goal, BaselineResult& out,
                                    std::string& failure) {
  const std::shared_ptr<const BPatch> map =
      options_.coarse_factor == 1 ? fine
                                  : std::make_shared<const BPatch>(BPatch::interpolate(
                                        decimate_grid(terrain.grid(), options_.coarse_factor)));
  PlanningProblem problem(map, vehicle_, start.position(), goal.position());
  problem.start_heading = start.theta;
  PlannerOptions options;
  options.global.threads = 1;  // plan() may run on several threads at once
  PlannerResult planned;
  try {
    planned = plan(problem, options);
  } catch (const InputError& refused) {  // e.g. a start the planner's vehicle cannot stand on
    failure = std::string("the time-optimal planner refused the query: ") + refused.what();
    return {};
  }
  out.counters["plan_candidates"] = planned.global.candidates.size();
  out.counters["plan_nodes_expanded"] = planned.global.expanded;
  const Trajectory* best = planned.best();
  if (best == nullptr) {
    failure = "no time-optimal high-level plan (" + std::string(to_string(planned.status)) +
              "): " + planned.message;
    return {};
  }
  ReferenceTrajectory waypoints =
      plan_waypoints(reference_trajectory(*best), options_.waypoint_spacing);
  const double cap = waypoint_speed(options_, vehicle_);
  for (double& v : waypoints.speed) v = std::min(v, cap);
  return waypoints;
}

}  // namespace

BaselineResult IagnemmaBaseline::solve(const RuledTerrain& terrain, const SE2Pose& start,
                                       const SE2Pose& goal) const {
  BaselineResult out;
  out.flags = {
      {"lookahead", options_.lookahead}, {"route_found", false}, {"vehicle_failed", false}};
  const auto t0 = Clock::now();
  // Shared: the time-optimal high level plans on it too when coarse-factor is 1.
  const auto fine = std::make_shared<const BPatch>(BPatch::interpolate(terrain.grid()));
  const BPatch& surface = *fine;
  const HazardMap hazards(terrain, surface, vehicle_);
  const auto t1 = Clock::now();
  out.preprocessing_seconds = seconds_between(t0, t1);
  out.stage_seconds["hazard_map"] = out.preprocessing_seconds;
  out.counters["hazard_nodes"] = hazards.hazards();
  if (!hazards.valid(start.position())) {
    out.status = BaselineStatus::kStartInvalid;
    out.message = "the start is on a hazard (too steep, or a step above the wheel radius)";
    return out;
  }
  if (!hazards.valid(goal.position())) {
    out.status = BaselineStatus::kGoalInvalid;
    out.message = "the goal is on a hazard (too steep, or a step above the wheel radius)";
    return out;
  }

  // High level: the waypoints of the time-optimal plan (or of the hazard-free route).
  std::string no_high_level;
  const ReferenceTrajectory waypoints =
      options_.time_optimal_plan
          ? plan_high_level(options_, vehicle_, terrain, fine, start, goal, out, no_high_level)
          : route_high_level(options_, vehicle_, terrain, hazards, start, goal, out, no_high_level);
  const auto t2 = Clock::now();
  out.stage_seconds["high_level"] = seconds_between(t1, t2);
  out.flags["route_found"] = no_high_level.empty();
  if (!no_high_level.empty()) {
    out.status = BaselineStatus::kNoPath;
    out.message = no_high_level;
    out.search_seconds = seconds_between(t1, t2);
    return out;
  }
  out.counters["waypoints"] = waypoints.points.size();

  // Low level: the potential-field navigator on the fine map.
  PotentialFieldNavigationOptions nav;
  nav.waypoint_radius = options_.waypoint_radius;
  nav.sensor_radius = options_.sensor_radius;
  nav.seed = options_.seed;
  nav.lookahead.enabled = options_.lookahead;
  nav.hazards_from_map = true;
  nav.simulation.output_interval = nav.simulation.control_period;
  const double budget_time = static_cast<double>(options_.budget) * nav.simulation.control_period;
  const bool budget_binds = budget_time < options_.time_limit;
  nav.time_limit = budget_binds ? budget_time : options_.time_limit;
  const PotentialFieldNavigationResult run = navigate_potential_field(
      surface, vehicle_, start.position(), start.theta, waypoints, {}, nav);
  const auto t3 = Clock::now();
  out.stage_seconds["navigation"] = seconds_between(t2, t3);
  out.search_seconds = seconds_between(t1, t3);
  out.counters["control_ticks"] = run.simulation.diagnostics.controller_calls;
  out.counters["waypoints_reached"] = run.waypoints_reached;
  out.counters["lookahead_caps_applied"] = run.lookahead_caps_applied;
  out.counters["cvode_steps"] = static_cast<std::size_t>(run.simulation.diagnostics.steps);

  std::ostringstream msg;
  switch (run.status) {
    case TrackingStatus::kReachedGoal:
      out.status = BaselineStatus::kFound;
      msg << "drove to the goal in " << run.navigation_time << " s (simulated) through "
          << waypoints.points.size() << " waypoints";
      break;
    case TrackingStatus::kTimeout:
      out.status = BaselineStatus::kBudgetExceeded;
      if (budget_binds)
        msg << "budget of " << options_.budget << " control ticks (" << nav.time_limit
            << " s simulated) spent before the goal";
      else
        msg << "time limit of " << options_.time_limit << " s (simulated) reached before the goal";
      break;
    default:
      out.status = BaselineStatus::kNoPath;
      out.flags["vehicle_failed"] = true;
      msg << "the simulated vehicle failed: " << to_string(run.status) << ": " << run.message;
      break;
  }
  out.message = msg.str();
  if (out.status != BaselineStatus::kFound) return out;
  out.path.reserve(run.simulation.trace.size());
  for (const VehicleSample& k : run.simulation.trace) {
    const SE2Pose q{k.state.position.x(), k.state.position.y(), k.state.yaw};
    if (!out.path.empty()) out.length_m += (q.position() - out.path.back().position()).norm();
    out.path.push_back(q);
  }
  return out;
}

BaselineEntry iagnemma_baseline_entry() {
  return {"iagnemma",
          "the near-optimal navigation of Iagnemma, Shimoda and Shiller (IROS 2008): waypoints "
          "along a hazard-free route (a shortest grid route standing in for the paper's "
          "time-optimal high-level plan), driven by the trajectory-space potential field with the "
          "model-based lookahead on the simulated vehicle, avoiding the hazards it senses on the "
          "map; the path is the driven path",
          option_specs(), make};
}

}  // namespace talus
