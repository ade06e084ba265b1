// The terrains of the global-search tests (test_global_search.cpp) that the
// multi-resolution tests (test_global_search_multi.cpp) rerun, in one place.
#pragma once

#include <cmath>

#include "talus/bspline/bpatch.hpp"
#include "talus/optimal/global_search.hpp"
#include "terrain_test_support.hpp"

namespace talus::global_search_test {

/// A Gaussian hill of `height` and standard deviation `sigma` [m] at (40, 30)
/// on an 80 m x 60 m grid of 1 m cells: between the tests' start and goal.
inline BPatch hill(double height, double sigma) {
  return BPatch::interpolate(terrain_test::grid_from_function(
      [&](double x, double y) {
        return height *
               std::exp(-((x - 40) * (x - 40) + (y - 30) * (y - 30)) / (2 * sigma * sigma));
      },
      0, 0, 80, 60, 1.0));
}

/// Twelve 6 m bumps on the same grid: many near-equal routes, for the
/// candidate options.
inline BPatch bumps() {
  return BPatch::interpolate(terrain_test::grid_from_function(
      [](double x, double y) {
        double z = 0.0;
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 3; ++j) {
            const double cx = 18.0 + 14.0 * i + 3.0 * (j % 2), cy = 12.0 + 16.0 * j;
            z += 6.0 * std::exp(-((x - cx) * (x - cx) + (y - cy) * (y - cy)) / 18.0);
          }
        return z;
      },
      0, 0, 80, 60, 1.0));
}

/// J recomputed independently along a candidate's vertices, edge by edge.
inline double recomputed_cost(const BPatch& terrain, const Vehicle& v, const CandidatePath& c,
                              double spacing) {
  double total = 0.0;
  for (std::size_t k = 0; k + 1 < c.vertices.size(); ++k) {
    const Vec2 a = c.vertices[k], b = c.vertices[k + 1];
    const int stations = edge_stations((b - a).norm(), spacing);
    total += edge_cost(terrain, v, a, b, stations).forward;
  }
  return total;
}

}  // namespace talus::global_search_test
