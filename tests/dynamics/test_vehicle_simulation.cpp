// The rigid-body vehicle simulation (vehicle_simulation.hpp) against physics:
// cornering slides at mu g, a tilt table tips near atan(b/h), a crest of radius
// R loses contact near sqrt(g R), straight-line acceleration is the drive (or
// friction) limit, energy is conserved without damping and friction, CVODE
// failures are statuses, and runs are deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/vehicle_simulation.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

Vehicle ugv() {
  return load_vehicle(std::string(TALUS_DATA_DIR) + "/vehicles/iagnemma_ugv.yaml");
}

/// A surface z = f(x, y) on a square grid (the fit reproduces bicubics exactly).
BPatch surface_of(const std::function<double(double, double)>& f, double half_size,
                  double spacing) {
  const auto n = static_cast<std::size_t>(std::lround(2.0 * half_size / spacing)) + 1;
  ElevationGrid grid(n, n, spacing, -half_size, -half_size);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 p = grid.node_position(i, j);
      grid.set(i, j, f(p.x(), p.y()));
    }
  return BPatch::interpolate(grid);
}

VehicleController constant(double steering, double drive_force) {
  return [=](double, const VehicleState&) { return VehicleControls{steering, drive_force, false}; };
}

/// Horizontal acceleration of the c.g. normal to its velocity, from the trace
/// by central differences of the world velocity (independent of the forces).
double lateral_acceleration(const VehicleSample& a, const VehicleSample& b,
                            const VehicleSample& c) {
  const Vec3 va = a.state.rotation() * a.state.velocity;
  const Vec3 vb = b.state.rotation() * b.state.velocity;
  const Vec3 vc = c.state.rotation() * c.state.velocity;
  const Vec3 acc = (vc - va) / (c.t - a.t);
  const Vec3 side = Vec3::UnitZ().cross(vb).normalized();
  return std::abs(acc.dot(side));
}

TEST(VehicleFile, BodyKeysAreOptionalAndValidated) {
  const Vehicle v = ugv();
  ASSERT_TRUE(v.body.has_value());
  EXPECT_DOUBLE_EQ(v.body->mass, 2.0);
  EXPECT_DOUBLE_EQ(v.body->wheel_radius, 0.06);
  const Vehicle rover = load_vehicle(std::string(TALUS_DATA_DIR) + "/vehicles/rover.yaml");
  EXPECT_FALSE(rover.body.has_value());
  // Defaults from the mass and the geometry.
  const Vehicle d = parse_vehicle(
      "{model: rigid_body, friction: 0.7, cg_height: 0.5, half_track: 0.6, half_wheelbase: 1.0, "
      "mass: 100}",
      "t");
  ASSERT_TRUE(d.body.has_value());
  EXPECT_NEAR(d.body->inertia_roll, 100.0 * (1.2 * 1.2 + 1.0) / 12.0, 1e-12);
  EXPECT_NEAR(d.body->suspension_stiffness, 25.0 * std::pow(2 * kPi * 3.0, 2), 1e-9);
  EXPECT_NEAR(d.body->wheel_radius, 0.25, 1e-15);
  EXPECT_THROW(parse_vehicle("{model: point_mass, friction: 0.7, cg_height: 0.5, half_track: "
                             "0.6, wheel_radius: 0.3}",
                             "t"),
               InputError);
  EXPECT_THROW(parse_vehicle("{model: point_mass, friction: 0.7, cg_height: 0.5, half_track: "
                             "0.6, mass: -1}",
                             "t"),
               InputError);
  EXPECT_THROW(parse_vehicle("{model: point_mass, friction: 0.7, cg_height: 0.5, half_track: "
                             "0.6, mass: 1, suspension_damping: -2}",
                             "t"),
               InputError);
}

TEST(VehicleSimulation, OptionsAndInputsAreValidated) {
  const BPatch flat = surface_of([](double, double) { return 0.0; }, 5.0, 0.5);
  const Vehicle v = ugv();
  const VehicleState s = resting_state(flat, v, Vec2(0, 0), 0.0);
  VehicleSimulationOptions o;
  o.end_time = -1.0;
  EXPECT_THROW(simulate_vehicle(flat, v, s, constant(0, 0), o), InputError);
  o = {};
  o.roll_limit = 2.0;
  EXPECT_THROW(o.validate(), InputError);
  Vehicle no_body = v;
  no_body.body.reset();
  EXPECT_THROW(simulate_vehicle(flat, no_body, s, constant(0, 0)), InputError);
  EXPECT_THROW(resting_state(flat, v, Vec2(9, 0), 0.0), InputError);
}

