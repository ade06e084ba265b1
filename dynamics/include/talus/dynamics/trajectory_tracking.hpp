#pragma once
/// @file
/// track_trajectory: drive a planned trajectory (a planar path with a speed
/// at each point, e.g. the trajectory.csv of `talus plan`) with the simulated
/// vehicle (vehicle_simulation.hpp) and report the margins it kept.
///
/// The driver, called every control period, has two loops:
/// - steering (TrackingOptions::steering_law), with L_d = max(min_lookahead,
///   lookahead_time · v) and L the wheelbase, clipped to ±max_steering:
///   - curvature (the default): the path's own curvature fed forward, with
///     feedback on the c.g.'s cross-track error e_y and course error e_χ (the
///     chassis heading plus the side-slip angle low-pass filtered over
///     slip_filter_time, against the path's tangent, both horizontal; with
///     the heading alone the vehicle holds its slip angle as an error and
///     drives wide of a curve, 7 % faster than the plan on the circles):
///     κ_cmd = κ_ref − e_y / L_d² − 2 sin e_χ / L_d, which makes the linearised
///     errors critically damped over L_d of travel; then yaw-rate feedback
///     against understeer, κ_c = κ_cmd + yaw_rate_gain (κ_cmd − r / v) (r the
///     yaw rate), and δ = atan(L κ_c / √(1 − (L κ_c / 2)²)), the bicycle's
///     steering for c.g. curvature κ_c with the c.g. midway between the
///     axles. κ_ref is the reference polyline's turning angle over
///     ±half_wheelbase (at least two segments) divided by its length. A
///     pure-pursuit chord cuts inside a curve; this law does not, so the
///     vehicle's path has the plan's curvature and the plan's lateral
///     acceleration.
///   - pure_pursuit (Coulter 1992): the look-ahead point lies on the
///     reference path L_d ahead of the vehicle's projection on the path; with
///     α the angle from the chassis heading to the line rear axle →
///     look-ahead point (both on the horizontal plane), δ = atan(2 L sin α /
///     L_d).
/// - speed: PI on the error e = v_des − v_x, v_des = speed_scale · v_ref(s_p)
///   at the preview station s_p = s + speed_preview_time · v_x where the plan
///   is slower there (a braking zone ahead: the force, which acts with the
///   loop's lag, is then on time), else s_p = s (an acceleration ahead is not
///   anticipated: it would take the vehicle above the plan at its station);
///   at least min_speed until the goal and at most the vehicle's top speed (Vehicle::max_speed:
///   a profile scaled above it is not asked of the drive, which has no top speed of its own in
///   the simulation); plus feed-forward of the weight's component along the
///   heading (g sin θ_up, θ_up the terrain's grade along the chassis heading over the wheelbase:
///   the chord from the rear to the front axle's ground point, not the chassis pitch, which rides
///   the suspension's oscillation on wheel-scale ground) and of the planned acceleration a_p = v_p
///   dv_p/ds at s_p (v_p = speed_scale · v_ref, 0 while v_p is below the floor or above the top
///   speed): F = m (g sin θ_up
///   + a_p + kp e + ki ∫e), the integral clamped to ±integral_limit (anti-windup). The simulation
///   clips F to the vehicle's drive and brake limits.
/// The projection s is the arc length along the reference polyline in the
/// plane, searched forward from the last one (a window of 2 L_d + 1 m), so
/// that a path that crosses itself is followed in order. The run ends when
/// s reaches the end minus goal_tolerance (kReachedGoal), at the time limit
/// (kTimeout) or at a failure of the simulation.
#include <string>
#include <string_view>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/vehicle_simulation.hpp"

