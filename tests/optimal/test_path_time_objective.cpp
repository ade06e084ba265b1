#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "talus/core/error.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/optimal/path_time_objective.hpp"
#include "talus/scenarios/fractal_battery.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

/// The shared point-mass rover with drive and brake limits, so that both bind somewhere.
Vehicle rover(double mu) {
  Vehicle v = vehicle_test::point_mass_rover(mu);
  v.max_accel = 2.5;
  v.max_decel = 4.0;
  return v;
}

BPatch hill() {
  return BPatch::interpolate(terrain_test::grid_from_function(
      terrain_test::gaussian_hill(Vec2(40, 30), 8.0, 7.0), 0, 0, 80, 60, 1.0));
}

/// Central differences with a step small enough not to cross an active-set
/// change in most coordinates, large enough for the profile's rounding.
Eigen::VectorXd central_differences(PathTimeObjective& objective, const Eigen::VectorXd& z,
                                    double step) {
  Eigen::VectorXd g(z.size()), probe = z;
  for (long i = 0; i < z.size(); ++i) {
    probe[i] = z[i] + step;
    const double plus = objective.evaluate(probe);
    probe[i] = z[i] - step;
    const double minus = objective.evaluate(probe);
    probe[i] = z[i];
    g[i] = (plus - minus) / (2.0 * step);
  }
  return g;
}

TEST(PathTimeObjective, StraightLineOnAPlaneHasTheAnalyticTimeAndNoLateralGradient) {
  const BPatch flat = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 60, 40, 1.0));
  const Vehicle v = rover(0.5);
  PathTimeObjective objective(flat, v, {5, 20}, {55, 20}, 6, 201, {});
  std::vector<Vec2> points;
  for (int i = 0; i < 6; ++i) points.emplace_back(5 + 10 * i, 20);
  const Eigen::VectorXd z = objective.variables(points);
  Eigen::VectorXd gradient;
  const double t = objective.evaluate(z, &gradient);
  // Rest to rest over 50 m: accelerate at 2.5, cruise at 10, brake at 4.
  const double accel = 100 / (2 * 2.5), brake = 100 / (2 * 4.0);
  const double exact = 10 / 2.5 + 10 / 4.0 + (50 - accel - brake) / 10;
  EXPECT_NEAR(t, exact, 0.01 * exact);  // conservative discretisation, first order
  EXPECT_GE(t, exact - 1e-9);
  ASSERT_EQ(gradient.size(), 8);
  for (long i = 1; i < gradient.size(); i += 2) EXPECT_NEAR(gradient[i], 0.0, 1e-9);  // y
  EXPECT_EQ(objective.finite_difference_fallbacks(), 0u);
}

TEST(PathTimeObjective, GradientMatchesFiniteDifferencesAtRandomControlPoints) {
  const BPatch terrain = hill();
  const Vehicle v = rover(0.4);
  std::mt19937 random(20261130);
  std::uniform_real_distribution<double> jitter(-6.0, 6.0);
  int checked = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 40 && checked < 8; ++trial) {
    PathTimeObjective objective(terrain, v, {5, 30}, {75, 30}, 7, 300, {});
    std::vector<Vec2> points;
    for (int i = 0; i < 7; ++i) {
      const double x = 5 + 70.0 * i / 6.0;
      const double y = 30 + ((i == 0 || i == 6) ? 0.0 : 14.0 + jitter(random));
      points.emplace_back(x, y);
    }
    const Eigen::VectorXd z = objective.variables(points);
    Eigen::VectorXd gradient;
    const double t = objective.evaluate(z, &gradient);
    if (!std::isfinite(t)) continue;  // this draw crosses the hill too steeply: no profile
    const Eigen::VectorXd fd = central_differences(objective, z, 1e-6);
    const double error = (gradient - fd).norm() / fd.norm();
    EXPECT_LT(error, 1e-4) << "trial " << trial << "\nadjoint " << gradient.transpose()
                           << "\nfinite  " << fd.transpose();
    EXPECT_EQ(objective.finite_difference_fallbacks(), 0u);
    worst = std::max(worst, error);
    ++checked;
  }
  EXPECT_EQ(checked, 8);
  std::printf("adjoint vs central differences: worst relative error %.2e over %d paths\n", worst,
              checked);
}