// At rest on level ground the c.g. is at h and every wheel carries m g / 4.
TEST(VehicleSimulation, RestsAtStaticLoad) {
  const BPatch flat = surface_of([](double, double) { return 0.0; }, 5.0, 0.5);
  const Vehicle v = ugv();
  VehicleSimulationOptions o;
  o.end_time = 1.0;
  const VehicleSimulationResult r =
      simulate_vehicle(flat, v, resting_state(flat, v, Vec2(0, 0), 0.3), constant(0, 0), o);
  ASSERT_EQ(r.status, SimulationStatus::kReachedEndTime) << r.message;
  EXPECT_NEAR(r.final.state.position.z(), v.cg_height, 1e-6);
  for (const WheelContact& w : r.final.wheels)
    EXPECT_NEAR(w.normal_load, v.body->mass * v.gravity / 4.0, 1e-4);
  EXPECT_NEAR(r.final.state.yaw, 0.3, 1e-9);
  // At rest on level ground the tyres carry no tangential force and the wheels the weight.
  EXPECT_NEAR(r.final.normal_load_ratio, 1.0, 1e-6);
  EXPECT_NEAR(r.diagnostics.min_total_normal_load_ratio, 1.0, 1e-6);
  EXPECT_LT(r.diagnostics.peak_friction_utilisation, 1e-6);
  std::cout << r.brief_report() << "\n";
}

// Parked across a side slope of tan(beta) = 0.5 mu (below sliding): the tyres hold the
// weight's downhill component, m g sin(beta), against mu m g cos(beta) of friction, so the
// vehicle uses tan(beta) / mu = 0.5 of its envelope, the point-mass planner's measure.
TEST(VehicleSimulation, FrictionUtilisationOnASideSlopeIsTanBetaOverMu) {
  const Vehicle v = ugv();
  const double slope = 0.5 * v.friction;
  const BPatch plane = surface_of([slope](double, double y) { return slope * y; }, 3.0, 0.5);
  VehicleSimulationOptions o;
  o.end_time = 3.0;
  const VehicleSimulationResult r =
      simulate_vehicle(plane, v, resting_state(plane, v, Vec2(0, 0), 0.0), constant(0, 0), o);
  ASSERT_EQ(r.status, SimulationStatus::kReachedEndTime) << r.message;
  std::cout << "side slope: utilisation " << r.final.friction_utilisation << ", normal load "
            << r.final.normal_load_ratio << " m g\n";
  // The tyres' static slip creeps the vehicle downhill, so a small residual speed remains.
  EXPECT_NEAR(r.final.friction_utilisation, 0.5, 0.01);
  EXPECT_NEAR(r.final.normal_load_ratio, 1.0 / std::sqrt(1.0 + slope * slope), 0.01);
}

