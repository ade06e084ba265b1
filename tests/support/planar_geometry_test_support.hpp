#pragma once
/// Planar geometry for independent checks in tests: orientation and the
/// convex hull, written without the library so that a test does not check
/// the library against itself.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "talus/core/types.hpp"

namespace talus::geometry_test {

/// Twice the signed area of the triangle (a, b, c): > 0 when c is left of a→b.
inline double cross(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// Convex hull (Andrew's monotone chain), counter-clockwise, without
/// collinear points; fewer than 3 points for a degenerate input.
inline std::vector<Vec2> convex_hull(std::vector<Vec2> pts) {
  if (pts.empty()) return pts;
  std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Vec2> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
    h[k++] = pts[i - 1];
  }
  h.resize(k > 0 ? k - 1 : 0);
  return h;
}

}  // namespace talus::geometry_test
