// talus/kinematic/hait/hait_scenarios.hpp: the generated terrains of the
// Haït reproductions hold the documented landforms on top of their fractal
// base, and the ridge-crossing classification of a path.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/kinematic/hait/hait_scenarios.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

/// max over the nodes of |(grid − base) − added(node position)|.
template <typename Added>
double worst_difference(const ElevationGrid& grid, const ElevationGrid& base, Added added) {
  double worst = 0.0;
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i)
      worst = std::max(worst,
                       std::abs(grid.at(i, j) - base.at(i, j) - added(grid.node_position(i, j))));
  return worst;
}

double hills_at(const std::vector<GaussianHill>& hills, const Vec2& p) {
  double z = 0.0;
  for (const GaussianHill& h : hills)
    z += h.height * std::exp(-(p - h.centre).squaredNorm() / (2.0 * h.sigma * h.sigma));
  return z;
}

TEST(HaitScenarios, HeuristicsCrescentAsDocumented) {
  for (const bool quick : {true, false}) {
    const HaitScenario s = hait_heuristics_scenario(quick);
    const std::size_t n = quick ? 61 : 141;
    const double side = 0.25 * static_cast<double>(n - 1);
    ASSERT_EQ(s.grid.ncols(), n);
    ASSERT_EQ(s.grid.nrows(), n);
    EXPECT_EQ(s.grid.cellsize(), 0.25);
    EXPECT_EQ(s.grid.x_min(), 0.0);
    EXPECT_EQ(s.grid.y_min(), 0.0);
    const std::size_t hills = quick ? 7 : 11;
    ASSERT_EQ(s.hills.size(), hills);
    const Vec2 centre(0.55 * side, 0.55 * side);
    for (std::size_t k = 0; k < hills; ++k) {
      EXPECT_EQ(s.hills[k].height, 2.0);
      EXPECT_EQ(s.hills[k].sigma, quick ? 0.7 : 1.0);
      const Vec2 d = s.hills[k].centre - centre;
      EXPECT_NEAR(d.norm(), 0.22 * side, 1e-12);
      // Evenly over 216°, centred on the north-east (π/4).
      const double angle = kPi / 4.0 - 0.6 * kPi +
                           1.2 * kPi * static_cast<double>(k) / static_cast<double>(hills - 1);
      EXPECT_NEAR(std::atan2(d.y(), d.x()), std::remainder(angle, 2.0 * kPi), 1e-12);
    }
    // The terrain is the fractal base plus the hills, at every node.
    const ElevationGrid base = hait_fractal_base(n, n, 0.25, quick ? 0.5 : 1.2, 7);
    EXPECT_LT(worst_difference(s.grid, base, [&](const Vec2& p) { return hills_at(s.hills, p); }),
              1e-12);
    EXPECT_NEAR(s.start.x, 0.12 * side, 1e-12);
    EXPECT_NEAR(s.start.y, 0.12 * side, 1e-12);
    EXPECT_NEAR(s.start.theta, kPi / 4.0, 1e-15);
    EXPECT_NEAR(s.goal.x, 0.88 * side, 1e-12);
    EXPECT_NEAR(s.goal.theta, kPi / 2.0, 1e-15);
  }
}

