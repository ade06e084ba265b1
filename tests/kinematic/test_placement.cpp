#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "random_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"
#include "talus/kinematic/hait/placement.hpp"
#include "talus/kinematic/hait/robot_validity.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using random_test::uniform;

using terrain_test::grid_around_origin;
constexpr double kPi = std::numbers::pi;

/// A 1.2 m x 0.8 m four-wheeled robot.
WheeledRobot rover() {
  WheeledRobot r;
  r.wheels = {{0.6, 0.4}, {0.6, -0.4}, {-0.6, -0.4}, {-0.6, 0.4}};
  r.cg_height = 0.45;
  r.max_spring_extension = 0.1;
  r.max_roll = 0.35;
  r.max_pitch = 0.4;
  return r;
}

ArticulatedChassis chassis() {
  ArticulatedChassis c;
  c.half_axle_width = 0.45;
  c.axle_spacing = 0.6;
  c.max_axle_roll_difference = 0.35;
  c.max_roll = 0.4;
  c.min_pitch = -0.4;
  c.max_pitch = 0.4;
  c.min_body_angle = kPi - 0.5;
  c.max_body_angle = kPi + 0.5;
  return c;
}

RuledTerrain plane(double gx, double gy, double half = 6.0, double cell = 0.25) {
  return RuledTerrain(
      grid_around_origin([=](double x, double y) { return 1.0 + gx * x + gy * y; }, half, cell));
}

/// Smooth rough terrain: a sum of six plane waves with seeded random directions and phases.
RuledTerrain rough(std::uint64_t seed, double amplitude, double half = 8.0) {
  std::mt19937_64 rng(seed);
  struct Wave {
    double kx, ky, phase, a;
  };
  std::vector<Wave> waves;
  for (int k = 0; k < 6; ++k) {
    const double dir = 2 * kPi * uniform(rng);
    const double wavelength = 2.0 + 6.0 * uniform(rng);
    waves.push_back({2 * kPi / wavelength * std::cos(dir), 2 * kPi / wavelength * std::sin(dir),
                     2 * kPi * uniform(rng), amplitude * (0.5 + uniform(rng))});
  }
  return RuledTerrain(grid_around_origin(
      [=](double x, double y) {
        double z = 0.0;
        for (const Wave& w : waves) z += w.a * std::sin(w.kx * x + w.ky * y + w.phase);
        return z;
      },
      half, 0.25));
}

// ---------------------------------------------------------------- Place_robot

TEST(PlaceRobot, PlaneGivesItsAttitudeAndRestSprings) {
  const double gx = 0.15, gy = -0.1;
  const RuledTerrain t = plane(gx, gy);
  for (double theta : {0.0, 0.7, 2.0, -2.5, kPi}) {
    const RobotPlacement p = place_robot(rover(), t, 0.3, -0.2, theta);
    ASSERT_EQ(p.status, PlacementStatus::kConverged) << theta;
    const double sf = gx * std::cos(theta) + gy * std::sin(theta);
    const double sg = -gx * std::sin(theta) + gy * std::cos(theta);
    const double norm = std::sqrt(1 + gx * gx + gy * gy);
    EXPECT_NEAR(p.pitch, std::atan(sf), 1e-9) << theta;
    EXPECT_NEAR(p.roll, std::asin(sg / norm), 1e-9) << theta;
    // G sits cg_height from the plane along its normal.
    EXPECT_NEAR(p.position.z(), 1.0 + gx * 0.3 - gy * 0.2 + 0.45 * norm, 1e-9);
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(p.extensions[j], 0.0, 1e-9);
    EXPECT_LE(p.iterations, 2);
    // The body's up axis is the plane's normal.
    const Vec3 n = Vec3(-gx, -gy, 1.0).normalized();
    EXPECT_NEAR(p.rotation().col(2).dot(n), 1.0, 1e-12);
  }
}

