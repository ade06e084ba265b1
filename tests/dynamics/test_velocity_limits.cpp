#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "path_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_around_origin;

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;

Vehicle point_mass(double mu, double h, double b, double gravity = kG) {
  Vehicle v;
  v.friction = mu;
  v.cg_height = h;
  v.half_track = b;
  v.gravity = gravity;
  return v;
}

/// Closed forms evaluated on exact station geometry: equal to rounding. A 1e-3 error in g or mu
/// (the third digit) is 1e9 times this tolerance.
void expect_exact(double actual, double expected, const std::string& what = "") {
  EXPECT_NEAR(actual, expected, 1e-12 * std::abs(expected)) << what;
}

/// Limits sampled along an interpolated cubic-spline circle through 256 points: its curvature is
/// second-order accurate in the point spacing (2e-4 relative at r = 30 m; the test
/// SplineCircleLimitConvergesAtSecondOrder checks the order), so 1e-3 relative here — still half
/// the 0.5 % that a 1 % error in mu or g moves sqrt(mu g r).
void expect_on_spline(double actual, double expected, const std::string& what = "") {
  EXPECT_NEAR(actual, expected, 1e-3 * std::abs(expected)) << what;
}

/// The closed-form cases run on Earth and on Mars (g = 3.71 m/s^2): a hard-coded 9.81 anywhere in
/// the limits fails the second instance.
class ClosedForm : public ::testing::TestWithParam<double> {
 protected:
  double g() const { return GetParam(); }
};

INSTANTIATE_TEST_SUITE_P(Gravity, ClosedForm, ::testing::Values(9.81, 3.71),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return info.param > 5.0 ? std::string("Earth") : std::string("Mars");
                         });

TEST_P(ClosedForm, SpeedLimits_FlatCircleSlidingLimitIsSqrtMuGR) {
  const double r = 25.0, mu = 0.6;
  const SpeedLimits l = speed_limits(point_mass(mu, 0.5, 2.0, g()), {0.0, 1.0 / r, 0.0, 0.0, 1.0});
  EXPECT_TRUE(l.traversable);
  expect_exact(l.v_max, std::sqrt(mu * g() * r));
  EXPECT_EQ(l.upper_binding, Constraint::kSliding);
  EXPECT_EQ(l.v_min, 0.0);
  EXPECT_EQ(l.lower_binding, Constraint::kNone);
  // Turning right is symmetric.
  EXPECT_DOUBLE_EQ(
      speed_limits(point_mass(mu, 0.5, 2.0, g()), {0.0, -1.0 / r, 0.0, 0.0, 1.0}).v_max, l.v_max);
}

TEST_P(ClosedForm, SpeedLimits_FlatCircleTipoverLimitWhenTrackIsNarrow) {
  const double r = 25.0, mu = 0.9, h = 1.0, b = 0.5;  // b/h = 0.5 < mu
  const SpeedLimits l = speed_limits(point_mass(mu, h, b, g()), {0.0, 1.0 / r, 0.0, 0.0, 1.0});
  expect_exact(l.v_max, std::sqrt(g() * r * b / h));
  EXPECT_EQ(l.upper_binding, Constraint::kTipover);
}

TEST(SpeedLimits, StraightFlatGroundHasNoLimitButMaxSpeed) {
  Vehicle v = point_mass(0.7, 0.5, 0.6);
  SpeedLimits l = speed_limits(v, {});
  EXPECT_TRUE(std::isinf(l.v_max));
  EXPECT_EQ(l.upper_binding, Constraint::kNone);
  v.max_speed = 12.0;
  l = speed_limits(v, {});
  EXPECT_DOUBLE_EQ(l.v_max, 12.0);
  EXPECT_EQ(l.upper_binding, Constraint::kMaxSpeed);
}

/// Geometry of a horizontal counter-clockwise circle of radius r on a track
/// banked by theta towards the centre (see the derivation in the test name's
/// issue: q points inwards and down, k_q = -sin theta).
StationGeometry banked_circle(double r, double theta) {
  return {std::sin(theta) / r, std::cos(theta) / r, 0.0, -std::sin(theta), std::cos(theta)};
}

