#include "talus/dynamics/vehicle_simulation.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <type_traits>

#include "cvode_integrator.hpp"
#include "talus/core/error.hpp"
#include "talus/core/memory_budget.hpp"

namespace talus {
namespace {

constexpr int kStates = 12;
constexpr int kRoots = 9;
enum RootIndex {
  kRootRoll = 0,
  kRootPitch,
  kRootLeftLift,
  kRootRightLift,
  kRootAllLift,
  kRootSideSlip,
  kRootStall,
  kRootDomain,
  kRootClearance
};

Mat3 euler_rotation(double roll, double pitch, double yaw) {
  const double cf = std::cos(roll), sf = std::sin(roll);
  const double ct = std::cos(pitch), st = std::sin(pitch);
  const double cp = std::cos(yaw), sp = std::sin(yaw);
  Mat3 r;
  r << cp * ct, cp * st * sf - sp * cf, cp * st * cf + sp * sf,  //
      sp * ct, sp * st * sf + cp * cf, sp * st * cf - cp * sf,   //
      -st, ct * sf, ct * cf;
  return r;
}

/// The brush tyre's lateral force (Pacejka, Tire and Vehicle Dynamics, ch. 3:
/// parabolic pressure, pure side slip) for cornering stiffness `ca` = C_α [N/rad],
/// slip tan α and `f_max` the friction the longitudinal force leaves [N]:
/// F_y = −C_α tan α (1 − x + x²/3) with x = C_α |tan α| / (3 f_max) below full
/// sliding (x < 1), and −f_max sign(α) from there on. It reaches the friction
/// circle at the finite slip tan α_sl = 3 f_max / C_α (the planner's envelope,
/// reached), with a continuous slope there (C¹, which BDF steps through).
double brush_lateral_force(double ca, double tan_alpha, double f_max) {
  if (f_max <= 0.0) return 0.0;
  const double x = ca * std::abs(tan_alpha) / (3.0 * f_max);
  const double magnitude = x < 1.0 ? ca * std::abs(tan_alpha) * (1.0 - x + x * x / 3.0) : f_max;
  return -std::copysign(magnitude, tan_alpha);
}

/// Dugoff's lateral force (Dugoff, Fancher, Segel 1970, pure side slip), with
/// the same arguments: linear while 2 C_α |tan α| <= f_max, then
/// f_max (1 − λ/2), λ = f_max / (2 C_α |tan α|): it tends to f_max only as the
/// slip grows without bound.
double dugoff_lateral_force(double ca, double tan_alpha, double f_max) {
  const double linear = 2.0 * ca * std::abs(tan_alpha);
  if (linear <= f_max) return -ca * tan_alpha;
  const double lambda = f_max / linear;
  return -std::copysign(f_max * (1.0 - 0.5 * lambda), tan_alpha);
}

/// What one evaluation of the model gives besides the derivative.
struct Evaluation {
  std::array<WheelContact, 4> wheels;
  std::array<double, 4> contact_measure{};  ///< e: < 0 off the ground, suspension fully extended
  double total_load = 0.0;
  double lateral_load_ratio = 0.0;
  /// |Σ tyre force on the tangent planes| / (μ ΣN): the vehicle's use of its friction
  /// envelope, the point-mass planner's |(f_t, f_q)| / (μ R); 0 when nothing is loaded.
  double friction_utilisation = 0.0;
  double wheel_friction_utilisation = 0.0;  ///< max over loaded wheels of |(F_x, F_y)| / (μ N)
  double roll_sin = 0.0;                    ///< body y · terrain normal under the c.g.
  double pitch_sin = 0.0;                   ///< body x · the same
  double domain_margin = 0.0;               ///< smallest distance of a wheel inside the domain [m]
  double energy = 0.0;
};

/// The vehicle model: parameters, the terrain and the held controls.
class Model {
 public:
  Model(const BPatch& surface, const Vehicle& vehicle, const VehicleSimulationOptions& options)
      : surface_(surface), vehicle_(vehicle), body_(*vehicle.body), options_(options) {
    const double m = body_.mass, g = vehicle.gravity;
    static_deflection_ = m * g / (4.0 * body_.suspension_stiffness);
    const double z = body_.wheel_radius - static_deflection_ - vehicle.cg_height;
    const double l = vehicle.half_wheelbase, b = vehicle.half_track;
    corners_ = {Vec3(l, b, z), Vec3(l, -b, z), Vec3(-l, b, z), Vec3(-l, -b, z)};
    max_drive_ = m * vehicle.max_accel;
    max_brake_ = m * vehicle.max_decel;
    const double h = vehicle.cg_height;
    roll_limit_ = options.roll_limit > 0.0 ? options.roll_limit : std::atan2(b, h);
    pitch_limit_ = options.pitch_limit > 0.0 ? options.pitch_limit : std::atan2(l, h);
    clearance_ =
        options.airborne_clearance > 0.0 ? options.airborne_clearance : 0.5 * body_.wheel_radius;
  }

  double roll_limit() const { return roll_limit_; }
  double pitch_limit() const { return pitch_limit_; }
  double clearance() const { return clearance_; }

