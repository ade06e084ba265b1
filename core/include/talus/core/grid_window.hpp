#pragma once
/// @file
/// Rectangular windows of an ElevationGrid, counted in node indices, and
/// positions of (fractional) node indices: cutting a study area out of a DEM
/// without losing its georeferencing.
///
/// Indices follow elevation_grid.hpp: column i from the west, row j from the
/// south, node (i, j) at (x_min + i h, y_min + j h).
#include <cstddef>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// A window of `ncols` × `nrows` nodes whose south-west node is node
/// (`col`, `row`) of the parent grid.
struct GridWindow {
  std::size_t col = 0;    ///< parent column of the window's west edge
  std::size_t row = 0;    ///< parent row of the window's south edge
  std::size_t ncols = 0;  ///< nodes along x (>= 2)
  std::size_t nrows = 0;  ///< nodes along y (>= 2)
};

/// The window `window` of `grid` as a grid of its own: same cell size, node
/// (i, j) holding the value and the NODATA mark of parent node
/// (col + i, row + j) and sitting at the parent node's position (up to the
/// rounding of x_min + (col + i) h against (x_min + col h) + i h).
/// Throws InputError, naming both sizes, if the window has fewer than 2 × 2
/// nodes or does not lie inside the grid.
ElevationGrid crop_grid(const ElevationGrid& grid, const GridWindow& window);

/// Every `factor`-th node of `grid` in both directions from its south-west
/// node (values and NODATA marks as they are, no filtering): the coarse map
/// data of a layered planner, cell size factor × h, same origin, and
/// (ncols − 1) / factor + 1 by (nrows − 1) / factor + 1 nodes. Throws
/// InputError for factor 0 or fewer than 2 × 2 nodes left.
ElevationGrid decimate_grid(const ElevationGrid& grid, std::size_t factor);

/// A node index that may fall between nodes: i columns east and j rows north
/// of the south-west node (fractions interpolate linearly).
struct GridIndex {
  double i = 0.0;
  double j = 0.0;
};

/// Position [m] of the (fractional) node index `index` of `grid`:
/// (x_min + i h, y_min + j h). The index need not lie inside the grid.
/// Throws InputError if an index is not finite.
Vec2 grid_position(const ElevationGrid& grid, const GridIndex& index);

}  // namespace talus