TEST_P(ClosedForm, SpeedLimits_BankedTrackMatchesTheTextbookFormula) {
  const double r = 40.0, mu = 0.5;
  for (double theta_deg : {5.0, 15.0, 25.0}) {
    const double th = theta_deg * kPi / 180.0;
    const SpeedLimits l = speed_limits(point_mass(mu, 0.3, 5.0, g()), banked_circle(r, th));
    const double v2 =
        r * g() * (std::sin(th) + mu * std::cos(th)) / (std::cos(th) - mu * std::sin(th));
    expect_exact(l.v_max, std::sqrt(v2), "bank " + std::to_string(theta_deg));
    EXPECT_EQ(l.upper_binding, Constraint::kSliding);
    EXPECT_EQ(l.v_min, 0.0);  // tan(theta) < mu: it can stand still on the bank
  }
}

TEST_P(ClosedForm, SpeedLimits_SteepBankHasALowerSpeedBound) {
  // tan(35°) = 0.70 > mu = 0.5: too slow and the vehicle slides into the bowl.
  const double r = 40.0, mu = 0.5, th = 35.0 * kPi / 180.0;
  const SpeedLimits l = speed_limits(point_mass(mu, 0.3, 5.0, g()), banked_circle(r, th));
  ASSERT_TRUE(l.traversable);
  const double v2_min =
      r * g() * (std::sin(th) - mu * std::cos(th)) / (std::cos(th) + mu * std::sin(th));
  expect_exact(l.v_min, std::sqrt(v2_min));
  EXPECT_EQ(l.lower_binding, Constraint::kSliding);
  EXPECT_GT(l.v_max, l.v_min);
}

TEST(SpeedLimits, BankSteeperThanTheCrossoverIsUnlimitedAbove) {
  // cos(theta) - mu sin(theta) < 0: friction plus banking hold any speed.
  const double r = 40.0, mu = 0.8, th = 60.0 * kPi / 180.0;
  const SpeedLimits l = speed_limits(point_mass(mu, 0.1, 5.0), banked_circle(r, th));
  EXPECT_TRUE(std::isinf(l.v_max));
  EXPECT_GT(l.v_min, 0.0);
}

TEST_P(ClosedForm, SpeedLimits_CrestContactLimit) {
  const double R = 30.0;
  const Vehicle v = point_mass(1.5, 0.2, 1.0, g());
  const SpeedLimits top = speed_limits(v, {-1.0 / R, 0.0, 0.0, 0.0, 1.0});
  expect_exact(top.v_max, std::sqrt(g() * R));
  EXPECT_EQ(top.upper_binding, Constraint::kContact);
  const double alpha = 0.3;
  const SpeedLimits side = speed_limits(v, {-1.0 / R, 0.0, std::sin(alpha), 0.0, std::cos(alpha)});
  expect_exact(side.v_max, std::sqrt(g() * R * std::cos(alpha)));
  EXPECT_EQ(side.upper_binding, Constraint::kContact);
}

TEST(SpeedLimits, SideSlopeSteeperThanFrictionIsNotTraversable) {
  const double alpha = std::atan(0.8);  // tan = 0.8 > mu = 0.6
  const StationGeometry g{0.0, 0.0, 0.0, std::sin(alpha), std::cos(alpha)};
  const SpeedLimits l = speed_limits(point_mass(0.6, 0.3, 1.0), g);
  EXPECT_FALSE(l.traversable);
  EXPECT_EQ(l.v_max, 0.0);
  EXPECT_EQ(l.upper_binding, Constraint::kSliding);
  EXPECT_FALSE(std::isnan(l.v_min));
  // Stable on friction but tips: b/h = 0.5 < tan = 0.8 < mu = 1.0.
  const SpeedLimits tip = speed_limits(point_mass(1.0, 1.0, 0.5), g);
  EXPECT_FALSE(tip.traversable);
  EXPECT_EQ(tip.upper_binding, Constraint::kTipover);
  // Numerically straight (curvature 1e-15) must read the same, not "traversable above 1e8 m/s".
  const SpeedLimits almost = speed_limits(point_mass(0.6, 0.3, 1.0),
                                          {1e-15, 1e-15, 0.0, std::sin(alpha), std::cos(alpha)});
  EXPECT_FALSE(almost.traversable);
}

