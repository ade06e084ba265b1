// Contact at the wheels of the rigid body (wheel_contact.hpp): the chassis
// curvature and the least-loaded wheel's, against closed forms on crests, and
// what they change in the limits against the point mass's.
#include <gtest/gtest.h>

#include <cmath>

#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/admissible_set.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/wheel_contact.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

constexpr double kG = 9.81;

/// The battery's UGV as a rigid body: l = 0.135, b = 0.124, h = 0.06, its
/// inertias (ρ_p = I_p / (m l²) = 0.4905, ρ_r = I_r / (m b²) = 0.4113).
Vehicle ugv(VehicleModel model) {
  Vehicle v;
  v.model = model;
  v.friction = 0.7;
  v.cg_height = 0.06;
  v.half_track = 0.124;
  v.half_wheelbase = 0.135;
  VehicleBody body = default_vehicle_body(2.0, 0.135, 0.124, 0.06);
  body.inertia_roll = 0.01265;
  body.inertia_pitch = 0.01788;
  v.body = body;
  return v;
}

/// The smallest contact limit v [m/s] along the straight path from `a` to `b`.
double lowest_contact_speed(const BPatch& surface, const Vehicle& vehicle, const Vec2& a,
                            const Vec2& b) {
  const SurfacePath path(surface, Curve2::interpolate({a, 0.5 * (a + b), b}));
  const VelocityLimits limits(vehicle, path, 2001);
  double lowest = std::numeric_limits<double>::infinity();
  for (const SpeedLimits& l : limits.all_limits()) lowest = std::min(lowest, l.contact.upper);
  return std::sqrt(lowest);
}

BPatch terrain(const terrain_test::HeightFunction& f) {
  return BPatch::interpolate(terrain_test::grid_from_function(f, -1.0, -0.6, 1.0, 0.6, 0.01));
}

/// The point mass's and the rigid body's lowest contact speed crossing a Gaussian ridge
/// along y (standard deviation sigma, height [m]) along x.
std::pair<double, double> transverse_ridge_limits(double sigma, double height) {
  const BPatch s =
      terrain([&](double x, double) { return height * std::exp(-x * x / (2 * sigma * sigma)); });
  return {lowest_contact_speed(s, ugv(VehicleModel::kPointMass), {-0.8, 0}, {0.8, 0}),
          lowest_contact_speed(s, ugv(VehicleModel::kRigidBody), {-0.8, 0}, {0.8, 0})};
}

TEST(WheelContact, TheLoadSharesAreTheRigidBodysClosedForm) {
  const WheelLayout layout = wheel_layout(ugv(VehicleModel::kRigidBody));
  const double rp = 0.01788 / (2.0 * 0.135 * 0.135), rr = 0.01265 / (2.0 * 0.124 * 0.124);
  // Front-left alone accelerates: its own load takes (1 + ρ_p + ρ_r) / 4, the diagonal
  // wheel (rear-right) (1 + ρ_p + ρ_r) / 4 − ρ_p / 2 − ρ_r / 2; the loads sum to the heave.
  EXPECT_NEAR(layout.loads(0, 0), (1 + rp + rr) / 4, 1e-12);
  EXPECT_NEAR(layout.loads(1, 0), (1 + rp - rr) / 4, 1e-12);
  EXPECT_NEAR(layout.loads(2, 0), (1 - rp + rr) / 4, 1e-12);
  EXPECT_NEAR(layout.loads(3, 0), (1 - rp - rr) / 4, 1e-12);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(layout.loads.col(i).sum(), 1.0, 1e-12);
}

TEST(WheelContact, OnTheTopOfACylinderCrestEveryWheelSeesItsOwnSlope) {
  // z = −x² / (2 R), crossed along x: at the top the axles stand at x = ±l, slope ∓l/R,
  // where the section's curvature is −(1/R) / (1 + (l/R)²)^(3/2) and each wheel runs
  // sqrt(1 + (l/R)²) times faster than the c.g.: κ_c = κ_w = −(1/R) / sqrt(1 + (l/R)²),
  // the point's own κ_n being −1/R.
  const double R = 0.5, l = 0.135;
  const BPatch s = terrain([&](double x, double) { return -x * x / (2 * R); });
  const SurfacePath path(s, Curve2::interpolate({Vec2(-0.4, 0), Vec2(0, 0), Vec2(0.4, 0)}));
  const VelocityLimits limits(ugv(VehicleModel::kRigidBody), path, 101);
  const StationGeometry& top = limits.geometry(50);
  const double expected = -(1 / R) / std::sqrt(1 + (l / R) * (l / R));
  EXPECT_NEAR(top.kappa_n, expected, 1e-4);
  EXPECT_NEAR(top.kappa_wheels, expected, 1e-4);
  EXPECT_NEAR(limits.frame(50).kappa_n, -1 / R, 1e-4);
  // The point mass's geometry is the c.g. point's.
  const VelocityLimits point(ugv(VehicleModel::kPointMass), path, 101);
  EXPECT_EQ(point.geometry(50).kappa_n, limits.frame(50).kappa_n);
  EXPECT_EQ(point.geometry(50).kappa_wheels, limits.frame(50).kappa_n);
}

