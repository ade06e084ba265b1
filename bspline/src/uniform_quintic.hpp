#pragma once
// Uniform quintic B-spline pieces on one interval, local parameter t in [0, 1]:
// the six basis functions that are non-zero there, or their t-derivatives of
// order 1 to 3 (the degree-5 B-patch, BPatch::interpolate with degree 5).
#include <array>

namespace talus::detail {

/// The d-th t-derivative (0 <= d <= 3) of the six uniform quintic B-splines
/// non-zero on [0, 1), at t; entry a weights control i + a of cell i.
inline std::array<double, 6> quintic_basis(double t, int d) {
  // Cox–de Boor on the integer knots, up to degree 5 − d ...
  const int p = 5 - d;
  std::array<double, 7> n{};
  n[0] = 1.0;
  double left[6], right[6];
  for (int j = 1; j <= p; ++j) {
    left[j] = t + j - 1.0;
    right[j] = j - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = n[r] / (right[r + 1] + left[j - r]);
      n[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    n[j] = saved;
  }
  // ... then each derivative of a uniform B-spline is the difference of two
  // of one degree lower: N'_a = M_{a−1} − M_a.
  for (int q = p; q < 5; ++q) {
    std::array<double, 7> m{};
    for (int a = 0; a <= q + 1; ++a) m[a] = (a > 0 ? n[a - 1] : 0.0) - (a <= q ? n[a] : 0.0);
    n = m;
  }
  return {n[0], n[1], n[2], n[3], n[4], n[5]};
}

}  // namespace talus::detail
