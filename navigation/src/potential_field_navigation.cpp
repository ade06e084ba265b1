#include "talus/navigation/potential_field_navigation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {
namespace {

void require(bool ok, const char* field, double value, const char* expected) {
  if (ok) return;
  std::ostringstream msg;
  msg << "PotentialFieldNavigationOptions." << field << " must be " << expected << ", got "
      << value;
  throw InputError(msg.str());
}

/// Curvature of the arc tangent to the x axis at the origin through (x, y).
double arc_curvature(const Vec2& p) {
  return 2.0 * p.y() / p.squaredNorm();
}

}  // namespace

void PotentialFieldNavigationOptions::validate() const {
  const double inf = std::numeric_limits<double>::infinity();
  require(velocity_unit > 0.0 && velocity_unit < inf, "velocity_unit", velocity_unit, "positive");
  descent.validate();
  require(max_steering > 0.0 && max_steering < std::numbers::pi / 2, "max_steering", max_steering,
          "in (0, pi/2)");
  require(waypoint_radius > 0.0 && waypoint_radius < inf, "waypoint_radius", waypoint_radius,
          "positive");
  require(sensor_radius > 0.0 && sensor_radius < inf, "sensor_radius", sensor_radius, "positive");
  require(speed_kp >= 0.0 && speed_kp < inf, "speed_kp", speed_kp, ">= 0");
  require(speed_kd >= 0.0 && speed_kd < inf, "speed_kd", speed_kd, ">= 0");
  require(time_limit > 0.0 && time_limit < inf, "time_limit", time_limit, "positive");
  lookahead.validate();
  hazard_detection.validate();
  simulation.validate();
}

std::string PotentialFieldNavigationResult::brief_report() const {
  char line[400];
  std::snprintf(line, sizeof line,
                "potential-field navigation: %s in %.4g s, %zu waypoints reached, hazard "
                "clearance %.3g m, lookahead capped the speed on %zu of %zu ticks%s%s\n",
                std::string(to_string(status)).c_str(), navigation_time, waypoints_reached,
                min_hazard_clearance, lookahead_caps_applied, commands.size(),
                message.empty() ? "" : "; ", message.c_str());
  return line + simulation.brief_report();
}

namespace {

/// The driver of navigate_potential_field (its file comment): the field's
/// inputs at a pose, the §IV lookahead, and the controller the simulation
/// calls in time order (copies share one state).
class FieldNavigator {
 public:
  FieldNavigator(const BPatch& surface, const Vehicle& vehicle,
                 const ReferenceTrajectory& waypoints, const std::vector<DiscHazard>& hazards,
                 const PotentialFieldNavigationOptions& options,
                 PotentialFieldNavigationResult& result)
      : surface(surface),
        vehicle(vehicle),
        waypoints(waypoints),
        hazards(hazards),
        options(options),
        ahead(options.lookahead),
        result(result),
        wheelbase(2.0 * vehicle.half_wheelbase),
        m(vehicle.body->mass),
        g(vehicle.gravity),
        goal_index(waypoints.points.size() - 1),
        driver(std::make_shared<Driver>()) {
    base.friction = vehicle.friction;
    base.half_track = vehicle.half_track;
    base.cg_height = vehicle.cg_height;
    base.max_curvature = std::tan(options.max_steering) / wheelbase;
    base.max_speed = std::isfinite(vehicle.max_speed) ? vehicle.max_speed : 1e3;
    base.velocity_unit = options.velocity_unit;
    base.gains = options.gains;
    driver->rng.seed(options.seed);
  }

