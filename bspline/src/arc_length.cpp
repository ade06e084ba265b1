#include "talus/bspline/arc_length.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {
namespace {

// 8-point Gauss–Legendre nodes and weights on [-1, 1].
constexpr std::array<double, 4> kNodes = {0.1834346424956498, 0.5255324099163290,
                                          0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> kWeights = {0.3626837833783620, 0.3137066458778873,
                                            0.2223810344533745, 0.1012285362903763};

double integrate(const ArcLengthTable::SpeedFunction& speed, double a, double b) {
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double sum = 0.0;
  for (std::size_t i = 0; i < kNodes.size(); ++i) {
    sum += kWeights[i] * (speed(mid - half * kNodes[i]) + speed(mid + half * kNodes[i]));
  }
  return sum * half;
}

}  // namespace

ArcLengthTable::ArcLengthTable(const std::vector<double>& breakpoints, int subdivisions,
                               const SpeedFunction& speed) {
  if (breakpoints.size() < 2) throw InputError("arc-length table needs >= 2 breakpoints");
  if (subdivisions < 1) throw InputError("arc-length table needs >= 1 subdivision per interval");
  parameters_.push_back(breakpoints.front());
  for (std::size_t k = 1; k < breakpoints.size(); ++k) {
    const double a = breakpoints[k - 1], b = breakpoints[k];
    if (!(b > a)) throw InputError("arc-length table: breakpoints must be strictly increasing");
    for (int m = 1; m <= subdivisions; ++m) parameters_.push_back(a + (b - a) * m / subdivisions);
    parameters_.back() = b;
  }
  cumulative_.assign(parameters_.size(), 0.0);
  for (std::size_t k = 1; k < parameters_.size(); ++k) {
    cumulative_[k] = cumulative_[k - 1] + integrate(speed, parameters_[k - 1], parameters_[k]);
  }
}

double ArcLengthTable::arc_length(double t, const SpeedFunction& speed) const {
  if (!(t >= parameter_begin() && t <= parameter_end())) {
    std::ostringstream msg;
    msg << "arc length requested at parameter " << t << " outside [" << parameter_begin() << ", "
        << parameter_end() << "]";
    throw InputError(msg.str());
  }
  const auto it = std::upper_bound(parameters_.begin(), parameters_.end(), t);
  const std::size_t k = std::min<std::size_t>(
      static_cast<std::size_t>(std::max<long>(it - parameters_.begin() - 1, 0)),
      parameters_.size() - 2);
  return cumulative_[k] + integrate(speed, parameters_[k], t);
}

double ArcLengthTable::parameter(double s, const SpeedFunction& speed) const {
  const double total = length();
  if (!(s >= 0.0 && s <= total)) {
    std::ostringstream msg;
    msg << "arc length " << s << " is outside the curve's [0, " << total << "]";
    throw InputError(msg.str());
  }
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  const std::size_t k = std::min<std::size_t>(
      static_cast<std::size_t>(std::max<long>(it - cumulative_.begin() - 1, 0)),
      cumulative_.size() - 2);
  double lo = parameters_[k], hi = parameters_[k + 1];
  const double s_lo = cumulative_[k], s_hi = cumulative_[k + 1];
  if (s_hi <= s_lo) return lo;  // zero-length piece
  double t = lo + (hi - lo) * (s - s_lo) / (s_hi - s_lo);
  // Newton on s(t) - s, kept inside the bracket [lo, hi] by bisection.
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double f = cumulative_[k] + integrate(speed, parameters_[k], t) - s;
    if (std::abs(f) <= 1e-12 * std::max(1.0, total)) break;
    if (f > 0)
      hi = t;
    else
      lo = t;
    const double v = speed(t);
    double next = v > 0 ? t - f / v : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    t = next;
  }
  return t;
}

}  // namespace talus
