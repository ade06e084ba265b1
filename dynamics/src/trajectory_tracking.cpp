#include "talus/dynamics/trajectory_tracking.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {
namespace {

void require(bool ok, const char* field, double value, const char* expected) {
  if (ok) return;
  std::ostringstream msg;
  msg << "TrackingOptions." << field << " must be " << expected << ", got " << value;
  throw InputError(msg.str());
}

/// The reference polyline with its cumulative planar arc length.
class Polyline {
 public:
  explicit Polyline(const ReferenceTrajectory& r) : points_(r.points), speed_(r.speed) {
    s_.resize(points_.size(), 0.0);
    for (std::size_t i = 1; i < points_.size(); ++i)
      s_[i] = s_[i - 1] + (points_[i] - points_[i - 1]).norm();
    // Each segment's heading, unwrapped along the path, so that a difference
    // of two is the turning angle between them.
    heading_.resize(points_.size() - 1);
    for (std::size_t k = 0; k + 1 < points_.size(); ++k) {
      const Vec2 d = points_[k + 1] - points_[k];
      const double raw = std::atan2(d.y(), d.x());
      heading_[k] =
          k == 0 ? raw
                 : heading_[k - 1] + std::remainder(raw - heading_[k - 1], 2.0 * std::numbers::pi);
    }
  }
  double length() const { return s_.back(); }
  std::size_t size() const { return points_.size(); }

  /// Segment index containing arc length s.
  std::size_t segment(double s) const {
    const auto it = std::upper_bound(s_.begin(), s_.end(), s);
    const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, it - s_.begin() - 1));
    return std::min(k, points_.size() - 2);
  }
  Vec2 point(double s) const {
    s = std::clamp(s, 0.0, length());
    const std::size_t k = segment(s);
    const double u = (s - s_[k]) / (s_[k + 1] - s_[k]);
    return points_[k] + u * (points_[k + 1] - points_[k]);
  }
  double speed(double s) const {
    s = std::clamp(s, 0.0, length());
    const std::size_t k = segment(s);
    const double u = (s - s_[k]) / (s_[k + 1] - s_[k]);
    return speed_[k] + u * (speed_[k + 1] - speed_[k]);
  }

  /// dv/ds of the planned speed on the segment containing s [1/s].
  double speed_slope(double s) const {
    s = std::clamp(s, 0.0, length());
    const std::size_t k = segment(s);
    return (speed_[k + 1] - speed_[k]) / (s_[k + 1] - s_[k]);
  }

  /// Unit tangent of the segment containing s.
  Vec2 tangent(double s) const {
    const std::size_t k = segment(std::clamp(s, 0.0, length()));
    return (points_[k + 1] - points_[k]).normalized();
  }

  /// Curvature at s [1/m], > 0 turning left: the turning angle between the
  /// segments at s − w and s + w (clamped to the path) over the arc length
  /// between their midpoints, w at least two segments' worth.
  double curvature(double s, double w) const {
    const std::size_t k0 = segment(std::clamp(s - w, 0.0, length()));
    const std::size_t k1 = segment(std::clamp(s + w, 0.0, length()));
    const std::size_t a = std::min(k0, k1 > 0 ? k1 - 1 : 0), b = std::max(k1, a + 1);
    if (b >= heading_.size()) return 0.0;  // a single segment: straight
    const double span = 0.5 * (s_[b] + s_[b + 1]) - 0.5 * (s_[a] + s_[a + 1]);
    return (heading_[b] - heading_[a]) / span;
  }

  /// Nearest point of the polyline to p among the segments meeting
  /// [s_from, s_to]: its arc length and signed distance (> 0 left).
  std::pair<double, double> project(const Vec2& p, double s_from, double s_to) const {
    const std::size_t k0 = segment(std::max(0.0, s_from));
    const std::size_t k1 = segment(std::min(length(), s_to));
    double best_d2 = std::numeric_limits<double>::infinity(), best_s = s_from, best_side = 0.0;
    for (std::size_t k = k0; k <= k1; ++k) {
      const Vec2 a = points_[k], d = points_[k + 1] - a;
      const double len2 = d.squaredNorm();
      const double u = std::clamp((p - a).dot(d) / len2, 0.0, 1.0);
      const Vec2 q = a + u * d;
      const double d2 = (p - q).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        best_s = s_[k] + u * std::sqrt(len2);
        const double cross = d.x() * (p - a).y() - d.y() * (p - a).x();
        best_side = cross >= 0.0 ? 1.0 : -1.0;
      }
    }
    return {best_s, best_side * std::sqrt(best_d2)};
  }

 private:
  std::vector<Vec2> points_;
  std::vector<double> speed_;
  std::vector<double> s_;
  std::vector<double> heading_;  // per segment [rad], unwrapped
};