TEST_P(ClosedForm, AccelerationBounds_InclinedPlaneUpAndDown) {
  const double mu = 0.7, alpha = 0.2;
  const Vehicle v = point_mass(mu, 0.5, 0.6, g());
  const StationGeometry up{0.0, 0.0, std::sin(alpha), 0.0, std::cos(alpha)};
  const StationGeometry down{0.0, 0.0, -std::sin(alpha), 0.0, std::cos(alpha)};
  for (double speed : {0.0, 5.0, 30.0}) {
    const AccelerationBounds a = acceleration_bounds(v, up, speed);
    ASSERT_TRUE(a.feasible);
    expect_exact(a.a_max, g() * (mu * std::cos(alpha) - std::sin(alpha)));
    expect_exact(a.a_min, -g() * (mu * std::cos(alpha) + std::sin(alpha)));
    const AccelerationBounds d = acceleration_bounds(v, down, speed);
    expect_exact(d.a_max, g() * (mu * std::cos(alpha) + std::sin(alpha)));
    expect_exact(d.a_min, -g() * (mu * std::cos(alpha) - std::sin(alpha)));
    EXPECT_EQ(a.upper_binding, Constraint::kSliding);
  }
}

TEST_P(ClosedForm, AccelerationBounds_DriveAndBrakeLimitTheTractionForce) {
  const double mu = 0.9, alpha = 0.1;
  Vehicle v = point_mass(mu, 0.5, 0.6, g());
  const double drive = 0.2 * g(), brake = 0.4 * g();  // both below mu g: the motors bind
  v.max_accel = drive;
  v.max_decel = brake;
  const AccelerationBounds flat = acceleration_bounds(v, {}, 3.0);
  expect_exact(flat.a_max, drive);
  expect_exact(flat.a_min, -brake);
  EXPECT_EQ(flat.upper_binding, Constraint::kDrive);
  EXPECT_EQ(flat.lower_binding, Constraint::kBrake);
  // Uphill the same drive force leaves g sin(alpha) less for acceleration.
  const AccelerationBounds up =
      acceleration_bounds(v, {0.0, 0.0, std::sin(alpha), 0.0, std::cos(alpha)}, 3.0);
  expect_exact(up.a_max, drive - g() * std::sin(alpha));
  expect_exact(up.a_min, -brake - g() * std::sin(alpha));
}

TEST(AccelerationBounds, SlopeSteeperThanFrictionCannotBeClimbedOrDescendedToAStop) {
  const double mu = 0.5, alpha = std::atan(0.6);
  const Vehicle v = point_mass(mu, 0.5, 0.6);
  for (double speed : {0.0, 2.0, 10.0, 40.0}) {
    EXPECT_LT(
        acceleration_bounds(v, {0.0, 0.0, std::sin(alpha), 0.0, std::cos(alpha)}, speed).a_max,
        0.0);
    EXPECT_GT(
        acceleration_bounds(v, {0.0, 0.0, -std::sin(alpha), 0.0, std::cos(alpha)}, speed).a_min,
        0.0);
  }
}

TEST_P(ClosedForm, AccelerationBounds_InfeasibleSpeedNamesTheConstraint) {
  const double r = 25.0;
  const Vehicle v = point_mass(0.6, 0.5, 2.0, g());
  const StationGeometry g{0.0, 1.0 / r, 0.0, 0.0, 1.0};
  const double v_max = speed_limits(v, g).v_max;
  EXPECT_TRUE(acceleration_bounds(v, g, 0.999 * v_max).feasible);
  const AccelerationBounds over = acceleration_bounds(v, g, 1.01 * v_max);
  EXPECT_FALSE(over.feasible);
  EXPECT_EQ(over.violated, Constraint::kSliding);
  // At the limit the only admissible acceleration is the one that cancels gravity.
  const AccelerationBounds at = acceleration_bounds(v, g, v_max);
  EXPECT_NEAR(at.a_max - at.a_min, 0.0, 1e-6);
}

TEST(RigidBody, LongVehicleAgreesWithThePointMassLaterally) {
  Vehicle pm = point_mass(0.8, 0.6, 0.7);
  Vehicle rb = pm;
  rb.model = VehicleModel::kRigidBody;
  rb.half_wheelbase = 50.0;  // much longer than wide
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    Vec3 up(0.4 * u(rng), 0.4 * u(rng), 1.0);
    up.normalize();
    const StationGeometry g{0.05 * u(rng), 0.05 * u(rng), up.x(), up.y(), up.z()};
    const SpeedLimits a = speed_limits(pm, g), b = speed_limits(rb, g);
    EXPECT_EQ(a.traversable, b.traversable);
    EXPECT_DOUBLE_EQ(a.v_max, b.v_max);
    EXPECT_DOUBLE_EQ(a.v_min, b.v_min);
    EXPECT_EQ(a.upper_binding, b.upper_binding);
    if (a.traversable && std::isfinite(a.v_max)) {
      const double speed = 0.5 * (a.v_min + a.v_max);
      const AccelerationBounds aa = acceleration_bounds(pm, g, speed),
                               bb = acceleration_bounds(rb, g, speed);
      EXPECT_DOUBLE_EQ(aa.a_max, bb.a_max);
      EXPECT_DOUBLE_EQ(aa.a_min, bb.a_min);
    }
  }
}

