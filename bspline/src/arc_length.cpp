#include "talus/bspline/arc_length.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr int kN = ArcLengthTable::kOrder;
constexpr std::size_t kStride = 2 * kN + 1;  // antiderivative (kN + 1) then speed (kN)
constexpr int kMaxDepth = 24;                // halvings of one initial piece

/// Chebyshev points of the first kind ξ_k = cos(π (k + 1/2) / n) and the
/// matrix cos(m π (k + 1/2) / n) of the discrete cosine transform.
struct ChebyshevTables {
  std::array<double, kN> nodes{};
  std::array<std::array<double, kN>, kN> cosines{};
  ChebyshevTables() {
    for (int k = 0; k < kN; ++k) {
      nodes[k] = std::cos(std::numbers::pi * (k + 0.5) / kN);
      for (int m = 0; m < kN; ++m) cosines[m][k] = std::cos(std::numbers::pi * m * (k + 0.5) / kN);
    }
  }
};

const ChebyshevTables& tables() {
  static const ChebyshevTables t;
  return t;
}

/// Σ_{m=0}^{count-1} c_m T_m(ξ) by Clenshaw's recurrence.
double clenshaw(const double* c, int count, double xi) {
  double b1 = 0.0, b2 = 0.0;
  const double two_xi = 2.0 * xi;
  for (int m = count - 1; m >= 1; --m) {
    const double b0 = c[m] + two_xi * b1 - b2;
    b2 = b1;
    b1 = b0;
  }
  return c[0] + xi * b1 - b2;
}

[[noreturn]] void outside(const char* what, double value, double lo, double hi) {
  std::ostringstream msg;
  msg << what << " " << value << " is outside the curve's [" << lo << ", " << hi << "]";
  throw InputError(msg.str());
}

}  // namespace

ArcLengthTable::ArcLengthTable(const std::vector<double>& breakpoints, int subdivisions,
                               const SpeedFunction& speed) {
  if (breakpoints.size() < 2) throw InputError("arc-length table needs >= 2 breakpoints");
  if (subdivisions < 1) throw InputError("arc-length table needs >= 1 subdivision per interval");
  for (std::size_t k = 1; k < breakpoints.size(); ++k) {
    if (!(breakpoints[k] > breakpoints[k - 1]))
      throw InputError("arc-length table: breakpoints must be strictly increasing");
  }
  parameters_.push_back(breakpoints.front());
  cumulative_.push_back(0.0);
  for (std::size_t k = 1; k < breakpoints.size(); ++k) {
    const double a = breakpoints[k - 1], b = breakpoints[k];
    double left = a;
    for (int m = 1; m <= subdivisions; ++m) {
      const double right = (m == subdivisions) ? b : a + (b - a) * m / subdivisions;
      add_piece(left, right, speed, 0, std::numeric_limits<double>::infinity());
      left = right;
    }
  }
}

void ArcLengthTable::add_piece(double a, double b, const SpeedFunction& speed, int depth,
                               double parent_tail) {
  const ChebyshevTables& t = tables();
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  std::array<double, kN> values{};
  for (int k = 0; k < kN; ++k) values[k] = speed(mid + half * t.nodes[k]);
  std::array<double, kN + 2> c{};  // speed coefficients, two zeros past the end
  for (int m = 0; m < kN; ++m) {
    double sum = 0.0;
    for (int k = 0; k < kN; ++k) sum += values[k] * t.cosines[m][k];
    c[m] = sum * 2.0 / kN;
  }
  c[0] *= 0.5;
  const double tail = std::max(std::abs(c[kN - 1]), std::abs(c[kN - 2]));
  // Halve while the series has not converged, as long as halving still helps
  // (a kink the breakpoints missed converges slowly; rounding noise not at all).
  if (tail > kTolerance * std::abs(c[0]) && depth < kMaxDepth && tail < 0.5 * parent_tail &&
      mid > a && mid < b) {
    add_piece(a, mid, speed, depth + 1, tail);
    add_piece(mid, b, speed, depth + 1, tail);
    return;
  }
  // Antiderivative in ξ, scaled to the parameter: F(ξ) = ∫_{-1}^{ξ} speed · half dξ'.
  std::array<double, kN + 1> big{};
  big[1] = (c[0] - 0.5 * c[2]) * half;
  for (int m = 2; m <= kN; ++m) big[m] = (c[m - 1] - c[m + 1]) / (2.0 * m) * half;
  double at_minus_one = 0.0;
  for (int m = 1; m <= kN; ++m) at_minus_one += (m % 2 == 0) ? big[m] : -big[m];
  big[0] = -at_minus_one;
  double total = 0.0;
  for (int m = 0; m <= kN; ++m) total += big[m];
  // Terms that cannot move s by a rounding unit of the piece's length are dropped.
  int count = kN + 1;
  for (double dropped = 0.0; count > 2; --count) {
    dropped += std::abs(big[count - 1]);
    if (dropped > 1e-16 * std::abs(total)) break;
  }
  counts_.push_back(static_cast<unsigned char>(count));
  coefficients_.insert(coefficients_.end(), big.begin(), big.end());
  coefficients_.insert(coefficients_.end(), c.begin(), c.begin() + kN);
  parameters_.push_back(b);
  cumulative_.push_back(cumulative_.back() + total);
}