  void set_controls(const VehicleControls& c) {
    controls_ = c;
    controls_.drive_force = std::clamp(c.drive_force, -max_brake_, max_drive_);
    if (!std::isfinite(controls_.steering)) controls_.steering = 0.0;
    if (std::isnan(controls_.drive_force)) controls_.drive_force = 0.0;
  }
  const VehicleControls& controls() const { return controls_; }
  double static_deflection() const { return static_deflection_; }
  bool stall_armed = false;

  /// Evaluates the model at y; writes the derivative to ydot when not null.
  /// Returns false where the Euler angles are singular (pitch ±90°).
  bool evaluate(const double* y, double* ydot, Evaluation& out) const {
    const Pose pose(y);
    if (std::abs(pose.cos_pitch) < 1e-6) return false;
    WheelFrames frames;
    wheel_contacts(pose, out, frames);
    Vec3 force(0.0, 0.0, -body_.mass * vehicle_.gravity), moment = Vec3::Zero();
    tyre_forces(frames, out, force, moment);
    attitude_to_terrain(pose, out);
    if (ydot != nullptr) rigid_body_derivative(pose, force, moment, ydot);
    return true;
  }

  /// The root functions (RootIndex order); each decreases through 0 at its event.
  void roots(const double* y, const Evaluation& ev, double* g) const {
    g[kRootRoll] = std::sin(roll_limit_) - std::abs(ev.roll_sin);
    g[kRootPitch] = std::sin(pitch_limit_) - std::abs(ev.pitch_sin);
    const auto& cm = ev.contact_measure;
    g[kRootLeftLift] =
        options_.side_lift_is_rollover ? std::max(cm[kFrontLeft], cm[kRearLeft]) : 1.0;
    g[kRootRightLift] =
        options_.side_lift_is_rollover ? std::max(cm[kFrontRight], cm[kRearRight]) : 1.0;
    g[kRootAllLift] = std::max({cm[0], cm[1], cm[2], cm[3]});
    const double vx = y[6], vy = y[7];
    g[kRootSideSlip] =
        std::tan(options_.side_slip_limit) *
            std::sqrt(vx * vx + options_.side_slip_min_speed * options_.side_slip_min_speed) -
        std::abs(vy);
    g[kRootStall] = stall_armed && controls_.drive_force > 0.0 ? vx - options_.stall_speed : 1.0;
    g[kRootDomain] = ev.domain_margin;
    // Every wheel more than the clearance above the ground: e < -clearance for all.
    g[kRootClearance] = clearance_ + std::max({cm[0], cm[1], cm[2], cm[3]});
  }

  /// Set by the callbacks when they catch an exception.
  mutable std::string callback_error;

 private:
  /// The chassis state y unpacked: position, Euler angles, body-frame velocities.
  struct Pose {
    explicit Pose(const double* y)
        : p(y[0], y[1], y[2]),
          roll(y[3]),
          pitch(y[4]),
          yaw(y[5]),
          v(y[6], y[7], y[8]),
          w(y[9], y[10], y[11]),
          cos_pitch(std::cos(pitch)),
          rot(euler_rotation(roll, pitch, yaw)),
          v_world(rot * v),
          w_world(rot * w) {}
    Vec3 p;
    double roll, pitch, yaw;
    Vec3 v, w;
    double cos_pitch;
    Mat3 rot;
    Vec3 v_world, w_world;
  };

  /// Each wheel's ground normal, lever arm to its contact, tyre axes and contact velocity.
  struct WheelFrames {
    std::array<Vec3, 4> normal, arm, tx, ty;
    std::array<Vec2, 4> contact_velocity;
  };