TEST(PlaceRobot, StepUnderTheLeftWheelsGivesItsRoll) {
  // Ground at 0 for y <= 0 and at s for y >= 0.25 (one cell of ramp between):
  // heading east, the left wheels (v = +0.4) stand s higher than the right ones,
  // and the springs rest when 2 * 0.4 * sin(roll) = s.
  const double s = 0.2;
  const RuledTerrain t(
      grid_around_origin([=](double, double y) { return y > 0.01 ? s : 0.0; }, 4.0, 0.25));
  const RobotPlacement p = place_robot(rover(), t, 0.0, 0.0, 0.0);
  ASSERT_TRUE(usable(p.status));
  EXPECT_NEAR(p.roll, std::asin(s / 0.8), 1e-5);
  EXPECT_NEAR(p.pitch, 0.0, 1e-9);
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(p.extensions[j], 0.0, 1e-5);
  // Heading west the same step is on the right: the roll changes sign.
  const RobotPlacement q = place_robot(rover(), t, 0.0, 0.0, kPi);
  EXPECT_NEAR(q.roll, -std::asin(s / 0.8), 1e-5);
}

TEST(PlaceRobot, TwistedGroundLoadsTheSpringsInTwist) {
  // z = k x y is bilinear, hence exact on the ruled patches: the best plane is
  // level and each spring takes up the ground height under its wheel.
  const double k = 0.2;
  const RuledTerrain t(
      grid_around_origin([=](double x, double y) { return k * x * y; }, 4.0, 0.25));
  const WheeledRobot r = rover();
  const RobotPlacement p = place_robot(r, t, 0.0, 0.0, 0.0);
  ASSERT_EQ(p.status, PlacementStatus::kConverged);
  EXPECT_NEAR(p.roll, 0.0, 1e-9);
  EXPECT_NEAR(p.pitch, 0.0, 1e-9);
  for (int j = 0; j < 4; ++j)
    EXPECT_NEAR(p.extensions[j], k * r.wheels[j].x() * r.wheels[j].y(), 1e-9) << j;
  EXPECT_NEAR(p.energy, 4 * std::pow(k * 0.24, 2), 1e-12);
}

TEST(PlaceRobot, EnergyNeverExceedsTheLevelStart) {
  const RuledTerrain t = rough(7, 0.15);
  std::mt19937_64 rng(11);
  for (int n = 0; n < 200; ++n) {
    const double x = -6 + 12 * uniform(rng), y = -6 + 12 * uniform(rng);
    const double th = 2 * kPi * uniform(rng);
    const RobotPlacement p = place_robot(rover(), t, x, y, th);
    ASSERT_TRUE(usable(p.status));
    // One plane fit already beats (or ties) the level start; the result is the best found.
    RobotPlacementOptions one;
    one.max_iterations = 1;
    const RobotPlacement first = place_robot(rover(), t, x, y, th, one);
    EXPECT_LE(p.energy, first.energy + 1e-15);
    // Each contact lies on the terrain.
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR(p.contacts[j].z(), t.elevation(p.contacts[j].head<2>()), 1e-12);
  }
}

TEST(PlaceRobot, OffMapAndNoDataAreStatuses) {
  const RuledTerrain t = plane(0.1, 0.0, 3.0);
  EXPECT_EQ(place_robot(rover(), t, 2.9, 0.0, 0.0).status, PlacementStatus::kOffMap);
  EXPECT_EQ(place_robot(rover(), t, 10.0, 0.0, 0.0).status, PlacementStatus::kOffMap);
  ElevationGrid g = grid_around_origin([](double, double) { return 0.0; }, 3.0, 0.25);
  // A void node under the front-left wheel at (0.6, 0.4).
  g.set_void(14, 14);
  EXPECT_EQ(place_robot(rover(), RuledTerrain(g), 0.0, 0.0, 0.0).status, PlacementStatus::kNoData);
  EXPECT_THROW(place_robot(rover(), t, std::nan(""), 0.0, 0.0), InputError);
  RobotPlacementOptions bad;
  bad.max_iterations = 0;
  EXPECT_THROW(place_robot(rover(), t, 0.0, 0.0, 0.0, bad), InputError);
}

