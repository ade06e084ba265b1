#include "talus/kinematic/hait/terrain_quadtree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "talus/core/error.hpp"

namespace talus {

void TerrainQuadtreeOptions::validate() const {
  if (!(h0 >= 0.0) || !std::isfinite(h0)) {
    throw InputError("TerrainQuadtreeOptions.h0 must be finite and >= 0, got " +
                     std::to_string(h0));
  }
}

// The face prepared for queries: its footprint and its plane as z = f(x, y).
struct TerrainQuadtree::Face {
  std::array<Vec2, 8> footprint;
  int n = 0;
  Vec2 centre = Vec2::Zero();
  double z_c = 0.0;
  Vec2 slope = Vec2::Zero();
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();  // footprint bounding box
  double height(const Vec2& p) const { return z_c + slope.dot(p - centre); }
};

// A convex polygon in the plane; clipping a face of <= 8 vertices by the four
// sides of a rectangle adds at most 4 vertices, so no allocation is needed.
struct TerrainQuadtree::Poly {
  std::array<Vec2, 16> v;
  int n = 0;
};

namespace {

using Poly16 = std::array<Vec2, 16>;

// One Sutherland–Hodgman pass keeping the side coord(axis) * sign >= bound * sign.
// Points created on the boundary get the boundary coordinate exactly, so later
// passes against the same line classify them consistently.
int clip_side(const Poly16& in, int n, Poly16& out, int axis, double bound, double sign) {
  int m = 0;
  for (int k = 0; k < n; ++k) {
    const Vec2& p = in[k];
    const Vec2& q = in[(k + 1) % n];
    const bool p_in = sign * (p[axis] - bound) >= 0.0;
    const bool q_in = sign * (q[axis] - bound) >= 0.0;
    if (p_in) out[m++] = p;
    if (p_in != q_in) {
      const double t = (bound - p[axis]) / (q[axis] - p[axis]);
      Vec2 x = p + t * (q - p);
      x[axis] = bound;
      out[m++] = x;
    }
  }
  return m;
}

// The polygon (in, n) clipped to [lo, hi]; returns the vertex count.
int clip_rect(const Poly16& in, int n, const Vec2& lo, const Vec2& hi, Poly16& out) {
  Poly16 tmp;
  n = clip_side(in, n, tmp, 0, lo.x(), 1.0);
  if (n == 0) return 0;
  n = clip_side(tmp, n, out, 0, hi.x(), -1.0);
  if (n == 0) return 0;
  n = clip_side(out, n, tmp, 1, lo.y(), 1.0);
  if (n == 0) return 0;
  return clip_side(tmp, n, out, 1, hi.y(), -1.0);
}

}  // namespace

TerrainQuadtree::TerrainQuadtree(RuledTerrain terrain, const TerrainQuadtreeOptions& options)
    : terrain_(std::move(terrain)), options_(options) {
  options_.validate();
  const ElevationGrid& g = terrain_.grid();
  if (g.ncols() > (std::size_t{1} << 30) || g.nrows() > (std::size_t{1} << 30)) {
    throw InputError("terrain too large for the quadtree's 32-bit cell indices");
  }
  double zabs = 0.0;
  if (const auto range = g.elevation_range()) {
    zabs = std::max(std::abs(range->first), std::abs(range->second));
  }
  margin_ = 1e-9 * (1.0 + zabs);
  // A full quadtree has < 4/3 as many cells as patches.
  cells_.reserve(terrain_.patch_cols() * terrain_.patch_rows() / 2 + 1);
  QuadtreeCell root;
  root.i1 = static_cast<std::uint32_t>(terrain_.patch_cols());
  root.j1 = static_cast<std::uint32_t>(terrain_.patch_rows());
  cells_.push_back(root);
  build(0, 0);
}

void TerrainQuadtree::fit(QuadtreeCell& cell) const {
  const ElevationGrid& g = terrain_.grid();
  const double h = g.cellsize();
  // Nodes of the cell: i0..i1 × j0..j1. On this full rectangular lattice the
  // offsets u = x − x_c, v = y − y_c sum to zero and Σuv = 0, so the normal
  // equations of z = z_c + g_x u + g_y v decouple.
  const double ic = 0.5 * (cell.i0 + cell.i1), jc = 0.5 * (cell.j0 + cell.j1);
  cell.centre = {g.x_min() + ic * h, g.y_min() + jc * h};
  double sz = 0.0, suz = 0.0, svz = 0.0, suu = 0.0, svv = 0.0;
  std::size_t count = 0;
  for (std::uint32_t j = cell.j0; j <= cell.j1; ++j) {
    const double v = (j - jc) * h;
    for (std::uint32_t i = cell.i0; i <= cell.i1; ++i) {
      if (!g.valid(i, j)) {
        cell.has_nodata = true;
        return;
      }
      const double u = (i - ic) * h, z = g.at(i, j);
      sz += z;
      suz += u * z;
      svz += v * z;
      suu += u * u;
      svv += v * v;
      ++count;
    }
  }
  cell.z_c = sz / static_cast<double>(count);
  cell.slope = {suz / suu, svz / svv};
  const double inv_norm = 1.0 / std::sqrt(1.0 + cell.slope.squaredNorm());
  double dmin = std::numeric_limits<double>::infinity(), dmax = -dmin;
  for (std::uint32_t j = cell.j0; j <= cell.j1; ++j) {
    const double v = (j - jc) * h;
    for (std::uint32_t i = cell.i0; i <= cell.i1; ++i) {
      const double u = (i - ic) * h;
      const double d = (g.at(i, j) - cell.z_c - cell.slope.x() * u - cell.slope.y() * v) * inv_norm;
      dmin = std::min(dmin, d);
      dmax = std::max(dmax, d);
    }
  }
  cell.d_min = dmin;
  cell.d_max = dmax;
}

void TerrainQuadtree::build(std::uint32_t index, std::size_t level) {
  fit(cells_[index]);
  const QuadtreeCell c = cells_[index];
  depth_ = std::max(depth_, level);
  const std::uint32_t w = c.i1 - c.i0, hgt = c.j1 - c.j0;
  const bool single_patch = (w == 1 && hgt == 1);
  if (single_patch || (!c.has_nodata && c.thickness() < options_.h0)) {
    ++leaves_;
    return;
  }
  // Split each side longer than one patch at its middle.
  const std::uint32_t im = c.i0 + w / 2, jm = c.j0 + hgt / 2;
  std::array<std::array<std::uint32_t, 4>, 4> parts{};
  int n = 0;
  const std::array<std::pair<std::uint32_t, std::uint32_t>, 2> xs{{{c.i0, im}, {im, c.i1}}};
  const std::array<std::pair<std::uint32_t, std::uint32_t>, 2> ys{{{c.j0, jm}, {jm, c.j1}}};
  for (int b = 0; b < (hgt > 1 ? 2 : 1); ++b) {
    for (int a = 0; a < (w > 1 ? 2 : 1); ++a) {
      const auto [xa, xb] = w > 1 ? xs[a] : std::pair{c.i0, c.i1};
      const auto [ya, yb] = hgt > 1 ? ys[b] : std::pair{c.j0, c.j1};
      parts[n++] = {xa, ya, xb, yb};
    }
  }
  const auto first = static_cast<std::uint32_t>(cells_.size());
  cells_[index].first_child = first;
  cells_[index].child_count = static_cast<std::uint8_t>(n);
  for (int k = 0; k < n; ++k) {
    QuadtreeCell child;
    child.i0 = parts[k][0];
    child.j0 = parts[k][1];
    child.i1 = parts[k][2];
    child.j1 = parts[k][3];
    cells_.push_back(child);
  }
  for (int k = 0; k < n; ++k) build(first + static_cast<std::uint32_t>(k), level + 1);
}

namespace {

// Validates a chassis face and returns it as footprint + plane.
template <class Face>
Face prepare_face(std::span<const Vec3> face) {
  const std::size_t n = face.size();
  if (n < 3 || n > 8) {
    throw InputError("a collision face needs 3 to 8 vertices, got " + std::to_string(n));
  }
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : face) {
    if (!v.allFinite()) throw InputError("a collision face has a non-finite vertex");
    c += v;
  }
  c /= static_cast<double>(n);
  // Newell's normal: exact for a planar polygon, twice its area in length.
  Vec3 normal = Vec3::Zero();
  double extent = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 p = face[k] - c, q = face[(k + 1) % n] - c;
    normal += p.cross(q);
    extent = std::max(extent, p.norm());
  }
  if (!(normal.z() > 1e-3 * normal.norm())) {
    throw InputError(
        "a collision face must be counter-clockwise seen from above and not vertical "
        "(its normal's z component is not positive)");
  }
  Face f;
  f.n = static_cast<int>(n);
  f.centre = c.head<2>();
  f.z_c = c.z();
  f.slope = {-normal.x() / normal.z(), -normal.y() / normal.z()};
  const double cos_tilt = normal.z() / normal.norm();
  const double planar_tol = 1e-6 * (1.0 + extent);
  f.lo = f.hi = face[0].head<2>();
  for (std::size_t k = 0; k < n; ++k) {
    f.footprint[k] = face[k].head<2>();
    f.lo = f.lo.cwiseMin(f.footprint[k]);
    f.hi = f.hi.cwiseMax(f.footprint[k]);
    if (std::abs(face[k].z() - f.height(f.footprint[k])) * cos_tilt > planar_tol) {
      std::ostringstream msg;
      msg << "collision face vertex " << k << " is "
          << std::abs(face[k].z() - f.height(f.footprint[k])) * cos_tilt
          << " m off the face's plane (not planar)";
      throw InputError(msg.str());
    }
  }
  const double convex_tol = 1e-12 * (1.0 + extent * extent);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 e0 = f.footprint[(k + 1) % n] - f.footprint[k];
    const Vec2 e1 = f.footprint[(k + 2) % n] - f.footprint[(k + 1) % n];
    if (e0.x() * e1.y() - e0.y() * e1.x() < -convex_tol) {
      throw InputError("collision face is not convex at vertex " + std::to_string((k + 1) % n));
    }
  }
  return f;
}

}  // namespace