  /// The suspension: each wheel's compression against the surface under it, its load
  /// (spring and damper, none off the ground), its tyre frame; the energy and the domain margin.
  void wheel_contacts(const Pose& pose, Evaluation& out, WheelFrames& f) const {
    const Vec3& p = pose.p;
    const Vec3 &v = pose.v, &w = pose.w;
    const double m = body_.mass, g = vehicle_.gravity;
    const double k = body_.suspension_stiffness, c = body_.suspension_damping;
    const double r = body_.wheel_radius;
    out.domain_margin = std::numeric_limits<double>::infinity();
    out.total_load = 0.0;
    out.energy = 0.5 * m * v.squaredNorm() +
                 0.5 * (body_.inertia_roll * w.x() * w.x() + body_.inertia_pitch * w.y() * w.y() +
                        body_.inertia_yaw * w.z() * w.z()) +
                 m * g * p.z();
    for (std::size_t i = 0; i < 4; ++i) {
      const Vec3 rc = pose.rot * corners_[i];
      const Vec3 centre = p + rc;
      const Vec2 xy(centre.x(), centre.y());
      out.domain_margin =
          std::min({out.domain_margin, xy.x() - surface_.x_min(), surface_.x_max() - xy.x(),
                    xy.y() - surface_.y_min(), surface_.y_max() - xy.y()});
      const Vec2 q(std::clamp(xy.x(), surface_.x_min(), surface_.x_max()),
                   std::clamp(xy.y(), surface_.y_min(), surface_.y_max()));
      const SurfacePoint sp = surface_.evaluate(q);
      const Vec3 n = Vec3(-sp.gradient.x(), -sp.gradient.y(), 1.0).normalized();
      // Height above the tangent plane at q (the plane's extension off the domain).
      const double dz = centre.z() - (sp.z + sp.gradient.dot(xy - q));
      const double d = dz * n.z();
      const double e = r - d;
      const Vec3 v_centre = pose.v_world + pose.w_world.cross(rc);
      const double e_dot = -n.dot(v_centre);
      WheelContact& wc = out.wheels[i];
      wc = WheelContact{};
      wc.compression = e;
      wc.normal_load = e > 0.0 ? std::max(0.0, k * e + c * e_dot) : 0.0;
      out.contact_measure[i] = e;
      if (e > 0.0) out.energy += 0.5 * k * e * e;
      out.total_load += wc.normal_load;
      f.normal[i] = n;
      f.arm[i] = rc - d * n;
      wc.contact_point = p + f.arm[i];
      wc.normal = n;
      // Tyre frame: the wheel's heading on the tangent plane.
      const double steer = i < 2 ? controls_.steering : 0.0;
      const Vec3 heading = pose.rot * Vec3(std::cos(steer), std::sin(steer), 0.0);
      Vec3 t = heading - heading.dot(n) * n;
      const double t_norm = t.norm();
      t = t_norm > 1e-9 ? Vec3(t / t_norm) : Vec3(n.unitOrthogonal());
      f.tx[i] = t;
      f.ty[i] = n.cross(t);
      const Vec3 v_contact = pose.v_world + pose.w_world.cross(f.arm[i]);
      f.contact_velocity[i] = Vec2(v_contact.dot(f.tx[i]), v_contact.dot(f.ty[i]));
    }
  }

  /// The tyres: each loaded wheel's share of the drive force and its lateral force within
  /// the friction left (combined slip), added with its load to `force` and `moment` (about
  /// the c.g.); the friction utilisations and the lateral load ratio.
  void tyre_forces(const WheelFrames& f, Evaluation& out, Vec3& force, Vec3& moment) const {
    const double mu = vehicle_.friction, ve = options_.tyre_min_speed;
    Vec3 tyre_force = Vec3::Zero();
    out.wheel_friction_utilisation = 0.0;
    double left = 0.0, right = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      WheelContact& wc = out.wheels[i];
      const double load = wc.normal_load;
      (i % 2 == 0 ? left : right) += load;
      const double vx = f.contact_velocity[i].x(), vy = f.contact_velocity[i].y();
      const double vreg = std::sqrt(vx * vx + ve * ve);
      wc.slip_angle = std::atan2(vy, vreg);
      if (load <= 0.0) continue;
      const double limit = mu * load;
      double fx = controls_.drive_force * load / out.total_load;
      if (controls_.drive_force < 0.0) fx *= vx / vreg;
      fx = std::clamp(fx, -limit, limit);
      const double f_max = std::sqrt(std::max(0.0, limit * limit - fx * fx));
      const double ca = body_.cornering_stiffness * load;
      const double fy = options_.tyre == TyreModel::kBrush
                            ? brush_lateral_force(ca, vy / vreg, f_max)
                            : dugoff_lateral_force(ca, vy / vreg, f_max);
      wc.longitudinal_force = fx;
      wc.lateral_force = fy;
      tyre_force += fx * f.tx[i] + fy * f.ty[i];
      out.wheel_friction_utilisation =
          std::max(out.wheel_friction_utilisation, std::hypot(fx, fy) / limit);
      const Vec3 wheel_force = load * f.normal[i] + fx * f.tx[i] + fy * f.ty[i];
      force += wheel_force;
      moment += f.arm[i].cross(wheel_force);
    }
    out.lateral_load_ratio = out.total_load > 0.0 ? (right - left) / out.total_load : 0.0;
    out.friction_utilisation =
        out.total_load > 0.0 ? tyre_force.norm() / (mu * out.total_load) : 0.0;
  }

  /// Roll and pitch of the body against the terrain normal under the c.g.
  void attitude_to_terrain(const Pose& pose, Evaluation& out) const {
    const Vec2 cg(std::clamp(pose.p.x(), surface_.x_min(), surface_.x_max()),
                  std::clamp(pose.p.y(), surface_.y_min(), surface_.y_max()));
    const SurfacePoint under = surface_.evaluate(cg);
    const Vec3 n_cg = Vec3(-under.gradient.x(), -under.gradient.y(), 1.0).normalized();
    out.roll_sin = pose.rot.col(1).dot(n_cg);
    out.pitch_sin = pose.rot.col(0).dot(n_cg);
  }

