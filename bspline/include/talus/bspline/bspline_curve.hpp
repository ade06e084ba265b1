#pragma once
/// @file
/// B-spline curves in 2-D and 3-D with derivatives up to third order, and
/// interpolation through points.
#include <vector>

#include <Eigen/Core>

#include "talus/bspline/knot_vector.hpp"

namespace talus {

/// A B-spline curve C(t) = sum_i N_i(t) P_i in Dim dimensions.
template <int Dim>
class BSplineCurve {
 public:
  using Point = Eigen::Matrix<double, Dim, 1>;
  /// Columns 0..3: C, C', C'', C''' at one parameter.
  using Derivatives = Eigen::Matrix<double, Dim, 4>;

  /// Throws InputError unless there are exactly knots.num_basis() finite control points.
  BSplineCurve(KnotVector knots, std::vector<Point> control_points);

  /// Curve of the given degree through `points` (at least 2, no two consecutive
  /// ones equal), with chord-length parameters normalised to [0, 1] and knots
  /// by averaging those parameters (the degree drops to points - 1 when there
  /// are too few points). The curve passes through every point exactly.
  static BSplineCurve interpolate(const std::vector<Point>& points, int degree = 3);

  const KnotVector& knots() const { return knots_; }
  const std::vector<Point>& control_points() const { return control_points_; }
  int degree() const { return knots_.degree(); }
  double parameter_begin() const { return knots_.domain_begin(); }
  double parameter_end() const { return knots_.domain_end(); }

  Point evaluate(double t) const;
  /// C and its derivatives up to `order` (<= 3) at t into columns 0..order of
  /// `out`; higher columns are zeroed. No allocation.
  void derivatives(double t, int order, Derivatives& out) const;

 private:
  /// Taylor coefficients C^(k)(t_span) / k! of every non-empty knot span, so
  /// that evaluation is a Horner scheme instead of a Cox–de Boor recursion
  /// (about 8x faster; curves are evaluated at every station of every path).
  using Taylor = Eigen::Matrix<double, Dim, kMaxDegree + 1>;
  void build_taylor_coefficients();

  KnotVector knots_;
  std::vector<Point> control_points_;
  std::vector<Taylor> taylor_;  ///< indexed by span - degree
};

using Curve2 = BSplineCurve<2>;
using Curve3 = BSplineCurve<3>;

extern template class BSplineCurve<2>;
extern template class BSplineCurve<3>;

}  // namespace talus
