#pragma once
/// @file
/// The terrain model of Haït, Siméon and Taïx, "Algorithms for rough terrain
/// trajectory planning" (Advanced Robotics 16(8), 2002), §2.1: the elevation
/// grid read as ruled surface patches. Each lattice cell [x_i, x_i+1] ×
/// [y_j, y_j+1] carries the bilinear patch through its four nodes,
///   z(a, b) = (1-a)(1-b) z_ij + a(1-b) z_i+1,j + (1-a) b z_i,j+1 + a b z_i+1,j+1,
/// with a, b ∈ [0, 1] the local coordinates. A bilinear patch is a ruled
/// surface (straight along every line a = const or b = const), it is C0 across
/// patch edges and reproduces the node values exactly.
#include <cstddef>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// Where a point falls on the patch lattice: patch (i, j) has its south-west
/// node at node (i, j); a, b ∈ [0, 1] are the local coordinates in it.
struct PatchLocation {
  std::size_t i = 0;  ///< patch column, 0 .. ncols-2
  std::size_t j = 0;  ///< patch row (from the south), 0 .. nrows-2
  double a = 0.0;     ///< (x - x_i) / h
  double b = 0.0;     ///< (y - y_j) / h
};

/// The elevation grid as the ruled (bilinear) surface of Haït et al. 2002 §2.
class RuledTerrain {
 public:
  /// Takes the grid by value and keeps its own copy.
  explicit RuledTerrain(ElevationGrid grid);

  /// The underlying node grid.
  const ElevationGrid& grid() const { return grid_; }
  /// Node spacing h [m].
  double spacing() const { return grid_.cellsize(); }
  /// Number of patch columns (ncols - 1) and rows (nrows - 1).
  std::size_t patch_cols() const { return grid_.ncols() - 1; }
  std::size_t patch_rows() const { return grid_.nrows() - 1; }

  /// True if p lies in the node lattice's bounding box [x_min, x_max] × [y_min, y_max].
  bool contains(const Vec2& p) const { return grid_.contains(p); }
  /// True if contains(p) and the four nodes of its patch are data (not NODATA).
  bool has_data(const Vec2& p) const;
  /// True if the four nodes of patch (i, j) are data. Unchecked indices.
  bool patch_has_data(std::size_t i, std::size_t j) const;

  /// The patch holding p and p's local coordinates. A point on a shared edge
  /// belongs to the patch to its north-east, except on the domain's east and
  /// north borders. Throws InputError if p is off the map.
  PatchLocation locate(const Vec2& p) const;

  /// Bilinear elevation z(p) [m]. Throws InputError off the map or on a NODATA patch.
  double elevation(const Vec2& p) const;
  /// Gradient (dz/dx, dz/dy) of the bilinear patch at p. On a patch edge the
  /// patch chosen by locate() decides (the surface is only C0 there). Same
  /// errors as elevation().
  Vec2 gradient(const Vec2& p) const;

  /// Envelopes for terrain uncertainty (§5.1): every node lowered / raised by dz >= 0.
  /// The paper gives an elevation interval δz per grid point and represents the
  /// terrain by the two ruled surfaces T_min, T_max through the lowered and
  /// raised node values; these build exactly those (NODATA stays NODATA).
  /// Because the bilinear interpolant is a convex combination of its nodes, any
  /// terrain whose nodes lie in [z - δz, z + δz] lies between the envelopes
  /// everywhere. Throws InputError if dz is negative or not finite.
  RuledTerrain lower_envelope(double dz) const;
  RuledTerrain upper_envelope(double dz) const;
  /// Same with a per-node interval δz(i, j) given as a grid of the same shape
  /// (its NODATA nodes count as δz = 0). Throws InputError on a shape mismatch
  /// or a negative / non-finite δz.
  RuledTerrain lower_envelope(const ElevationGrid& dz) const;
  RuledTerrain upper_envelope(const ElevationGrid& dz) const;

 private:
  RuledTerrain shifted(const ElevationGrid& dz, double sign) const;
  RuledTerrain shifted(double dz, double sign) const;
  void require_data(const Vec2& p, const PatchLocation& loc) const;

  ElevationGrid grid_;
};

}  // namespace talus