  VehicleControls operator()(double t, const VehicleState& s) const {
    VehicleControls c;
    const Mat3 rot = s.rotation();
    const Vec2 cg(s.position.x(), s.position.y());
    const Vec3 fx = rot.col(0);
    const Vec2 forward = Vec2(fx.x(), fx.y()).normalized();
    const Vec3 gravity_body = rot.transpose() * Vec3(0.0, 0.0, -g);
    // The given hazards, and those the sensor sees on the map from here.
    std::vector<DiscHazard> seen = hazards;
    if (options.hazards_from_map) {
      HazardDetectionOptions detection = options.hazard_detection;
      detection.sensor_radius = options.sensor_radius;
      for (const DiscHazard& h : detect_hazards(surface, vehicle, cg, detection)) seen.push_back(h);
    }
    const TrajectorySpaceInputs in =
        inputs_at(cg, forward, gravity_body.y(), -gravity_body.z(), driver->waypoint, seen);
    const Vec2 target = waypoints.points[driver->waypoint];
    if (driver->waypoint == goal_index && (target - cg).norm() < options.waypoint_radius) {
      result.waypoints_reached = waypoints.points.size();
      c.stop = true;
      return c;
    }
    result.waypoints_reached = driver->waypoint;
    if (t == 0.0) driver->command = TrajectoryPoint{std::max(0.0, s.velocity.x()), 0.0};
    driver->command = descend(in, driver->command, driver->rng, options.descent);
    // The cap limits the speed sent to the vehicle, not the descent's own
    // point: were the capped speed fed back, every next step would start far
    // from the desired speed, the velocity term (quartic) would take the
    // whole normalised step, and the curvature would freeze, so a vehicle
    // slowed near a hazard could never steer away from it.
    TrajectoryPoint applied = driver->command;
    Lookahead look;
    if (ahead.enabled) {
      // The prediction draws from a copy of the descent's generator, so the
      // lookahead never changes the actual run's random sequence.
      look = lookahead_cap(cg, std::atan2(forward.y(), forward.x()), std::max(0.0, s.velocity.x()),
                           driver->waypoint, driver->command, driver->rng, seen);
      if (applied.speed > look.cap) {
        applied.speed = look.cap;
        ++result.lookahead_caps_applied;
      }
    }
    result.commands.push_back(applied);
    result.command_times.push_back(t);
    result.lookahead_caps.push_back(look.cap);
    result.lookahead_safe_speeds.push_back(look.here);
    c.steering = std::clamp(std::atan(wheelbase * applied.curvature), -options.max_steering,
                            options.max_steering);
    const double dt = t - driver->last_t;
    const double accel = dt > 0.0 ? (s.velocity.x() - driver->last_v) / dt : 0.0;
    driver->last_t = t;
    driver->last_v = s.velocity.x();
    c.drive_force = m * (g * fx.z() + options.speed_kp * (applied.speed - s.velocity.x()) -
                         options.speed_kd * accel);
    return c;
  }

 private:
  struct Driver {
    std::size_t waypoint = 0;
    TrajectoryPoint command;
    double last_t = 0.0, last_v = 0.0;
    std::mt19937_64 rng;
  };
  struct Lookahead {
    double cap = std::numeric_limits<double>::infinity();
    double here = std::numeric_limits<double>::quiet_NaN();
  };

  // The field's inputs at a planar pose (c.g. `cg`, heading `forward`) with
  // the gravity components in the body frame, towards waypoint `waypoint`
  // (advanced past those within reach); the actual state and the
  // lookahead's predictions both use it.
  TrajectorySpaceInputs inputs_at(const Vec2& cg, const Vec2& forward, double gravity_lateral,
                                  double gravity_normal, std::size_t& waypoint,
                                  const std::vector<DiscHazard>& seen) const {
    // A waypoint is done when reached, or passed: the c.g. is beyond the
    // line through it normal to the leg to the next one (else one missed by
    // more than waypoint_radius would have the vehicle turn back for it).
    const auto done = [&](std::size_t w) {
      const Vec2 leg = waypoints.points[w + 1] - waypoints.points[w];
      return (waypoints.points[w] - cg).norm() < options.waypoint_radius ||
             (cg - waypoints.points[w]).dot(leg) > 0.0;
    };
    while (waypoint < goal_index && done(waypoint)) ++waypoint;
    const Vec2 left(-forward.y(), forward.x());
    const auto local = [&](const Vec2& p) {
      return Vec2((p - cg).dot(forward), (p - cg).dot(left));
    };
    TrajectorySpaceInputs in = base;
    const Vec2 to_target = local(waypoints.points[waypoint]);
    const double bearing = std::atan2(to_target.y(), to_target.x());
    const double arc = arc_curvature(to_target);
    in.desired_curvature = std::clamp(arc, -in.max_curvature, in.max_curvature);
    // A goal inside the turning circle (its arc tighter than the steering allows) is
    // approached by driving on until it is outside, then along the arc through it: turning
    // at full lock instead orbited it (0.4 m round it, the UGV's smallest radius, outside
    // the goal's 0.3 m) until the time limit.
    if (waypoint == goal_index && std::abs(arc) > in.max_curvature) in.desired_curvature = 0.0;
    in.desired_speed = waypoints.speed[waypoint];
    in.gravity_lateral = gravity_lateral;
    in.gravity_normal = std::max(1e-6, gravity_normal);
    // Capturing the goal: no faster than the arc to it can be driven without sliding,
    // sqrt(mu g_n / kappa). The goal, unlike the waypoints before it, is never passed, and
    // one that fell inside the turning circle at speed was orbited at the side-slip field's
    // curvature (1.2 m round it at 2.5 m/s) until the time limit.
    if (waypoint == goal_index)
      in.desired_speed =
          std::min(in.desired_speed, std::sqrt(in.friction * in.gravity_normal /
                                               std::max(std::abs(in.desired_curvature), 1e-9)));
    for (const DiscHazard& h : seen) {
      const Vec2 c_local = local(h.centre);
      const double distance = c_local.norm() - h.radius;
      if (distance > options.sensor_radius) continue;
      TrajectorySpaceHazard th;
      th.distance = std::max(0.0, distance);
      th.waypoint_angle = std::abs(bearing);
      if (distance <= 0.0) {
        th.kappa_min = -in.max_curvature;
        th.kappa_max = in.max_curvature;
      } else {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        bool ahead = false;
        for (int k = -1; k < 64; ++k) {
          const double a = 2.0 * std::numbers::pi * k / 64.0;
          const Vec2 p = k < 0 ? c_local : c_local + h.radius * Vec2(std::cos(a), std::sin(a));
          if (p.x() <= 0.0) continue;
          ahead = true;
          const double kappa = arc_curvature(p);
          lo = std::min(lo, kappa);
          hi = std::max(hi, kappa);
        }
        if (!ahead || hi <= lo) continue;
        th.kappa_min = lo;
        th.kappa_max = hi;
      }
      in.hazards.push_back(th);
    }
    return in;
  }

