#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "talus/bspline/curve_fit.hpp"
#include "talus/core/error.hpp"

namespace talus {
namespace {

/// The fit's chord-length parameters of a polyline, recomputed here.
std::vector<double> chord_parameters(const std::vector<Vec2>& polyline) {
  std::vector<double> u{0.0};
  for (std::size_t k = 1; k < polyline.size(); ++k)
    u.push_back(u.back() + (polyline[k] - polyline[k - 1]).norm());
  for (double& value : u) value /= u.back();
  return u;
}

// Exact reproduction of a cubic polynomial curve is not a property of this
// fit: it fits at chord-length parameters, and vertices of a curved cubic c(t)
// are never at chord-length parameters that are a polynomial in t (that would
// need |c'| constant). What it does reproduce exactly is anything in its
// spline space *as a function of the chord-length parameter*: for a straight
// line, however unevenly sampled, the chord-length parameter is the fraction
// of the distance along it, so the line is the linear polynomial
// P0 + u (P1 - P0), and the least-squares fit must return it.
TEST(CurveFit, KeepsTheEndsAndReproducesAnUnevenlySampledLineExactly) {
  const Vec2 p0(1.0, -2.0), p1(11.0, 3.0);
  std::vector<Vec2> polyline;
  for (int k = 0; k <= 60; ++k) {
    const double t = k / 60.0;
    const double s = t * t * (3.0 - 2.0 * t);  // smoothstep: dense at both ends
    polyline.push_back(p0 + s * (p1 - p0));
  }
  for (std::size_t m : {4u, 6u, 10u, 17u}) {
    const Curve2 fit = fit_clamped_cubic(polyline, m);
    EXPECT_EQ(fit.control_points().size(), m);
    EXPECT_EQ(fit.evaluate(0.0), polyline.front());
    EXPECT_LT((fit.evaluate(1.0) - polyline.back()).norm(), 1e-12);
    for (int k = 0; k <= 200; ++k) {
      const double u = k / 200.0;
      EXPECT_LT((fit.evaluate(u) - (p0 + u * (p1 - p0))).norm(), 1e-12) << m << " " << u;
    }
  }
}

// On a curved cubic the fit is a least-squares fit at the chord-length
// parameters: the sum of squared vertex residuals S is a quadratic in each
// interior control point with zero slope at the fit, so moving one by ±e
// changes S by the same amount both ways, (S+ - S-) = 4 e (gradient) = 0,
// while (S+ + S- - 2 S) = 2 e^2 |basis column|^2 > 0.
TEST(CurveFit, FitOfACubicCurveIsTheLeastSquaresFitAtChordLengthParameters) {
  std::vector<Vec2> polyline;
  for (int k = 0; k <= 200; ++k) {
    const double t = k / 200.0;
    polyline.emplace_back(10.0 * t, 2.0 * t * t * (1.0 - t));
  }
  const std::vector<double> u = chord_parameters(polyline);
  const auto squares = [&](const Curve2& c) {
    double sum = 0.0;
    for (std::size_t k = 0; k < polyline.size(); ++k)
      sum += (c.evaluate(u[k]) - polyline[k]).squaredNorm();
    return sum;
  };
  for (std::size_t m : {4u, 6u, 10u}) {
    const Curve2 fit = fit_clamped_cubic(polyline, m);
    EXPECT_EQ(fit.evaluate(0.0), polyline.front());
    EXPECT_LT((fit.evaluate(1.0) - polyline.back()).norm(), 1e-12);
    const double s0 = squares(fit), e = 1e-3;
    for (std::size_t j = 1; j + 1 < m; ++j)
      for (int axis = 0; axis < 2; ++axis) {
        std::vector<Vec2> plus = fit.control_points(), minus = fit.control_points();
        plus[j][axis] += e;
        minus[j][axis] -= e;
        const double sp = squares(Curve2(fit.knots(), plus));
        const double sm = squares(Curve2(fit.knots(), minus));
        const double curvature = sp + sm - 2 * s0;
        ASSERT_GT(curvature, 0.0);
        // An error of 1e-9 m in a control point gives |sp - sm| / curvature
        // ~ 2e-6; round-off in the sums is ~1e-13 of S.
        EXPECT_LT(std::abs(sp - sm), 1e-8 * curvature) << m << " " << j << " " << axis;
      }
  }
}

TEST(CurveFit, MoreControlPointsFollowAWigglyPolylineCloser) {
  std::vector<Vec2> polyline;
  for (int k = 0; k <= 300; ++k) polyline.emplace_back(k * 0.1, std::sin(k * 0.1));
  const std::vector<double> u = chord_parameters(polyline);  // the fit's own parameters
  // 2, 4, ..., 64 spans: nested spline spaces, so the residual cannot grow.
  double previous = INFINITY;
  for (std::size_t m : {5u, 7u, 11u, 19u, 35u, 67u}) {
    const Curve2 fit = fit_clamped_cubic(polyline, m);
    double sum = 0.0;
    for (std::size_t k = 0; k < polyline.size(); ++k)
      sum += (fit.evaluate(u[k]) - polyline[k]).squaredNorm();
    EXPECT_LT(sum, previous) << m;
    previous = sum;
  }
  EXPECT_LT(previous, 5e-3);
}

TEST(CurveFit, TwoVerticesGiveTheStraightSegmentAtUniformSpeed) {
  const Curve2 fit = fit_clamped_cubic({Vec2(1, 2), Vec2(5, -2)}, 7);
  for (double t : {0.0, 0.2, 0.5, 0.9, 1.0}) {
    EXPECT_LT((fit.evaluate(t) - (Vec2(1, 2) + t * Vec2(4, -4))).norm(), 1e-12) << t;
  }
}

TEST(CurveFit, RejectsBadInput) {
  EXPECT_THROW(fit_clamped_cubic({Vec2(0, 0)}, 4), InputError);
  EXPECT_THROW(fit_clamped_cubic({Vec2(0, 0), Vec2(1, 1)}, 3), InputError);
  EXPECT_THROW(fit_clamped_cubic({Vec2(0, 0), Vec2(0, 0), Vec2(1, 1)}, 4), InputError);
  EXPECT_THROW(fit_clamped_cubic({Vec2(0, 0), Vec2(1, 0), Vec2(2, 1), Vec2(3, 0)}, 12), InputError);
}

}  // namespace
}  // namespace talus
