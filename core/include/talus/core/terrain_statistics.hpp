#pragma once
/// @file
/// Summary statistics of an elevation grid's node values: roughness as mean
/// second differences, the highest node, and a nearest-rank quantile. Plain
/// node arithmetic, independent of any fitted surface.
#include <cstddef>
#include <optional>
#include <vector>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// Mean absolute second difference of the node values along each axis [m]:
/// mean of |z(i+1, j) − 2 z(i, j) + z(i−1, j)| (x) and of
/// |z(i, j+1) − 2 z(i, j) + z(i, j−1)| (y) over the interior nodes
/// (1 <= i <= ncols − 2, 1 <= j <= nrows − 2) whose three-node stencil along
/// that axis is valid. A plane gives 0 along both axes; a row-wise terracing
/// artefact shows as mean_abs_y well above mean_abs_x.
struct SecondDifferences {
  double mean_abs_x = 0.0;     ///< [m]; 0 if no stencil along x is valid
  double mean_abs_y = 0.0;     ///< [m]; 0 if no stencil along y is valid
  std::size_t stencils_x = 0;  ///< interior nodes counted along x
  std::size_t stencils_y = 0;  ///< interior nodes counted along y
};
SecondDifferences second_differences(const ElevationGrid& grid);

/// A node of a grid with its index, position [m] and elevation [m].
struct GridNode {
  std::size_t i = 0, j = 0;
  Vec2 position = Vec2::Zero();
  double z = 0.0;
};

/// The valid node with the largest elevation; among equal maxima the first
/// in row-major order (row 0, the southern one, first). nullopt if every
/// node is NODATA.
std::optional<GridNode> highest_node(const ElevationGrid& grid);

/// Nearest-rank quantile: the element of rank round(q (n − 1)) (0-based, ties
/// of the rounding upwards) of `values` in ascending order, so q = 0 is the
/// minimum, q = 1 the maximum and q = 0.5 the median of an odd count.
/// Throws InputError if `values` is empty, holds a NaN, or q is outside [0, 1].
double quantile(std::vector<double> values, double q);

}  // namespace talus