/// Sine of the terrain's grade along `forward` (unit, horizontal) at `cg`: the
/// chord between the ground points one half-wheelbase behind and ahead (the
/// axles'), each clamped to the map. > 0 uphill.
double terrain_grade(const BPatch& surface, const Vec2& cg, const Vec2& forward,
                     double half_wheelbase) {
  const auto ground = [&](const Vec2& p) {
    return surface
        .evaluate(Vec2(std::clamp(p.x(), surface.x_min(), surface.x_max()),
                       std::clamp(p.y(), surface.y_min(), surface.y_max())))
        .z;
  };
  const double rise = ground(cg + half_wheelbase * forward) - ground(cg - half_wheelbase * forward);
  const double run = 2.0 * half_wheelbase;
  return rise / std::sqrt(rise * rise + run * run);
}

/// Below this planar speed [m/s] the side slip is taken as 0 and the
/// yaw-rate feedback is off: the velocity's direction is noise there.
constexpr double kCourseSpeedFloor = 0.3;

TrackingStatus from_simulation(SimulationStatus s) {
  switch (s) {
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
      return TrackingStatus::kSolverFailure;
    case SimulationStatus::kStopped:
      return TrackingStatus::kReachedGoal;
    case SimulationStatus::kReachedEndTime:
      return TrackingStatus::kTimeout;
  }
  return TrackingStatus::kSolverFailure;
}

}  // namespace

void ReferenceTrajectory::validate() const {
  if (points.size() < 2)
    throw InputError("ReferenceTrajectory: needs at least 2 points, got " +
                     std::to_string(points.size()));
  if (speed.size() != points.size())
    throw InputError("ReferenceTrajectory: " + std::to_string(speed.size()) + " speeds for " +
                     std::to_string(points.size()) + " points");
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      throw InputError("ReferenceTrajectory: point " + std::to_string(i) + " is not finite");
    if (!(speed[i] >= 0.0 && std::isfinite(speed[i])))
      throw InputError("ReferenceTrajectory: speed " + std::to_string(i) +
                       " must be finite and >= 0");
    if (i > 0 && points[i] == points[i - 1])
      throw InputError("ReferenceTrajectory: points " + std::to_string(i - 1) + " and " +
                       std::to_string(i) + " coincide");
  }
  // Driven, it would stand at the start until the time limit (2,000,000 solver steps).
  if (std::all_of(speed.begin(), speed.end(), [](double v) { return v == 0.0; }))
    throw InputError("ReferenceTrajectory: every speed is 0: the trajectory never moves");
}

double tracking_steering_limit(const TrackingOptions& options, const Vehicle& vehicle) {
  if (options.max_steering > 0.0) return options.max_steering;
  return std::isfinite(vehicle.max_steering) ? vehicle.max_steering : kDefaultTrackingSteering;
}

void TrackingOptions::validate() const {
  const double inf = std::numeric_limits<double>::infinity();
  require(speed_scale > 0.0 && speed_scale < inf, "speed_scale", speed_scale, "positive");
  require(lookahead_time >= 0.0 && lookahead_time < inf, "lookahead_time", lookahead_time, ">= 0");
  require(min_lookahead >= 0.0 && min_lookahead < inf, "min_lookahead", min_lookahead, ">= 0");
  require(max_steering >= 0.0 && max_steering < std::numbers::pi / 2, "max_steering", max_steering,
          "in [0, pi/2)");
  require(slip_filter_time > 0.0 && slip_filter_time < inf, "slip_filter_time", slip_filter_time,
          "positive");
  require(yaw_rate_gain >= 0.0 && yaw_rate_gain < inf, "yaw_rate_gain", yaw_rate_gain, ">= 0");
  require(speed_kp >= 0.0 && speed_kp < inf, "speed_kp", speed_kp, ">= 0");
  require(speed_ki >= 0.0 && speed_ki < inf, "speed_ki", speed_ki, ">= 0");
  require(integral_limit >= 0.0 && integral_limit < inf, "integral_limit", integral_limit, ">= 0");
  require(min_speed > 0.0 && min_speed < inf, "min_speed", min_speed, "positive");
  require(speed_preview_time >= 0.0 && speed_preview_time < inf, "speed_preview_time",
          speed_preview_time, ">= 0");
  require(goal_tolerance >= 0.0 && goal_tolerance < inf, "goal_tolerance", goal_tolerance, ">= 0");
  require(time_factor >= 1.0 && time_factor < inf, "time_factor", time_factor, ">= 1");
  require(time_margin >= 0.0 && time_margin < inf, "time_margin", time_margin, ">= 0");
  simulation.validate();
}

