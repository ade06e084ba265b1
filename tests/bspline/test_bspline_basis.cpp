#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/knot_vector.hpp"
#include "talus/core/error.hpp"

namespace talus {
namespace {

KnotVector irregular_clamped(int degree) {
  return KnotVector::clamped(degree, {0.0, 0.13, 0.5, 0.51, 1.2, 2.0, 3.7});
}

TEST(KnotVector, PartitionOfUnityForClampedAndUniformKnots) {
  for (int p = 1; p <= 5; ++p) {
    for (const KnotVector& kv : {irregular_clamped(p), KnotVector::uniform(p, -1.0, 0.25, 12)}) {
      Eigen::MatrixXd basis(1, p + 1);
      for (int k = 0; k <= 200; ++k) {
        const double t = kv.domain_begin() + (kv.domain_end() - kv.domain_begin()) * k / 200.0;
        kv.basis_derivatives(kv.find_span(t), t, basis);
        EXPECT_NEAR(basis.sum(), 1.0, 1e-14) << "degree " << p << " t " << t;
        EXPECT_GE(basis.minCoeff(), -1e-15);
      }
    }
  }
}

TEST(KnotVector, DerivativesMatchFiniteDifferences) {
  std::mt19937_64 rng(7);
  for (int p = 1; p <= 5; ++p) {
    const KnotVector kv = irregular_clamped(p);
    std::uniform_real_distribution<double> pick(kv.domain_begin() + 1e-3, kv.domain_end() - 1e-3);
    const int orders = std::min(p, 3) + 1;
    for (int trial = 0; trial < 50; ++trial) {
      const double t = pick(rng), eps = 1e-6;
      const std::size_t span = kv.find_span(t);
      // Stay inside one span so that the finite difference sees one polynomial.
      if (t - eps < kv.knots()[span] || t + eps >= kv.knots()[span + 1]) continue;
      Eigen::MatrixXd at(orders, p + 1), plus(orders, p + 1), minus(orders, p + 1);
      kv.basis_derivatives(span, t, at);
      kv.basis_derivatives(span, t + eps, plus);
      kv.basis_derivatives(span, t - eps, minus);
      for (int d = 1; d < orders; ++d) {
        const Eigen::VectorXd fd = (plus.row(d - 1) - minus.row(d - 1)).transpose() / (2 * eps);
        const double scale = std::max(1.0, at.row(d).cwiseAbs().maxCoeff());
        EXPECT_LT((fd - at.row(d).transpose()).cwiseAbs().maxCoeff() / scale, 1e-5)
            << "degree " << p << " derivative " << d << " at t = " << t;
      }
    }
  }
}

TEST(KnotVector, RejectsBadInput) {
  EXPECT_THROW(KnotVector(0, {0, 0, 1, 1}), InputError);
  EXPECT_THROW(KnotVector(3, {0, 0, 0, 1, 1, 1}), InputError);  // too few knots
  EXPECT_THROW(KnotVector(1, {0, 1, 0.5, 2}), InputError);      // decreasing
  EXPECT_THROW(KnotVector(1, {0, 0, 0, 0}), InputError);        // empty domain
  EXPECT_THROW(irregular_clamped(3).find_span(-0.1), InputError);
  EXPECT_THROW(irregular_clamped(3).find_span(std::nan("")), InputError);
  EXPECT_EQ(irregular_clamped(3).find_span(3.7), irregular_clamped(3).num_basis() - 1);
}

TEST(BSplineCurve, SingleSpanCubicIsTheBezierCurveWithItsDerivatives) {
  // Clamped knots without interior knots make the B-spline a Bezier curve,
  // whose Bernstein form and derivatives are known in closed form.
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 2, -1}, {3, 3, 2}, {4, 0, 1}};
  const double t0 = 2.0, t1 = 4.5, span = t1 - t0;
  const Curve3 curve(KnotVector::clamped(3, {t0, t1}), p);
  for (double t : {2.0, 2.6, 3.3, 4.5}) {
    const double u = (t - t0) / span, v = 1 - u;
    const Eigen::Vector3d c =
        v * v * v * p[0] + 3 * u * v * v * p[1] + 3 * u * u * v * p[2] + u * u * u * p[3];
    const Eigen::Vector3d d1 =
        3 * (v * v * (p[1] - p[0]) + 2 * u * v * (p[2] - p[1]) + u * u * (p[3] - p[2])) / span;
    const Eigen::Vector3d d2 =
        6 * (v * (p[2] - 2 * p[1] + p[0]) + u * (p[3] - 2 * p[2] + p[1])) / (span * span);
    const Eigen::Vector3d d3 = 6 * (p[3] - 3 * p[2] + 3 * p[1] - p[0]) / (span * span * span);
    Curve3::Derivatives d;
    curve.derivatives(t, 3, d);
    EXPECT_LT((d.col(0) - c).norm(), 1e-13) << t;
    EXPECT_LT((d.col(1) - d1).norm(), 1e-12) << t;
    EXPECT_LT((d.col(2) - d2).norm(), 1e-12) << t;
    EXPECT_LT((d.col(3) - d3).norm(), 1e-12) << t;
  }
}

TEST(BSplineCurve, InterpolationPassesThroughEveryPoint) {
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 25; ++k) {
    const double a = 0.3 * k;
    points.emplace_back(10 * std::cos(a) + 0.1 * k * k, 7 * std::sin(a));
  }
  for (int degree : {1, 2, 3, 5}) {
    const Curve2 curve = Curve2::interpolate(points, degree);
    // Recompute the chord-length parameters and check the points.
    double total = 0.0;
    std::vector<double> u{0.0};
    for (std::size_t k = 1; k < points.size(); ++k)
      u.push_back(total += (points[k] - points[k - 1]).norm());
    for (std::size_t k = 0; k < points.size(); ++k) {
      EXPECT_LT((curve.evaluate(u[k] / total) - points[k]).norm(), 1e-10) << "degree " << degree;
    }
  }
}

TEST(BSplineCurve, CurveDerivativesMatchFiniteDifferences) {
  std::vector<Eigen::Vector2d> points = {{0, 0}, {3, 1}, {4, 5}, {8, 6}, {9, 2}, {12, 0}};
  const Curve2 curve = Curve2::interpolate(points);
  for (double t : {0.05, 0.31, 0.5, 0.77, 0.93}) {
    const double eps = 1e-5;
    Curve2::Derivatives at, plus, minus;
    curve.derivatives(t, 3, at);
    curve.derivatives(t + eps, 3, plus);
    curve.derivatives(t - eps, 3, minus);
    for (int k = 1; k <= 3; ++k) {
      const Eigen::Vector2d fd = (plus.col(k - 1) - minus.col(k - 1)) / (2 * eps);
      EXPECT_LT((fd - at.col(k)).norm() / std::max(1.0, at.col(k).norm()), 1e-4)
          << "order " << k << " at " << t;
    }
  }
}

TEST(BSplineCurve, RejectsBadInput) {
  EXPECT_THROW(Curve2::interpolate({Eigen::Vector2d(1, 1)}), InputError);
  EXPECT_THROW(Curve2::interpolate({Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 1)}), InputError);
  EXPECT_THROW(Curve2::interpolate({Eigen::Vector2d(1, 1), Eigen::Vector2d(std::nan(""), 1)}),
               InputError);
  EXPECT_THROW(Curve2(KnotVector::uniform(3, 0, 1, 5), std::vector<Eigen::Vector2d>(4)),
               InputError);
}

}  // namespace
}  // namespace talus