// Constant steering, speed slowly rising: the lateral acceleration saturates
// at mu g (the friction circle of every tyre), then the vehicle slides.
TEST(VehicleSimulation, SteadyCorneringSlidesAtMuG) {
  const BPatch flat = surface_of([](double, double) { return 0.0; }, 12.0, 1.0);
  const Vehicle v = ugv();
  VehicleSimulationOptions o;
  o.end_time = 4.0;
  o.output_interval = 0.005;
  // Speed target rising at 0.3 m/s^2 from 3.6 m/s, held by a P controller
  // (the force needed is the cornering drag, a few % of the friction circle).
  const double m = v.body->mass;
  const VehicleController ramp = [m](double t, const VehicleState& s) {
    return VehicleControls{0.1, m * 10.0 * (3.6 + 0.3 * t - s.velocity.x()), false};
  };
  const VehicleSimulationResult r =
      simulate_vehicle(flat, v, resting_state(flat, v, Vec2(0, -2.7), 0.0, 3.6), ramp, o);
  double peak = 0.0;
  for (std::size_t k = 1; k + 1 < r.trace.size(); ++k)
    peak = std::max(peak, lateral_acceleration(r.trace[k - 1], r.trace[k], r.trace[k + 1]));
  const double mu_g = v.friction * v.gravity;
  std::cout << "cornering: peak lateral acceleration " << peak << " m/s^2 = " << peak / mu_g
            << " mu g; " << r.brief_report() << "\n";
  EXPECT_EQ(r.status, SimulationStatus::kSideSlip) << r.message;
  // A sustained slide: the run ends once the slip has lasted side_slip_time.
  EXPECT_GE(r.diagnostics.longest_side_slip, o.side_slip_time - 1e-9) << r.brief_report();
  EXPECT_NEAR(peak / mu_g, 1.0, 0.04);
  EXPECT_LE(peak, mu_g * 1.001);
  // The slide is the envelope used up: utilisation reaches 1 (to the tyres' transient).
  EXPECT_GT(r.diagnostics.peak_friction_utilisation, 0.98) << r.brief_report();
  EXPECT_LE(r.diagnostics.peak_friction_utilisation, 1.0 + 1e-12);
  EXPECT_LE(r.diagnostics.peak_wheel_friction_utilisation, 1.0 + 1e-12);
}

/// Tilt-table run: a plane of side slope `beta` (rising to the vehicle's left),
/// the vehicle at rest across it for 3 s. Friction 3 (no sliding before
/// tipping) and a heavily overdamped suspension (damping ratio 5: the chassis
/// creeps into its equilibrium roll without overshoot, so the test is
/// quasi-static; the equilibrium does not depend on the damping). The
/// suspension is `stiffness_scale` times the UGV's. `strict`: the uphill
/// wheels' lift ends the run as rollover (the onset, which quasi-statically is
/// the tip angle); otherwise the default, physical event.
VehicleSimulationResult tilt(double beta, bool strict = true, double stiffness_scale = 1.0) {
  Vehicle v = ugv();
  v.friction = 3.0;
  v.body->suspension_stiffness *= stiffness_scale;
  v.body->suspension_damping =
      2.0 * 5.0 * std::sqrt(v.body->suspension_stiffness * v.body->mass / 4.0);
  const double slope = std::tan(beta);
  const BPatch plane = surface_of([slope](double, double y) { return slope * y; }, 2.0, 0.25);
  VehicleSimulationOptions o;
  o.end_time = 3.0;
  o.output_interval = 0.0;
  o.side_lift_is_rollover = strict;
  return simulate_vehicle(plane, v, resting_state(plane, v, Vec2(0, 0), 0.0), constant(0, 0), o);
}

TEST(VehicleFailureEvents, RolloverIsAtTheStaticTipAngleNotAtWheelLift) {
  // A stiff suspension (100 x: 0.16 mm static deflection), so the vehicle's
  // tip angle is the rigid atan(b/h) to a few hundredths of a degree.
  const Vehicle v = ugv();
  const double tip = std::atan(v.half_track / v.cg_height), degree = kPi / 180.0;
  const VehicleSimulationResult stands = tilt(tip - degree, false, 100.0);
  const VehicleSimulationResult tips = tilt(tip + degree, false, 100.0);
  std::cout << "tip angle " << tip / degree << " deg; -1 deg: " << stands.brief_report()
            << "\n+1 deg: " << tips.brief_report() << "\n";
  EXPECT_EQ(stands.status, SimulationStatus::kReachedEndTime) << stands.message;
  EXPECT_EQ(tips.status, SimulationStatus::kRollover) << tips.message;
  EXPECT_NEAR(stands.diagnostics.roll_limit, tip, 1e-12);
  EXPECT_NE(tips.message.find("roll relative to the terrain"), std::string::npos) << tips.message;
  // With the UGV's own soft suspension the uphill wheels lift a few degrees
  // below the rigid tip angle: at 3 degrees below it they are off the ground
  // (the onset), yet the vehicle leans on its downhill wheels and stands.
  const VehicleSimulationResult lifted = tilt(tip - 3.0 * degree, false, 1.0);
  const VehicleSimulationResult strict = tilt(tip - 3.0 * degree, true, 1.0);
  EXPECT_EQ(strict.status, SimulationStatus::kRollover) << strict.message;
  EXPECT_NE(strict.message.find("wheels left the ground"), std::string::npos) << strict.message;
  if (lifted.status == SimulationStatus::kReachedEndTime) {
    EXPECT_GT(lifted.diagnostics.side_lift_time, 1.0) << lifted.brief_report();
  } else {
    // Past the compliant vehicle's own tip angle: then it is a real rollover.
    EXPECT_EQ(lifted.status, SimulationStatus::kRollover) << lifted.message;
  }
}

