#pragma once
/// @file
/// A regular elevation grid with a NODATA mask.
///
/// Conventions (also in the README):
/// - x east, y north, z up, all in metres.
/// - Values are *node* values at cell centres. Node (i, j) — column i counted
///   west to east, row j counted **south to north** — sits at
///   (x_min + i h, y_min + j h), where h is the cell size and (x_min, y_min) is
///   the centre of the south-west cell. An ESRI `xllcorner` is therefore
///   `x_min - h/2`; files list rows north to south and the reader flips them.
/// - The grid's domain is the rectangle spanned by the nodes,
///   [x_min, x_max] × [y_min, y_max] with x_max = x_min + (ncols - 1) h.
#include <cstddef>
#include <optional>
#include <vector>

#include "talus/core/types.hpp"

namespace talus {

/// Largest |elevation| Talus accepts [m] (readers and generators refuse
/// more). Earth's relief spans about 2e4 m; the bound keeps squares and
/// B-patch fits far from overflow, and catches a float NODATA (-3.4e38) that
/// the file forgot to declare.
inline constexpr double kMaxElevationMagnitude = 1e9;

/// Regular grid of elevations [m] with a validity mask (false = NODATA).
class ElevationGrid {
 public:
  ElevationGrid() = default;
  /// Grid of `ncols` × `nrows` nodes, all valid and at elevation `fill`.
  /// Throws InputError if a size is < 2 or the cell size is not positive and finite.
  ElevationGrid(std::size_t ncols, std::size_t nrows, double cellsize, double x_min, double y_min,
                double fill = 0.0);

  std::size_t ncols() const { return ncols_; }
  std::size_t nrows() const { return nrows_; }
  double cellsize() const { return cellsize_; }
  double x_min() const { return x_min_; }
  double y_min() const { return y_min_; }
  double x_max() const { return x_min_ + static_cast<double>(ncols_ - 1) * cellsize_; }
  double y_max() const { return y_min_ + static_cast<double>(nrows_ - 1) * cellsize_; }
  Vec2 node_position(std::size_t i, std::size_t j) const;

  /// Elevation at node (column i, row j from the south). Unchecked.
  double& at(std::size_t i, std::size_t j) { return z_[j * ncols_ + i]; }
  double at(std::size_t i, std::size_t j) const { return z_[j * ncols_ + i]; }
  bool valid(std::size_t i, std::size_t j) const { return valid_[j * ncols_ + i] != 0; }
  void set_void(std::size_t i, std::size_t j) { valid_[j * ncols_ + i] = 0; }
  void set(std::size_t i, std::size_t j, double z);

  std::size_t void_count() const;
  /// Smallest and largest valid elevation; nullopt if every node is NODATA.
  std::optional<std::pair<double, double>> elevation_range() const;

  /// True if (x, y) lies in the domain [x_min, x_max] × [y_min, y_max].
  bool contains(const Vec2& p) const;
  /// Bilinear interpolation of the four surrounding nodes, for reference and
  /// tests. Throws InputError if p is outside the domain or a corner is NODATA.
  double bilinear(const Vec2& p) const;

  /// Row-major storage, row j (from the south) after row j-1.
  const std::vector<double>& values() const { return z_; }

 private:
  std::size_t ncols_ = 0, nrows_ = 0;
  double cellsize_ = 1.0, x_min_ = 0.0, y_min_ = 0.0;
  std::vector<double> z_;
  std::vector<unsigned char> valid_;
};

/// Ways to fill NODATA nodes, used only when the caller names one.
enum class VoidFill {
  /// Each void takes the value of the nearest valid node in Chebyshev distance (the number of
  /// 8-neighbour steps); ties go to the node whose breadth-first wave arrives first (valid
  /// nodes start in row-major order).
  kNearest,
};

/// A copy of `grid` with every NODATA node filled by `method`.
/// Throws InputError if the grid has no valid node at all.
ElevationGrid fill_voids(const ElevationGrid& grid, VoidFill method);

}  // namespace talus
