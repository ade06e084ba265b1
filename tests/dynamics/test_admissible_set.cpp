// One conformance test for every vehicle model (kVehicleModels): the
// AdmissibleSet's queries must agree with each other at random stations and
// states, whatever the model's conditions are. Plus the extension point: a
// model defined here, in one class, and a model that breaks the contract.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "talus/core/error.hpp"
#include "talus/dynamics/vehicle_physics.hpp"

namespace talus {
namespace {

Vehicle vehicle_of(VehicleModel model, int variant) {
  Vehicle v;
  v.model = model;
  v.friction = 0.5 + 0.15 * variant;
  v.cg_height = 0.5;
  v.half_track = 0.25 + 0.2 * variant;      // b/h below, near and above mu
  v.half_wheelbase = 0.15 + 0.2 * variant;  // l/h below and above mu
  if (variant % 2 == 1) {
    v.max_speed = 12.0;
    v.max_accel = 2.5;
    v.max_decel = 5.0;
  }
  return v;
}

StationGeometry random_station(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 up(0.5 * u(rng), 0.5 * u(rng), 1.0);
  up.normalize();
  return {0.08 * u(rng), 0.08 * u(rng), up.x(), up.y(), up.z()};
}

class EveryVehicleModel : public ::testing::TestWithParam<VehicleModel> {};

TEST_P(EveryVehicleModel, QueriesAgreeAtRandomStations) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int variant = 0; variant < 4; ++variant) {
    const Vehicle v = vehicle_of(GetParam(), variant);
    const AdmissibleSet set(v);
    for (int trial = 0; trial < 400; ++trial) {
      const StationGeometry g = random_station(rng);
      const SpeedLimits limits = set.speed_limits(g);
      const SquaredSpeedInterval lean = set.squared_speeds(g);
      ASSERT_EQ(limits.traversable, !lean.empty());
      if (!limits.traversable || !std::isfinite(limits.v_max)) continue;
      EXPECT_NEAR(std::sqrt(lean.upper), limits.v_max, 1e-9 * (1 + limits.v_max));
      for (const double f : {0.0, 0.25, 0.5, 0.999}) {
        const double speed = limits.v_min + f * (limits.v_max - limits.v_min);
        const double x = speed * speed;
        // Every speed inside the limits admits some s̈ ...
        const AccelerationBounds b = set.acceleration_bounds(g, speed);
        ASSERT_TRUE(b.feasible) << to_string(b.violated) << " at " << speed;
        ASSERT_LE(b.a_min, b.a_max);
        // ... and the step solver's known-state interval is the same one,
        // widened by rounding only.
        const AccelerationInterval at = set.accelerations_at(g, x);
        const double tol = 1e-8 * (1 + std::abs(b.a_min) + std::abs(b.a_max));
        EXPECT_NEAR(at.lower, b.a_min, tol);
        EXPECT_NEAR(at.upper, b.a_max, tol);
        // The line query with beta = 0 is the known-state query.
        const AccelerationInterval flat =
            set.accelerations_along(g, x, 0.0, 0.0, std::numeric_limits<double>::infinity());
        EXPECT_NEAR(flat.lower, b.a_min, tol);
        EXPECT_NEAR(flat.upper, b.a_max, tol);
        // Along a step's line x + beta u, every u inside the interval lands on
        // an admissible state (up to the kRounding slack of the state bounds,
        // hence the clamp) with u admissible there; just beyond, not.
        const double beta = 2.0 * (0.05 + unit(rng));
        const double lo = limits.v_min * limits.v_min, hi = limits.v_max * limits.v_max;
        const AccelerationInterval line = set.accelerations_along(g, x, beta, lo, hi);
        if (line.empty()) continue;
        for (const double w : {0.0, 0.5, 1.0}) {
          const double u = line.lower + w * (line.upper - line.lower);
          const double end = std::clamp(x + beta * u, lo, hi);
          const AccelerationBounds e = set.acceleration_bounds(g, std::sqrt(end));
          ASSERT_TRUE(e.feasible) << to_string(e.violated) << " at u " << u << ", x " << end;
          EXPECT_GE(u, e.a_min - 1e-6 * (1 + std::abs(u)));
          EXPECT_LE(u, e.a_max + 1e-6 * (1 + std::abs(u)));
        }
        const double beyond = line.upper + 1e-4 * (1 + std::abs(line.upper));
        const double end = x + beta * beyond;
        if (end <= hi) {
          const AccelerationBounds e = set.acceleration_bounds(g, std::sqrt(std::max(end, 0.0)));
          EXPECT_TRUE(!e.feasible || beyond > e.a_max || beyond < e.a_min)
              << "the line's interval is not tight at its upper end";
        }
      }
      // The traction range at a speed is the acceleration bounds plus g k_t.
      const double mid = 0.5 * (limits.v_min + limits.v_max);
      const TangentialForceRange f = set.tangential_forces(g, mid * mid);
      const AccelerationBounds b = set.acceleration_bounds(g, mid);
      EXPECT_NEAR(f.upper - v.gravity * g.k_t, b.a_max, 1e-12 * (1 + std::abs(b.a_max)));
      EXPECT_NEAR(f.lower - v.gravity * g.k_t, b.a_min, 1e-12 * (1 + std::abs(b.a_min)));
      EXPECT_EQ(f.upper_binding, b.upper_binding);
    }
  }
}