namespace talus {

/// The steering limit of a vehicle file without max_steering [rad]: a typical
/// car-like front axle.
inline constexpr double kDefaultTrackingSteering = 0.6;

/// A planned trajectory: planar points and the planned speed at each.
struct ReferenceTrajectory {
  std::vector<Vec2> points;   ///< (x, y) [m], at least 2, consecutive points distinct
  std::vector<double> speed;  ///< planned speed at each point [m/s] (finite, >= 0)
  /// Throws InputError naming what is wrong.
  void validate() const;
};

/// The tracker's steering law (see the file comment).
enum class SteeringLaw { kCurvature, kPurePursuit };
/// "curvature", "pure_pursuit".
std::string_view to_string(SteeringLaw law);
/// Inverse of to_string; throws InputError listing the choices.
SteeringLaw parse_steering_law(std::string_view name);

struct TrackingOptions {
  double speed_scale = 1.0;  ///< multiplies the planned speed (> 0): 0.9, 1.0, 1.1, ...
  SteeringLaw steering_law = SteeringLaw::kCurvature;
  double lookahead_time = 0.4;  ///< L_d per unit speed [s] (>= 0)
  double min_lookahead = 0.0;   ///< [m] (>= 0); 0 = 4 half_wheelbase (two wheelbases)
  /// The curvature law's yaw-rate feedback [-] (>= 0); 0 = none.
  double yaw_rate_gain = 1.0;
  /// The curvature law's side-slip filter time constant [s] (> 0). 0.5: at
  /// 0.2 the banked circle side-slipped at 100 %, and on the raw course
  /// (no filter) the flat circle slid at 95 %.
  double slip_filter_time = 0.5;
  /// [rad] [0, π/2); 0 (the default) = the vehicle's max_steering, or
  /// kDefaultTrackingSteering for a vehicle without one.
  double max_steering = 0.0;
  double speed_kp = 4.0;        ///< [1/s] (>= 0)
  double speed_ki = 1.0;        ///< [1/s²] (>= 0)
  double integral_limit = 2.0;  ///< bound on ki ∫e [m/s²] (>= 0)
  double min_speed = 0.3;       ///< v_des floor before the goal [m/s] (> 0)
  /// The speed loop's preview [s] (>= 0): where the plan slows within
  /// speed_preview_time · v ahead, v_des and a_p are the plan's there.
  /// 0 (the default) = none, the speed at the projection itself: with a 0.3 s
  /// preview a plan that brakes and accelerates all along (a plan at its
  /// limit) was driven up to 20 % slower than planned, since every braking
  /// zone starts early by the preview.
  double speed_preview_time = 0.0;
  double goal_tolerance = 0.0;  ///< [m] (>= 0); 0 = 2 half_wheelbase
  /// Time limit: time_factor × the planned travel time (at speed_scale, with
  /// the min_speed floor) + time_margin [s]. time_factor >= 1, time_margin >= 0.
  double time_factor = 2.0;
  double time_margin = 5.0;
  /// Integration, events and trace; its end_time is replaced by the time limit.
  VehicleSimulationOptions simulation;
  /// Throws InputError naming the field.
  void validate() const;
};

enum class TrackingStatus {
  kReachedGoal,  ///< the projection reached the end of the path
  kTimeout,      ///< the time limit came first
  kRollover,     ///< the simulation's failures, as SimulationStatus
  kSideSlip,
  kLossOfContact,
  kStall,
  kLeftTerrain,
  kSolverFailure,
};
/// "reached_goal", "timeout", then as SimulationStatus.
std::string_view to_string(TrackingStatus status);

/// One trace sample's tracking quantities (parallel to simulation.trace).
struct TrackingSample {
  double s = 0.0;              ///< projection on the reference path [m]
  double cross_track = 0.0;    ///< signed distance to it, > 0 left of the path [m]
  double desired_speed = 0.0;  ///< v_des at that instant [m/s]
};

struct TrackingResult {
  TrackingStatus status = TrackingStatus::kTimeout;
  std::string message;
  VehicleSimulationResult simulation;    ///< trace, margins, CVODE counters
  std::vector<TrackingSample> tracking;  ///< one per simulation.trace sample
  double path_length = 0.0;              ///< of the reference polyline [m]
  double progress = 0.0;                 ///< s reached / path_length [-]
  double travel_time = 0.0;              ///< simulated time at the end [s]
  double planned_time = 0.0;             ///< Σ ds / v_ref on the polyline at speed_scale [s]
  double max_cross_track = 0.0;          ///< [m]
  double rms_cross_track = 0.0;          ///< over the trace [m]
  double max_speed_excess = 0.0;         ///< max (v − v_des) over the trace [m/s]
  double seconds = 0.0;                  ///< wall time [s]
  /// A few lines: status, progress, times, tracking errors, the simulation's report.
  std::string brief_report() const;
};

/// Drives `reference` on `surface` with `vehicle` (which needs a body),
/// starting at rest-compression at the first point, heading along the first
/// segment, at the first point's planned speed × speed_scale. InputError for
/// invalid input (reference, options, a vehicle without body, a start off
/// the domain); the run's failures are statuses.
/// The tracker's steering limit: options.max_steering when > 0, else the
/// vehicle's max_steering when it has one, else kDefaultTrackingSteering [rad].
double tracking_steering_limit(const TrackingOptions& options, const Vehicle& vehicle);

TrackingResult track_trajectory(const BPatch& surface, const Vehicle& vehicle,
                                const ReferenceTrajectory& reference,
                                const TrackingOptions& options = {});

}  // namespace talus