// ---------------------------------------------------------------- Place_axle

TEST(PlaceAxle, PlaneOfSlopeAlphaInOneIteration) {
  for (double theta : {0.0, 0.9, -2.2}) {
    for (double alpha : {0.05, -0.2, 0.4}) {
      // Rises by tan(alpha) per metre to the left of the heading, and by 0.3 ahead.
      const Vec2 f(std::cos(theta), std::sin(theta)), g(-std::sin(theta), std::cos(theta));
      const Vec2 grad = std::tan(alpha) * g + 0.3 * f;
      const RuledTerrain t = plane(grad.x(), grad.y());
      const AxlePlacement a = place_axle(t, 0.45, 0.4, 0.1, theta);
      ASSERT_EQ(a.status, PlacementStatus::kConverged);
      EXPECT_EQ(a.iterations, 1);
      EXPECT_NEAR(a.roll, alpha, 1e-12);
      EXPECT_NEAR(a.z, 1.0 + grad.x() * 0.4 + grad.y() * 0.1, 1e-12);
    }
  }
  // Level across the axle: nothing to do.
  const AxlePlacement level = place_axle(plane(0.3, 0.0), 0.45, 0.0, 0.0, 0.0);
  EXPECT_EQ(level.iterations, 0);
  EXPECT_NEAR(level.roll, 0.0, 1e-15);
}

TEST(PlaceAxle, RoughTerrainSolvesEquationTwo) {
  const RuledTerrain t = rough(3, 0.2);
  std::mt19937_64 rng(5);
  const double l = 0.45;
  for (int n = 0; n < 300; ++n) {
    const double x = -6 + 12 * uniform(rng), y = -6 + 12 * uniform(rng);
    const double th = 2 * kPi * uniform(rng);
    const AxlePlacement a = place_axle(t, l, x, y, th);
    ASSERT_EQ(a.status, PlacementStatus::kConverged);
    const Vec2 off = l * std::cos(a.roll) * Vec2(-std::sin(th), std::cos(th));
    const double zl = t.elevation(Vec2(x, y) + off), zr = t.elevation(Vec2(x, y) - off);
    EXPECT_NEAR(2 * l * std::sin(a.roll) - (zl - zr), 0.0, 1e-6);
    EXPECT_NEAR(a.z, 0.5 * (zl + zr), 1e-12);
  }
}

// ---------------------------------------------------------------- chassis

TEST(PlaceChassis, PlaneGivesEqualAxleRollsAndThePlanePitch) {
  const double gx = -0.12, gy = 0.2;
  const RuledTerrain t = plane(gx, gy);
  for (double theta : {0.0, 0.6, 2.5, -1.3}) {
    const ChassisPlacement p = place_chassis(chassis(), t, 0.2, 0.3, theta);
    ASSERT_EQ(p.status, PlacementStatus::kConverged);
    const double sf = gx * std::cos(theta) + gy * std::sin(theta);
    const double sg = -gx * std::sin(theta) + gy * std::cos(theta);
    EXPECT_NEAR(p.roll_middle, std::atan(sg), 1e-12);
    EXPECT_NEAR(p.roll_front, p.roll_middle, 1e-12);
    EXPECT_NEAR(p.roll_rear, p.roll_middle, 1e-12);
    EXPECT_NEAR(p.pitch(), std::atan(sf), 1e-9);
    EXPECT_NEAR(p.pitch_front, -p.pitch_rear, 1e-9);
    EXPECT_NEAR(p.body_angle(), kPi, 1e-9);
    EXPECT_NEAR(p.z, 1.0 + gx * 0.2 + gy * 0.3, 1e-12);
    // Place_axle once for the middle; for each other axle once at ψ = 0 and once
    // at β, which on a plane already solves G(β) = 0.
    EXPECT_EQ(p.axle_placements, 1 + 2 * 2);
  }
}

