#include <gtest/gtest.h>

#include <cmath>

#include "talus/bspline/curve_fit.hpp"
#include "talus/core/error.hpp"

namespace talus {
namespace {

TEST(CurveFit, KeepsTheEndsAndReproducesACubicExactly) {
  // Vertices of one cubic polynomial curve at chord-length-like parameters:
  // with 4 control points (a single Bezier span) the least-squares fit is exact
  // only if the parameters match, so sample a straight-ish cubic densely and
  // check the residual is tiny and the ends are exact.
  std::vector<Vec2> polyline;
  for (int k = 0; k <= 200; ++k) {
    const double t = k / 200.0;
    polyline.emplace_back(10.0 * t, 2.0 * t * t * (1.0 - t));
  }
  for (std::size_t m : {4u, 6u, 10u}) {
    const Curve2 fit = fit_clamped_cubic(polyline, m);
    EXPECT_EQ(fit.control_points().size(), m);
    EXPECT_LT((fit.evaluate(0.0) - polyline.front()).norm(), 1e-12);
    EXPECT_LT((fit.evaluate(1.0) - polyline.back()).norm(), 1e-12);
    double worst = 0.0;
    for (int k = 0; k <= 100; ++k) {
      const Vec2 p = fit.evaluate(k / 100.0);
      double nearest = INFINITY;
      for (const Vec2& q : polyline) nearest = std::min(nearest, (p - q).norm());
      worst = std::max(worst, nearest);
    }
    EXPECT_LT(worst, 0.06) << m;  // within the polyline's own vertex spacing
  }
}

TEST(CurveFit, MoreControlPointsFollowAWigglyPolylineCloser) {
  std::vector<Vec2> polyline;
  for (int k = 0; k <= 300; ++k) polyline.emplace_back(k * 0.1, std::sin(k * 0.1));
  std::vector<double> u{0.0};  // the fit's own chord-length parameters
  for (std::size_t k = 1; k < polyline.size(); ++k)
    u.push_back(u.back() + (polyline[k] - polyline[k - 1]).norm());
  for (double& value : u) value /= u.back();
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