// The rigid body judges its normal load and contact at the wheels (wheel_contact.hpp): the
// adjoint carries them through the chassis' and the least-loaded wheel's curvature, whose
// derivatives come from the B-patch at the four wheels. On a rough field where the wheels
// see other bumps than the c.g., with a wheelbase of 2 m.
TEST(PathTimeObjective, TheRigidBodysGradientThroughItsWheelsMatchesFiniteDifferences) {
  const BPatch terrain = BPatch::interpolate(terrain_test::grid_from_function(
      [](double x, double y) {
        return 0.6 * std::sin(0.5 * x) * std::cos(0.4 * y) + 0.3 * std::sin(0.9 * x + 0.7 * y);
      },
      0, 0, 80, 60, 0.5));
  for (const bool axle_friction : {false, true}) {
    Vehicle v = rover(0.6);
    v.model = VehicleModel::kRigidBody;
    v.half_wheelbase = 1.0;
    // With axle_friction the friction cone is the lighter axle's pair of coupled cones: the
    // adjoint follows whichever of the two is touched.
    v.axle_friction = axle_friction;
    int checked = 0, wheel_bound = 0;
    for (int trial = 0; trial < 12 && checked < 4; ++trial) {
      PathTimeObjective objective(terrain, v, {5, 30}, {75, 30}, 7, 300, {});
      std::vector<Vec2> points;
      for (int i = 0; i < 7; ++i) {
        const double y = (i == 0 || i == 6) ? 30.0 : 30.0 + 3.0 * std::sin(1.7 * i + trial);
        points.emplace_back(5 + 70.0 * i / 6.0, y);
      }
      const Eigen::VectorXd z = objective.variables(points);
      Eigen::VectorXd gradient;
      if (!std::isfinite(objective.evaluate(z, &gradient))) continue;
      const Eigen::VectorXd fd = central_differences(objective, z, 1e-6);
      EXPECT_LT((gradient - fd).norm() / fd.norm(), 1e-4)
          << "trial " << trial << "\nadjoint " << gradient.transpose() << "\nfinite  "
          << fd.transpose();
      EXPECT_EQ(objective.finite_difference_fallbacks(), 0u);
      ++checked;
      // The wheels' contact binds somewhere on these paths (else the test would not reach it).
      const SurfacePath path(terrain, objective.curve(z));
      const VelocityLimits limits(v, path, 300);
      for (std::size_t k = 0; k < limits.size(); ++k) {
        const StationGeometry& g = limits.geometry(k);
        if (g.kappa_wheels < g.kappa_n - 1e-3 &&
            limits.limits(k).upper_binding == Constraint::kContact)
          ++wheel_bound;
      }
    }
    EXPECT_EQ(checked, 4);
    EXPECT_GT(wheel_bound, 0);
  }
}

