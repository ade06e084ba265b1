// second_differences, highest_node and quantile (talus/core/terrain_statistics.hpp)
// against grids whose statistics are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/terrain_statistics.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_of_nodes;

TEST(TerrainStatistics, SecondDifferencesOfAPlaneAreZero) {
  const ElevationGrid plane =
      grid_of_nodes([](double x, double y) { return 3.0 * x - 2.0 * y + 7.0; }, 6, 5, 1.0, 0, 0);
  const SecondDifferences d = second_differences(plane);
  EXPECT_EQ(d.mean_abs_x, 0.0);
  EXPECT_EQ(d.mean_abs_y, 0.0);
  EXPECT_EQ(d.stencils_x, 4u * 3u);  // interior nodes
  EXPECT_EQ(d.stencils_y, 4u * 3u);
}

TEST(TerrainStatistics, SecondDifferencesOfQuadraticsAreTheirSecondDerivativeTimesHSquared) {
  // z = a x² + b y² at cell h: the second difference is 2 a h² along x, 2 b h² along y,
  // whatever the sign convention of the terrain.
  const double h = 2.0;
  const ElevationGrid bowl = grid_of_nodes(
      [](double x, double y) { return 0.25 * x * x - 1.5 * y * y + 0.5 * x; }, 7, 6, h, -4.0, 2.0);
  const SecondDifferences d = second_differences(bowl);
  EXPECT_NEAR(d.mean_abs_x, 2.0 * 0.25 * h * h, 1e-12);
  EXPECT_NEAR(d.mean_abs_y, 2.0 * 1.5 * h * h, 1e-11);
}

TEST(TerrainStatistics, SecondDifferencesSkipStencilsWithNodata) {
  ElevationGrid grid = grid_of_nodes([](double x, double) { return x * x; }, 5, 5, 1.0, 0, 0);
  grid.set_void(2, 2);  // the centre: its own stencils and those of its four neighbours
  grid.set_void(0, 1);  // the west edge: the x stencil of (1, 1) only
  grid.at(0, 1) = 1e6;  // a NODATA value must not leak into the mean
  const SecondDifferences d = second_differences(grid);
  EXPECT_EQ(d.stencils_x, 9u - 1u - 2u - 1u);
  EXPECT_EQ(d.stencils_y, 9u - 1u - 2u);
  EXPECT_EQ(d.mean_abs_x, 2.0);
  EXPECT_EQ(d.mean_abs_y, 0.0);
}

TEST(TerrainStatistics, HighestNodeIsTheFirstValidMaximumInRowMajorOrder) {
  ElevationGrid grid(4, 3, 10.0, 500.0, 600.0, 1.0);
  grid.set(2, 0, 5.0);
  grid.set(1, 2, 5.0);  // equal, later in row-major order
  grid.set(3, 1, 9.0);
  grid.set_void(3, 1);  // the true maximum is NODATA
  const std::optional<GridNode> top = highest_node(grid);
  ASSERT_TRUE(top.has_value());
  EXPECT_EQ(top->i, 2u);
  EXPECT_EQ(top->j, 0u);
  EXPECT_EQ(top->z, 5.0);
  EXPECT_EQ(top->position, Vec2(520.0, 600.0));

  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) grid.set_void(i, j);
  EXPECT_FALSE(highest_node(grid).has_value());
}

TEST(TerrainStatistics, NearestRankQuantile) {
  const std::vector<double> values{5.0, 1.0, 4.0, 2.0, 3.0};
  EXPECT_EQ(quantile(values, 0.0), 1.0);
  EXPECT_EQ(quantile(values, 1.0), 5.0);
  EXPECT_EQ(quantile(values, 0.5), 3.0);
  EXPECT_EQ(quantile(values, 0.25), 2.0);   // rank 1
  EXPECT_EQ(quantile(values, 0.375), 3.0);  // rank 1.5 rounds up to 2
  EXPECT_EQ(quantile(values, 0.37), 2.0);   // rank 1.48
  EXPECT_EQ(quantile({7.0}, 0.99), 7.0);
  // 99th percentile of 0..99: rank round(98.01) = 98.
  std::vector<double> hundred;
  for (int k = 99; k >= 0; --k) hundred.push_back(k);
  EXPECT_EQ(quantile(hundred, 0.99), 98.0);
}

TEST(TerrainStatistics, QuantileRefusesEmptyInputNaNAndQOutsideTheUnitInterval) {
  EXPECT_THROW(quantile({}, 0.5), InputError);
  EXPECT_THROW(quantile({1.0, 2.0}, -0.01), InputError);
  EXPECT_THROW(quantile({1.0, 2.0}, 1.01), InputError);
  EXPECT_THROW(quantile({1.0, 2.0}, std::nan("")), InputError);
  EXPECT_THROW(quantile({1.0, std::nan(""), 2.0}, 0.5), InputError);
}

}  // namespace
}  // namespace talus