/// A vehicle dropped flat onto level ground with every wheel `clearance` clear
/// of it, moving up at `rise` [m/s] and forward at 2 m/s.
VehicleSimulationResult drop(double clearance, double rise, const VehicleSimulationOptions& o) {
  const BPatch flat = surface_of([](double, double) { return 0.0; }, 8.0, 1.0);
  const Vehicle v = ugv();
  VehicleState s = resting_state(flat, v, Vec2(-4.0, 0.0), 0.0, 2.0);
  // resting_state compresses each spring by its static share: undo it, then lift.
  s.position.z() += v.body->mass * v.gravity / (4.0 * v.body->suspension_stiffness) + clearance;
  s.velocity.z() = rise;
  return simulate_vehicle(flat, v, s, constant(0.0, 0.0), o);
}

TEST(VehicleFailureEvents, AHopIsNotLossOfContactButASustainedFlightIs) {
  VehicleSimulationOptions o;
  o.end_time = 1.0;
  o.output_interval = 0.0;
  // A 1 cm drop: airborne for sqrt(2 h / g) = 45 ms, never r/2 = 3 cm clear.
  const VehicleSimulationResult hop = drop(0.01, 0.0, o);
  EXPECT_EQ(hop.status, SimulationStatus::kReachedEndTime) << hop.message;
  EXPECT_NEAR(hop.diagnostics.longest_airborne, std::sqrt(2.0 * 0.01 / 9.81), 0.012)
      << hop.brief_report();
  // The strict event ends the same run at once.
  VehicleSimulationOptions strict = o;
  strict.airborne_time = 0.0;
  const VehicleSimulationResult at_once = drop(0.01, 0.0, strict);
  EXPECT_EQ(at_once.status, SimulationStatus::kLossOfContact) << at_once.message;
  EXPECT_LT(at_once.end_time, 0.011);
  // A flight of 2 v / g = 0.24 s (apex 7 cm up; the clearance bound raised
  // out of the way) ends when it has lasted airborne_time.
  VehicleSimulationOptions high_bound = o;
  high_bound.airborne_clearance = 1.0;
  const VehicleSimulationResult flight = drop(0.0, 1.2, high_bound);
  EXPECT_EQ(flight.status, SimulationStatus::kLossOfContact) << flight.message;
  EXPECT_NEAR(flight.end_time, o.airborne_time, 0.011) << flight.message;
  // The same flight with the default bound ends as it rises past half the
  // wheel radius (3 cm).
  const VehicleSimulationResult leap = drop(0.0, 1.2, o);
  EXPECT_EQ(leap.status, SimulationStatus::kLossOfContact) << leap.message;
  EXPECT_NE(leap.message.find("clear of the ground"), std::string::npos) << leap.message;
  const double rise_to_clearance =  // 1.2 t - g t^2 / 2 = 0.03
      (1.2 - std::sqrt(1.2 * 1.2 - 2.0 * 9.81 * 0.03)) / 9.81;
  EXPECT_NEAR(leap.end_time, rise_to_clearance, 0.005);
}

