#pragma once
/// @file
/// The hierarchical terrain model for collision checking of Haït, Siméon and
/// Taïx 2002, §3.3: a quadtree over the ruled terrain whose every cell holds
/// the least-squares mean plane of its grid points and the min / max signed
/// distance of those points to it, so that the terrain inside the cell lies in
/// a slab ("parallelepiped") between two parallel planes.
///
/// Why the slab of the grid points bounds the whole surface: a point of a
/// bilinear patch is (x, y, z)(a, b) = Σ w_k (x_k, y_k, z_k) with weights
/// (1-a)(1-b), a(1-b), (1-a)b, ab ≥ 0 summing to 1 (x and y are affine in
/// a, b), a convex combination of its four corner nodes. Its signed distance to
/// any plane is therefore between the corners' extremes.
///
/// Choices the paper leaves open, made here:
/// - The mean plane is the vertical least-squares fit z = z_c + g_x (x - x_c) +
///   g_y (y - y_c) over the cell's valid nodes; distances are orthogonal to it.
/// - A cell spans a rectangle of patches and splits at the middle of each side
///   (in two when one side is a single patch), so any grid size works.
/// - A cell touching a NODATA node has no slab and is always descended; a
///   NODATA patch under the face collides or not as the options say. The
///   terrain outside the grid is absent: a face never collides there.
/// - For terrain uncertainty (§5.1.2) build the tree on T_max
///   (RuledTerrain::upper_envelope), as the paper does.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// Options of TerrainQuadtree.
struct TerrainQuadtreeOptions {
  /// Subdivision stops when a cell's thickness (max − min orthogonal distance
  /// of its nodes to its mean plane) is below h0 [m] (>= 0; 0 = always go
  /// down to single patches). 2 cm: below the vertical accuracy of the DEMs and
  /// placements we use, so finer cells would rarely decide a query.
  double h0 = 0.02;
  /// Whether a face over a NODATA patch collides (true: unknown terrain is an
  /// obstacle).
  bool nodata_collides = true;
  /// Throws InputError naming the offending field.
  void validate() const;
};

/// One quadtree cell: patches [i0, i1) × [j0, j1) and their slab.
struct QuadtreeCell {
  std::uint32_t i0 = 0, j0 = 0, i1 = 0, j1 = 0;  ///< patch index ranges (half-open)
  std::uint32_t first_child = 0;                 ///< index of the first child in cells()
  std::uint8_t child_count = 0;                  ///< 0 (leaf), 2 or 4; children are contiguous
  bool has_nodata = false;                       ///< touches a NODATA node: no slab
  Vec2 centre = Vec2::Zero();                    ///< (x_c, y_c) of the mean plane [m]
  double z_c = 0.0;                              ///< mean plane elevation at the centre [m]
  Vec2 slope = Vec2::Zero();                     ///< mean plane gradient (g_x, g_y)
  double d_min = 0.0, d_max = 0.0;  ///< min / max signed orthogonal distance of nodes [m]
  /// Slab thickness d_max − d_min [m].
  double thickness() const { return d_max - d_min; }
  /// Mean plane elevation at p [m].
  double plane(const Vec2& p) const { return z_c + slope.dot(p - centre); }
};

/// Work counters of one collision query.
struct QuadtreeQueryStats {
  std::size_t cells_visited = 0;   ///< cells whose slab was compared with the face
  std::size_t patches_tested = 0;  ///< exact face-vs-bilinear-patch tests
};

/// Quadtree collision model of a ruled terrain (Haït et al. 2002, §3.3).
class TerrainQuadtree {
 public:
  /// Builds the tree in O(N log N) for N nodes. Keeps its own copy of the terrain.
  explicit TerrainQuadtree(RuledTerrain terrain, const TerrainQuadtreeOptions& options = {});

  /// True if the terrain rises strictly above the planar convex polygon `face`
  /// somewhere in the face's footprint (its vertical projection), i.e. the
  /// chassis face penetrates the ground. `face`: 3–8 vertices in world
  /// coordinates [m], counter-clockwise seen from above, coplanar, convex, not
  /// vertical. Slab rule per cell (§3.3.2): the upper slab plane below the face
  /// over the footprint part in the cell → free; the lower slab plane above the
  /// face somewhere there → collision; otherwise descend, and at a leaf test
  /// each patch under the footprint exactly. Exact test: on patch (i, j) the
  /// height of the terrain above the face plane is g = A + B a + C b + r a b
  /// in the patch's local coordinates, r = z00 − z10 − z01 + z11. Its Hessian
  /// [[0, r], [r, 0]] is indefinite unless r = 0 (then g is affine), so g has
  /// no interior maximum over the convex region footprint ∩ patch: the maximum
  /// lies on the region's boundary. Along an edge g is a quadratic in the edge
  /// parameter with leading coefficient r·Δa·Δb, so the maximum is at a vertex
  /// or, if that coefficient is negative, at the edge's stationary point.
  /// Collision iff that maximum is > 0. Throws InputError on a bad face.
  bool collides(std::span<const Vec3> face, QuadtreeQueryStats* stats = nullptr) const;

  /// Same answer as collides() by the exact test on every patch under the
  /// footprint, without the tree (reference for tests and benchmarks).
  bool brute_force_collides(std::span<const Vec3> face, QuadtreeQueryStats* stats = nullptr) const;

  /// The terrain the tree was built on.
  const RuledTerrain& terrain() const { return terrain_; }
  const TerrainQuadtreeOptions& options() const { return options_; }
  /// All cells, the root first.
  std::span<const QuadtreeCell> cells() const { return cells_; }
  std::size_t leaf_count() const { return leaves_; }
  /// Levels below the root of the deepest leaf.
  std::size_t depth() const { return depth_; }

 private:
  struct Face;
  struct Poly;
  void build(std::uint32_t cell, std::size_t level);
  void fit(QuadtreeCell& cell) const;
  bool descend(const QuadtreeCell& cell, const Poly& part, const Face& face,
               QuadtreeQueryStats& stats) const;
  bool test_patches(std::uint32_t i0, std::uint32_t j0, std::uint32_t i1, std::uint32_t j1,
                    const Face& face, QuadtreeQueryStats& stats) const;

  RuledTerrain terrain_;
  TerrainQuadtreeOptions options_;
  std::vector<QuadtreeCell> cells_;
  std::size_t leaves_ = 0;
  std::size_t depth_ = 0;
  double margin_ = 0.0;  // slab decisions need this much clearance [m] (rounding guard)
};

}  // namespace talus
