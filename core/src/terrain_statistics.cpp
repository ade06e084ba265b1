#include "talus/core/terrain_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "talus/core/error.hpp"

namespace talus {

SecondDifferences second_differences(const ElevationGrid& grid) {
  SecondDifferences result;
  double sum_x = 0.0, sum_y = 0.0;
  for (std::size_t j = 1; j + 1 < grid.nrows(); ++j)
    for (std::size_t i = 1; i + 1 < grid.ncols(); ++i) {
      if (!grid.valid(i, j)) continue;
      const double z = grid.at(i, j);
      if (grid.valid(i - 1, j) && grid.valid(i + 1, j)) {
        sum_x += std::abs(grid.at(i + 1, j) - 2.0 * z + grid.at(i - 1, j));
        ++result.stencils_x;
      }
      if (grid.valid(i, j - 1) && grid.valid(i, j + 1)) {
        sum_y += std::abs(grid.at(i, j + 1) - 2.0 * z + grid.at(i, j - 1));
        ++result.stencils_y;
      }
    }
  if (result.stencils_x > 0) result.mean_abs_x = sum_x / static_cast<double>(result.stencils_x);
  if (result.stencils_y > 0) result.mean_abs_y = sum_y / static_cast<double>(result.stencils_y);
  return result;
}

std::optional<GridNode> highest_node(const ElevationGrid& grid) {
  std::optional<GridNode> best;
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      if (!grid.valid(i, j)) continue;
      if (!best || grid.at(i, j) > best->z)
        best = GridNode{i, j, grid.node_position(i, j), grid.at(i, j)};
    }
  return best;
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) throw InputError("quantile: no values");
  if (!(q >= 0.0 && q <= 1.0)) {
    throw InputError("quantile: q must lie in [0, 1], got " + std::to_string(q));
  }
  if (std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); })) {
    throw InputError("quantile: the values hold a NaN");
  }
  const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

}  // namespace talus