TEST(VehicleFailureEvents, AMomentarySideSlipIsNotAFailureButASustainedOneIs) {
  const BPatch flat = surface_of([](double, double) { return 0.0; }, 12.0, 1.0);
  const Vehicle v = ugv();
  VehicleSimulationOptions o;
  o.end_time = 1.5;
  o.output_interval = 0.0;
  // A sideways kick: v = (3, 2) m/s, side slip 0.59 rad > 0.5, which the
  // tyres take out within a tenth of a second.
  VehicleState kicked = resting_state(flat, v, Vec2(-6.0, 0.0), 0.0, 3.0);
  kicked.velocity.y() = 2.0;
  const VehicleSimulationResult recovers = simulate_vehicle(flat, v, kicked, constant(0, 0), o);
  EXPECT_EQ(recovers.status, SimulationStatus::kReachedEndTime) << recovers.message;
  EXPECT_GT(recovers.diagnostics.longest_side_slip, 0.0) << recovers.brief_report();
  EXPECT_LT(recovers.diagnostics.longest_side_slip, 0.2) << recovers.brief_report();
  VehicleSimulationOptions strict = o;
  strict.side_slip_time = 0.0;
  const VehicleSimulationResult strict_run =
      simulate_vehicle(flat, v, kicked, constant(0, 0), strict);
  EXPECT_EQ(strict_run.status, SimulationStatus::kSideSlip) << strict_run.message;
}

// Full steering lock at speed on flat ground, driving on: the vehicle spins out, its forward
// speed falling through zero while it slides sideways. That is loss of control (side slip),
// not a stall, whose forward speed is lost while the vehicle does not slide.
TEST(VehicleFailureEvents, ASpinOutIsSideSlipNotStall) {
  const BPatch flat = surface_of([](double, double) { return 0.0; }, 12.0, 1.0);
  const Vehicle v = ugv();
  VehicleSimulationOptions o;
  o.end_time = 4.0;
  o.output_interval = 0.01;
  const VehicleSimulationResult r =
      simulate_vehicle(flat, v, resting_state(flat, v, Vec2(0.0, -4.0), 0.0, 6.0),
                       constant(0.6, 0.5 * v.body->mass * v.gravity), o);
  double min_forward = std::numeric_limits<double>::infinity();
  for (const VehicleSample& s : r.trace) min_forward = std::min(min_forward, s.state.velocity.x());
  std::cout << "spin-out: " << r.message << "; lowest forward speed " << min_forward << " m/s\n";
  EXPECT_EQ(r.status, SimulationStatus::kSideSlip) << r.message;
  EXPECT_LT(min_forward, o.stall_speed);  // the forward speed was lost, as in a stall
}

TEST(VehicleSimulation, TiltTableTipsNearAtanBOverH) {
  const Vehicle v = ugv();
  const double rigid = std::atan(v.half_track / v.cg_height);
  double lo = rigid - 0.3, hi = rigid + 0.05;  // stands at lo, tips at hi
  ASSERT_EQ(tilt(lo).status, SimulationStatus::kReachedEndTime);
  ASSERT_EQ(tilt(hi).status, SimulationStatus::kRollover);
  for (int k = 0; k < 9; ++k) {
    const double mid = 0.5 * (lo + hi);
    (tilt(mid).status == SimulationStatus::kRollover ? hi : lo) = mid;
  }
  // The deflected geometry at the largest stable angle: the c.g.'s lever about
  // the downhill contact line and its height above the plane.
  const VehicleSimulationResult stable = tilt(lo);
  ASSERT_EQ(stable.status, SimulationStatus::kReachedEndTime);
  const Vec3 n = stable.final.wheels[kFrontRight].normal;
  const Vec3 downhill = Vec3(0.0, -1.0, 0.0).cross(n).cross(n).normalized() * -1.0;
  const Vec3 foot = 0.5 * (stable.final.wheels[kFrontRight].contact_point +
                           stable.final.wheels[kRearRight].contact_point);
  const Vec3 cg = stable.final.state.position;
  const double lever = (foot - cg).dot(downhill), height = (cg - foot).dot(n);
  const double deflected = std::atan(lever / height);
  const double roll = stable.final.state.roll - lo;  // chassis roll relative to the plane
  std::cout << "tilt table: tips between " << lo * 180 / kPi << " and " << hi * 180 / kPi
            << " deg; rigid atan(b/h) = " << rigid * 180 / kPi
            << " deg; deflected geometry at the last stable angle: lever " << lever
            << " m, c.g. height " << height << " m, atan = " << deflected * 180 / kPi
            << " deg; suspension roll there " << roll * 180 / kPi << " deg\n";
  EXPECT_LT(hi, rigid);                      // the suspension's roll and rise reduce it
  EXPECT_GT(lo, rigid - 5.0 * kPi / 180.0);  // ... by a few degrees
  EXPECT_NEAR(0.5 * (lo + hi), deflected, 0.5 * kPi / 180.0);
}