TEST(PlaceChassis, ValleyBendsTheBodiesAndRidgeTheOtherWay) {
  for (double c : {0.3, -0.3}) {
    const RuledTerrain t(
        grid_around_origin([=](double x, double) { return c * x * x; }, 4.0, 0.05));
    const ChassisPlacement p = place_chassis(chassis(), t, 0.0, 0.0, 0.0);
    ASSERT_EQ(p.status, PlacementStatus::kConverged);
    // The outer axles satisfy d sin ψ = c (d cos ψ)^2 on z = c x^2 (up to the bilinear error).
    const double d = 0.6;
    EXPECT_NEAR(d * std::sin(p.pitch_front), c * std::pow(d * std::cos(p.pitch_front), 2), 1e-3);
    EXPECT_NEAR(p.pitch_front, p.pitch_rear, 1e-9);
    EXPECT_NEAR(p.pitch(), 0.0, 1e-9);
    EXPECT_EQ(p.body_angle() > kPi, c > 0);
  }
}

TEST(PlaceOtherAxle, DirectionAndErrors) {
  const RuledTerrain t = plane(0.25, 0.0);
  const OtherAxlePlacement f = place_other_axle(t, chassis(), 0.0, 0.0, 1.0, 0.0, +1);
  const OtherAxlePlacement r = place_other_axle(t, chassis(), 0.0, 0.0, 1.0, 0.0, -1);
  EXPECT_NEAR(f.pitch, std::atan(0.25), 1e-9);
  EXPECT_NEAR(r.pitch, -std::atan(0.25), 1e-9);
  EXPECT_NEAR(f.center.x(), 0.6 * std::cos(f.pitch), 1e-12);
  EXPECT_NEAR(r.center.x(), -0.6 * std::cos(r.pitch), 1e-12);
  EXPECT_EQ(f.iterations, 1);
  EXPECT_THROW(place_other_axle(t, chassis(), 0.0, 0.0, 1.0, 0.0, 0), InputError);
  AxlePlacementOptions bad;
  bad.tolerance = 0.0;
  EXPECT_THROW(place_chassis(chassis(), t, 0.0, 0.0, 0.0, bad), InputError);
  EXPECT_THROW(place_axle(t, 0.45, 0.0, 0.0, 0.0, bad), InputError);
  EXPECT_EQ(place_chassis(chassis(), t, 5.9, 0.0, 0.0).status, PlacementStatus::kOffMap);
}

// ---------------------------------------------------------------- preprocessing table

