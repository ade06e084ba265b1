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

ElevationGrid decimate_grid(const ElevationGrid& grid, std::size_t factor) {
  if (factor == 0) throw InputError("decimate_grid: the factor must be >= 1");
  const std::size_t nc = (grid.ncols() - 1) / factor + 1, nr = (grid.nrows() - 1) / factor + 1;
  if (nc < 2 || nr < 2) {
    throw InputError("decimate_grid: every " + std::to_string(factor) + "th node of a " +
                     std::to_string(grid.ncols()) + " × " + std::to_string(grid.nrows()) +
                     "-node grid leaves fewer than 2 × 2 nodes");
  }
  ElevationGrid out(nc, nr, static_cast<double>(factor) * grid.cellsize(), grid.x_min(),
                    grid.y_min());
  for (std::size_t j = 0; j < nr; ++j)
    for (std::size_t i = 0; i < nc; ++i) {
      out.at(i, j) = grid.at(i * factor, j * factor);
      if (!grid.valid(i * factor, j * factor)) out.set_void(i, j);
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