/// Driving at `speed` (held by a P controller with the slope's feedforward)
/// over the Gaussian crest z = A exp(-x² / (2σ²)), σ = 2 m, A = σ²/R, whose
/// curvature at the apex is 1/R and falls off on both sides (inflections at
/// ±σ, slope at most 0.61 σ/R), from x = -3σ to x = σ/2. At constant speed the
/// unloading v² κ / (g n_z) peaks at the apex. The B-patch interpolates it at
/// 0.2 m spacing (curvature within 0.1 %).
VehicleSimulationResult crest(double radius, double speed) {
  Vehicle v = ugv();
  v.max_accel = v.max_decel = std::numeric_limits<double>::infinity();
  const double sigma = 2.0, amplitude = sigma * sigma / radius;
  const BPatch hill = surface_of(
      [=](double x, double) { return amplitude * std::exp(-x * x / (2.0 * sigma * sigma)); },
      3.2 * sigma, 0.2);
  const double m = v.body->mass, g = v.gravity;
  const VehicleController hold = [=](double, const VehicleState& s) {
    const double uphill = s.rotation()(2, 0);  // sine of the body x axis's elevation
    return VehicleControls{0.0, m * (g * uphill + 10.0 * (speed - s.velocity.x())),
                           s.position.x() > 0.5 * sigma};
  };
  // Start in equilibrium: the springs carry m (g n_z - v² κ) / 4 each, not the
  // resting share, and the suspension is critically damped, so that no heave
  // transient lifts the wheels before the crest does.
  v.body->suspension_damping = 2.0 * std::sqrt(v.body->suspension_stiffness * v.body->mass / 4.0);
  const double x0 = -3.0 * sigma;
  const SurfacePoint sp = hill.evaluate(Vec2(x0, 0.0));
  const double slope = sp.gradient.x(), n_z = 1.0 / std::sqrt(1.0 + slope * slope);
  const double kappa = -sp.hessian(0, 0) * n_z * n_z * n_z;  // > 0 on a crest
  VehicleState s = resting_state(hill, v, Vec2(x0, 0.0), 0.0, speed);
  const double unload = m * speed * speed * kappa / (4.0 * v.body->suspension_stiffness);
  s.position += unload * Vec3(-slope, 0.0, 1.0) * n_z;
  VehicleSimulationOptions o;
  o.end_time = 10.0;
  o.output_interval = 0.0;
  o.airborne_time = 0.0;  // the strict event: the first instant all four wheels are off
  return simulate_vehicle(hill, v, s, hold, o);
}

TEST(VehicleSimulation, CrestLosesContactNearSqrtGR) {
  const double radius = 8.0, g = 9.81;
  const double predicted = std::sqrt(g * radius);
  double lo = 0.8 * predicted, hi = 1.1 * predicted;
  ASSERT_EQ(crest(radius, lo).status, SimulationStatus::kStopped);
  const VehicleSimulationResult fast = crest(radius, hi);
  ASSERT_EQ(fast.status, SimulationStatus::kLossOfContact) << fast.message;
  for (int k = 0; k < 10; ++k) {
    const double mid = 0.5 * (lo + hi);
    (crest(radius, mid).status == SimulationStatus::kLossOfContact ? hi : lo) = mid;
  }
  const VehicleSimulationResult at = crest(radius, hi);
  std::cout << "crest R = " << radius << " m: contact lost from " << hi
            << " m/s; sqrt(g R) = " << predicted << " m/s (ratio " << hi / predicted
            << "), sqrt(g (R + h)) = " << std::sqrt(g * (radius + 0.06))
            << "; at x = " << at.final.state.position.x() << " m\n";
  EXPECT_NEAR(hi / predicted, 1.0, 0.03);
  EXPECT_NEAR(at.final.state.position.x(), 0.0, 0.75);  // near the apex, not on the approach
}