TEST(ChassisTable, EqualsDirectPlacementAtNodesAndSlicesAndInterpolatesBetween) {
  const RuledTerrain t = rough(21, 0.15, 4.0);
  ChassisTableOptions opt;
  opt.theta_slices = 12;
  const ChassisPlacementTable table(chassis(), t, opt);
  const ElevationGrid& g = t.grid();
  EXPECT_EQ(table.diagnostics().placements, static_cast<long long>(12 * g.ncols() * g.nrows()));
  EXPECT_EQ(table.diagnostics().slices, 12);
  EXPECT_GT(table.diagnostics().seconds, 0.0);
  std::mt19937_64 rng(9);
  for (int n = 0; n < 100; ++n) {
    const auto i = static_cast<std::size_t>(8 + uniform(rng) * (g.ncols() - 16));
    const auto j = static_cast<std::size_t>(8 + uniform(rng) * (g.nrows() - 16));
    const int k = static_cast<int>(uniform(rng) * 12);
    const Vec2 p = g.node_position(i, j);
    const double th0 = table.slice_angle(k), th1 = table.slice_angle((k + 1) % 12);
    const AxlePlacement direct0 = place_axle(t, 0.45, p.x(), p.y(), th0);
    const AxlePlacement direct1 = place_axle(t, 0.45, p.x(), p.y(), th1);
    const AxlePlacement at0 = table.axle(p.x(), p.y(), th0);
    ASSERT_TRUE(usable(at0.status));
    EXPECT_NEAR(at0.z, direct0.z, 1e-12);
    EXPECT_NEAR(at0.roll, direct0.roll, 1e-12);
    // A quarter of the way to the next slice: linear in θ.
    const double th = th0 + 0.25 * (2 * kPi / 12);
    const AxlePlacement mid = table.axle(p.x(), p.y(), th + 4 * kPi);  // wraps
    EXPECT_NEAR(mid.z, 0.75 * direct0.z + 0.25 * direct1.z, 1e-12);
    EXPECT_NEAR(mid.roll, 0.75 * direct0.roll + 0.25 * direct1.roll, 1e-12);
    // Half-way across a cell: the mean of the two nodes (bilinear).
    const Vec2 q = 0.5 * (p + g.node_position(i + 1, j));
    const AxlePlacement side = table.axle(q.x(), q.y(), th0);
    const AxlePlacement next = place_axle(t, 0.45, q.x() + 0.125, q.y(), th0);
    EXPECT_NEAR(side.roll, 0.5 * (direct0.roll + next.roll), 1e-12);
  }
  EXPECT_EQ(table.axle(100.0, 0.0, 0.0).status, PlacementStatus::kOffMap);
  EXPECT_THROW((void)table.place_interval(0.0, 0.0, 0.0), InputError);
}

TEST(ChassisTable, ChassisOnAPlaneMatchesDirectPlacement) {
  const RuledTerrain t = plane(0.1, -0.15);
  ChassisTableOptions opt;
  opt.theta_slices = 8;
  const ChassisPlacementTable table(chassis(), t, opt);
  for (double theta : {0.0, 0.3, 1.9, 4.0}) {
    const ChassisPlacement a = table.place(0.37, -0.21, theta);
    const ChassisPlacement b = place_chassis(chassis(), t, 0.37, -0.21, theta);
    ASSERT_TRUE(usable(a.status));
    // Roll varies with θ like atan(sg(θ)), which the slices interpolate linearly;
    // elevations are exact (bilinear of a plane).
    EXPECT_NEAR(a.z, b.z, 1e-12);
    EXPECT_NEAR(a.roll_middle, b.roll_middle, 0.02);
    EXPECT_NEAR(a.pitch(), b.pitch(), 1e-9);
  }
}

TEST(ChassisTable, ChassisOnRoughTerrainIsCloseToDirect) {
  const RuledTerrain t = rough(4, 0.1, 4.0);
  ChassisTableOptions opt;
  opt.theta_slices = 72;
  const ChassisPlacementTable table(chassis(), t, opt);
  std::mt19937_64 rng(2);
  for (int n = 0; n < 100; ++n) {
    const double x = -2.5 + 5 * uniform(rng), y = -2.5 + 5 * uniform(rng);
    const double th = 2 * kPi * uniform(rng);
    const ChassisPlacement a = table.place(x, y, th);
    const ChassisPlacement b = place_chassis(chassis(), t, x, y, th);
    ASSERT_TRUE(usable(a.status));
    EXPECT_NEAR(a.z, b.z, 0.02);
    EXPECT_NEAR(a.roll(), b.roll(), 0.03);
    EXPECT_NEAR(a.pitch(), b.pitch(), 0.03);
  }
}

// ---------------------------------------------------------------- validity