std::string_view to_string(SteeringLaw law) {
  return law == SteeringLaw::kCurvature ? "curvature" : "pure_pursuit";
}

SteeringLaw parse_steering_law(std::string_view name) {
  if (name == "curvature") return SteeringLaw::kCurvature;
  if (name == "pure_pursuit") return SteeringLaw::kPurePursuit;
  throw InputError("unknown steering law '" + std::string(name) +
                   "' (choices: curvature, pure_pursuit)");
}

std::string_view to_string(TrackingStatus status) {
  switch (status) {
    case TrackingStatus::kReachedGoal:
      return "reached_goal";
    case TrackingStatus::kTimeout:
      return "timeout";
    case TrackingStatus::kRollover:
      return "rollover";
    case TrackingStatus::kSideSlip:
      return "side_slip";
    case TrackingStatus::kLossOfContact:
      return "loss_of_contact";
    case TrackingStatus::kStall:
      return "stall";
    case TrackingStatus::kLeftTerrain:
      return "left_terrain";
    case TrackingStatus::kSolverFailure:
      return "solver_failure";
  }
  return "unknown";
}

std::string TrackingResult::brief_report() const {
  char line[512];
  std::snprintf(line, sizeof line,
                "tracking: %s, %.1f %% of %.4g m in %.4g s (planned %.4g s); cross-track max "
                "%.3g m, rms %.3g m; speed above desired by up to %.3g m/s%s%s\n",
                std::string(to_string(status)).c_str(), 100.0 * progress, path_length, travel_time,
                planned_time, max_cross_track, rms_cross_track, max_speed_excess,
                message.empty() ? "" : "; ", message.c_str());
  return line + simulation.brief_report();
}

namespace {

/// The tracker's controller (the file comment): steering by the chosen law,
/// speed PI at a preview station with the weight's feed-forward. Called in
/// time order by the simulation; copies share one state.
class Tracker {
 public:
  Tracker(const BPatch& surface, const Vehicle& vehicle, const Polyline& path,
          const TrackingOptions& options)
      : surface_(surface),
        vehicle_(vehicle),
        path_(path),
        options_(options),
        wheelbase_(2.0 * vehicle.half_wheelbase),
        min_lookahead_(options.min_lookahead > 0.0 ? options.min_lookahead : 2.0 * wheelbase_),
        goal_tolerance_(options.goal_tolerance > 0.0 ? options.goal_tolerance : wheelbase_),
        max_steering_(tracking_steering_limit(options, vehicle)),
        state_(std::make_shared<State>()) {}

  double min_lookahead() const { return min_lookahead_; }
  /// The speed the tracker aims for at arc length s [m/s].
  double desired(double s) const {
    return std::max(options_.min_speed,
                    std::min(options_.speed_scale * path_.speed(s), vehicle_.max_speed));
  }

  VehicleControls operator()(double t, const VehicleState& state) const {
    const Mat3 rot = state.rotation();
    const Vec3 forward3 = rot.col(0);
    const Vec2 forward = Vec2(forward3.x(), forward3.y()).normalized();
    const Vec2 cg(state.position.x(), state.position.y());
    const double v = state.velocity.x();
    const double lookahead = std::max(min_lookahead_, options_.lookahead_time * std::abs(v));
    const auto [s, cross_track] =
        path_.project(cg, state_->s - 0.5, state_->s + 2.0 * lookahead + 1.0);
    state_->s = s;
    VehicleControls c;
    if (state_->s >= path_.length() - goal_tolerance_) {
      c.stop = true;
      return c;
    }
    const double steering = options_.steering_law == SteeringLaw::kCurvature
                                ? curvature_steering(t, state, forward, cross_track, lookahead)
                                : pure_pursuit_steering(cg, forward, lookahead);
    c.steering = std::clamp(steering, -max_steering_, max_steering_);
    c.drive_force = drive_force(t, cg, forward, v);
    return c;
  }