  /// Newton–Euler in the body frame and the Euler-angle kinematics: ẏ.
  void rigid_body_derivative(const Pose& pose, const Vec3& force, const Vec3& moment,
                             double* ydot) const {
    const Vec3 &v = pose.v, &w = pose.w;
    const Vec3 f_body = pose.rot.transpose() * force;
    const Vec3 m_body = pose.rot.transpose() * moment;
    const Vec3 inertia(body_.inertia_roll, body_.inertia_pitch, body_.inertia_yaw);
    const Vec3 vdot = f_body / body_.mass - w.cross(v);
    const Vec3 iw = inertia.cwiseProduct(w);
    const Vec3 wdot = (m_body - w.cross(iw)).cwiseQuotient(inertia);
    const double sf = std::sin(pose.roll), cf = std::cos(pose.roll);
    ydot[0] = pose.v_world.x();
    ydot[1] = pose.v_world.y();
    ydot[2] = pose.v_world.z();
    ydot[3] = w.x() + (w.y() * sf + w.z() * cf) * std::tan(pose.pitch);
    ydot[4] = w.y() * cf - w.z() * sf;
    ydot[5] = (w.y() * sf + w.z() * cf) / pose.cos_pitch;
    for (int j = 0; j < 3; ++j) {
      ydot[6 + j] = vdot[j];
      ydot[9 + j] = wdot[j];
    }
  }

  const BPatch& surface_;
  const Vehicle& vehicle_;
  const VehicleBody& body_;
  const VehicleSimulationOptions& options_;
  std::array<Vec3, 4> corners_;
  double static_deflection_ = 0.0;
  double max_drive_ = 0.0, max_brake_ = 0.0;
  double roll_limit_ = 0.0, pitch_limit_ = 0.0, clearance_ = 0.0;
  VehicleControls controls_;
};

int rhs_callback(sunrealtype /*t*/, N_Vector y, N_Vector ydot, void* user_data) {
  auto* model = static_cast<Model*>(user_data);
  const double* state = N_VGetArrayPointer(y);
  for (int i = 0; i < kStates; ++i) {
    if (!std::isfinite(state[i])) return 1;  // recoverable: CVODE retries a smaller step
  }
  try {
    Evaluation ev;
    return model->evaluate(state, N_VGetArrayPointer(ydot), ev) ? 0 : 1;
  } catch (const std::exception& e) {
    model->callback_error = e.what();
    return -1;
  }
}

int root_callback(sunrealtype /*t*/, N_Vector y, sunrealtype* g, void* user_data) {
  auto* model = static_cast<Model*>(user_data);
  const double* state = N_VGetArrayPointer(y);
  try {
    Evaluation ev;
    if (!model->evaluate(state, nullptr, ev)) return 1;
    model->roots(state, ev, g);
    return 0;
  } catch (const std::exception& e) {
    model->callback_error = e.what();
    return -1;
  }
}

void unpack(const double* y, VehicleState& s) {
  s.position = Vec3(y[0], y[1], y[2]);
  s.roll = y[3];
  s.pitch = y[4];
  s.yaw = y[5];
  s.velocity = Vec3(y[6], y[7], y[8]);
  s.angular_velocity = Vec3(y[9], y[10], y[11]);
}

void pack(const VehicleState& s, double* y) {
  for (int j = 0; j < 3; ++j) {
    y[j] = s.position[j];
    y[6 + j] = s.velocity[j];
    y[9 + j] = s.angular_velocity[j];
  }
  y[3] = s.roll;
  y[4] = s.pitch;
  y[5] = s.yaw;
}

void require(bool ok, const char* field, double value, const char* expected) {
  if (ok) return;
  std::ostringstream msg;
  msg << "VehicleSimulationOptions." << field << " must be " << expected << ", got " << value;
  throw InputError(msg.str());
}

double degrees(double rad) {
  return rad * 180.0 / std::numbers::pi;
}

}  // namespace

Mat3 VehicleState::rotation() const {
  return euler_rotation(roll, pitch, yaw);
}

VehicleState resting_state(const BPatch& surface, const Vehicle& vehicle, const Vec2& xy,
                           double yaw, double speed) {
  if (!surface.contains(xy)) {
    std::ostringstream msg;
    msg << "resting_state: (" << xy.x() << ", " << xy.y() << ") is off the terrain's domain";
    throw InputError(msg.str());
  }
  const SurfacePoint sp = surface.evaluate(xy);
  const Vec3 n = Vec3(-sp.gradient.x(), -sp.gradient.y(), 1.0).normalized();
  const Vec3 heading(std::cos(yaw), std::sin(yaw), 0.0);
  const Vec3 x = (heading - heading.dot(n) * n).normalized();
  const Vec3 y = n.cross(x);
  VehicleState s;
  // Each wheel carries m g n_z / 4 (the weight's share normal to the ground):
  // its compression is δ_s n_z, which lifts the c.g. by δ_s (1 − n_z).
  double lift = 0.0;
  if (vehicle.body)
    lift = vehicle.body->mass * vehicle.gravity / (4.0 * vehicle.body->suspension_stiffness) *
           (1.0 - n.z());
  s.position = Vec3(xy.x(), xy.y(), sp.z) + (vehicle.cg_height + lift) * n;
  // Z-Y-X Euler angles of R = [x y n].
  s.pitch = -std::asin(std::clamp(x.z(), -1.0, 1.0));
  s.roll = std::atan2(y.z(), n.z());
  s.yaw = std::atan2(x.y(), x.x());
  s.velocity = Vec3(speed, 0.0, 0.0);
  return s;
}

