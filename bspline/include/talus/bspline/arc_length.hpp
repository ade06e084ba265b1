#pragma once
/// @file
/// Arc-length table of a parametric curve and the inverse map s -> parameter.
#include <cstddef>
#include <functional>
#include <vector>

namespace talus {

/// Cumulative arc length s(t) = integral of |C'(t)| from t_begin as a
/// piecewise Chebyshev series: on every piece the speed |C'| is interpolated
/// at kOrder Chebyshev points and the interpolant integrated exactly, so s(t)
/// anywhere costs one Clenshaw sum (about kOrder multiply-adds) and no
/// evaluation of the curve. Pieces are refined adaptively (halved while the
/// last two Chebyshev coefficients exceed kTolerance times the mean speed,
/// and while halving still shrinks them), so on pieces where the speed is
/// analytic (the caller puts breakpoints wherever it is not smooth) s(t)
/// agrees with exact integration to about 1e-14 relative. The inverse map
/// is safeguarded Newton on the same series. The table holds numbers only:
/// an owner that copies or moves it never leaves it pointing at a dead curve.
class ArcLengthTable {
 public:
  using SpeedFunction = std::function<double(double)>;
  /// Chebyshev points (and series length) per piece.
  static constexpr int kOrder = 16;
  /// Refinement target: tail coefficients below this times the piece's mean speed.
  static constexpr double kTolerance = 1e-14;

  /// `breakpoints`: strictly increasing parameters where the speed may be
  /// non-smooth (the knots, cell edges); each interval is split into
  /// `subdivisions` equal pieces before adaptive refinement. `speed` is
  /// called only here (about kOrder times per piece); exceptions it throws
  /// propagate.
  ArcLengthTable(const std::vector<double>& breakpoints, int subdivisions,
                 const SpeedFunction& speed);

  double length() const { return cumulative_.back(); }
  double parameter_begin() const { return parameters_.front(); }
  double parameter_end() const { return parameters_.back(); }
  /// Number of tabulated pieces (after refinement).
  std::size_t pieces() const { return parameters_.size() - 1; }
  /// s(t) for t in the parameter range (InputError otherwise).
  double arc_length(double t) const;
  /// s(t) as above, starting the piece search at `piece` and leaving there
  /// the piece holding t: O(1) per call when t increases in small steps
  /// (stations along a path). Any start value is valid.
  double arc_length(double t, std::size_t& piece) const;
  /// The interpolated speed ds/dt at t (same range and errors as arc_length).
  double speed(double t) const;
  /// t(s) for s in [0, length()] (InputError otherwise); |s(t(s)) - s| <= 1e-13 length.
  double parameter(double s) const;
  /// t(s) as above with a piece hint, as in arc_length(t, piece).
  double parameter(double s, std::size_t& piece) const;

  /// The forms before the table became self-contained; `speed` is ignored.
  double arc_length(double t, const SpeedFunction& /*speed*/) const { return arc_length(t); }
  double parameter(double s, const SpeedFunction& /*speed*/) const { return parameter(s); }

 private:
  void add_piece(double a, double b, const SpeedFunction& speed, int depth, double parent_tail);
  std::size_t locate_parameter(double t, std::size_t piece) const;
  double integral_in_piece(std::size_t k, double t) const;
  double speed_in_piece(std::size_t k, double t) const;

  std::vector<double> parameters_;  ///< piece ends, pieces() + 1
  std::vector<double> cumulative_;  ///< s at the piece ends, pieces() + 1
  /// Per piece, kOrder + 1 Chebyshev coefficients of s − s(a) on [a, b] in ξ ∈ [−1, 1]
  /// (value 0 at ξ = −1), then kOrder coefficients of the speed.
  std::vector<double> coefficients_;
  /// Per piece, how many of the kOrder + 1 antiderivative coefficients matter.
  std::vector<unsigned char> counts_;
};

}  // namespace talus
