#include "talus/bspline/knot_vector.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {

KnotVector::KnotVector(int degree, std::vector<double> knots)
    : degree_(degree), knots_(std::move(knots)) {
  if (degree < 1 || degree > kMaxDegree) {
    throw InputError("B-spline degree must be in [1, " + std::to_string(kMaxDegree) + "], got " +
                     std::to_string(degree));
  }
  const std::size_t p = static_cast<std::size_t>(degree);
  if (knots_.size() < 2 * (p + 1)) {
    throw InputError("a degree-" + std::to_string(degree) + " knot vector needs at least " +
                     std::to_string(2 * (p + 1)) + " knots, got " + std::to_string(knots_.size()));
  }
  for (std::size_t k = 0; k < knots_.size(); ++k) {
    if (!std::isfinite(knots_[k])) throw InputError("knot " + std::to_string(k) + " is not finite");
    if (k > 0 && knots_[k] < knots_[k - 1]) {
      std::ostringstream msg;
      msg << "knots must be non-decreasing, but knot " << k << " = " << knots_[k] << " < knot "
          << k - 1 << " = " << knots_[k - 1];
      throw InputError(msg.str());
    }
  }
  if (!(domain_end() > domain_begin())) throw InputError("knot vector has an empty domain");
}

KnotVector KnotVector::clamped(int degree, const std::vector<double>& breakpoints) {
  if (breakpoints.size() < 2) throw InputError("a clamped knot vector needs >= 2 breakpoints");
  for (std::size_t k = 1; k < breakpoints.size(); ++k) {
    if (!(breakpoints[k] > breakpoints[k - 1])) {
      throw InputError("clamped knot vector: breakpoints must be strictly increasing (index " +
                       std::to_string(k) + ")");
    }
  }
  std::vector<double> knots;
  const int ends = std::max(degree, 0) + 1;
  knots.insert(knots.end(), static_cast<std::size_t>(ends), breakpoints.front());
  knots.insert(knots.end(), breakpoints.begin() + 1, breakpoints.end() - 1);
  knots.insert(knots.end(), static_cast<std::size_t>(ends), breakpoints.back());
  return KnotVector(degree, std::move(knots));
}

KnotVector KnotVector::uniform(int degree, double t0, double spacing, std::size_t num_basis) {
  if (!(spacing > 0.0)) throw InputError("uniform knot spacing must be positive");
  std::vector<double> knots(num_basis + static_cast<std::size_t>(std::max(degree, 0)) + 1);
  for (std::size_t k = 0; k < knots.size(); ++k) knots[k] = t0 + static_cast<double>(k) * spacing;
  return KnotVector(degree, std::move(knots));
}

std::size_t KnotVector::find_span(double t) const {
  const double lo = domain_begin(), hi = domain_end();
  if (!(t >= lo && t <= hi)) {
    std::ostringstream msg;
    msg << "B-spline parameter " << t << " is outside the domain [" << lo << ", " << hi << "]";
    throw InputError(msg.str());
  }
  const std::size_t p = static_cast<std::size_t>(degree_);
  const std::size_t n = num_basis();
  if (t >= knots_[n]) {
    std::size_t k = n - 1;
    while (knots_[k] == knots_[k + 1]) --k;  // skip empty spans at a clamped end
    return k;
  }
  // Last knot <= t among knots[p .. n]: its span is [knots[k], knots[k+1]).
  const auto it = std::upper_bound(knots_.begin() + static_cast<long>(p),
                                   knots_.begin() + static_cast<long>(n) + 1, t);
  return static_cast<std::size_t>(it - knots_.begin()) - 1;
}

void KnotVector::basis_derivatives(std::size_t span, double t,
                                   Eigen::Ref<Eigen::MatrixXd> out) const {
  // Cox–de Boor triangle in the stable form that keeps the knot differences
  // (ndu's lower triangle) so that derivatives come from the same table.
  const int p = degree_;
  constexpr int kN = kMaxDegree + 1;
  // Left uninitialised on purpose: every entry is written before it is read,
  // and zeroing 80 doubles per call was a third of the cost of a path frame.
  std::array<std::array<double, kN>, kN> ndu;
  std::array<double, kN> left, right;
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots_[span + 1 - static_cast<std::size_t>(j)];
    right[j] = knots_[span + static_cast<std::size_t>(j)] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];  // knot difference
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  const int orders = static_cast<int>(out.rows());
  if (orders > p + 1) out.bottomRows(orders - p - 1).setZero();
  for (int j = 0; j <= p; ++j) out(0, j) = ndu[j][p];
  // Derivatives by the recurrence on the coefficients a_{k,j}.
  std::array<std::array<double, kN>, 2> a;
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k < orders && k <= p; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      out(k, r) = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k < orders && k <= p; ++k) {
    for (int j = 0; j <= p; ++j) out(k, j) *= factor;
    factor *= (p - k);
  }
}

}  // namespace talus
