// crop_grid and grid_position (talus/core/grid_window.hpp): a window keeps the
// parent's values, NODATA marks and georeferencing; bad windows are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "talus/core/error.hpp"
#include "talus/core/grid_window.hpp"

namespace talus {
namespace {

/// 9 × 7 nodes, cell 2.5 m, south-west node at (1000.5, -200.25), value 100 i + j,
/// NODATA at (3, 2) and (6, 5).
ElevationGrid parent_grid() {
  ElevationGrid grid(9, 7, 2.5, 1000.5, -200.25);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) grid.set(i, j, 100.0 * i + j);
  grid.set_void(3, 2);
  grid.set_void(6, 5);
  return grid;
}

TEST(GridWindow, CropKeepsValuesVoidsAndPositionsOfTheParentNodes) {
  const ElevationGrid parent = parent_grid();
  const GridWindow window{2, 1, 5, 5};
  const ElevationGrid crop = crop_grid(parent, window);
  ASSERT_EQ(crop.ncols(), 5u);
  ASSERT_EQ(crop.nrows(), 5u);
  EXPECT_EQ(crop.cellsize(), parent.cellsize());
  EXPECT_EQ(crop.void_count(), 2u);  // both NODATA nodes lie in the window
  for (std::size_t j = 0; j < crop.nrows(); ++j)
    for (std::size_t i = 0; i < crop.ncols(); ++i) {
      const std::size_t pi = i + window.col, pj = j + window.row;
      ASSERT_EQ(crop.valid(i, j), parent.valid(pi, pj)) << i << ", " << j;
      if (crop.valid(i, j)) {
        EXPECT_EQ(crop.at(i, j), parent.at(pi, pj)) << i << ", " << j;
      }
      const Vec2 a = crop.node_position(i, j), b = parent.node_position(pi, pj);
      EXPECT_NEAR(a.x(), b.x(), 1e-12 * std::abs(b.x()));
      EXPECT_NEAR(a.y(), b.y(), 1e-12 * std::abs(b.y()));
    }
  EXPECT_FALSE(crop.valid(1, 1));  // parent (3, 2)
  EXPECT_FALSE(crop.valid(4, 4));  // parent (6, 5)
  EXPECT_EQ(crop.at(0, 0), 201.0);
  EXPECT_EQ(crop.x_min(), 1000.5 + 2 * 2.5);
  EXPECT_EQ(crop.y_min(), -200.25 + 2.5);
}

TEST(GridWindow, WholeGridWindowIsACopy) {
  const ElevationGrid parent = parent_grid();
  const ElevationGrid copy = crop_grid(parent, {0, 0, parent.ncols(), parent.nrows()});
  EXPECT_EQ(copy.values(), parent.values());
  EXPECT_EQ(copy.x_min(), parent.x_min());
  EXPECT_EQ(copy.y_min(), parent.y_min());
  EXPECT_EQ(copy.x_max(), parent.x_max());
  EXPECT_EQ(copy.y_max(), parent.y_max());
  EXPECT_EQ(copy.void_count(), parent.void_count());
}

TEST(GridWindow, NorthEastCornerWindowEndsOnTheParentsLastNode) {
  const ElevationGrid parent = parent_grid();
  const ElevationGrid crop = crop_grid(parent, {7, 5, 2, 2});
  EXPECT_EQ(crop.at(1, 1), parent.at(8, 6));
  EXPECT_NEAR(crop.x_max(), parent.x_max(), 1e-12 * parent.x_max());
  EXPECT_NEAR(crop.y_max(), parent.y_max(), 1e-12 * std::abs(parent.y_max()));
}

TEST(GridWindow, WindowsOutsideTheGridOrTooSmallAreRefused) {
  const ElevationGrid parent = parent_grid();
  constexpr std::size_t kHuge = std::numeric_limits<std::size_t>::max();
  EXPECT_THROW(crop_grid(parent, {0, 0, 10, 7}), InputError);  // one column too many
  EXPECT_THROW(crop_grid(parent, {0, 0, 9, 8}), InputError);   // one row too many
  EXPECT_THROW(crop_grid(parent, {8, 0, 2, 2}), InputError);   // starts on the last column
  EXPECT_THROW(crop_grid(parent, {0, 6, 2, 2}), InputError);
  EXPECT_THROW(crop_grid(parent, {kHuge, 0, 2, 2}), InputError);  // col + ncols would wrap
  EXPECT_THROW(crop_grid(parent, {2, 0, kHuge, 2}), InputError);
  EXPECT_THROW(crop_grid(parent, {0, kHuge - 1, 2, 3}), InputError);
  EXPECT_THROW(crop_grid(parent, {0, 0, 1, 5}), InputError);  // fewer than 2 x 2 nodes
  EXPECT_THROW(crop_grid(parent, {0, 0, 5, 0}), InputError);
  EXPECT_THROW(crop_grid(ElevationGrid(), {0, 0, 2, 2}), InputError);
  try {
    crop_grid(parent, {3, 4, 7, 2});
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("7 × 2"), std::string::npos) << message;
    EXPECT_NE(message.find("9 × 7"), std::string::npos) << message;
  }
}

TEST(GridWindow, GridPositionOfFractionalIndices) {
  const ElevationGrid parent = parent_grid();
  const Vec2 p = grid_position(parent, {1.5, 2.25});
  EXPECT_DOUBLE_EQ(p.x(), 1000.5 + 1.5 * 2.5);
  EXPECT_DOUBLE_EQ(p.y(), -200.25 + 2.25 * 2.5);
  // Whole indices are the node positions; indices outside the grid extrapolate.
  EXPECT_EQ(grid_position(parent, {4.0, 3.0}), parent.node_position(4, 3));
  EXPECT_DOUBLE_EQ(grid_position(parent, {-2.0, 0.0}).x(), 1000.5 - 5.0);
  EXPECT_THROW(grid_position(parent, {std::nan(""), 0.0}), InputError);
  EXPECT_THROW(grid_position(parent, {0.0, std::numeric_limits<double>::infinity()}), InputError);
}

}  // namespace
}  // namespace talus

namespace talus {
namespace {

TEST(DecimateGrid, KeepsEveryKthNodeItsVoidAndItsPosition) {
  ElevationGrid grid(10, 7, 2.0, 100.0, 50.0);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) grid.at(i, j) = 10.0 * i + j;
  grid.set_void(3, 3);
  const ElevationGrid coarse = decimate_grid(grid, 3);
  ASSERT_EQ(coarse.ncols(), 4u);  // nodes 0, 3, 6, 9
  ASSERT_EQ(coarse.nrows(), 3u);  // nodes 0, 3, 6
  EXPECT_DOUBLE_EQ(coarse.cellsize(), 6.0);
  for (std::size_t j = 0; j < coarse.nrows(); ++j)
    for (std::size_t i = 0; i < coarse.ncols(); ++i) {
      EXPECT_EQ(coarse.node_position(i, j), grid.node_position(3 * i, 3 * j));
      EXPECT_EQ(coarse.valid(i, j), !(i == 1 && j == 1));
      if (coarse.valid(i, j)) {
        EXPECT_DOUBLE_EQ(coarse.at(i, j), 10.0 * (3 * i) + 3 * j);
      }
    }
  EXPECT_EQ(decimate_grid(grid, 1).ncols(), grid.ncols());
  EXPECT_THROW(decimate_grid(grid, 0), InputError);
  EXPECT_THROW(decimate_grid(grid, 7), InputError);  // 7 rows: one node left
}

}  // namespace
}  // namespace talus