TEST(WheelContact, ACrestUnderOneWheelTrackLowersTheContactLimitBelowThePointMasss) {
  // A bump 0.1 m across (shorter than the 0.27 m wheelbase) under the left wheels' track,
  // y = b, driven along y = 0: the c.g.'s line passes its tail, the left wheels its top.
  const double b = 0.124, sigma = 0.05, height = 0.01;
  const BPatch s = terrain([&](double x, double y) {
    return height * std::exp(-(x * x + (y - b) * (y - b)) / (2 * sigma * sigma));
  });
  const double point = lowest_contact_speed(s, ugv(VehicleModel::kPointMass), {-0.8, 0}, {0.8, 0});
  const double rigid = lowest_contact_speed(s, ugv(VehicleModel::kRigidBody), {-0.8, 0}, {0.8, 0});
  // The left wheel over the top: κ = −A/σ² there, load share (1 + ρ_p + ρ_r)/4 of the
  // front-left's own and the rear-left's (on flat ground then): v² = g / (share A/σ²).
  const double rp = 0.01788 / (2.0 * 0.135 * 0.135), rr = 0.01265 / (2.0 * 0.124 * 0.124);
  const double share = (1 + rp + rr) / 4;
  const double expected = std::sqrt(kG * sigma * sigma / (share * height));
  EXPECT_LT(rigid, 0.7 * point) << "rigid " << rigid << " point mass " << point;
  EXPECT_NEAR(rigid, expected, 0.05 * expected);
}

TEST(WheelContact, ATransverseCrestShorterThanTheWheelbaseIsSpannedByTheChassis) {
  // A ridge along y, 0.1 m across, crossed along x: the point mass takes its top at
  // v² = g σ² / A; the chassis meets it one axle at a time, whose wheels carry
  // (1 + ρ_p) / 2 of that axle's acceleration: v² = 2 g σ² / ((1 + ρ_p) A), 1.34 times.
  const double sigma = 0.05, height = 0.01;
  const auto [point, rigid] = transverse_ridge_limits(sigma, height);
  const double rp = 0.01788 / (2.0 * 0.135 * 0.135);
  EXPECT_NEAR(point, std::sqrt(kG * sigma * sigma / height), 0.01 * point);
  EXPECT_NEAR(rigid, std::sqrt(2 * kG * sigma * sigma / ((1 + rp) * height)), 0.03 * rigid);
  EXPECT_GT(rigid, 1.1 * point);
}

TEST(WheelContact, ACrestLongerThanTheVehicleGivesThePointMasssLimit) {
  const auto [point, rigid] = transverse_ridge_limits(2.0, 0.5);
  EXPECT_NEAR(rigid, point, 0.01 * point);
}

TEST(WheelContact, TheWheelsOfATurningChassisFollowTheirOwnArcs) {
  // Flat ground tilted into a bowl z = (x² + y²) / (2 R), a circle of radius r about its
  // centre: the inner wheels run slower than the c.g. (ρ = (1 − b/r)² + (l/r)²), the outer
  // faster; on the bowl every direction has κ ≈ 1/R, so κ_c ≈ (1/R) mean ρ_j.
  const double R = 5.0, r = 0.5;
  const BPatch s = terrain([&](double x, double y) { return (x * x + y * y) / (2 * R); });
  std::vector<Vec2> points;
  for (int k = 0; k <= 8; ++k) points.emplace_back(r * std::cos(0.25 * k), r * std::sin(0.25 * k));
  const SurfacePath path(s, Curve2::interpolate(points));
  const VelocityLimits limits(ugv(VehicleModel::kRigidBody), path, 51);
  const double l = 0.135, b = 0.124;
  const double inner = (1 - b / r) * (1 - b / r) + (l / r) * (l / r);
  const double outer = (1 + b / r) * (1 + b / r) + (l / r) * (l / r);
  const StationGeometry& g = limits.geometry(25);
  // Slopes up to (r + b)/R = 0.125 change the curvature and the lifts by about 2 %.
  EXPECT_NEAR(g.kappa_n, (1 / R) * 0.5 * (inner + outer), 0.03 / R);
}

}  // namespace
}  // namespace talus