void VehicleSimulationOptions::validate() const {
  const double inf = std::numeric_limits<double>::infinity();
  require(end_time > 0.0 && end_time < inf, "end_time", end_time, "a positive finite time");
  require(control_period > 0.0 && control_period < inf, "control_period", control_period,
          "a positive finite time");
  require(output_interval >= 0.0 && output_interval < inf, "output_interval", output_interval,
          "finite and >= 0");
  require(relative_tolerance > 0.0 && relative_tolerance < inf, "relative_tolerance",
          relative_tolerance, "positive");
  require(absolute_tolerance > 0.0 && absolute_tolerance < inf, "absolute_tolerance",
          absolute_tolerance, "positive");
  require(max_steps >= 1, "max_steps", static_cast<double>(max_steps), ">= 1");
  require(max_step >= 0.0 && max_step < inf, "max_step", max_step, "finite and >= 0");
  require(tyre_min_speed > 0.0 && tyre_min_speed < inf, "tyre_min_speed", tyre_min_speed,
          "positive");
  require(roll_limit >= 0.0 && roll_limit < std::numbers::pi / 2, "roll_limit", roll_limit,
          "in [0, pi/2) (0 = the vehicle's static tip angle)");
  require(pitch_limit >= 0.0 && pitch_limit < std::numbers::pi / 2, "pitch_limit", pitch_limit,
          "in [0, pi/2) (0 = the vehicle's static tip angle)");
  require(airborne_time >= 0.0 && airborne_time < inf, "airborne_time", airborne_time,
          "finite and >= 0");
  require(airborne_clearance >= 0.0 && airborne_clearance < inf, "airborne_clearance",
          airborne_clearance, "finite and >= 0");
  require(side_slip_time >= 0.0 && side_slip_time < inf, "side_slip_time", side_slip_time,
          "finite and >= 0");
  require(side_slip_limit > 0.0 && side_slip_limit < std::numbers::pi / 2, "side_slip_limit",
          side_slip_limit, "in (0, pi/2)");
  require(side_slip_min_speed > 0.0 && side_slip_min_speed < inf, "side_slip_min_speed",
          side_slip_min_speed, "positive");
  require(stall_speed > 0.0 && stall_speed < inf, "stall_speed", stall_speed, "positive");
}

std::string_view to_string(SimulationStatus status) {
  switch (status) {
    case SimulationStatus::kReachedEndTime:
      return "reached_end_time";
    case SimulationStatus::kStopped:
      return "stopped";
    case SimulationStatus::kRollover:
      return "rollover";
    case SimulationStatus::kSideSlip:
      return "side_slip";
    case SimulationStatus::kLossOfContact:
      return "loss_of_contact";
    case SimulationStatus::kStall:
      return "stall";
    case SimulationStatus::kLeftTerrain:
      return "left_terrain";
    case SimulationStatus::kSolverFailure:
      return "solver_failure";
  }
  return "unknown";
}

bool is_vehicle_failure(SimulationStatus status) {
  return status == SimulationStatus::kRollover || status == SimulationStatus::kSideSlip ||
         status == SimulationStatus::kLossOfContact || status == SimulationStatus::kStall;
}

double VehicleSimulationResult::real_time_factor() const {
  return seconds > 0.0 ? end_time / seconds : std::numeric_limits<double>::infinity();
}

std::string VehicleSimulationResult::brief_report() const {
  const VehicleSimulationDiagnostics& d = diagnostics;
  char line[1536];
  std::snprintf(
      line, sizeof line,
      "simulation: %s at t = %.4g s; peak |LTR| %.3f, min normal load %.4g N (%.3f of "
      "static), peak slip angle %.2f deg, peak side slip %.2f deg, peak speed %.3g m/s%s%s\n"
      "  margins: peak roll %.1f of %.1f deg, peak pitch %.1f of %.1f deg; longest airborne "
      "%.3g s, longest side slip beyond its limit %.3g s, one side lifted %.3g s; friction "
      "utilisation %.3f (wheel %.3f), min total normal load %.3f m g\n"
      "  CVODE BDF: %ld steps, %ld RHS, %ld Jacobians, %ld error-test and %ld Newton "
      "failures; %ld restarts, %zu controller calls; %.3g s wall (%.3g x real time)",
      std::string(to_string(status)).c_str(), end_time, d.peak_lateral_load_ratio,
      d.min_normal_load, d.min_normal_load_ratio, degrees(d.peak_slip_angle),
      degrees(d.peak_side_slip), d.peak_speed, message.empty() ? "" : "; ", message.c_str(),
      degrees(d.peak_roll), degrees(d.roll_limit), degrees(d.peak_pitch), degrees(d.pitch_limit),
      d.longest_airborne, d.longest_side_slip, d.side_lift_time, d.peak_friction_utilisation,
      d.peak_wheel_friction_utilisation, d.min_total_normal_load_ratio, d.steps, d.rhs_evaluations,
      d.jacobian_evaluations, d.error_test_failures, d.nonlinear_failures, d.restarts,
      d.controller_calls, seconds, real_time_factor());
  return line;
}