  // §IV: the reduced model driven by the field over the horizon from the
  // actual pose and command; the cap is the safe speed where the prediction
  // exceeds the safe profile (the smallest such), +inf where it never does;
  // `here` the safe profile at the c.g. itself (figure 8's limit curve).
  Lookahead lookahead_cap(Vec2 cg, double heading, double speed, std::size_t waypoint,
                          TrajectoryPoint command, std::mt19937_64 rng,
                          const std::vector<DiscHazard>& seen) const {
    const auto steps = static_cast<std::size_t>(std::ceil(ahead.horizon / ahead.step - 1e-9));
    std::vector<Vec2> points = {cg};
    std::vector<double> speeds = {speed};
    for (std::size_t k = 0; k < steps; ++k) {
      // The ground under the predicted c.g., once per step: the field's gravity inputs (from
      // the second step on: the first is the actual state's) and the slope the speed feels.
      double slope_sine = 0.0;
      if (surface.contains(cg)) {
        const SurfacePoint z = surface.evaluate(cg);
        slope_sine = slope_sine_along(z.gradient, heading);
        if (k > 0) {
          const Vec3 normal = Vec3(-z.gradient.x(), -z.gradient.y(), 1.0).normalized();
          const Vec3 along =
              Vec3(std::cos(heading), std::sin(heading),
                   z.gradient.x() * std::cos(heading) + z.gradient.y() * std::sin(heading))
                  .normalized();
          const Vec3 left = normal.cross(along);
          const TrajectorySpaceInputs in = inputs_at(cg, Vec2(std::cos(heading), std::sin(heading)),
                                                     -g * left.z(), g * normal.z(), waypoint, seen);
          command = descend(in, command, rng, options.descent);
        }
      } else if (k > 0) {
        break;
      }
      speed = reduced_model_speed(vehicle, slope_sine, speed, command.speed, options.speed_kp,
                                  ahead.step);
      heading += speed * command.curvature * ahead.step;
      cg += speed * ahead.step * Vec2(std::cos(heading), std::sin(heading));
      points.push_back(cg);
      speeds.push_back(speed);
      // The run ends at the goal: nothing beyond it needs to be safe.
      if ((waypoints.points[goal_index] - cg).norm() < options.waypoint_radius) break;
    }
    Lookahead out;
    if (points.size() < 2) return out;
    const std::vector<double> safe = safe_speed_profile(surface, vehicle, points);
    out.here = safe.front();
    for (std::size_t k = 0; k < points.size(); ++k) {
      // The top speed is a limit of its own, not a dynamic one to keep a margin from.
      if (safe[k] >= vehicle.max_speed) continue;
      const double allowed = ahead.safety_factor * safe[k];
      if (speeds[k] > allowed) out.cap = std::min(out.cap, allowed);
    }
    return out;
  }