TEST_P(ClosedForm, RigidBody_PitchesOverUnderBrakingWhenTallAndShort) {
  Vehicle rb = point_mass(0.9, 1.0, 0.8, g());
  rb.model = VehicleModel::kRigidBody;
  rb.half_wheelbase = 0.4;  // l/h = 0.4 < mu = 0.9
  const AccelerationBounds a = acceleration_bounds(rb, {}, 10.0);
  expect_exact(a.a_min, -g() * 0.4);
  expect_exact(a.a_max, g() * 0.4);
  EXPECT_EQ(a.lower_binding, Constraint::kPitchover);
  // The point mass ignores pitch and brakes at mu g.
  const AccelerationBounds pm = acceleration_bounds(point_mass(0.9, 1.0, 0.8, g()), {}, 10.0);
  expect_exact(pm.a_min, -g() * 0.9);
}

TEST(VelocityLimits, FlatCirclePathAtEveryStation) {
  const BPatch flat =
      BPatch::interpolate(grid_around_origin([](double, double) { return 100.0; }, 40, 2.0));
  const double r = 30.0, mu = 0.7;
  const SurfacePath path(flat, path_test::circle(r, 256));
  const VelocityLimits limits(point_mass(mu, 0.5, 1.0), path, 500);
  ASSERT_EQ(limits.size(), 500u);
  EXPECT_EQ(limits.first_untraversable(), limits.size());
  for (std::size_t k = 0; k < limits.size(); ++k) {
    expect_on_spline(limits.limits(k).v_max, std::sqrt(mu * kG * r),
                     "station " + std::to_string(k));
  }
  EXPECT_NEAR(limits.frame(limits.size() - 1).s, 2 * kPi * r, 1e-6);
}

double max_relative_error_on_circle(int points) {
  const BPatch flat =
      BPatch::interpolate(grid_around_origin([](double, double) { return 100.0; }, 40, 2.0));
  const double r = 30.0, mu = 0.7, exact = std::sqrt(mu * kG * r);
  const VelocityLimits limits(point_mass(mu, 0.5, 1.0),
                              SurfacePath(flat, path_test::circle(r, points)), 400);
  double worst = 0.0;
  for (std::size_t k = 0; k < limits.size(); ++k) {
    worst = std::max(worst, std::abs(limits.limits(k).v_max - exact) / exact);
  }
  return worst;
}

TEST(VelocityLimits, SplineCircleLimitConvergesAtSecondOrder) {
  // The only error is the spline's curvature, O(h^2) in the point spacing h: halving h divides
  // the error by about 4. A discretisation error of any other origin would not shrink.
  double previous = max_relative_error_on_circle(32);
  for (int points : {64, 128, 256}) {
    const double error = max_relative_error_on_circle(points);
    const double order = std::log2(previous / error);
    EXPECT_GT(order, 1.8) << points << " points: error " << error;
    previous = error;
  }
  EXPECT_LT(previous, 5e-4);
}

TEST(VelocityLimits, BankedBowlPathAgreesWithTheFormula) {
  const double theta = 15.0 * kPi / 180.0, r = 20.0, mu = 0.5;
  const BPatch cone = BPatch::interpolate(grid_around_origin(
      [&](double x, double y) { return std::tan(theta) * std::hypot(x, y); }, 30, 0.5));
  const SurfacePath path(cone, path_test::circle(r, 256));
  const VelocityLimits limits(point_mass(mu, 0.3, 5.0), path, 200);
  const double v2 =
      r * kG * (std::sin(theta) + mu * std::cos(theta)) / (std::cos(theta) - mu * std::sin(theta));
  for (std::size_t k = 0; k < limits.size(); k += 17) {
    expect_on_spline(limits.limits(k).v_max, std::sqrt(v2));
  }
}