 private:
  struct State {
    double s = 0.0;
    double integral = 0.0;
    double last_t = 0.0;
    double slip = 0.0, slip_t = 0.0;
  };

  /// Pure pursuit from the rear axle.
  double pure_pursuit_steering(const Vec2& cg, const Vec2& forward, double lookahead) const {
    const Vec2 rear = cg - vehicle_.half_wheelbase * forward;
    const Vec2 to_target = path_.point(state_->s + lookahead) - rear;
    const double alpha = std::atan2(forward.x() * to_target.y() - forward.y() * to_target.x(),
                                    forward.dot(to_target));
    const double distance = std::max(to_target.norm(), 1e-6);
    return std::atan(2.0 * wheelbase_ * std::sin(alpha) / distance);
  }

  /// The path's curvature fed forward, cross-track and course feedback, then
  /// yaw-rate feedback (file comment).
  double curvature_steering(double t, const VehicleState& state, const Vec2& forward,
                            double cross_track, double lookahead) const {
    const Mat3 rot = state.rotation();
    const Vec3 velocity = rot * state.velocity;
    const Vec2 planar(velocity.x(), velocity.y());
    const double speed = planar.norm();
    // The side-slip angle β (chassis heading to velocity), low-pass filtered:
    // heading + filtered β is the course without the lateral dynamics' fast
    // part, which destabilised a loop closed on the raw course.
    const double slip =
        speed > kCourseSpeedFloor
            ? std::atan2(forward.x() * planar.y() - forward.y() * planar.x(), forward.dot(planar))
            : 0.0;
    const double dt = std::max(0.0, t - state_->slip_t);
    state_->slip_t = t;
    state_->slip += (1.0 - std::exp(-dt / options_.slip_filter_time)) * (slip - state_->slip);
    const Vec2 tangent = path_.tangent(state_->s);
    const double course_error =
        std::atan2(tangent.x() * forward.y() - tangent.y() * forward.x(), tangent.dot(forward)) +
        state_->slip;
    const double wanted = path_.curvature(state_->s, vehicle_.half_wheelbase) -
                          cross_track / (lookahead * lookahead) -
                          2.0 * std::sin(course_error) / lookahead;
    double kappa = wanted;
    if (speed > kCourseSpeedFloor) {
      const double yaw_rate = (rot * state.angular_velocity).z();
      kappa += options_.yaw_rate_gain * (wanted - yaw_rate / speed);
    }
    const double half = 0.5 * wheelbase_ * kappa;
    return std::atan(wheelbase_ * kappa / std::sqrt(std::max(1.0 - half * half, 0.25)));
  }

  /// Speed PI at the preview station, with the weight's feed-forward. The
  /// preview station where the plan is slower (braking ahead), else the
  /// projection: an acceleration is not anticipated, which would put the
  /// vehicle above the plan's speed at the station it is on.
  double drive_force(double t, const Vec2& cg, const Vec2& forward, double v) const {
    const double ahead = state_->s + options_.speed_preview_time * std::max(0.0, v);
    const double preview = desired(ahead) < desired(state_->s) ? ahead : state_->s;
    const double error = desired(preview) - v;
    const double dt = std::max(0.0, t - state_->last_t);
    state_->last_t = t;
    state_->integral = std::clamp(state_->integral + options_.speed_ki * error * dt,
                                  -options_.integral_limit, options_.integral_limit);
    // The planned acceleration v dv/ds at the desired speed (zero on the floor).
    const double planned = options_.speed_scale * path_.speed(preview);
    const double feed_forward = planned > options_.min_speed && planned < vehicle_.max_speed
                                    ? planned * options_.speed_scale * path_.speed_slope(preview)
                                    : 0.0;
    return vehicle_.body->mass *
           (vehicle_.gravity * terrain_grade(surface_, cg, forward, vehicle_.half_wheelbase) +
            feed_forward + options_.speed_kp * error + state_->integral);
  }