TEST(HaitScenarios, GorgeRidgeAsDocumented) {
  for (const bool quick : {true, false}) {
    const HaitScenario s = hait_gorge_scenario(quick);
    const std::size_t n = quick ? 81 : 141;
    const double side = 0.25 * static_cast<double>(n - 1);
    ASSERT_EQ(s.grid.ncols(), n);
    EXPECT_TRUE(s.hills.empty());
    EXPECT_NEAR(s.gorge.x(), 0.5 * side, 1e-12);
    EXPECT_NEAR(s.gorge.y(), 0.35 * side, 1e-12);
    EXPECT_NEAR(s.ridge_end_y, 0.6 * side, 1e-12);
    EXPECT_EQ(s.ridge_half_thickness, 1.5);
    EXPECT_EQ(s.gorge_half_width, 0.9 + 0.35);  // the documented floor half-width + wall
    const ElevationGrid base = hait_fractal_base(n, n, 0.25, 0.15, 11);
    const auto added = [&](std::size_t i, std::size_t j) {
      return s.grid.at(i, j) - base.at(i, j);
    };
    const std::size_t axis = (n - 1) / 2;  // x = W/2 is a node column
    const auto row_of = [](double y) { return static_cast<std::size_t>(std::lround(y / 0.25)); };
    const std::size_t gorge_row = row_of(s.gorge.y());
    // On the ridge's axis, south of the gorge and away from its walls: 2.5 m.
    EXPECT_NEAR(added(axis, 0), 2.5, 1e-12);
    EXPECT_NEAR(added(axis, gorge_row - 6), 2.5, 1e-12);  // 1.5 m > 0.9 + 0.35 m off the gorge
    EXPECT_NEAR(added(axis, gorge_row + 6), 2.5, 1e-12);
    // Half-way down the raised-cosine flank (0.75 m off the axis): half the height.
    EXPECT_NEAR(added(axis + 3, 0), 1.25, 1e-12);
    EXPECT_NEAR(added(axis - 3, 0), 1.25, 1e-12);
    // Beyond the ridge's 1.5 m half thickness, and on the gorge floor: nothing.
    EXPECT_NEAR(added(axis + 6, 0), 0.0, 1e-12);
    EXPECT_NEAR(added(0, gorge_row), 0.0, 1e-12);
    for (int d = -3; d <= 3; ++d)  // |y − yc| <= 0.75 m < 0.9 m
      EXPECT_NEAR(added(axis, gorge_row + d), 0.0, 1e-12);
    // 1.5 m north of the ridge's end it has died out to exp(−(1.5/0.6)²) of its height.
    const std::size_t north = row_of(s.ridge_end_y + 1.5);
    EXPECT_NEAR(added(axis, north), 2.5 * std::exp(-6.25), 1e-12);
    EXPECT_NEAR(s.start.y, s.gorge.y(), 1e-12);
    EXPECT_NEAR(s.goal.y, s.gorge.y(), 1e-12);
    EXPECT_NEAR(s.start.x, 0.15 * side, 1e-12);
    EXPECT_NEAR(s.goal.x, 0.85 * side, 1e-12);
  }
}

TEST(HaitScenarios, RoughTerrainIsTheScaledBasePlusItsHills) {
  const std::size_t n = 81;
  const double h = 0.25, extent = 20.0;
  const ElevationGrid base = hait_fractal_base(n, n, h, 1.2 * std::pow(extent / 35.0, 0.8), 3);
  const ElevationGrid bare = hait_rough_terrain(n, n, h, 0, 3);
  EXPECT_EQ(worst_difference(bare, base, [](const Vec2&) { return 0.0; }), 0.0);
  // One hill: 1.8 m high somewhere; at its nearest node at least
  // 1.8 exp(−(h/√2)² / (2 · 1.4²)), and nowhere above 1.8 m or below 0.
  const ElevationGrid one = hait_rough_terrain(n, n, h, 1, 3);
  double lowest = 1e9, highest = -1e9;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const double added = one.at(i, j) - base.at(i, j);
      lowest = std::min(lowest, added);
      highest = std::max(highest, added);
    }
  EXPECT_GE(lowest, -1e-12);
  EXPECT_LE(highest, 1.8 + 1e-12);
  EXPECT_GE(highest, 1.8 * std::exp(-(h * h / 2.0) / (2.0 * 1.4 * 1.4)) - 1e-12);
  // Deterministic.
  EXPECT_EQ(hait_rough_terrain(n, n, h, 4, 3).values(), hait_rough_terrain(n, n, h, 4, 3).values());
}