TEST(VelocityLimits, FastSamplingArcLengthMatchesTheExactMap) {
  const BPatch hills = BPatch::interpolate(grid_around_origin(
      [](double x, double y) { return 3 * std::sin(0.1 * x) * std::cos(0.13 * y); }, 40, 1.0));
  const SurfacePath path(
      hills, Curve2::interpolate({Vec2(-35, -30), Vec2(-10, 5), Vec2(12, -8), Vec2(33, 30)}));
  for (std::size_t n : {5u, 200u, 5000u}) {
    std::vector<PathFrame> frames;
    path.sample_uniform_parameter(n, frames);
    ASSERT_EQ(frames.size(), n);
    for (std::size_t k = 0; k < n; k += std::max<std::size_t>(1, n / 7)) {
      EXPECT_NEAR(frames[k].s, path.frame_at_parameter(frames[k].parameter).s, 1e-6)
          << n << " " << k;
    }
    EXPECT_DOUBLE_EQ(frames.back().s, path.length());
  }
}

TEST(VehicleFile, ParsesYamlAndJson) {
  const Vehicle v = parse_vehicle(
      "model: rigid_body\nfriction: 0.8\ncg_height: 0.5\nhalf_track: 0.6\nhalf_wheelbase: 1.2\n"
      "max_speed: 15\nmax_accel: 3\nmax_decel: 6\n",
      "v.yaml");
  EXPECT_EQ(v.model, VehicleModel::kRigidBody);
  EXPECT_DOUBLE_EQ(v.gravity, 9.81);
  EXPECT_DOUBLE_EQ(v.half_wheelbase, 1.2);
  EXPECT_DOUBLE_EQ(v.max_decel, 6.0);
  const Vehicle j = parse_vehicle(
      R"({"model": "point_mass", "gravity": 3.71, "friction": 0.5, "cg_height": 0.4, "half_track": 0.5})",
      "v.json");
  EXPECT_EQ(j.model, VehicleModel::kPointMass);
  EXPECT_DOUBLE_EQ(j.gravity, 3.71);
  EXPECT_TRUE(std::isinf(j.max_speed));
}

TEST(VehicleFile, RejectsBadFilesWithClearMessages) {
  const std::string base = "model: point_mass\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\n";
  const auto expect_error = [](const std::string& text, const std::string& fragment) {
    try {
      parse_vehicle(text, "bad.yaml");
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    }
  };
  expect_error(base + "wheels: 4\n", "unknown key 'wheels'");
  expect_error("model: point_mass\ncg_height: 0.5\nhalf_track: 0.6\n",
               "missing required key 'friction'");
  expect_error("model: rigid_body\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\n",
               "half_wheelbase");
  expect_error("friction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\n", "'model'");
  expect_error("model: tank\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\n",
               "point_mass or rigid_body");
  expect_error("model: point_mass\nfriction: 0\ncg_height: 0.5\nhalf_track: 0.6\n",
               "friction must be a positive");
  expect_error("model: point_mass\nfriction: -0.3\ncg_height: 0.5\nhalf_track: 0.6\n", "friction");
  expect_error("model: point_mass\nfriction: 0.7\ncg_height: -1\nhalf_track: 0.6\n", "cg_height");
  expect_error("model: point_mass\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0\n", "half_track");
  expect_error(base + "max_speed: -3\n", "max_speed");
  expect_error(base + "gravity: fast\n", "must be a number");
  expect_error("[1, 2, 3]", "mapping");
  expect_error("model: [unclosed\n", "not valid YAML");
  EXPECT_THROW(load_vehicle("/nonexistent/vehicle.yaml"), InputError);
}

}  // namespace
}  // namespace talus

namespace talus {
namespace {

TEST(SpeedLimits, LeanIntervalAgreesWithTheFullLimits) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const double b : {0.3, 0.6, 2.0}) {  // b/h below, near and above mu
    Vehicle v;
    v.friction = 0.7;
    v.cg_height = 0.5;
    v.half_track = b;
    v.max_speed = 25.0;
    for (int k = 0; k < 500; ++k) {
      Vec3 up(0.6 * u(rng), 0.6 * u(rng), 1.0);
      up.normalize();
      const StationGeometry g{0.1 * u(rng), 0.1 * u(rng), up.x(), up.y(), up.z()};
      const SpeedLimits full = speed_limits(v, g);
      const SquaredSpeedInterval lean = admissible_squared_speeds(v, g);
      ASSERT_EQ(full.traversable, !lean.empty());
      if (!full.traversable) continue;
      EXPECT_NEAR(std::sqrt(lean.upper), full.v_max, 1e-12 * (1 + full.v_max));
      EXPECT_NEAR(std::sqrt(lean.lower), full.v_min, 1e-9 * (1 + full.v_min));
    }
  }
}

}  // namespace
}  // namespace talus