// Brakes but no drive limit, moving start and end, map coordinates of UTM
// size: every braking arc still has its equation (no fallback), and the
// gradient stays exact far from the origin.
TEST(PathTimeObjective, GradientWithBrakesOnlyMovingEndsAndUtmCoordinates) {
  const double x0 = 556000.0, y0 = 4373000.0;
  const BPatch terrain = BPatch::interpolate(terrain_test::grid_from_function(
      [&](double x, double y) {
        const double dx = x - x0 - 40, dy = y - y0 - 30;
        return 1500.0 + 8.0 * std::exp(-(dx * dx + dy * dy) / (2 * 7.0 * 7.0));
      },
      x0, y0, x0 + 80, y0 + 60, 1.0));
  Vehicle v = rover(0.4);
  v.max_accel = std::numeric_limits<double>::infinity();
  v.max_decel = 3.0;
  ProfileOptions speeds;
  speeds.start_speed = 2.0;
  speeds.end_speed = 1.0;
  const Vec2 start(x0 + 5, y0 + 30), goal(x0 + 75, y0 + 30);
  PathTimeObjective objective(terrain, v, start, goal, 6, 300, speeds);
  const Eigen::VectorXd z = objective.variables({start,
                                                 {x0 + 20, y0 + 45},
                                                 {x0 + 35, y0 + 47},
                                                 {x0 + 50, y0 + 46},
                                                 {x0 + 62, y0 + 40},
                                                 goal});
  Eigen::VectorXd gradient;
  ASSERT_TRUE(std::isfinite(objective.evaluate(z, &gradient)));
  const Eigen::VectorXd fd = central_differences(objective, z, 1e-5);
  EXPECT_LT((gradient - fd).norm() / fd.norm(), 1e-4) << gradient.transpose() << "\n"
                                                      << fd.transpose();
  EXPECT_EQ(objective.finite_difference_fallbacks(), 0u);
}

// A 16-point path of the optimiser on battery seed 2 whose profile rides the tip of a sliding
// limit: a station a few 1e-9 below the lateral limit, where the step's control sits on the
// edge of a friction ellipse only sqrt(1e-9) wide. That station is pinned by the ellipse, not
// by f_t = 0 nor by the speed limit; before the adjoint tried the ellipse first, the system
// was singular there and the gradient came from finite differences (66 such fallbacks over the
// 25 battery plans, 2 after).
TEST(PathTimeObjective, AStationAtTheEdgeOfATipOfTheSlidingLimitKeepsTheAdjointGradient) {
  const BPatch terrain =
      BPatch::interpolate(generate_fractal_terrain(scenarios::battery_terrain(2)));
  PathTimeObjective objective(terrain, scenarios::battery_point_mass_ugv(),
                              scenarios::kBatteryStart, scenarios::kBatteryGoal, 16, 1793, {});
  const std::vector<double> point = {
      4.8006015604918026, 3.9961784414680657, 6.7728746421058883, 3.1306739766234832,
      5.7654721870557859, 9.0670620077550037, 4.7995032902675021, 18.50941737981525,
      4.2118975078538412, 18.028224388214255, 7.7192823732873848, 21.151528172847115,
      13.75378473511643,  23.75784206756326,  13.939659491555245, 21.76331859789061,
      15.155664284950092, 22.601583264572987, 15.63299139219402,  24.83111682620407,
      16.313152822083815, 27.636916886774472, 18.29833979291076,  28.475168981290551,
      22.906117018912909, 27.348703694255565, 25.416763802106846, 26.772812399354706};
  const Eigen::VectorXd z = Eigen::Map<const Eigen::VectorXd>(point.data(), 28);
  Eigen::VectorXd gradient;
  ASSERT_TRUE(std::isfinite(objective.evaluate(z, &gradient)));
  EXPECT_EQ(objective.finite_difference_fallbacks(), 0u);
  // Measured 2e-7 at a 1e-6 m step (a 1e-5 m step crosses an active-set change).
  const Eigen::VectorXd fd = central_differences(objective, z, 1e-6);
  EXPECT_LT((gradient - fd).norm() / fd.norm(), 1e-4) << gradient.transpose() << "\n"
                                                      << fd.transpose();
}

TEST(PathTimeObjective, OffTheMapIsInfinite) {
  const BPatch terrain = hill();
  PathTimeObjective objective(terrain, rover(0.4), {5, 30}, {75, 30}, 5, 100, {});
  const Eigen::VectorXd z = objective.variables({{5, 30}, {20, 90}, {40, 30}, {60, 30}, {75, 30}});
  Eigen::VectorXd gradient;
  EXPECT_TRUE(std::isinf(objective.evaluate(z, &gradient)));
  EXPECT_THROW(PathTimeObjective(terrain, rover(0.4), {5, 30}, {75, 30}, 3, 100, {}), InputError);
}

}  // namespace
}  // namespace talus
