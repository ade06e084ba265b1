#pragma once
/// @file
/// simulate_vehicle: a 6-DOF rigid chassis on four spring–damper wheels
/// driving over a B-patch terrain, integrated with SUNDIALS CVODE.
///
/// Model (SI units; world frame x east, y north, z up; body frame x forward,
/// y left, z up, origin at the centre of mass):
/// - State (12): c.g. position p (world), Z-Y-X Euler angles yaw ψ, pitch θ,
///   roll φ (R = Rz(ψ) Ry(θ) Rx(φ) maps body to world), body-frame velocity v
///   and angular velocity ω. Newton–Euler: m (v̇ + ω × v) = F, I ω̇ + ω × Iω = M,
///   I = diag(inertia_roll, inertia_pitch, inertia_yaw).
/// - Wheels: massless, at body points c_i = (±l, ±b, r − δ_s − h) (l
///   half_wheelbase, b half_track, h cg_height, r wheel_radius, δ_s = m g /(4k)
///   the static deflection), so that at rest on level ground the c.g. is h
///   above it. The suspension (spring k, damper c, lumping tyre radial
///   compliance) acts along the terrain normal n at the wheel: with d the
///   distance of c_i from the terrain's tangent plane below it (d = Δz n_z,
///   Δz its height above z(x, y)), the compression is e = r − d and the normal
///   load N = max(0, k e + c ė) while e > 0 (ė = −n·v_c, exact on a plane);
///   a wheel with e <= 0 is off the ground. On a plane without damping and
///   friction this is a conservative force, so energy is conserved.
/// - Tyres: the wheel's heading (body x, the front pair turned by the steering
///   angle δ; no Ackermann geometry) projected on the tangent plane gives the
///   tyre frame (t_x, t_y = n × t_x). The contact point's velocity there gives
///   the slip angle α with tan α = v_y / sqrt(v_x² + v_ε²) (v_ε = the low-speed
///   regularisation, Options::tyre_min_speed). Wheels are force-controlled
///   (ideal traction and brake control): the drive force command F_d is shared
///   between the wheels in proportion to their normal loads, F_x = F_d N_i / ΣN
///   (a brake command also times v_x / sqrt(v_x² + v_ε²), so that it stops the
///   vehicle and does not reverse it), clipped to μ N. The lateral force is
///   the brush model's (Pacejka, Tire and Vehicle Dynamics, ch. 3, pure side
///   slip): F_y = −C_α tan α (1 − x + x²/3), x = C_α |tan α| / (3 F_max),
///   C_α = cornering_stiffness · N, up to full sliding at tan α_sl =
///   3 F_max / C_α and −F_max sign(α) beyond, where F_max = sqrt((μN)² − F_x²)
///   is what the friction circle leaves beside F_x. So |(F_x, F_y)| <= μ N
///   always, and the tyre reaches the friction circle, the planner's
///   envelope f_t² + f_q² <= μ² R², at a finite slip (14.7° for the UGV's
///   μ 0.7 and C_α/N 8 in pure side slip), where Dugoff's model only tends to
///   it (0.88 μN at 10°; TyreModel::kDugoff, for studies: F_y = −C_α tan α
///   f(λ), λ = F_max / (2 C_α |tan α|), f = 1 for λ >= 1 and λ (2 − λ)
///   below). The contact force N n + F_x t_x + F_y t_y
///   acts at the contact point c_i − d n.
/// - Inputs: VehicleControls (steering angle, drive/brake force), from a
///   controller called at every control tick and held in between (zero-order
///   hold, as a digital controller). Where they change, the right-hand side
///   jumps, and CVODE is restarted there (CVodeReInit).
/// - Integration: CVODE BDF with Newton iterations on a dense difference-
///   quotient Jacobian. BDF because the system is stiff: the regularised tyre
///   forces at low speed act as dampers with time constants m v_ε / (C_α m g)
///   of a fraction of a millisecond, the suspension's are a few milliseconds,
///   while the motion of interest takes seconds; an explicit method would be
///   held to the fastest of them by stability, not accuracy.
/// - Failures (the defaults are physical events; the strict ones of earlier
///   versions stay available as options for studies). Each onset is a CVODE
///   root-finding event, located to the integrator's precision; an event
///   that must last (airborne, side slip) ends the run at the first step
///   after it has lasted its time (steps are at most one control period):
///   - rollover: the chassis's roll (pitch) relative to the terrain normal
///     under the c.g. beyond Options::roll_limit (pitch_limit), by default
///     the vehicle's own static tip angle atan(b/h) (atan(l/h)): turned that
///     far about its contact line, the c.g. is over that line on level ground
///     and past it on any slope it tips down, so no restoring moment is left.
///     Two wheels of one side off the ground is the onset (wheel lift), not
///     rollover, unless Options::side_lift_is_rollover (the strict event);
///   - loss of contact (airborne): all four wheels off the ground for longer
///     than Options::airborne_time (0.2 s), or every wheel more than
///     Options::airborne_clearance clear of it (half the wheel radius by
///     default); a hop over a crest that lands within the time is not an
///     event (airborne_time 0 is the strict event: the first instant);
///   - side slip (loss of control): body |v_y| > tan(side_slip_limit)
///     sqrt(v_x² + side_slip_min_speed²) for longer than
///     Options::side_slip_time (0.5 s: a skid that the vehicle recovers from
///     sooner is not a failure; 0 = the strict event);
///   - stall: forward speed below stall_speed while driving forward, after
///     it had been above twice that, and not in side slip beyond
///     side_slip_limit (a vehicle that loses its forward speed while sliding
///     sideways has spun out: that is side slip, judged by its own time);
///   - a wheel leaving the terrain's domain.
///   A wheel is "off the ground" when e < 0: the wheel (massless, hanging at
///   the spring's free length: the model has no droop travel beyond it) is
///   clear of the ground, so its tyre has left it. A wheel whose load is
///   momentarily zero while its damper extends (e > 0) is wheel hop, not off
///   the ground; it shows in the minimum normal load. Every run reports its
///   margins (VehicleSimulationDiagnostics). A CVODE error is a status,
///   never a crash.
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus {

/// The integrated state of the chassis.
struct VehicleState {
  Vec3 position = Vec3::Zero();  ///< centre of mass, world [m]
  double roll = 0.0;             ///< φ [rad] (Z-Y-X Euler angles)
  double pitch = 0.0;            ///< θ [rad]; > 0 nose down (right-handed about body y, left)
  double yaw = 0.0;              ///< ψ [rad], CCW from east
  Vec3 velocity = Vec3::Zero();  ///< c.g. velocity in the body frame [m/s]
  Vec3 angular_velocity = Vec3::Zero();  ///< body frame [rad/s]
  /// Body-to-world rotation R = Rz(ψ) Ry(θ) Rx(φ).
  Mat3 rotation() const;
};

/// A vehicle standing on `surface` at `xy` (body z along the terrain normal n
/// there, heading `yaw` projected on the tangent plane, each wheel compressed
/// by its static share of the weight's normal component, δ_s n_z, so the c.g.
/// is h + δ_s (1 − n_z) above the ground along n) moving forward at
/// `speed` [m/s]. InputError if `xy` is off the domain.
VehicleState resting_state(const BPatch& surface, const Vehicle& vehicle, const Vec2& xy,
                           double yaw, double speed = 0.0);

/// The driver's inputs, held for one control period.
struct VehicleControls {
  double steering = 0.0;     ///< front-wheel steering angle δ [rad], > 0 turns left
  double drive_force = 0.0;  ///< total drive (> 0) or brake (< 0) force [N]
  bool stop = false;         ///< true ends the run (status kStopped), e.g. at a goal
};

/// The controller: called at t = 0 and every control period with the state.
using VehicleController = std::function<VehicleControls(double t, const VehicleState& state)>;

/// Wheel order in every per-wheel array.
enum WheelIndex : std::size_t { kFrontLeft = 0, kFrontRight = 1, kRearLeft = 2, kRearRight = 3 };

/// One wheel's contact at one instant.
struct WheelContact {
  double normal_load = 0.0;           ///< N [N]
  double compression = 0.0;           ///< e = r − d [m]; <= 0 off the ground
  double slip_angle = 0.0;            ///< α [rad]
  double longitudinal_force = 0.0;    ///< F_x [N]
  double lateral_force = 0.0;         ///< F_y [N]
  Vec3 contact_point = Vec3::Zero();  ///< c_i − d n, world [m]
  Vec3 normal = Vec3::UnitZ();        ///< terrain normal there
};

/// A recorded instant.
struct VehicleSample {
  double t = 0.0;  ///< [s]
  VehicleState state;
  VehicleControls controls;
  std::array<WheelContact, 4> wheels;
  /// (N_right − N_left) / ΣN; ±1 when one side carries everything; 0 airborne.
  double lateral_load_ratio = 0.0;
  double side_slip = 0.0;  ///< body side-slip angle atan2(v_y, |v_x|) [rad]
  double speed = 0.0;      ///< |velocity| [m/s]
  /// Kinetic + gravitational (m g z) + spring energy [J].
  double energy = 0.0;
  /// |Σ tyre force on the tangent planes| / (μ ΣN) [-]: how much of its friction envelope
  /// the vehicle uses, the point-mass planner's |(f_t, f_q)| / (μ R); at most 1 (every
  /// tyre keeps |(F_x, F_y)| <= μ N), 0 with no wheel loaded.
  double friction_utilisation = 0.0;
  double normal_load_ratio = 0.0;  ///< ΣN / (m g) [-]: 1 at rest on level ground, 0 airborne
};

/// Samples carrying less than this fraction of the weight (ΣN < 0.05 m g: the vehicle all
/// but airborne) do not count towards the peak friction utilisations, where any tyre force
/// is a large fraction of a vanishing envelope; the airborne and minimum-load diagnostics
/// report those instants.
inline constexpr double kUtilisationLoadFloor = 0.05;

/// The tyres' lateral force model (both keep |(F_x, F_y)| <= μ N).
enum class TyreModel {
  kBrush,   ///< brush model: the friction circle at a finite slip (the default)
  kDugoff,  ///< Dugoff, Fancher, Segel 1970: tends to it as the slip grows (earlier versions)
};

struct VehicleSimulationOptions {
  double end_time = 10.0;        ///< simulated time [s] (> 0, finite)
  double control_period = 0.01;  ///< controller call interval [s] (> 0)
  /// Trace interval [s] (>= 0): a sample at every multiple of it (CVODE's
  /// interpolant, so the steps are not shortened), plus the first and the
  /// last. 0 = only the first and the last.
  double output_interval = 0.01;
  double relative_tolerance = 1e-6;  ///< CVODE reltol (> 0)
  double absolute_tolerance = 1e-8;  ///< CVODE abstol, every component (> 0)
  /// Most internal CVODE steps in the whole run (>= 1); more is status kSolverFailure.
  long max_steps = 2'000'000;
  double max_step = 0.0;               ///< CVODE hmax [s] (>= 0; 0 = none)
  double tyre_min_speed = 0.1;         ///< v_ε of the slip regularisation [m/s] (> 0)
  TyreModel tyre = TyreModel::kBrush;  ///< the lateral force model (see the file's comment)
  /// Rollover when |roll| relative to the terrain exceeds this [rad], [0, π/2);
  /// 0 (the default) = the vehicle's static tip angle atan(half_track / cg_height).
  double roll_limit = 0.0;
  /// The same for |pitch| [rad], [0, π/2); 0 = atan(half_wheelbase / cg_height).
  double pitch_limit = 0.0;
  /// Rollover also when both wheels of one side leave the ground (the strict
  /// event of earlier versions: wheel lift is the onset of rollover, not rollover).
  bool side_lift_is_rollover = false;
  /// Loss of contact when all four wheels have been off the ground this long [s] (>= 0;
  /// 0 = at the first instant, the strict event).
  double airborne_time = 0.2;
  /// ... or at once when every wheel is more than this clear of the ground [m] (>= 0;
  /// 0 = half the wheel radius).
  double airborne_clearance = 0.0;
  double side_slip_limit = 0.5;      ///< [rad] (0, π/2)
  double side_slip_min_speed = 0.5;  ///< below about this speed side slip is not judged [m/s] (> 0)
  /// Side slip is a failure when beyond side_slip_limit for this long [s] (>= 0; 0 = the
  /// strict event, at the first instant).
  double side_slip_time = 0.5;
  double stall_speed = 0.05;  ///< [m/s] (> 0)
  /// Called at every control tick with the simulated time reached [s] (for a
  /// progress display; empty = none). It must not throw.
  std::function<void(double t)> progress;
  /// Throws InputError naming the field.
  void validate() const;
};

enum class SimulationStatus {
  kReachedEndTime,  ///< ran to end_time without a failure
  kStopped,         ///< the controller asked to stop (VehicleControls::stop)
  kRollover,        ///< roll/pitch beyond the tip angle (or side lift, if strict)
  kSideSlip,        ///< body side slip beyond side_slip_limit for side_slip_time
  kLossOfContact,   ///< airborne: all four wheels off the ground for airborne_time
  kStall,           ///< forward speed fell below stall_speed while driving forward, not sliding
  kLeftTerrain,     ///< a wheel left the terrain's domain
  kSolverFailure,   ///< CVODE failed (message has its flag and text) or max_steps
};
/// "reached_end_time", "stopped", "rollover", "side_slip", "loss_of_contact",
/// "stall", "left_terrain", "solver_failure".
std::string_view to_string(SimulationStatus status);
/// True for the vehicle's failures (rollover, side slip, loss of contact, stall).
bool is_vehicle_failure(SimulationStatus status);

struct VehicleSimulationDiagnostics {
  long steps = 0;            ///< CVODE internal steps
  long rhs_evaluations = 0;  ///< right-hand sides (including the Jacobian's)
  long jacobian_evaluations = 0;
  long root_evaluations = 0;
  long error_test_failures = 0;
  long nonlinear_failures = 0;
  int cvode_flag = 0;  ///< the last CVODE return flag (0 = CV_SUCCESS)
  long restarts = 0;   ///< CVodeReInit calls at control ticks whose controls changed
  /// Peaks and minima over every internal step and trace sample.
  double peak_lateral_load_ratio = 0.0;  ///< max |LTR|
  double min_normal_load = 0.0;          ///< min over wheels and time [N]
  /// min_normal_load / (m g / 4) [-].
  double min_normal_load_ratio = 0.0;
  double peak_slip_angle = 0.0;  ///< max |α| over wheels on the ground [rad]
  double peak_side_slip = 0.0;   ///< max |side slip| above side_slip_min_speed [rad]
  double peak_speed = 0.0;       ///< [m/s]
  double peak_roll = 0.0;        ///< max |roll relative to the terrain| [rad]
  double peak_pitch = 0.0;       ///< max |pitch relative to the terrain| [rad]
  double roll_limit = 0.0;       ///< the roll limit in force (the tip angle by default) [rad]
  double pitch_limit = 0.0;      ///< the pitch limit in force [rad]
  /// Longest spell with all four wheels off the ground [s] (up to the samples' resolution).
  double longest_airborne = 0.0;
  /// Longest spell with the side slip beyond side_slip_limit [s].
  double longest_side_slip = 0.0;
  /// Time with both wheels of one side off the ground (wheel lift, the onset of rollover) [s].
  double side_lift_time = 0.0;
  /// max VehicleSample::friction_utilisation over samples with ΣN >= kUtilisationLoadFloor m g.
  double peak_friction_utilisation = 0.0;
  /// max over those samples and loaded wheels of |(F_x, F_y)| / (μ N) [-].
  double peak_wheel_friction_utilisation = 0.0;
  /// min ΣN / (m g) [-] (0: airborne at some instant).
  double min_total_normal_load_ratio = 0.0;
  std::size_t controller_calls = 0;
};

struct VehicleSimulationResult {
  SimulationStatus status = SimulationStatus::kReachedEndTime;
  std::string message;               ///< what happened, where and when; empty for kReachedEndTime
  double end_time = 0.0;             ///< simulated time reached [s] (the event's time on a failure)
  VehicleSample final;               ///< the state at end_time
  std::vector<VehicleSample> trace;  ///< every output_interval, the first and the last
  VehicleSimulationDiagnostics diagnostics;
  double seconds = 0.0;  ///< wall time [s]
  /// Simulated per wall second (end_time / seconds).
  double real_time_factor() const;
  /// Three lines: status, time and peaks; the failure events' margins; CVODE
  /// counters and the wall time.
  std::string brief_report() const;
};

/// Simulates `vehicle` (which needs a body: InputError otherwise) from
/// `initial` on `surface` under `controller`. The drive force is clipped to
/// [−m max_decel, m max_accel]. InputError for invalid options or vehicle,
/// or an initial c.g. off the domain; every failure during the run is a status.
VehicleSimulationResult simulate_vehicle(const BPatch& surface, const Vehicle& vehicle,
                                         const VehicleState& initial,
                                         const VehicleController& controller,
                                         const VehicleSimulationOptions& options = {});

}  // namespace talus