namespace {

/// A condition that is a failure only once it has lasted (airborne, side
/// slip), judged at the end of every step (steps end at least every control tick).
struct Spell {
  double& longest;      ///< the diagnostics' longest spell [s]
  double since = -1.0;  ///< start of the current spell [s]; < 0 outside one
  /// The condition at the end of the step (t_before, t]; returns the spell's
  /// length, or -1 outside a spell.
  double update(bool holds, double t_before, double t) {
    if (!holds) {
      since = -1.0;
      return -1.0;
    }
    if (since < 0.0) since = t_before;
    longest = std::max(longest, t - since);
    return t - since;
  }
};

/// The samples of one run and the diagnostics they feed.
class Recorder {
 public:
  Recorder(Model& model, const Vehicle& vehicle, const VehicleSimulationOptions& options,
           VehicleSimulationDiagnostics& diag)
      : model_(model),
        options_(options),
        diag_(diag),
        weight_(vehicle.body->mass * vehicle.gravity) {}

  /// The sample at (t, state), its margins added to the diagnostics.
  VehicleSample sample(double t, const double* state) {
    VehicleSample s;
    s.t = t;
    unpack(state, s.state);
    s.controls = model_.controls();
    Evaluation ev;
    if (!model_.evaluate(state, nullptr, ev)) return s;
    s.wheels = ev.wheels;
    s.lateral_load_ratio = ev.lateral_load_ratio;
    s.speed = s.state.velocity.norm();
    s.side_slip = std::atan2(s.state.velocity.y(), std::abs(s.state.velocity.x()));
    s.energy = ev.energy;
    s.friction_utilisation = ev.friction_utilisation;
    s.normal_load_ratio = ev.total_load / weight_;
    add_margins(s, ev);
    if (s.state.velocity.x() > 2.0 * options_.stall_speed) model_.stall_armed = true;
    return s;
  }

  double weight() const { return weight_; }

 private:
  void add_margins(const VehicleSample& s, const Evaluation& ev) {
    VehicleSimulationDiagnostics& d = diag_;
    if (ev.total_load > 0.0)
      d.peak_lateral_load_ratio =
          std::max(d.peak_lateral_load_ratio, std::abs(ev.lateral_load_ratio));
    for (const WheelContact& w : ev.wheels) {
      d.min_normal_load = std::min(d.min_normal_load, w.normal_load);
      if (w.normal_load > 0.0)
        d.peak_slip_angle = std::max(d.peak_slip_angle, std::abs(w.slip_angle));
    }
    if (std::hypot(s.state.velocity.x(), s.state.velocity.y()) > options_.side_slip_min_speed)
      d.peak_side_slip = std::max(d.peak_side_slip, std::abs(s.side_slip));
    d.peak_speed = std::max(d.peak_speed, s.speed);
    d.min_total_normal_load_ratio = std::min(d.min_total_normal_load_ratio, s.normal_load_ratio);
    if (s.normal_load_ratio >= kUtilisationLoadFloor) {
      d.peak_friction_utilisation = std::max(d.peak_friction_utilisation, ev.friction_utilisation);
      d.peak_wheel_friction_utilisation =
          std::max(d.peak_wheel_friction_utilisation, ev.wheel_friction_utilisation);
    }
    d.peak_roll = std::max(d.peak_roll, std::asin(std::min(1.0, std::abs(ev.roll_sin))));
    d.peak_pitch = std::max(d.peak_pitch, std::asin(std::min(1.0, std::abs(ev.pitch_sin))));
  }

  Model& model_;
  const VehicleSimulationOptions& options_;
  VehicleSimulationDiagnostics& diag_;
  double weight_;
};

/// The failure events of VehicleSimulationOptions at the end of one step
/// (t_before, t] with sample `now` and the roots CVODE found in it.
class EventJudge {
 public:
  EventJudge(const Model& model, const VehicleSimulationOptions& options,
             VehicleSimulationDiagnostics& diag, double weight)
      : model_(model),
        options_(options),
        diag_(diag),
        weight_(weight),
        airborne_{diag.longest_airborne},
        slipping_{diag.longest_side_slip} {}

