#include <gtest/gtest.h>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"

namespace talus {
namespace {

TEST(ElevationGrid, NodePositionsFollowTheDocumentedConvention) {
  ElevationGrid grid(4, 3, 2.0, 10.0, 20.0);
  EXPECT_DOUBLE_EQ(grid.x_max(), 16.0);
  EXPECT_DOUBLE_EQ(grid.y_max(), 24.0);
  EXPECT_EQ(grid.node_position(3, 2), Vec2(16.0, 24.0));
  EXPECT_TRUE(grid.contains({16.0, 24.0}));
  EXPECT_FALSE(grid.contains({16.0001, 24.0}));
}

TEST(ElevationGrid, BilinearReproducesAPlaneAndRejectsPointsOffTheMap) {
  ElevationGrid grid(5, 4, 0.5, -1.0, 2.0);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const Vec2 p = grid.node_position(i, j);
      grid.at(i, j) = 3.0 + 0.2 * p.x() - 0.7 * p.y();
    }
  for (const Vec2& p : {Vec2(-0.8, 2.3), Vec2(1.0, 3.5), Vec2(0.1234, 2.9)}) {
    EXPECT_NEAR(grid.bilinear(p), 3.0 + 0.2 * p.x() - 0.7 * p.y(), 1e-12);
  }
  EXPECT_THROW(grid.bilinear({1.5, 2.0}), InputError);
  EXPECT_THROW(grid.bilinear({0.0, 1.9}), InputError);
}

TEST(ElevationGrid, RejectsDegenerateShapes) {
  EXPECT_THROW(ElevationGrid(1, 5, 1.0, 0, 0), InputError);
  EXPECT_THROW(ElevationGrid(5, 5, 0.0, 0, 0), InputError);
  EXPECT_THROW(ElevationGrid(5, 5, -1.0, 0, 0), InputError);
  EXPECT_THROW(ElevationGrid(5, 5, std::nan(""), 0, 0), InputError);
}

TEST(ElevationGrid, NearestFillTakesTheClosestValidValue) {
  ElevationGrid grid(5, 1 + 1, 1.0, 0, 0);
  for (std::size_t i = 0; i < 5; ++i) {
    grid.set(i, 0, static_cast<double>(i));
    grid.set(i, 1, static_cast<double>(i));
  }
  grid.set_void(0, 0);
  grid.set_void(4, 1);
  EXPECT_EQ(grid.void_count(), 2u);
  EXPECT_THROW(grid.bilinear({0.5, 0.5}), InputError);
  const ElevationGrid filled = fill_voids(grid, VoidFill::kNearest);
  EXPECT_EQ(filled.void_count(), 0u);
  EXPECT_DOUBLE_EQ(filled.at(4, 1), 3.0);  // neighbours: (3,1)=3, (3,0)=3, (4,0)=4; (3,0) is first
  EXPECT_DOUBLE_EQ(filled.at(0, 0),
                   1.0);  // ties at equal distance go to the first valid node in scan order
}

TEST(ElevationGrid, VoidFillUsesTheChebyshevDistance) {
  // Two valid nodes on a 5 x 5 void grid: (3, 3) = 10 and (0, 4) = 20. From (0, 0) the first is
  // 3 steps away in Chebyshev distance (Euclidean 4.24, Manhattan 6), the second 4 (Euclidean and
  // Manhattan 4): only the Chebyshev metric picks 10 there.
  ElevationGrid grid(5, 5, 1.0, 0, 0);
  for (std::size_t j = 0; j < 5; ++j)
    for (std::size_t i = 0; i < 5; ++i) grid.set_void(i, j);
  grid.set(3, 3, 10.0);
  grid.set(0, 4, 20.0);
  const ElevationGrid filled = fill_voids(grid, VoidFill::kNearest);
  EXPECT_EQ(filled.at(0, 0), 10.0);
  EXPECT_EQ(filled.at(0, 3), 20.0);  // 1 step from (0, 4), 3 from (3, 3)
  EXPECT_EQ(filled.at(4, 0), 10.0);  // 3 steps from (3, 3), 4 from (0, 4)
  EXPECT_EQ(filled.at(3, 3), 10.0);  // valid nodes keep their values
  EXPECT_EQ(filled.at(0, 4), 20.0);
}

TEST(ElevationGrid, FillingAnAllVoidGridIsAnError) {
  ElevationGrid grid(3, 3, 1.0, 0, 0);
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < 3; ++i) grid.set_void(i, j);
  EXPECT_FALSE(grid.elevation_range().has_value());
  EXPECT_THROW(fill_voids(grid, VoidFill::kNearest), InputError);
}

}  // namespace
}  // namespace talus
