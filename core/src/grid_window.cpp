#include "talus/core/grid_window.hpp"

#include <cmath>
#include <string>

#include "talus/core/error.hpp"

namespace talus {

ElevationGrid crop_grid(const ElevationGrid& grid, const GridWindow& window) {
  // Written so that col + ncols cannot wrap.
  const bool fits = window.col <= grid.ncols() && window.ncols <= grid.ncols() - window.col &&
                    window.row <= grid.nrows() && window.nrows <= grid.nrows() - window.row;
  if (window.ncols < 2 || window.nrows < 2 || !fits) {
    throw InputError("crop_grid: a window of " + std::to_string(window.ncols) + " × " +
                     std::to_string(window.nrows) + " nodes at column " +
                     std::to_string(window.col) + ", row " + std::to_string(window.row) +
                     (window.ncols < 2 || window.nrows < 2
                          ? " has fewer than 2 × 2 nodes"
                          : " does not fit the " + std::to_string(grid.ncols()) + " × " +
                                std::to_string(grid.nrows()) + "-node grid"));
  }
  const double h = grid.cellsize();
  ElevationGrid out(window.ncols, window.nrows, h,
                    grid.x_min() + static_cast<double>(window.col) * h,
                    grid.y_min() + static_cast<double>(window.row) * h);
  for (std::size_t j = 0; j < window.nrows; ++j)
    for (std::size_t i = 0; i < window.ncols; ++i) {
      // The stored value of a NODATA node is copied too, so that a whole-grid
      // window is an exact copy.
      out.at(i, j) = grid.at(window.col + i, window.row + j);
      if (!grid.valid(window.col + i, window.row + j)) out.set_void(i, j);
    }
  return out;
}

Vec2 grid_position(const ElevationGrid& grid, const GridIndex& index) {
  if (!std::isfinite(index.i) || !std::isfinite(index.j)) {
    throw InputError("grid_position: node index (" + std::to_string(index.i) + ", " +
                     std::to_string(index.j) + ") is not finite");
  }
  return {grid.x_min() + index.i * grid.cellsize(), grid.y_min() + index.j * grid.cellsize()};
}

}  // namespace talus