  const BPatch& surface_;
  const Vehicle& vehicle_;
  const Polyline& path_;
  const TrackingOptions& options_;
  double wheelbase_, min_lookahead_, goal_tolerance_, max_steering_;
  std::shared_ptr<State> state_;
};

/// Tracking quantities along the trace (an independent forward projection).
/// The window ahead covers the controller's own, plus how far the vehicle
/// can have driven since the last sample (twice the faster of the two
/// samples' speeds over the interval): with a trace much coarser than the
/// control period a fixed window lagged behind the vehicle, and the
/// projection then reported cross-track errors of hundreds of metres and a
/// progress short of 1 for a run that reached the goal.
void measure_tracking(const Polyline& path, const Tracker& tracker, const TrackingOptions& options,
                      TrackingResult& result) {
  const VehicleSimulationResult& r = result.simulation;
  double s = 0.0, sum2 = 0.0, last_t = 0.0, last_speed = 0.0;
  result.tracking.reserve(r.trace.size());
  for (const VehicleSample& k : r.trace) {
    const Vec2 cg(k.state.position.x(), k.state.position.y());
    const double driven = 2.0 * std::max(k.speed, last_speed) * (k.t - last_t);
    const double window =
        2.0 * std::max(tracker.min_lookahead(), options.lookahead_time * k.speed) + 1.0 + driven;
    last_t = k.t;
    last_speed = k.speed;
    const auto [sk, dk] = path.project(cg, s - 0.5, s + window);
    s = sk;
    TrackingSample t;
    t.s = sk;
    t.cross_track = dk;
    t.desired_speed = tracker.desired(sk);
    result.tracking.push_back(t);
    result.max_cross_track = std::max(result.max_cross_track, std::abs(dk));
    sum2 += dk * dk;
    result.max_speed_excess = std::max(result.max_speed_excess, k.speed - t.desired_speed);
  }
  if (!r.trace.empty())
    result.rms_cross_track = std::sqrt(sum2 / static_cast<double>(r.trace.size()));
  result.progress = std::clamp(s / path.length(), 0.0, 1.0);
}

}  // namespace

TrackingResult track_trajectory(const BPatch& surface, const Vehicle& vehicle,
                                const ReferenceTrajectory& reference,
                                const TrackingOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  reference.validate();
  options.validate();
  vehicle.validate();
  if (!vehicle.body)
    throw InputError(
        "track_trajectory: the vehicle has no body (a vehicle file needs 'mass', see "
        "data/vehicles/README.md)");
  if (!surface.contains(reference.points.front()))
    throw InputError("track_trajectory: the trajectory's first point is off the terrain");

  const Polyline path(reference);
  TrackingResult result;
  result.path_length = path.length();
  for (std::size_t i = 1; i < reference.points.size(); ++i) {
    const double ds = (reference.points[i] - reference.points[i - 1]).norm();
    const double v0 = std::max(options.min_speed, options.speed_scale * reference.speed[i - 1]);
    const double v1 = std::max(options.min_speed, options.speed_scale * reference.speed[i]);
    result.planned_time += 2.0 * ds / (v0 + v1);
  }
  const Tracker tracker(surface, vehicle, path, options);
  VehicleSimulationOptions sim = options.simulation;
  sim.end_time = options.time_factor * result.planned_time + options.time_margin;
  const Vec2 heading = reference.points[1] - reference.points[0];
  const VehicleState start = resting_state(
      surface, vehicle, reference.points.front(), std::atan2(heading.y(), heading.x()),
      std::min(options.speed_scale * reference.speed.front(), vehicle.max_speed));
  result.simulation = simulate_vehicle(surface, vehicle, start, tracker, sim);
  const VehicleSimulationResult& r = result.simulation;
  result.status = from_simulation(r.status);
  result.message = r.status == SimulationStatus::kStopped ? "" : r.message;
  if (result.status == TrackingStatus::kTimeout)
    result.message =
        "the time limit of " + std::to_string(sim.end_time) + " s came before the goal";
  measure_tracking(path, tracker, options, result);
  result.travel_time = r.end_time;
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace talus