  /// The step's failure as (status, message), or an empty message when none.
  std::pair<SimulationStatus, std::string> judge(const VehicleSample& now,
                                                 const std::array<int, kRoots>& found,
                                                 double t_before, double t) {
    const auto& w = now.wheels;
    const auto off = [&](std::size_t i) { return w[i].compression < 0.0; };
    const double vx = now.state.velocity.x(), vy = now.state.velocity.y();
    const bool over_slip = std::abs(vy) > std::tan(options_.side_slip_limit) *
                                              std::hypot(vx, options_.side_slip_min_speed);
    const double airborne_for = airborne_.update(
        (off(0) && off(1) && off(2) && off(3)) || found[kRootAllLift] != 0, t_before, t);
    const double slipping_for =
        slipping_.update(over_slip || found[kRootSideSlip] != 0, t_before, t);
    // Stall is forward speed lost while moving no faster sideways: a vehicle whose
    // forward speed falls while it slides sideways has spun out, which is side slip,
    // judged by its own time. The root finds the onset; polling catches a stall that
    // begins while a slide ends (no root crossing then).
    const bool stalled_now =
        model_.stall_armed && model_.controls().drive_force > 0.0 && vx < options_.stall_speed;
    if ((off(kFrontLeft) && off(kRearLeft)) || (off(kFrontRight) && off(kRearRight)))
      diag_.side_lift_time += t - t_before;

    // A duration of 0 is the strict event: any spell (found by its root, or
    // already under way at the start, where no root can find it).
    const bool airborne_event = found[kRootClearance] || airborne_for >= options_.airborne_time;
    const bool slip_event = slipping_for >= options_.side_slip_time;
    // The strict side-lift event (roots inert unless side_lift_is_rollover).
    const bool side_lift = found[kRootLeftLift] || found[kRootRightLift];
    // One side lifting while the other carries (almost) nothing is the
    // vehicle leaving the ground, not tipping over.
    const double other_side = found[kRootLeftLift]
                                  ? std::max(w[kFrontRight].compression, w[kRearRight].compression)
                                  : std::max(w[kFrontLeft].compression, w[kRearLeft].compression);
    const bool side_lift_airborne =
        side_lift && (w[0].normal_load + w[1].normal_load + w[2].normal_load + w[3].normal_load <
                          0.01 * weight_ ||
                      other_side < 0.01 * model_.static_deflection());
    std::ostringstream msg;
    msg << std::fixed;
    msg.precision(4);
    SimulationStatus status = SimulationStatus::kReachedEndTime;
    if (airborne_event || side_lift_airborne) {
      status = SimulationStatus::kLossOfContact;
      if (found[kRootClearance])
        msg << "every wheel was more than " << model_.clearance()
            << " m clear of the ground at t = " << t << " s";
      else if (side_lift_airborne || options_.airborne_time == 0.0)
        msg << (side_lift_airborne ? "the vehicle" : "all four wheels")
            << " left the ground at t = " << t << " s";
      else
        msg << "airborne (all four wheels off the ground) for " << airborne_for << " s at t = " << t
            << " s";
    } else if (found[kRootRoll] || found[kRootPitch] || side_lift) {
      status = SimulationStatus::kRollover;
      if (side_lift)
        msg << "both " << (found[kRootLeftLift] ? "left" : "right")
            << " wheels left the ground at t = " << t << " s";
      else
        msg << (found[kRootRoll] ? "roll" : "pitch") << " relative to the terrain reached "
            << degrees(found[kRootRoll] ? model_.roll_limit() : model_.pitch_limit())
            << " deg at t = " << t << " s";
    } else if (slip_event) {
      status = SimulationStatus::kSideSlip;
      msg << "side slip beyond " << degrees(options_.side_slip_limit) << " deg";
      if (options_.side_slip_time > 0.0) msg << " for " << slipping_for << " s";
      msg << " at t = " << t << " s";
    } else if (!over_slip && (found[kRootStall] || stalled_now)) {
      status = SimulationStatus::kStall;
      msg << "stalled (forward speed below " << options_.stall_speed
          << " m/s while driving) at t = " << t << " s";
    } else if (found[kRootDomain]) {
      status = SimulationStatus::kLeftTerrain;
      msg << "a wheel left the terrain's domain at t = " << t << " s";
    }
    if (msg.str().empty()) return {status, ""};
    msg << ", c.g. at (" << now.state.position.x() << ", " << now.state.position.y() << ", "
        << now.state.position.z() << ") m, speed " << now.speed << " m/s";
    return {status, msg.str()};
  }

 private:
  const Model& model_;
  const VehicleSimulationOptions& options_;
  VehicleSimulationDiagnostics& diag_;
  double weight_;
  Spell airborne_, slipping_;
};

void add_counters(const detail::CvodeCounters& counted, VehicleSimulationDiagnostics& diag) {
  diag.rhs_evaluations += counted.rhs_evaluations;
  diag.jacobian_evaluations += counted.jacobian_evaluations;
  diag.root_evaluations += counted.root_evaluations;
  diag.error_test_failures += counted.error_test_failures;
  diag.nonlinear_failures += counted.nonlinear_failures;
}

/// The trace samples every output_interval up to `t` (the step just taken),
/// from CVODE's interpolant; `next` the index of the next one.
void sample_outputs(detail::CvodeIntegrator& cvode, Recorder& recorder,
                    const VehicleSimulationOptions& options, double t, std::size_t& next,
                    std::vector<VehicleSample>& trace) {
  while (static_cast<double>(next) * options.output_interval <= t &&
         static_cast<double>(next) * options.output_interval < options.end_time) {
    const double t_out = static_cast<double>(next) * options.output_interval;
    if (const double* state = cvode.interpolate(t_out))
      trace.push_back(recorder.sample(t_out, state));
    ++next;
  }
}

void check_simulation_inputs(const BPatch& surface, const Vehicle& vehicle,
                             const VehicleState& initial, const VehicleController& controller,
                             const VehicleSimulationOptions& options) {
  options.validate();
  vehicle.validate();
  if (!vehicle.body)
    throw InputError(
        "simulate_vehicle: the vehicle has no body (a vehicle file needs 'mass', see "
        "data/vehicles/README.md)");
  if (!controller) throw InputError("simulate_vehicle: the controller is empty");
  if (!surface.contains(Vec2(initial.position.x(), initial.position.y())))
    throw InputError("simulate_vehicle: the initial centre of mass is off the terrain's domain");
  // The trace, estimated before it grows (--trace-interval 1e-9 reached 1.6 GB).
  if (options.output_interval > 0.0) {
    const double samples = options.end_time / options.output_interval + 2.0;
    require_memory(samples * static_cast<double>(sizeof(VehicleSample)),
                   "a trace of " + std::to_string(static_cast<long long>(std::min(samples, 9e18))) +
                       " samples",
                   "use a longer trace interval (--trace-interval)");
  }
}

}  // namespace