/// Full drive on level ground from 1 m/s for 1 s: the mean acceleration.
double straight_acceleration(const Vehicle& v, double force) {
  const BPatch flat = surface_of([](double, double) { return 0.0; }, 6.0, 1.0);
  VehicleSimulationOptions o;
  o.end_time = 1.0;
  const VehicleSimulationResult r = simulate_vehicle(
      flat, v, resting_state(flat, v, Vec2(-5.0, 0.0), 0.0, 1.0), constant(0.0, force), o);
  EXPECT_EQ(r.status, SimulationStatus::kReachedEndTime) << r.message;
  // Over the last 0.5 s (after the pitch transient).
  const VehicleSample& a = r.trace[r.trace.size() / 2];
  const VehicleSample& b = r.trace.back();
  return (b.state.velocity.x() - a.state.velocity.x()) / (b.t - a.t);
}

TEST(VehicleSimulation, StraightLineAccelerationIsTheDriveOrFrictionLimit) {
  const Vehicle v = ugv();  // max_accel 3 < mu g = 6.87
  const double drive = straight_acceleration(v, 1e3);
  Vehicle unlimited = v;
  unlimited.max_accel = std::numeric_limits<double>::infinity();
  const double grip = straight_acceleration(unlimited, 1e3);
  std::cout << "straight line: " << drive << " m/s^2 (drive limit " << v.max_accel << "), " << grip
            << " m/s^2 (friction limit mu g = " << v.friction * v.gravity << ")\n";
  EXPECT_NEAR(drive, v.max_accel, 1e-3 * v.max_accel);
  EXPECT_NEAR(grip, v.friction * v.gravity, 1e-3 * v.friction * v.gravity);
}

// No damping, (practically) no friction: a bouncing, rolling, pitching
// vehicle on a side slope keeps its energy to the integrator's tolerance.
TEST(VehicleSimulation, EnergyIsConservedWithoutDampingOrFriction) {
  Vehicle v = ugv();
  v.friction = 1e-12;
  v.body->suspension_damping = 0.0;
  const BPatch plane = surface_of([](double x, double y) { return 0.1 * x + 0.05 * y; }, 3.0, 0.5);
  VehicleState s = resting_state(plane, v, Vec2(0, 0), 0.5, 1.0);
  s.position.z() += 0.01;  // dropped from 1 cm: the wheels leave the ground and land
  s.angular_velocity = Vec3(2.0, 1.0, 0.3);
  VehicleSimulationOptions o;
  o.end_time = 1.0;
  o.relative_tolerance = 1e-10;
  o.absolute_tolerance = 1e-12;
  const VehicleSimulationResult r = simulate_vehicle(plane, v, s, constant(0, 0), o);
  ASSERT_EQ(r.status, SimulationStatus::kReachedEndTime) << r.message;
  // Scale: the energy above the vehicle's rest.
  const double e0 = r.trace.front().energy;
  double drift = 0.0, swing = 0.0;
  double min_z = 1e9, max_z = -1e9;
  for (const VehicleSample& k : r.trace) {
    drift = std::max(drift, std::abs(k.energy - e0));
    const double kinetic = 0.5 * v.body->mass * k.state.velocity.squaredNorm();
    swing = std::max(swing, kinetic);
    min_z = std::min(min_z, k.state.position.z());
    max_z = std::max(max_z, k.state.position.z());
  }
  std::cout << "energy: max |E - E0| = " << drift << " J of kinetic energy up to " << swing
            << " J (" << drift / swing << "); " << r.brief_report() << "\n";
  EXPECT_LT(drift / swing, 1e-6);
  // Not trivially conserved: the vehicle slid down the slope and bounced.
  EXPECT_GT(max_z - min_z, 0.05);
}

TEST(VehicleSimulation, CvodeFailuresAreStatuses) {
  const BPatch flat = surface_of([](double, double) { return 0.0; }, 6.0, 1.0);
  const Vehicle v = ugv();
  const VehicleState s = resting_state(flat, v, Vec2(-4.0, 0.0), 0.0, 2.0);
  VehicleSimulationOptions o;
  o.end_time = 1.0;
  o.relative_tolerance = 1e-300;
  o.absolute_tolerance = 1e-300;
  const VehicleSimulationResult tight = simulate_vehicle(flat, v, s, constant(0.1, 5.0), o);
  EXPECT_EQ(tight.status, SimulationStatus::kSolverFailure);
  EXPECT_NE(tight.message.find("CVODE"), std::string::npos) << tight.message;
  EXPECT_LT(tight.diagnostics.cvode_flag, 0);
  std::cout << tight.message << "\n";
  o = {};
  o.max_steps = 5;
  const VehicleSimulationResult few = simulate_vehicle(flat, v, s, constant(0.1, 5.0), o);
  EXPECT_EQ(few.status, SimulationStatus::kSolverFailure);
  EXPECT_NE(few.message.find("max_steps"), std::string::npos) << few.message;
  EXPECT_EQ(few.diagnostics.steps, 5);
  EXPECT_LT(few.end_time, o.end_time);
}