namespace talus {
namespace {

TEST(PlanningReserves, AContactReserveKeepsRAboveRgAtTheCgAndAtEveryWheel) {
  const double R = 3.0, r = 0.2;
  const BPatch s = BPatch::interpolate(terrain_test::grid_from_function(
      [&](double x, double) { return -x * x / (2 * R); }, -1.0, -0.6, 1.0, 0.6, 0.01));
  for (const VehicleModel model : kVehicleModels) {
    Vehicle v = ugv(model);
    const double plain = lowest_contact_speed(s, v, {-0.5, 0}, {0.5, 0});
    v.contact_reserve = r;
    const double reserved = lowest_contact_speed(s, v, {-0.5, 0}, {0.5, 0});
    // Both limits are g k_r / |κ| scaled: R >= r g at k_r = 1 takes (1 − r) of v².
    EXPECT_NEAR(reserved * reserved / (plain * plain), 1.0 - r, 2e-3) << static_cast<int>(model);
  }
  // The bump under one wheel track: the wheel's load keeps r g as well.
  const double b = 0.124, sigma = 0.05, height = 0.01;
  const BPatch bump = terrain([&](double x, double y) {
    return height * std::exp(-(x * x + (y - b) * (y - b)) / (2 * sigma * sigma));
  });
  Vehicle v = ugv(VehicleModel::kRigidBody);
  const double plain = lowest_contact_speed(bump, v, {-0.8, 0}, {0.8, 0});
  v.contact_reserve = r;
  const double reserved = lowest_contact_speed(bump, v, {-0.8, 0}, {0.8, 0});
  EXPECT_NEAR(reserved * reserved / (plain * plain), 1.0 - r, 5e-3);
}

TEST(PlanningReserves, AFrictionReserveShrinksTheFrictionConeTheSimulationKeepsMu) {
  // A flat circle of radius 2 m: v² = (1 − ε) μ g ρ.
  const BPatch flat = terrain([](double, double) { return 0.0; });
  Vehicle v = ugv(VehicleModel::kPointMass);
  v.half_track = 10.0;  // no tip-over: sliding binds
  v.friction_reserve = 0.25;
  const AdmissibleSet set(v);
  EXPECT_DOUBLE_EQ(set.friction(), 0.75 * v.friction);
  StationGeometry g;
  g.kappa_g = 1.0 / 2.0;
  g.kappa_wheels = 0.0;
  const SpeedLimits limits = set.speed_limits(g);
  EXPECT_NEAR(limits.v_max, std::sqrt(0.75 * 0.7 * kG * 2.0), 1e-9);
  EXPECT_EQ(limits.upper_binding, Constraint::kSliding);
}

TEST(PlanningReserves, ADriveReserveShrinksTheDriveAndBrakeLimitsTheSimulationKeepsThem) {
  // On level ground at rest f_t = s̈: the planner's bounds are ±(1 − ε_d) of the limits.
  Vehicle v = ugv(VehicleModel::kPointMass);
  v.max_accel = 3.0;
  v.max_decel = 5.0;
  const AdmissibleSet plain(v);
  v.drive_reserve = 0.1;
  const AdmissibleSet reserved(v);
  StationGeometry g;
  g.kappa_wheels = 0.0;
  const AccelerationBounds full = plain.acceleration_bounds(g, 0.0);
  const AccelerationBounds kept = reserved.acceleration_bounds(g, 0.0);
  EXPECT_NEAR(full.a_max, 3.0, 1e-12);
  EXPECT_NEAR(full.a_min, -5.0, 1e-12);
  EXPECT_NEAR(kept.a_max, 0.9 * 3.0, 1e-12);
  EXPECT_NEAR(kept.a_min, -0.9 * 5.0, 1e-12);
}

TEST(PlanningReserves, AReserveOutsideZeroToOneIsAnInputErrorNamingTheKey) {
  for (const char* key : {"contact_reserve", "friction_reserve", "drive_reserve"}) {
    for (const char* value : {"-0.1", "1", "nan"}) {
      const std::string yaml = std::string(
                                   "model: point_mass\nfriction: 0.7\ncg_height: 0.5\n"
                                   "half_track: 0.6\n") +
                               key + ": " + value + "\n";
      try {
        parse_vehicle(yaml, "reserve.yaml");
        ADD_FAILURE() << key << " = " << value << " accepted";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      }
    }
  }
  const Vehicle v = parse_vehicle(
      "model: point_mass\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\n"
      "contact_reserve: 0.1\nfriction_reserve: 0.2\ndrive_reserve: 0.15\n",
      "reserve.yaml");
  EXPECT_EQ(v.contact_reserve, 0.1);
  EXPECT_EQ(v.friction_reserve, 0.2);
  EXPECT_EQ(v.drive_reserve, 0.15);
}

TEST(PlanningReserves, AxleFrictionIsARigidBodyKeyTakingTrueOrFalse) {
  const std::string rigid =
      "model: rigid_body\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\nhalf_wheelbase: 1\n";
  EXPECT_FALSE(parse_vehicle(rigid, "axle.yaml").axle_friction);
  EXPECT_TRUE(parse_vehicle(rigid + "axle_friction: true\n", "axle.yaml").axle_friction);
  for (const std::string& bad :
       {rigid + "axle_friction: 0.5\n",
        std::string("model: point_mass\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\n"
                    "axle_friction: true\n")}) {
    try {
      parse_vehicle(bad, "axle.yaml");
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("axle_friction"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace talus