VehicleSimulationResult simulate_vehicle(const BPatch& surface, const Vehicle& vehicle,
                                         const VehicleState& initial,
                                         const VehicleController& controller,
                                         const VehicleSimulationOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  check_simulation_inputs(surface, vehicle, initial, controller, options);
  Model model(surface, vehicle, options);
  VehicleSimulationResult result;
  VehicleSimulationDiagnostics& diag = result.diagnostics;
  diag.roll_limit = model.roll_limit();
  diag.pitch_limit = model.pitch_limit();
  diag.min_normal_load = std::numeric_limits<double>::infinity();
  diag.min_total_normal_load_ratio = std::numeric_limits<double>::infinity();

  std::array<double, kStates> start{};
  pack(initial, start.data());
  detail::CvodeIntegrator cvode(
      kStates, start.data(), rhs_callback, kRoots, root_callback, &model,
      {options.relative_tolerance, options.absolute_tolerance, options.max_step});
  double* yv = cvode.state();
  Recorder recorder(model, vehicle, options, diag);
  EventJudge judge(model, options, diag, recorder.weight());
  const auto call_controller = [&](double t, const double* state) {
    VehicleState s;
    unpack(state, s);
    ++diag.controller_calls;
    model.set_controls(controller(t, s));
  };

  double t = 0.0;
  call_controller(0.0, yv);
  result.trace.push_back(recorder.sample(0.0, yv));
  bool done = model.controls().stop;
  if (done) {
    result.status = SimulationStatus::kStopped;
    result.message = "the controller stopped the run at t = 0";
  }
  std::size_t next_output = 1;
  long tick = 0;
  while (!done) {
    ++tick;
    const double t_tick =
        std::min(options.end_time, static_cast<double>(tick) * options.control_period);
    if (options.progress) options.progress(t);
    cvode.set_stop_time(t_tick);
    while (t < t_tick && !done) {
      if (diag.steps >= options.max_steps) {
        result.status = SimulationStatus::kSolverFailure;
        std::ostringstream msg;
        msg << "CVODE took max_steps = " << options.max_steps << " steps before t = " << t << " s";
        result.message = msg.str();
        done = true;
        break;
      }
      const double t_before = t;
      const int flag = cvode.step(t_tick, t);
      diag.cvode_flag = flag;
      if (flag < 0) {
        result.status = SimulationStatus::kSolverFailure;
        std::ostringstream msg;
        msg << "CVODE failed at t = " << t << " s (" << cvode.failure(flag);
        if (!model.callback_error.empty()) msg << "; model: " << model.callback_error;
        result.message = msg.str();
        done = true;
        break;
      }
      ++diag.steps;
      // Trace samples inside the step just taken.
      if (options.output_interval > 0.0)
        sample_outputs(cvode, recorder, options, t, next_output, result.trace);
      VehicleSample now = recorder.sample(t, yv);
      std::array<int, kRoots> found{};
      if (flag == CV_ROOT_RETURN) cvode.roots_found(found.data());
      auto [status, message] = judge.judge(now, found, t_before, t);
      if (!message.empty()) {
        result.status = status;
        result.message = std::move(message);
        result.trace.push_back(now);
        done = true;
      }
    }
    if (done) break;
    if (t >= options.end_time) {
      result.status = SimulationStatus::kReachedEndTime;
      result.trace.push_back(recorder.sample(t, yv));
      break;
    }
    const VehicleControls before = model.controls();
    call_controller(t, yv);
    // The right-hand side jumps with the controls: restart the BDF history
    // there (its predictor would otherwise carry the old derivative, and the
    // error test would cut the step to nothing at a large jump).
    if (model.controls().steering != before.steering ||
        model.controls().drive_force != before.drive_force) {
      cvode.restart(t);
      ++diag.restarts;
    }
    if (model.controls().stop) {
      result.status = SimulationStatus::kStopped;
      std::ostringstream msg;
      msg << "the controller stopped the run at t = " << t << " s";
      result.message = msg.str();
      result.trace.push_back(recorder.sample(t, yv));
      done = true;
    }
  }

  result.end_time = t;
  result.final = result.trace.back();
  add_counters(cvode.counters(), diag);
  if (!std::isfinite(diag.min_normal_load)) diag.min_normal_load = 0.0;
  if (!std::isfinite(diag.min_total_normal_load_ratio)) diag.min_total_normal_load_ratio = 0.0;
  diag.min_normal_load_ratio = diag.min_normal_load / (recorder.weight() / 4.0);
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace talus