TEST(HaitScenarios, RidgeCrossing) {
  const auto path = [](std::vector<Vec2> points) {
    std::vector<PathPoint> out;
    for (const Vec2& p : points) out.push_back({{p.x(), p.y(), 0.0}, {}});
    return out;
  };
  // Crosses x = 5 between (4, 1) and (6, 3): at y = 2.
  EXPECT_NEAR(first_crossing_y(path({Vec2(0, 0), Vec2(4, 1), Vec2(6, 3), Vec2(4, 9)}), 5.0), 2.0,
              1e-15);
  EXPECT_TRUE(std::isnan(first_crossing_y(path({Vec2(0, 0), Vec2(4, 9)}), 5.0)));
  EXPECT_TRUE(std::isnan(first_crossing_y({}, 5.0)));

  HaitScenario gorge;
  gorge.gorge = Vec2(5.0, 2.0);
  gorge.ridge_end_y = 6.0;
  gorge.gorge_half_width = 1.0;
  EXPECT_TRUE(passes_through_gorge(path({Vec2(0, 2), Vec2(10, 2)}), gorge));
  EXPECT_TRUE(passes_through_gorge(path({Vec2(0, 1.1), Vec2(10, 2.9)}), gorge));  // y = 2 at x = 5
  // Round the ridge's north end.
  EXPECT_FALSE(passes_through_gorge(path({Vec2(0, 2), Vec2(0, 8), Vec2(10, 8)}), gorge));
  // Over the ridge south of its end but outside the gorge, on either side of it.
  EXPECT_FALSE(passes_through_gorge(path({Vec2(0, 4), Vec2(10, 4)}), gorge));
  EXPECT_FALSE(passes_through_gorge(path({Vec2(0, 3.2), Vec2(10, 3.2)}), gorge));
  EXPECT_FALSE(passes_through_gorge(path({Vec2(0, 0.5), Vec2(10, 0.5)}), gorge));
  // Only the first crossing counts: over the ridge, then back through the gorge.
  EXPECT_FALSE(passes_through_gorge(
      path({Vec2(0, 4), Vec2(10, 4), Vec2(10, 2), Vec2(0, 2), Vec2(0, 2.1), Vec2(10, 2.1)}),
      gorge));
  EXPECT_FALSE(passes_through_gorge(path({Vec2(0, 2), Vec2(4, 2)}), gorge));  // never crosses
}

TEST(HaitScenarios, UncertaintyDiscMap) {
  const ElevationGrid grid(9, 7, 0.5, 10.0, 20.0, 3.0);
  const ElevationGrid dz = uncertainty_disc_map(grid, 0.02, Vec2(12.0, 21.5), 1.0, 0.3);
  ASSERT_EQ(dz.ncols(), 9u);
  ASSERT_EQ(dz.nrows(), 7u);
  EXPECT_EQ(dz.cellsize(), 0.5);
  EXPECT_EQ(dz.x_min(), 10.0);
  EXPECT_EQ(dz.y_min(), 20.0);
  std::size_t high = 0;
  for (std::size_t j = 0; j < 7; ++j)
    for (std::size_t i = 0; i < 9; ++i) {
      const double d = (grid.node_position(i, j) - Vec2(12.0, 21.5)).norm();
      EXPECT_EQ(dz.at(i, j), d <= 1.0 ? 0.3 : 0.02) << i << ", " << j;
      high += dz.at(i, j) == 0.3;
    }
  // Nodes (i, j) with (i - 4)^2 + (j - 3)^2 <= 4 at 0.5 m spacing: 13 (the centre, 4 at 0.5 m,
  // 4 at 0.71 m, 4 at 1 m).
  EXPECT_EQ(high, 13u);
  EXPECT_THROW(uncertainty_disc_map(grid, -0.1, Vec2(12, 21), 1.0, 0.3), InputError);
  EXPECT_THROW(uncertainty_disc_map(grid, 0.0, Vec2(12, 21), 1.0, std::nan("")), InputError);
}

TEST(HaitScenarios, LengthWithinDisc) {
  const auto path = [](std::vector<Vec2> points) {
    std::vector<PathPoint> out;
    for (const Vec2& p : points) out.push_back({{p.x(), p.y(), 0.0}, {}});
    return out;
  };
  // Through the centre: the diameter.
  EXPECT_NEAR(length_within_disc(path({Vec2(-5, 0), Vec2(5, 0)}), Vec2(0, 0), 2.0), 4.0, 1e-12);
  // A chord at distance 1 from the centre of a disc of radius 2: 2 sqrt(3), over several pieces.
  EXPECT_NEAR(length_within_disc(path({Vec2(-5, 1), Vec2(-0.5, 1), Vec2(0.7, 1), Vec2(5, 1)}),
                                 Vec2(0, 0), 2.0),
              2.0 * std::sqrt(3.0), 1e-12);
  // Starting inside: from the centre out.
  EXPECT_NEAR(length_within_disc(path({Vec2(3, 4), Vec2(3, 9)}), Vec2(3, 4), 1.5), 1.5, 1e-12);
  // Missing, tangent, and degenerate paths.
  EXPECT_EQ(length_within_disc(path({Vec2(-5, 3), Vec2(5, 3)}), Vec2(0, 0), 2.0), 0.0);
  EXPECT_EQ(length_within_disc(path({Vec2(-5, 2), Vec2(5, 2)}), Vec2(0, 0), 2.0), 0.0);
  EXPECT_EQ(length_within_disc(path({Vec2(0, 0)}), Vec2(0, 0), 2.0), 0.0);
}

}  // namespace
}  // namespace talus