TEST(Validity, RigidBodyLimitsAndMargins) {
  const WheeledRobot r = rover();
  const RobotPlacement flat = place_robot(r, plane(0.0, 0.0), 0.0, 0.0, 0.0);
  Validity v = check_validity(r, flat);
  EXPECT_TRUE(v.valid());
  EXPECT_NEAR(v.margin, 1.0, 1e-9);
  // Side slope: roll = asin(s / sqrt(1 + s^2)) = atan(s); margin 1 - roll / max_roll.
  v = check_validity(r, place_robot(r, plane(0.0, 0.2), 0.0, 0.0, 0.0));
  EXPECT_TRUE(v.valid());
  EXPECT_NEAR(v.margin, 1.0 - std::atan(0.2) / r.max_roll, 1e-9);
  v = check_validity(r, place_robot(r, plane(0.0, 0.4), 0.0, 0.0, 0.0));
  EXPECT_EQ(v.failed, ValidityCheck::kRoll);
  EXPECT_EQ(v.margin, 0.0);
  v = check_validity(r, place_robot(r, plane(-0.5, 0.0), 0.0, 0.0, 0.0));
  EXPECT_EQ(v.failed, ValidityCheck::kPitch);
  // Twist loads each spring by k u v = 0.24 k.
  const auto twist = [](double k) {
    return RuledTerrain(grid_around_origin([=](double x, double y) { return k * x * y; }, 4, 0.25));
  };
  v = check_validity(r, place_robot(r, twist(0.2), 0.0, 0.0, 0.0));
  EXPECT_TRUE(v.valid());
  EXPECT_NEAR(v.margin, 1.0 - 0.048 / 0.1, 1e-9);
  v = check_validity(r, place_robot(r, twist(0.5), 0.0, 0.0, 0.0));
  EXPECT_EQ(v.failed, ValidityCheck::kSpringExtension);
  v = check_validity(r, place_robot(r, plane(0, 0, 3.0), 2.9, 0.0, 0.0));
  EXPECT_EQ(v.failed, ValidityCheck::kPlacement);
  EXPECT_STREQ(to_string(ValidityCheck::kSpringExtension), "spring_extension");
}

TEST(Validity, ChassisLimits) {
  const ArticulatedChassis c = chassis();
  EXPECT_TRUE(check_validity(c, place_chassis(c, plane(0.1, 0.1), 0, 0, 0)).valid());
  EXPECT_EQ(check_validity(c, place_chassis(c, plane(0.0, 0.5), 0, 0, 0)).failed,
            ValidityCheck::kRoll);
  EXPECT_EQ(check_validity(c, place_chassis(c, plane(0.5, 0.0), 0, 0, 0)).failed,
            ValidityCheck::kPitch);
  EXPECT_EQ(check_validity(c, place_chassis(c, plane(-0.5, 0.0), 0, 0, 0)).failed,
            ValidityCheck::kPitch);
  // Twist z = k x y: the outer axles roll by ±atan(k d cos ψ), the middle not.
  const RuledTerrain twist(
      grid_around_origin([](double x, double y) { return 0.7 * x * y; }, 4, 0.25));
  const ChassisPlacement tw = place_chassis(c, twist, 0, 0, 0);
  EXPECT_NEAR(tw.roll_middle, 0.0, 1e-12);
  EXPECT_NEAR(tw.roll_front, std::atan(0.7 * 0.6), 1e-9);
  EXPECT_EQ(check_validity(c, tw).failed, ValidityCheck::kAxleRollDifference);
  // A sharp valley folds the bodies past min/max body angle.
  const RuledTerrain valley(grid_around_origin([](double x, double) { return x * x; }, 4, 0.05));
  EXPECT_EQ(check_validity(c, place_chassis(c, valley, 0, 0, 0)).failed, ValidityCheck::kBodyAngle);
  // Mild valley: valid, the margin is the body-angle one.
  const RuledTerrain mild(
      grid_around_origin([](double x, double) { return 0.2 * x * x; }, 4, 0.05));
  const ChassisPlacement m = place_chassis(c, mild, 0, 0, 0);
  const Validity v = check_validity(c, m);
  ASSERT_TRUE(v.valid());
  EXPECT_NEAR(v.margin, 1.0 - (m.body_angle() - kPi) / 0.5, 1e-12);
}

