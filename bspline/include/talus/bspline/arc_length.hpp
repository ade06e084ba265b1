#pragma once
/// @file
/// Arc-length table of a parametric curve and the inverse map s -> parameter.
#include <functional>
#include <vector>

namespace talus {

/// Cumulative arc length s(t) = integral of |C'(t)| from t_begin, tabulated at
/// subdivisions of the given breakpoints with 8-point Gauss–Legendre
/// quadrature (exact for polynomial speed up to degree 15), and inverted by
/// safeguarded Newton iteration. The table holds numbers only: the speed
/// function is passed to every query, so an owner that copies or moves the
/// table never leaves it pointing at a dead curve.
class ArcLengthTable {
 public:
  using SpeedFunction = std::function<double(double)>;

  /// `breakpoints`: strictly increasing parameters where the speed may be
  /// non-smooth (the knots); each interval is split into `subdivisions` pieces.
  ArcLengthTable(const std::vector<double>& breakpoints, int subdivisions,
                 const SpeedFunction& speed);

  double length() const { return cumulative_.back(); }
  double parameter_begin() const { return parameters_.front(); }
  double parameter_end() const { return parameters_.back(); }
  /// Number of tabulated pieces.
  std::size_t pieces() const { return parameters_.size() - 1; }
  /// s(t) for t in the parameter range (InputError otherwise); `speed` is
  /// the same function the table was built with.
  double arc_length(double t, const SpeedFunction& speed) const;
  /// t(s) for s in [0, length()] (InputError otherwise); |s(t(s)) - s| <= 1e-10 length.
  double parameter(double s, const SpeedFunction& speed) const;

 private:
  std::vector<double> parameters_;
  std::vector<double> cumulative_;
};

}  // namespace talus