TEST(VehicleSimulation, IsDeterministic) {
  const BPatch bumpy = surface_of(
      [](double x, double y) { return 0.05 * std::sin(1.3 * x) * std::cos(0.9 * y); }, 6.0, 0.25);
  const Vehicle v = ugv();
  const VehicleController c = [](double t, const VehicleState&) {
    return VehicleControls{0.2 * std::sin(2.0 * t), 4.0, false};
  };
  VehicleSimulationOptions o;
  o.end_time = 2.0;
  const VehicleState s = resting_state(bumpy, v, Vec2(-4.0, 0.0), 0.0, 1.0);
  const VehicleSimulationResult a = simulate_vehicle(bumpy, v, s, c, o);
  const VehicleSimulationResult b = simulate_vehicle(bumpy, v, s, c, o);
  ASSERT_EQ(a.trace.size(), b.trace.size());
  for (std::size_t k = 0; k < a.trace.size(); ++k) {
    EXPECT_EQ(a.trace[k].t, b.trace[k].t);
    EXPECT_EQ(a.trace[k].state.position, b.trace[k].state.position);
    EXPECT_EQ(a.trace[k].state.velocity, b.trace[k].state.velocity);
  }
  EXPECT_EQ(a.diagnostics.steps, b.diagnostics.steps);
  EXPECT_EQ(a.status, b.status);
}

// Full drive up a slope the drive limit cannot climb (g sin 25 deg = 4.1 m/s^2
// > max_accel 3 m/s^2): the vehicle slows from 1.5 m/s and stalls where the
// kinematics say, v0^2 / (2 (g sin a - a_max)) up the slope.
TEST(VehicleSimulation, StallsOnASlopeBeyondTheDriveLimit) {
  const Vehicle v = ugv();
  const double slope = std::tan(25.0 * kPi / 180.0);
  const BPatch ramp = surface_of([slope](double x, double) { return slope * x; }, 4.0, 0.5);
  VehicleSimulationOptions o;
  o.end_time = 5.0;
  const VehicleSimulationResult r = simulate_vehicle(
      ramp, v, resting_state(ramp, v, Vec2(-2.0, 0.0), 0.0, 1.5), constant(0.0, 1e3), o);
  ASSERT_EQ(r.status, SimulationStatus::kStall) << r.message;
  const double decel = v.gravity * std::sin(25.0 * kPi / 180.0) - v.max_accel;
  const double travelled = (r.final.state.position.x() + 2.0) / std::cos(25.0 * kPi / 180.0);
  const double expected = (1.5 * 1.5 - o.stall_speed * o.stall_speed) / (2.0 * decel);
  std::cout << "stall after " << travelled << " m up the slope (kinematics " << expected
            << " m) at t = " << r.end_time << " s\n";
  EXPECT_NEAR(travelled, expected, 0.05 * expected);
}

TEST(VehicleSimulation, DrivingOffTheMapIsLeftTerrain) {
  const BPatch flat = surface_of([](double, double) { return 0.0; }, 3.0, 0.5);
  const Vehicle v = ugv();
  const VehicleSimulationResult r = simulate_vehicle(
      flat, v, resting_state(flat, v, Vec2(0.0, 0.0), 0.0, 2.0), constant(0.0, 0.0));
  ASSERT_EQ(r.status, SimulationStatus::kLeftTerrain) << r.message;
  // The front wheels' centres reach x = 3 m: the c.g. is half a wheelbase behind.
  EXPECT_NEAR(r.final.state.position.x(), 3.0 - v.half_wheelbase, 1e-3);
}

}  // namespace
}  // namespace talus