TEST(LowerFaces, RigidBodyFaceOnAPlane) {
  const WheeledRobot r = rover();
  const double gx = 0.1, gy = 0.05;
  const RobotPlacement p = place_robot(r, plane(gx, gy), 0.0, 0.0, 0.8);
  const auto faces = lower_faces(r, p);
  ASSERT_EQ(faces.size(), 1u);
  const Vec3 n = Vec3(-gx, -gy, 1.0).normalized();
  double area = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Vec3& a = faces[0][k];
    const Vec3& b = faces[0][(k + 1) % 4];
    // Each corner is `clearance` above the terrain plane, measured along its normal.
    EXPECT_NEAR(n.dot(a - Vec3(0, 0, 1.0)), r.body.clearance, 1e-9);
    area += a.x() * b.y() - b.x() * a.y();
  }
  EXPECT_GT(area, 0.0);  // counter-clockwise from above
  EXPECT_NEAR((faces[0][1] - faces[0][0]).norm() * (faces[0][2] - faces[0][1]).norm(),
              (r.body.front + r.body.rear) * 2 * r.body.half_width, 1e-9);
}

TEST(LowerFaces, ChassisFacesOnAPlane) {
  const ArticulatedChassis c = chassis();
  const double gx = -0.2, gy = 0.1;
  const ChassisPlacement p = place_chassis(c, plane(gx, gy), 0.0, 0.0, 2.0);
  const auto faces = lower_faces(c, p);
  ASSERT_EQ(faces.size(), 2u);
  const Vec3 n = Vec3(-gx, -gy, 1.0).normalized();
  for (const Quad& q : faces) {
    double area = 0.0;
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(n.dot(q[k] - Vec3(0, 0, 1.0)), c.body.clearance, 1e-9);
      area += q[k].x() * q[(k + 1) % 4].y() - q[(k + 1) % 4].x() * q[k].y();
    }
    EXPECT_GT(area, 0.0);
  }
  EXPECT_TRUE(lower_faces(c, place_chassis(c, plane(0, 0, 3.0), 2.9, 0, 0)).empty());
}

// ---------------------------------------------------------------- uncertainty

TEST(Uncertainty, FlatGroundIntervalsAreAnalytic) {
  const double dz = 0.03;
  const RuledTerrain t = plane(0.0, 0.0);
  const RuledTerrain lo = t.lower_envelope(dz), hi = t.upper_envelope(dz);
  const RobotPlacementInterval r = place_robot_interval(rover(), t, lo, hi, 0.0, 0.0, 0.3);
  ASSERT_TRUE(usable(r.status));
  EXPECT_NEAR(r.z.lo, 1.0 + 0.45 - dz, 1e-9);
  EXPECT_NEAR(r.z.hi, 1.0 + 0.45 + dz, 1e-9);
  // Left wheels on T_max, right ones on T_min: 2 * 0.4 * sin(roll) = 2 dz.
  EXPECT_NEAR(r.roll.hi, std::asin(dz / 0.4), 1e-6);
  EXPECT_NEAR(r.roll.lo, -std::asin(dz / 0.4), 1e-6);
  EXPECT_NEAR(r.pitch.hi, std::asin(dz / 0.6), 1e-6);
  // Twist assignment: each spring takes dz.
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(r.extensions[j].hi, dz, 1e-6);
    EXPECT_NEAR(r.extensions[j].lo, -dz, 1e-6);
  }
  const ChassisPlacementInterval c = place_chassis_interval(chassis(), t, lo, hi, 0.0, 0.0, 0.3);
  ASSERT_TRUE(usable(c.status));
  EXPECT_NEAR(c.z.lo, 1.0 - dz, 1e-12);
  EXPECT_NEAR(c.z.hi, 1.0 + dz, 1e-12);
  EXPECT_NEAR(c.roll_middle.hi, std::asin(dz / 0.45), 2e-6);
  EXPECT_NEAR(c.roll_front.lo, -std::asin(dz / 0.45), 2e-6);
  // Middle at +dz, front on T_min: d sin ψ = -2 dz.
  EXPECT_NEAR(c.pitch_front.lo, -std::asin(2 * dz / 0.6), 2e-6);
  EXPECT_NEAR(c.pitch_rear.hi, std::asin(2 * dz / 0.6), 2e-6);
  // The table gives the same intervals on a plane.
  ChassisTableOptions opt;
  opt.theta_slices = 8;
  opt.terrain_uncertainty = dz;
  const ChassisPlacementTable table(chassis(), t, opt);
  EXPECT_EQ(table.diagnostics().surface_sets, 5);
  const ChassisPlacementInterval ct = table.place_interval(0.0, 0.0, 0.3);
  EXPECT_NEAR(ct.z.lo, c.z.lo, 1e-12);
  EXPECT_NEAR(ct.roll_middle.hi, c.roll_middle.hi, 1e-9);
  EXPECT_NEAR(ct.pitch_front.lo, c.pitch_front.lo, 1e-9);
  EXPECT_NEAR(ct.pitch_rear.hi, c.pitch_rear.hi, 1e-9);
}

