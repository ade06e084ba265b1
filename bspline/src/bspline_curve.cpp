#include "talus/bspline/bspline_curve.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <cmath>
#include <string>

#include "chord_length.hpp"
#include "talus/core/error.hpp"

namespace talus {

template <int Dim>
BSplineCurve<Dim>::BSplineCurve(KnotVector knots, std::vector<Point> control_points)
    : knots_(std::move(knots)), control_points_(std::move(control_points)) {
  if (control_points_.size() != knots_.num_basis()) {
    throw InputError("B-spline curve: knot vector needs " + std::to_string(knots_.num_basis()) +
                     " control points, got " + std::to_string(control_points_.size()));
  }
  for (std::size_t i = 0; i < control_points_.size(); ++i) {
    if (!control_points_[i].allFinite()) {
      throw InputError("B-spline curve: control point " + std::to_string(i) + " is not finite");
    }
  }
  build_taylor_coefficients();
}

template <int Dim>
void BSplineCurve<Dim>::build_taylor_coefficients() {
  const int p = knots_.degree();
  const std::vector<double>& t = knots_.knots();
  const std::size_t first_span = static_cast<std::size_t>(p);
  const std::size_t last_span = knots_.num_basis() - 1;
  taylor_.assign(last_span - first_span + 1, Taylor::Zero());
  Eigen::MatrixXd basis(p + 1, p + 1);
  for (std::size_t span = first_span; span <= last_span; ++span) {
    if (t[span] == t[span + 1]) continue;  // empty span: never located
    knots_.basis_derivatives(span, t[span], basis);
    Taylor& c = taylor_[span - first_span];
    double factorial = 1.0;
    for (int k = 0; k <= p; ++k) {
      if (k > 0) factorial *= k;
      for (int j = 0; j <= p; ++j) {
        c.col(k) += basis(k, j) / factorial *
                    control_points_[span - first_span + static_cast<std::size_t>(j)];
      }
    }
  }
}

template <int Dim>
typename BSplineCurve<Dim>::Point BSplineCurve<Dim>::evaluate(double t) const {
  Derivatives d;
  derivatives(t, 0, d);
  return d.col(0);
}

template <int Dim>
void BSplineCurve<Dim>::derivatives(double t, int order, Derivatives& out) const {
  if (order < 0 || order > 3) throw InputError("curve derivative order must be in [0, 3]");
  const std::size_t span = knots_.find_span(t);
  const int p = knots_.degree();
  const Taylor& c = taylor_[span - static_cast<std::size_t>(p)];
  const double dt = t - knots_.knots()[span];
  out.setZero();
  // Horner for C and its derivatives: C^(k)(t) = sum_{m>=k} m!/(m-k)! c_m dt^(m-k).
  for (int k = 0; k <= std::min(order, p); ++k) {
    Point value = Point::Zero();
    for (int m = p; m >= k; --m) {
      double falling = 1.0;  // m! / (m - k)!
      for (int i = 0; i < k; ++i) falling *= (m - i);
      value = value * dt + falling * c.col(m);
    }
    out.col(k) = value;
  }
}

template <int Dim>
BSplineCurve<Dim> BSplineCurve<Dim>::interpolate(const std::vector<Point>& points, int degree) {
  const std::size_t n = points.size();
  if (n < 2)
    throw InputError("curve interpolation needs at least 2 points, got " + std::to_string(n));
  const std::vector<double> params = detail::chord_length_parameters(points, "curve interpolation");
  const int p = std::min<int>(degree, static_cast<int>(n) - 1);
  // Knots by averaging p consecutive parameters keep the collocation matrix
  // totally positive and well conditioned (Schoenberg–Whitney holds).
  std::vector<double> knots(static_cast<std::size_t>(p) + 1, 0.0);
  for (std::size_t j = 1; j + static_cast<std::size_t>(p) < n; ++j) {
    double sum = 0.0;
    for (std::size_t i = j; i < j + static_cast<std::size_t>(p); ++i) sum += params[i];
    knots.push_back(sum / p);
  }
  knots.insert(knots.end(), static_cast<std::size_t>(p) + 1, 1.0);
  KnotVector kv(p, std::move(knots));

  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd basis(1, p + 1);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t span = kv.find_span(params[k]);
    kv.basis_derivatives(span, params[k], basis);
    for (int j = 0; j <= p; ++j) {
      if (basis(0, j) != 0.0) {
        entries.emplace_back(static_cast<int>(k), static_cast<int>(span) - p + j, basis(0, j));
      }
    }
  }
  Eigen::SparseMatrix<double> a(static_cast<long>(n), static_cast<long>(n));
  a.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(a);
  if (lu.info() != Eigen::Success)
    throw SolverError("curve interpolation: singular collocation matrix");
  Eigen::MatrixXd rhs(static_cast<long>(n), Dim);
  for (std::size_t k = 0; k < n; ++k) rhs.row(static_cast<long>(k)) = points[k].transpose();
  const Eigen::MatrixXd solution = lu.solve(rhs);
  std::vector<Point> control(n);
  for (std::size_t k = 0; k < n; ++k) control[k] = solution.row(static_cast<long>(k)).transpose();
  return BSplineCurve(std::move(kv), std::move(control));
}

template class BSplineCurve<2>;
template class BSplineCurve<3>;

}  // namespace talus
