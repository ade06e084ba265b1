#pragma once
// Uniform cubic B-spline pieces on one interval, local parameter t in [0, 1]:
// the four basis functions that are non-zero there and their t-derivatives
// (the third derivative is constant on the interval: {-1, 3, -3, 1}).
#include <array>

namespace talus::detail {

struct CubicBasis {
  std::array<double, 4> value, first, second;
};

inline constexpr std::array<double, 4> kCubicThird{-1.0, 3.0, -3.0, 1.0};

inline CubicBasis cubic_basis(double t) {
  const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
  CubicBasis b;
  b.value = {s * s * s / 6.0, (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0,
             (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0, t3 / 6.0};
  b.first = {-0.5 * s * s, 1.5 * t2 - 2.0 * t, -1.5 * t2 + t + 0.5, 0.5 * t2};
  b.second = {s, 3.0 * t - 2.0, 1.0 - 3.0 * t, t};
  return b;
}

}  // namespace talus::detail