TEST_P(EveryVehicleModel, TractionConditionsRemoveNoSpeed) {
  const AdmissibleSet set(vehicle_of(GetParam(), 1));
  for (const ForceCondition& c : set.traction_conditions()) {
    EXPECT_NE(c.t, 0.0);
    EXPECT_GE(c.c, 0.0) << to_string(c.constraint);
  }
  EXPECT_EQ(set.conditions().front().constraint, Constraint::kContact);
  EXPECT_EQ(vehicle_physics(GetParam()).name(),
            GetParam() == VehicleModel::kPointMass ? "point_mass" : "rigid_body");
}

INSTANTIATE_TEST_SUITE_P(VehiclePhysics, EveryVehicleModel, ::testing::ValuesIn(kVehicleModels),
                         [](const auto& info) {
                           return std::string(vehicle_physics(info.param).name());
                         });

/// A model in one class: a rigid body whose centre of mass sits ahead of the
/// wheelbase's middle (front axle l_f, rear l_r), so it pitches over forwards
/// under braking earlier than backwards under acceleration.
class OffsetRigidBody final : public VehiclePhysics {
 public:
  std::string_view name() const override { return "offset_rigid_body"; }

 protected:
  void add_model_conditions(const Vehicle& v, ForceConditions& out) const override {
    out.add_lateral_ratio(Constraint::kTipover, v.half_track / v.cg_height);
    const double front = 0.2, rear = 0.6;                                   // [m]
    out.add({Constraint::kPitchover, -1.0, 0.0, rear / v.cg_height, 0.0});  // accelerating
    out.add({Constraint::kPitchover, 1.0, 0.0, front / v.cg_height, 0.0});  // braking
  }
};

TEST(VehiclePhysics, ANewModelIsOneSubclass) {
  Vehicle v = vehicle_of(VehicleModel::kRigidBody, 2);
  v.friction = 1.5;  // the cone (1.5 g) leaves both pitch limits binding
  const AdmissibleSet set = OffsetRigidBody().admissible_set(v);
  const AccelerationBounds level = set.acceleration_bounds({}, 3.0);
  ASSERT_TRUE(level.feasible);
  EXPECT_NEAR(level.a_max, v.gravity * 0.6 / 0.5, 1e-12);
  EXPECT_NEAR(level.a_min, -v.gravity * 0.2 / 0.5, 1e-12);
  EXPECT_EQ(level.lower_binding, Constraint::kPitchover);
  // Its speed limits are the rigid body's: pitch-over removes no speed.
  const AdmissibleSet rigid(v);
  std::mt19937_64 rng(5);
  for (int k = 0; k < 100; ++k) {
    const StationGeometry g = random_station(rng);
    EXPECT_EQ(set.speed_limits(g).v_max, rigid.speed_limits(g).v_max);
  }
}

class SpeedRemovingModel final : public VehiclePhysics {
 public:
  std::string_view name() const override { return "broken"; }

 protected:
  void add_model_conditions(const Vehicle&, ForceConditions& out) const override {
    out.add({Constraint::kDrive, -1.0, 0.0, 0.0, -1.0});  // f_t <= -1: f_t = 0 inadmissible
  }
};

TEST(VehiclePhysics, RejectsATractionConditionThatRemovesSpeeds) {
  EXPECT_THROW(SpeedRemovingModel().admissible_set(Vehicle{}), std::logic_error);
}

TEST(VehiclePhysics, ValidatesTheVehicle) {
  Vehicle v;
  v.friction = -1.0;
  EXPECT_THROW(AdmissibleSet{v}, InputError);
}

}  // namespace
}  // namespace talus