bool TerrainQuadtree::test_patches(std::uint32_t i0, std::uint32_t j0, std::uint32_t i1,
                                   std::uint32_t j1, const Face& face,
                                   QuadtreeQueryStats& stats) const {
  const ElevationGrid& g = terrain_.grid();
  const double h = g.cellsize();
  // Restrict the range to the patches the footprint's bounding box touches.
  const auto index_range = [h](double lo, double hi, double origin, std::uint32_t a,
                               std::uint32_t b) {
    const double flo = std::floor((lo - origin) / h), fhi = std::floor((hi - origin) / h);
    const auto first = static_cast<std::uint32_t>(std::clamp(flo, double(a), double(b)));
    const auto last = static_cast<std::uint32_t>(std::clamp(fhi + 1.0, double(a), double(b)));
    return std::pair{first, last};
  };
  const auto [ia, ib] = index_range(face.lo.x(), face.hi.x(), g.x_min(), i0, i1);
  const auto [ja, jb] = index_range(face.lo.y(), face.hi.y(), g.y_min(), j0, j1);
  Poly16 in;
  std::copy_n(face.footprint.begin(), face.n, in.begin());
  Poly16 q;
  for (std::uint32_t j = ja; j < jb; ++j) {
    for (std::uint32_t i = ia; i < ib; ++i) {
      const Vec2 lo = g.node_position(i, j), hi = g.node_position(i + 1, j + 1);
      const int m = clip_rect(in, face.n, lo, hi, q);
      if (m == 0) continue;
      ++stats.patches_tested;
      if (!terrain_.patch_has_data(i, j)) {
        if (options_.nodata_collides) return true;
        continue;
      }
      const double z00 = g.at(i, j), z10 = g.at(i + 1, j);
      const double z01 = g.at(i, j + 1), z11 = g.at(i + 1, j + 1);
      const double r = z00 - z10 - z01 + z11;
      const auto height_above = [&](const Vec2& p) {
        const double a = (p.x() - lo.x()) / h, b = (p.y() - lo.y()) / h;
        const double z = z00 + (z10 - z00) * a + (z01 - z00) * b + r * a * b;
        return z - face.height(p);
      };
      // Maximum of height_above over the convex region: vertices, and the
      // stationary point of each edge where the edge's quadratic is concave.
      for (int k = 0; k < m; ++k) {
        const Vec2& p0 = q[k];
        const Vec2& p1 = q[(k + 1) % m];
        const double g0 = height_above(p0);
        if (g0 > 0.0) return true;
        const double kq = r * (p1.x() - p0.x()) * (p1.y() - p0.y()) / (h * h);
        if (kq < 0.0) {
          const double g1 = height_above(p1);
          // g(t) = g0 + (g1 - g0 - kq) t + kq t^2 on t in [0, 1].
          const double lin = g1 - g0 - kq;
          const double t = -lin / (2.0 * kq);
          if (t > 0.0 && t < 1.0 && g0 + lin * t + kq * t * t > 0.0) return true;
        }
      }
    }
  }
  return false;
}