TEST(Uncertainty, NeverAcceptsWhatTheCertainCheckRejects) {
  const RuledTerrain t = rough(31, 0.25, 5.0);
  const double dz = 0.02;
  const RuledTerrain lo = t.lower_envelope(dz), hi = t.upper_envelope(dz);
  ChassisTableOptions opt;
  opt.theta_slices = 24;
  opt.terrain_uncertainty = dz;
  const ArticulatedChassis c = chassis();
  const ChassisPlacementTable table(c, t, opt);
  const WheeledRobot r = rover();
  std::mt19937_64 rng(1234);
  int rigid_certain_valid = 0, rigid_only_certain = 0;
  int chassis_certain_valid = 0, chassis_only_certain = 0;
  for (int n = 0; n < 400; ++n) {
    const double x = -4.2 + 8.4 * uniform(rng), y = -4.2 + 8.4 * uniform(rng);
    const double th = 2 * kPi * uniform(rng);
    const Validity rc = check_validity(r, place_robot(r, t, x, y, th));
    const Validity ru = check_validity(r, place_robot_interval(r, t, lo, hi, x, y, th));
    if (!rc.valid()) {
      EXPECT_FALSE(ru.valid()) << x << " " << y << " " << th;
    }
    EXPECT_LE(ru.margin, rc.margin + 1e-12);
    rigid_certain_valid += rc.valid();
    rigid_only_certain += rc.valid() && !ru.valid();

    const Validity cc = check_validity(c, place_chassis(c, t, x, y, th));
    const Validity cu = check_validity(c, place_chassis_interval(c, t, lo, hi, x, y, th));
    if (!cc.valid()) {
      EXPECT_FALSE(cu.valid()) << x << " " << y << " " << th;
    }
    EXPECT_LE(cu.margin, cc.margin + 1e-12);
    chassis_certain_valid += cc.valid();
    chassis_only_certain += cc.valid() && !cu.valid();

    // The same through the preprocessed surfaces.
    const Validity tc = check_validity(c, table.place(x, y, th));
    const Validity tu = check_validity(c, table.place_interval(x, y, th));
    if (!tc.valid()) {
      EXPECT_FALSE(tu.valid()) << x << " " << y << " " << th;
    }
  }
  std::printf("rigid: %d certain-valid, %d rejected only under uncertainty; chassis: %d, %d\n",
              rigid_certain_valid, rigid_only_certain, chassis_certain_valid, chassis_only_certain);
  // The sample exercises both outcomes, and uncertainty does reject more.
  EXPECT_GT(rigid_certain_valid, 40);
  EXPECT_LT(rigid_certain_valid, 390);
  EXPECT_GT(rigid_only_certain, 0);
  EXPECT_GT(chassis_certain_valid, 40);
  EXPECT_LT(chassis_certain_valid, 390);
  EXPECT_GT(chassis_only_certain, 0);
}

}  // namespace
}  // namespace talus
