// Test terrains from formulas: elevation grids holding z = f(x, y) at every node.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>

#include "talus/core/elevation_grid.hpp"

namespace talus::terrain_test {

/// A height z = f(x, y) [m] over the plane.
using HeightFunction = std::function<double(double, double)>;

/// `ncols` x `nrows` nodes at spacing `cell`, the south-west one at (x0, y0),
/// each holding f at its position.
inline ElevationGrid grid_of_nodes(const HeightFunction& f, std::size_t ncols, std::size_t nrows,
                                   double cell, double x0, double y0) {
  ElevationGrid grid(ncols, nrows, cell, x0, y0);
  for (std::size_t j = 0; j < nrows; ++j)
    for (std::size_t i = 0; i < ncols; ++i) {
      const Vec2 p = grid.node_position(i, j);
      grid.at(i, j) = f(p.x(), p.y());
    }
  return grid;
}

/// The nodes at spacing `cell` over [x0, x1] x [y0, y1] (the extents rounded
/// to whole cells), each holding f at its position.
inline ElevationGrid grid_from_function(const HeightFunction& f, double x0, double y0, double x1,
                                        double y1, double cell) {
  const auto ncols = static_cast<std::size_t>(std::lround((x1 - x0) / cell)) + 1;
  const auto nrows = static_cast<std::size_t>(std::lround((y1 - y0) / cell)) + 1;
  return grid_of_nodes(f, ncols, nrows, cell, x0, y0);
}

/// The square [-half_width, half_width]^2 at spacing `cell`, holding f.
inline ElevationGrid grid_around_origin(const HeightFunction& f, double half_width, double cell) {
  return grid_from_function(f, -half_width, -half_width, half_width, half_width, cell);
}

/// A Gaussian hill z = height exp(-|p - centre|^2 / (2 sigma^2)) [m] on flat ground at z = 0.
inline HeightFunction gaussian_hill(const Vec2& centre, double height, double sigma) {
  return [centre, height, sigma](double x, double y) {
    return height * std::exp(-(Vec2(x, y) - centre).squaredNorm() / (2 * sigma * sigma));
  };
}

}  // namespace talus::terrain_test