  const BPatch& surface;
  const Vehicle& vehicle;
  const ReferenceTrajectory& waypoints;
  const std::vector<DiscHazard>& hazards;
  const PotentialFieldNavigationOptions& options;
  const NavigationLookaheadOptions& ahead;
  PotentialFieldNavigationResult& result;
  double wheelbase, m, g;
  std::size_t goal_index;
  TrajectorySpaceInputs base;
  std::shared_ptr<Driver> driver;
};

void check_navigation_inputs(const Vehicle& vehicle, double yaw,
                             const ReferenceTrajectory& waypoints,
                             const std::vector<DiscHazard>& hazards,
                             const PotentialFieldNavigationOptions& options) {
  options.validate();
  vehicle.validate();
  if (!vehicle.body) throw InputError("navigate_potential_field: the vehicle has no body");
  if (waypoints.points.empty() || waypoints.speed.size() != waypoints.points.size())
    throw InputError("navigate_potential_field: needs waypoints, each with a speed");
  for (std::size_t i = 0; i < waypoints.points.size(); ++i) {
    if (!waypoints.points[i].allFinite() ||
        !(waypoints.speed[i] >= 0.0 && std::isfinite(waypoints.speed[i])))
      throw InputError("navigate_potential_field: waypoint " + std::to_string(i) +
                       " is not finite, or its speed is not >= 0");
  }
  for (const DiscHazard& h : hazards) {
    if (!h.centre.allFinite() || !(h.radius > 0.0 && std::isfinite(h.radius)))
      throw InputError("navigate_potential_field: a hazard needs a finite centre and radius > 0");
  }
  if (!std::isfinite(yaw)) throw InputError("navigate_potential_field: yaw must be finite");
}

/// The navigation's status for the simulation's (stopped by the driver: the goal).
TrackingStatus navigation_status(SimulationStatus status) {
  switch (status) {
    case SimulationStatus::kStopped:
      return TrackingStatus::kReachedGoal;
    case SimulationStatus::kReachedEndTime:
      return TrackingStatus::kTimeout;
    case SimulationStatus::kRollover:
      return TrackingStatus::kRollover;
    case SimulationStatus::kSideSlip:
      return TrackingStatus::kSideSlip;
    case SimulationStatus::kLossOfContact:
      return TrackingStatus::kLossOfContact;
    case SimulationStatus::kStall:
      return TrackingStatus::kStall;
    case SimulationStatus::kLeftTerrain:
      return TrackingStatus::kLeftTerrain;
    case SimulationStatus::kSolverFailure:
      break;
  }
  return TrackingStatus::kSolverFailure;
}

}  // namespace

PotentialFieldNavigationResult navigate_potential_field(
    const BPatch& surface, const Vehicle& vehicle, const Vec2& start, double yaw,
    const ReferenceTrajectory& waypoints, const std::vector<DiscHazard>& hazards,
    const PotentialFieldNavigationOptions& options) {
  check_navigation_inputs(vehicle, yaw, waypoints, hazards, options);
  PotentialFieldNavigationResult result;
  const FieldNavigator navigator(surface, vehicle, waypoints, hazards, options, result);
  VehicleSimulationOptions sim = options.simulation;
  sim.end_time = options.time_limit;
  const VehicleState initial = resting_state(surface, vehicle, start, yaw, 0.0);
  result.simulation = simulate_vehicle(surface, vehicle, initial, navigator, sim);
  const VehicleSimulationResult& r = result.simulation;
  result.status = navigation_status(r.status);
  if (result.status == TrackingStatus::kTimeout)
    result.message = "the time limit came before the goal";
  if (result.status != TrackingStatus::kReachedGoal && result.status != TrackingStatus::kTimeout)
    result.message = r.message;
  result.navigation_time = r.end_time;
  result.min_hazard_clearance = std::numeric_limits<double>::infinity();
  for (const VehicleSample& k : r.trace) {
    const Vec2 cg(k.state.position.x(), k.state.position.y());
    for (const DiscHazard& h : hazards)
      result.min_hazard_clearance =
          std::min(result.min_hazard_clearance, (cg - h.centre).norm() - h.radius);
  }
  return result;
}

}  // namespace talus
