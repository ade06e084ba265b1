// Test paths: closed curves with known geometry.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include "talus/bspline/bspline_curve.hpp"
#include "talus/core/types.hpp"

namespace talus::path_test {

/// A closed counter-clockwise ellipse with semi-axes `a` along x and `b` along y [m] around
/// `centre`, interpolated through `points` + 1 equally spaced angles (the first repeated last).
/// Its curvature is second-order accurate in the point spacing.
inline Curve2 ellipse(const Vec2& centre, double a, double b, int points) {
  std::vector<Vec2> pts;
  pts.reserve(static_cast<std::size_t>(points) + 1);
  for (int k = 0; k <= points; ++k) {
    const double th = 2 * std::numbers::pi * k / points;
    pts.push_back(centre + Vec2(a * std::cos(th), b * std::sin(th)));
  }
  return Curve2::interpolate(pts);
}

/// A circle of radius `r` [m] around the origin: ellipse(0, r, r, points).
inline Curve2 circle(double r, int points) {
  return ellipse(Vec2::Zero(), r, r, points);
}

}  // namespace talus::path_test
