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
  // The rigid body's variants 2 and 3 judge friction at the lighter axle (its coupled cones).
  v.axle_friction = model == VehicleModel::kRigidBody && variant >= 2;
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
        // The line query with beta = 0 is the known-state query, widened by kRounding
        // relative to its quadratics' roots: the lighter axle's coupled cones have one root
        // at the lateral force's scale, 2 beta |f_q| away.
        const AccelerationInterval flat =
            set.accelerations_along(g, x, 0.0, 0.0, std::numeric_limits<double>::infinity());
        const double line_tol = tol + 4.0 * AdmissibleSet::kRounding * set.friction_coupling() *
                                          std::abs(v.gravity * g.k_q + g.kappa_g * x);
        EXPECT_NEAR(flat.lower, b.a_min, line_tol);
        EXPECT_NEAR(flat.upper, b.a_max, line_tol);
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

/// The largest |f_t| the lighter axle's own condition admits at normal load R and lateral
/// force Q (AdmissibleSet::friction_coupling): Q² <= (R − tau w)² (μ² − w²/R²), by bisection
/// (its left side falls with w on [0, μ R]).
double axle_root(double mu, double tau, double R, double Q) {
  double lo = 0.0, hi = mu * R;
  for (int k = 0; k < 200; ++k) {
    const double w = 0.5 * (lo + hi);
    const bool holds = (R - tau * w) * (R - tau * w) * (mu * mu - w * w / (R * R)) >= Q * Q;
    (holds ? lo : hi) = w;
  }
  return lo;
}

// With axle_friction the rigid body's friction is judged at its lighter axle: the coupled
// cones lie inside the axle's own condition (checked against its root found by bisection),
// equal it where f_q = 0 (driving and braking straight keep μ R) and where f_t = 0 (every
// speed limit is the friction cone's), and the coupling sits just above tau μ.
TEST(VehiclePhysics, TheLighterAxlesFrictionLiesInsideTheAxlesConditionAndKeepsTheSpeeds) {
  Vehicle ugv;  // data/vehicles/iagnemma_ugv.yaml's geometry, without drive limits
  ugv.model = VehicleModel::kRigidBody;
  ugv.friction = 0.7;
  ugv.cg_height = 0.06;
  ugv.half_track = 0.124;
  ugv.half_wheelbase = 0.135;
  Vehicle axle = ugv;
  axle.axle_friction = true;
  const AdmissibleSet cone(ugv), lighter(axle);
  const double mu = 0.7, tau = 0.06 / 0.135, g = ugv.gravity;
  EXPECT_EQ(cone.friction_coupling(), 0.0);
  EXPECT_GE(lighter.friction_coupling(), tau * mu);
  EXPECT_LE(lighter.friction_coupling(), 1.02 * tau * mu);
  double worst_gap = 0.0;
  for (int i = 0; i <= 40; ++i) {
    // A plane tilted sideways by up to the friction angle: R = g cos θ, Q = g sin θ at rest.
    const double theta = std::atan(mu) * i / 40.0;
    const StationGeometry side{0.0, 0.0, 0.0, std::sin(theta), std::cos(theta)};
    const double R = g * std::cos(theta), Q = g * std::sin(theta);
    const TangentialForceRange f = lighter.tangential_forces(side, 0.0);
    const double exact = axle_root(mu, tau, R, Q);
    EXPECT_LE(f.upper, exact * (1.0 + 1e-12) + 1e-12) << "theta " << theta;
    EXPECT_NEAR(f.lower, -f.upper, 1e-12 * (1.0 + f.upper));
    worst_gap = std::max(worst_gap, (exact - f.upper) / (mu * R));
    if (i == 0) {
      EXPECT_NEAR(f.upper, mu * g, 1e-12 * mu * g);  // f_q = 0: the whole μ R
    }
  }
  EXPECT_LT(worst_gap, 0.1);  // of μ R, at worst near |f_t| = 0.95 μ R
  // The speed limits are the cone's, station by station.
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 300; ++trial) {
    const StationGeometry s = random_station(rng);
    const SpeedLimits a = cone.speed_limits(s), b = lighter.speed_limits(s);
    ASSERT_EQ(a.traversable, b.traversable);
    if (!a.traversable) continue;
    EXPECT_EQ(a.v_max, b.v_max);
    EXPECT_EQ(a.v_min, b.v_min);
    EXPECT_EQ(a.upper_binding, b.upper_binding);
  }
  // A vehicle whose lighter axle unloads before its tyres slide (mu h / l = 1) has no such
  // cone: an InputError naming the key, not a bound outside the axle's condition.
  Vehicle tall = axle;
  tall.friction = 1.0;
  tall.cg_height = tall.half_wheelbase;
  try {
    const AdmissibleSet refused(tall);
    ADD_FAILURE() << "coupling " << refused.friction_coupling();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("axle_friction"), std::string::npos) << e.what();
  }
  // Only a rigid body has axles.
  Vehicle point = axle;
  point.model = VehicleModel::kPointMass;
  EXPECT_THROW(point.validate(), InputError);
}

TEST(VehiclePhysics, ANewModelIsOneSubclass) {
  Vehicle v = vehicle_of(VehicleModel::kRigidBody, 2);
  v.friction = 1.5;         // the cone (1.5 g) leaves both pitch limits binding
  v.axle_friction = false;  // at mu h / l = 1.36 the lighter axle has no cone (see above)
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