std::size_t ArcLengthTable::locate_parameter(double t, std::size_t piece) const {
  const std::size_t last = pieces() - 1;
  if (piece > last) piece = last;
  // A few steps forward or back cover stations walking along the curve.
  for (int step = 0; step < 4; ++step) {
    if (t < parameters_[piece]) {
      if (piece == 0) return 0;
      --piece;
    } else if (t > parameters_[piece + 1] && piece < last) {
      ++piece;
    } else {
      return piece;
    }
  }
  const auto it = std::upper_bound(parameters_.begin(), parameters_.end(), t);
  return std::min<std::size_t>(
      static_cast<std::size_t>(std::max<long>(it - parameters_.begin() - 1, 0)), last);
}

double ArcLengthTable::integral_in_piece(std::size_t k, double t) const {
  const double a = parameters_[k], b = parameters_[k + 1];
  const double xi = std::clamp((2.0 * t - a - b) / (b - a), -1.0, 1.0);
  return cumulative_[k] + clenshaw(&coefficients_[k * kStride], counts_[k], xi);
}

double ArcLengthTable::speed_in_piece(std::size_t k, double t) const {
  const double a = parameters_[k], b = parameters_[k + 1];
  const double xi = std::clamp((2.0 * t - a - b) / (b - a), -1.0, 1.0);
  return clenshaw(&coefficients_[k * kStride + kN + 1], kN, xi);
}

double ArcLengthTable::arc_length(double t, std::size_t& piece) const {
  if (!(t >= parameter_begin() && t <= parameter_end()))
    outside("arc length requested at parameter", t, parameter_begin(), parameter_end());
  piece = locate_parameter(t, piece);
  if (t == parameters_[piece + 1]) return cumulative_[piece + 1];
  return integral_in_piece(piece, t);
}

double ArcLengthTable::arc_length(double t) const {
  std::size_t piece = 0;
  return arc_length(t, piece);
}

double ArcLengthTable::speed(double t) const {
  if (!(t >= parameter_begin() && t <= parameter_end()))
    outside("speed requested at parameter", t, parameter_begin(), parameter_end());
  return speed_in_piece(locate_parameter(t, 0), t);
}

double ArcLengthTable::parameter(double s, std::size_t& piece) const {
  const double total = length();
  if (!(s >= 0.0 && s <= total)) outside("arc length", s, 0.0, total);
  const std::size_t last = pieces() - 1;
  std::size_t k = std::min(piece, last);
  if (!(s >= cumulative_[k] && s <= cumulative_[k + 1])) {
    if (k < last && s >= cumulative_[k + 1] && s <= cumulative_[k + 2]) {
      ++k;
    } else {
      const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
      k = std::min<std::size_t>(
          static_cast<std::size_t>(std::max<long>(it - cumulative_.begin() - 1, 0)), last);
    }
  }
  piece = k;
  double lo = parameters_[k], hi = parameters_[k + 1];
  const double s_lo = cumulative_[k], s_hi = cumulative_[k + 1];
  if (s <= s_lo) return lo;
  if (s >= s_hi) return hi;
  double t = lo + (hi - lo) * (s - s_lo) / (s_hi - s_lo);
  // Newton on s(t) - s, kept inside the bracket [lo, hi] by bisection.
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double f = integral_in_piece(k, t) - s;
    if (std::abs(f) <= 1e-14 * std::max(1.0, total)) break;
    (f > 0 ? hi : lo) = t;
    const double v = speed_in_piece(k, t);
    double next = v > 0 ? t - f / v : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == t) break;
    t = next;
  }
  return t;
}

double ArcLengthTable::parameter(double s) const {
  std::size_t piece = 0;
  return parameter(s, piece);
}

}  // namespace talus