bool TerrainQuadtree::descend(const QuadtreeCell& cell, const Poly& part, const Face& face,
                              QuadtreeQueryStats& stats) const {
  ++stats.cells_visited;
  const ElevationGrid& g = terrain_.grid();
  Poly q;
  q.n = clip_rect(part.v, part.n, g.node_position(cell.i0, cell.j0),
                  g.node_position(cell.i1, cell.j1), q.v);
  if (q.n == 0) return false;
  if (!cell.has_nodata) {
    // Face-to-mean-plane offset s = plane − face is affine: its maximum over
    // the convex part is at a vertex. Slab planes are plane + d·√(1+|g|²).
    double s_max = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < q.n; ++k) s_max = std::max(s_max, cell.plane(q.v[k]) - face.height(q.v[k]));
    const double norm = std::sqrt(1.0 + cell.slope.squaredNorm());
    if (s_max + cell.d_max * norm < -margin_) return false;
    if (s_max + cell.d_min * norm > margin_) return true;
  }
  if (cell.child_count == 0) return test_patches(cell.i0, cell.j0, cell.i1, cell.j1, face, stats);
  for (std::uint32_t k = 0; k < cell.child_count; ++k) {
    if (descend(cells_[cell.first_child + k], q, face, stats)) return true;
  }
  return false;
}

bool TerrainQuadtree::collides(std::span<const Vec3> face, QuadtreeQueryStats* stats) const {
  const Face f = prepare_face<Face>(face);
  QuadtreeQueryStats local;
  Poly p;
  p.n = f.n;
  std::copy_n(f.footprint.begin(), f.n, p.v.begin());
  const bool hit = descend(cells_[0], p, f, local);
  if (stats) *stats = local;
  return hit;
}

bool TerrainQuadtree::brute_force_collides(std::span<const Vec3> face,
                                           QuadtreeQueryStats* stats) const {
  const Face f = prepare_face<Face>(face);
  QuadtreeQueryStats local;
  const bool hit = test_patches(0, 0, static_cast<std::uint32_t>(terrain_.patch_cols()),
                                static_cast<std::uint32_t>(terrain_.patch_rows()), f, local);
  if (stats) *stats = local;
  return hit;
}

}  // namespace talus
