#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>

#include "path_test_support.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_around_origin;

constexpr double kPi = std::numbers::pi;

Curve2 segment(const Vec2& a, const Vec2& b) {
  return Curve2::interpolate({a, b});
}

/// Exact derivatives of the spherical cap z = sqrt(R^2 - x^2 - y^2).
SurfacePoint sphere_point(double R, const Vec2& p) {
  const double w = std::sqrt(R * R - p.squaredNorm()), w3 = w * w * w;
  SurfacePoint sp;
  sp.z = w;
  sp.gradient = -p / w;
  sp.hessian << -(R * R - p.y() * p.y()) / w3, -p.x() * p.y() / w3, -p.x() * p.y() / w3,
      -(R * R - p.x() * p.x()) / w3;
  return sp;
}

TEST(SurfaceFrame, SphereNormalCurvatureIsMinusOneOverRInEveryDirection) {
  const double R = 7.0;
  for (const Vec2& p : {Vec2(0, 0), Vec2(1.5, -2.0), Vec2(-3.0, 4.0)}) {
    for (double heading = 0; heading < 2 * kPi; heading += 0.4) {
      const Vec2 d1(std::cos(heading), std::sin(heading));
      for (const Vec2& d2 : {Vec2(0, 0), Vec2(0.3, -1.1)}) {
        const PathFrame f = lift_to_surface(p, sphere_point(R, p), d1, d2);
        EXPECT_NEAR(f.kappa_n, -1.0 / R, 1e-12);
        EXPECT_NEAR(f.tangent.dot(f.normal), 0.0, 1e-14);
        EXPECT_NEAR(f.lateral.norm(), 1.0, 1e-14);
        EXPECT_NEAR(f.k_t * f.k_t + f.k_q * f.k_q + f.k_r * f.k_r, 1.0, 1e-14);
        EXPECT_GT(f.k_r, 0.0);
      }
    }
  }
}

TEST(SurfaceFrame, CircleInATiltedPlaneHasGeodesicCurvatureOneOverRadius) {
  // Plane z = tan(alpha) x; a circle of radius rho lying in it projects onto
  // the ellipse x = rho cos(alpha) cos(th), y = rho sin(th).
  const double alpha = 0.4, rho = 3.0, c = std::cos(alpha);
  SurfacePoint plane;
  plane.gradient = Vec2(std::tan(alpha), 0.0);
  for (double th = 0; th < 2 * kPi; th += 0.3) {
    const Vec2 p(rho * c * std::cos(th), rho * std::sin(th));
    const Vec2 d1(-rho * c * std::sin(th), rho * std::cos(th));
    const Vec2 d2(-rho * c * std::cos(th), -rho * std::sin(th));
    const PathFrame f = lift_to_surface(p, plane, d1, d2);
    EXPECT_NEAR(f.kappa_g, 1.0 / rho, 1e-12) << th;
    EXPECT_NEAR(f.kappa_n, 0.0, 1e-12) << th;
    // k_t is the sine of the path's climb angle: dz/ds along the plane.
    EXPECT_NEAR(f.k_t, std::tan(alpha) * d1.x() / std::hypot(d1.norm(), std::tan(alpha) * d1.x()),
                1e-12);
  }
}

TEST(SurfaceFrame, ZeroPlanarVelocityIsAnInputError) {
  EXPECT_THROW(lift_to_surface(Vec2::Zero(), SurfacePoint{}, Vec2::Zero(), Vec2(1, 0)), InputError);
}

TEST(SurfacePath, FlatCircleHasGeodesicCurvatureOneOverRadiusAndLengthTwoPiR) {
  const BPatch flat =
      BPatch::interpolate(grid_around_origin([](double, double) { return 5.0; }, 10, 1.0));
  const double r = 4.0;
  const SurfacePath path(flat, path_test::ellipse(Vec2(0.5, -0.5), r, r, 400));
  EXPECT_NEAR(path.length(), 2 * kPi * r, 1e-6);
  for (const PathFrame& f : path.sample(37)) {
    EXPECT_NEAR(f.kappa_g, 1.0 / r, 1e-4);
    EXPECT_NEAR(f.kappa_n, 0.0, 1e-12);
    EXPECT_NEAR(f.k_r, 1.0, 1e-12);
    EXPECT_NEAR(f.k_t, 0.0, 1e-12);
    EXPECT_NEAR(f.k_q, 0.0, 1e-12);
    EXPECT_NEAR(f.point.z(), 5.0, 1e-12);
  }
}

TEST(SurfacePath, CircleInATiltedPlaneOnAFittedPatch) {
  const double alpha = 0.35, rho = 5.0;
  const BPatch plane = BPatch::interpolate(
      grid_around_origin([&](double x, double) { return std::tan(alpha) * x; }, 10, 0.5));
  const SurfacePath path(plane, path_test::ellipse(Vec2::Zero(), rho * std::cos(alpha), rho, 400));
  EXPECT_NEAR(path.length(), 2 * kPi * rho, 1e-5);
  for (const PathFrame& f : path.sample(25)) {
    EXPECT_NEAR(f.kappa_g, 1.0 / rho, 1e-4);
    EXPECT_NEAR(f.kappa_n, 0.0, 1e-9);
    EXPECT_NEAR(f.k_r, std::cos(alpha), 1e-12);
  }
}

TEST(SurfacePath, StraightLineUpAPlaneHasSlopeComponents) {
  const double alpha = 0.3;
  const BPatch plane = BPatch::interpolate(
      grid_around_origin([&](double x, double) { return std::tan(alpha) * x; }, 10, 1.0));
  const SurfacePath up(plane, segment({-8, 1}, {8, 1}));
  EXPECT_NEAR(up.length(), 16.0 / std::cos(alpha), 1e-9);
  const PathFrame f = up.frame_at_arc_length(3.0);
  EXPECT_NEAR(f.k_t, std::sin(alpha), 1e-12);  // uphill: k_t > 0
  EXPECT_NEAR(f.k_q, 0.0, 1e-12);
  EXPECT_NEAR(f.k_r, std::cos(alpha), 1e-12);
  EXPECT_NEAR(f.kappa_n, 0.0, 1e-12);
  EXPECT_NEAR(f.kappa_g, 0.0, 1e-12);
  EXPECT_NEAR(f.s, 3.0, 1e-12);
  // Across the slope heading north, the ground rises to the right (east): k_q < 0.
  const PathFrame across = SurfacePath(plane, segment({2, -8}, {2, 8})).frame_at_arc_length(4.0);
  EXPECT_NEAR(across.k_q, -std::sin(alpha), 1e-12);
  EXPECT_NEAR(across.k_t, 0.0, 1e-12);
}

TEST(SurfacePath, SphereCapOnAFittedPatch) {
  const double R = 40.0;
  const BPatch cap = BPatch::interpolate(grid_around_origin(
      [&](double x, double y) { return std::sqrt(R * R - x * x - y * y); }, 12, 0.25));
  const double a = 6.0;  // planar radius of a circle of latitude
  const SurfacePath path(cap, path_test::ellipse(Vec2::Zero(), a, a, 400));
  EXPECT_NEAR(path.length(), 2 * kPi * a, 1e-4);
  for (const PathFrame& f : path.sample(20)) {
    EXPECT_NEAR(f.kappa_n, -1.0 / R, 1e-3 / R);
    // kappa^2 = kappa_n^2 + kappa_g^2 for a circle of radius a.
    EXPECT_NEAR(f.kappa_g, std::sqrt(1.0 / (a * a) - 1.0 / (R * R)), 1e-4);
  }
  const PathFrame top =
      SurfacePath(cap, segment({-5, -5}, {5, 5})).frame_at_arc_length(0.5 * 14.15);
  EXPECT_NEAR(top.kappa_n, -1.0 / R, 1e-3 / R);
  EXPECT_NEAR(top.kappa_g, 0.0, 1e-5);
}

TEST(SurfacePath, CylinderCrestAlongAndAcrossTheAxis) {
  const double R = 30.0;  // axis along x at height 0: z = sqrt(R^2 - y^2) - R
  const BPatch crest = BPatch::interpolate(
      grid_around_origin([&](double, double y) { return std::sqrt(R * R - y * y) - R; }, 10, 0.25));
  // Along the axis, offset y0: a straight ruling with a side slope.
  const double y0 = -6.0,
               slope = std::asin(-y0 / R);  // ground rises towards the axis (to the left)
  const PathFrame along = SurfacePath(crest, segment({-8, y0}, {8, y0})).frame_at_arc_length(8.0);
  EXPECT_NEAR(along.kappa_n, 0.0, 1e-6);
  EXPECT_NEAR(along.kappa_g, 0.0, 1e-6);
  EXPECT_NEAR(along.k_q, std::sin(slope), 1e-6);
  EXPECT_NEAR(along.k_t, 0.0, 1e-9);
  // Across the axis: a circle of radius R in a vertical plane.
  const SurfacePath across(crest, segment({1, -9}, {1, 9}));
  for (const PathFrame& f : across.sample(9)) {
    EXPECT_NEAR(f.kappa_n, -1.0 / R, 1e-4 / R);
    EXPECT_NEAR(f.kappa_g, 0.0, 1e-9);
    EXPECT_NEAR(f.k_t, -f.point.y() / R, 1e-6);  // uphill before the axis, downhill after
    EXPECT_NEAR(f.k_q, 0.0, 1e-9);
  }
}

TEST(SurfacePath, ArcLengthInverseRoundTrips) {
  const BPatch cap = BPatch::interpolate(grid_around_origin(
      [](double x, double y) { return 0.1 * x * x - 0.05 * x * y + std::sin(y); }, 10, 0.5));
  const SurfacePath path(cap,
                         Curve2::interpolate({Vec2(-8, -8), Vec2(-2, 0), Vec2(3, -4), Vec2(8, 7)}));
  for (double s = 0; s <= path.length(); s += path.length() / 13) {
    const PathFrame f = path.frame_at_arc_length(s);
    EXPECT_NEAR(path.frame_at_parameter(f.parameter).s, s, 1e-9 * path.length());
  }
  EXPECT_THROW(path.frame_at_arc_length(path.length() * 1.01), InputError);
  EXPECT_THROW(path.frame_at_arc_length(-1e-3), InputError);
}

TEST(SurfacePath, APathLeavingTheTerrainIsAnInputError) {
  const BPatch flat =
      BPatch::interpolate(grid_around_origin([](double, double) { return 0.0; }, 5, 1.0));
  try {
    SurfacePath(flat, segment({0, 0}, {7, 0}));
    ADD_FAILURE() << "path off the map accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("leaves the terrain"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace talus

namespace talus {
namespace {

// A path holds its surface (BPatch copies share their immutable coefficients): it stays
// valid once the caller's surface object is gone, and copies of a surface are the same
// surface (one identity) while a new fit is another.
TEST(SurfacePath, OutlivesTheSurfaceObjectItWasBuiltOn) {
  const ElevationGrid grid =
      grid_around_origin([](double x, double y) { return 0.1 * x * y; }, 10, 1.0);
  std::optional<BPatch> surface(BPatch::interpolate(grid));
  const SurfacePath path(*surface, segment({-5, -2}, {5, 3}));
  const PathFrame before = path.frame_at_arc_length(0.5 * path.length());
  const std::uint64_t identity = surface->identity();
  surface.reset();
  const PathFrame after = path.frame_at_arc_length(0.5 * path.length());
  EXPECT_EQ(after.point, before.point);
  EXPECT_EQ(after.kappa_n, before.kappa_n);
  EXPECT_EQ(path.surface().identity(), identity);
  EXPECT_NE(BPatch::interpolate(grid).identity(), identity);
}

TEST(SurfacePath, CopiesAndMovesStayValidAfterTheOriginalIsGone) {
  const BPatch flat =
      BPatch::interpolate(grid_around_origin([](double x, double) { return 0.1 * x; }, 10, 1.0));
  std::vector<SurfacePath> paths;
  {
    SurfacePath original(flat, segment({-5, 0}, {5, 0}));
    SurfacePath copy = original;
    paths.push_back(std::move(original));
    paths.push_back(copy);
  }  // the original and the copy are gone; the vector holds a moved and a copied path
  for (const SurfacePath& p : paths) {
    EXPECT_NEAR(p.length(), 10.0 * std::hypot(1.0, 0.1), 1e-9);
    EXPECT_NEAR(p.frame_at_arc_length(0.5 * p.length()).point.x(), 0.0, 1e-9);
  }
}

}  // namespace
}  // namespace talus

namespace talus {
namespace {

/// 3-D arc length of `curve` on `surface` over [a, b] by composite 8-point
/// Gauss–Legendre on `pieces` equal pieces, straight from the curve and surface
/// derivatives (independent of SurfacePath's arc-length table).
double direct_arc_length(const BPatch& surface, const Curve2& curve, double a, double b,
                         int pieces) {
  static constexpr std::array<double, 4> nodes = {0.1834346424956498, 0.5255324099163290,
                                                  0.7966664774136267, 0.9602898564975363};
  static constexpr std::array<double, 4> weights = {0.3626837833783620, 0.3137066458778873,
                                                    0.2223810344533745, 0.1012285362903763};
  const auto speed = [&](double sigma) {
    Curve2::Derivatives d;
    curve.derivatives(sigma, 1, d);
    const Vec2 d1 = d.col(1);
    return std::hypot(d1.x(), d1.y(), surface.evaluate(d.col(0)).gradient.dot(d1));
  };
  double sum = 0.0;
  for (int p = 0; p < pieces; ++p) {
    const double lo = a + (b - a) * p / pieces, hi = a + (b - a) * (p + 1) / pieces;
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    for (std::size_t i = 0; i < nodes.size(); ++i)
      sum += half * weights[i] * (speed(mid - half * nodes[i]) + speed(mid + half * nodes[i]));
  }
  return sum;
}

TEST(SurfacePath, StationArcLengthsMatchDirectQuadratureAtAnyStationCount) {
  // A curved path over bumpy 1 m cells: the speed |P'| has a kink in its third derivative at
  // every cell edge it crosses (about 60 here). The reference integrates each station interval
  // on pieces of about 1.5 mm, where those kinks leave < 1e-13 m.
  const BPatch bumpy = BPatch::interpolate(grid_around_origin(
      [](double x, double y) {
        return 0.6 * std::sin(1.3 * x) * std::cos(0.9 * y) + 0.05 * x * y + 0.3 * std::sin(2.1 * y);
      },
      12, 1.0));
  const Curve2 curve =
      Curve2::interpolate({Vec2(-9, -8), Vec2(-4, 1), Vec2(2, -3), Vec2(5, 6), Vec2(9, 9)});
  const SurfacePath path(bumpy, curve);
  for (const std::size_t stations : {7u, 301u, 4001u}) {
    std::vector<PathFrame> frames;
    path.sample_uniform_parameter(stations, frames);
    const int pieces = static_cast<int>(30000 / (stations - 1)) + 1;
    double reference = 0.0;
    double worst = 0.0;
    for (std::size_t k = 1; k < stations; ++k) {
      reference +=
          direct_arc_length(bumpy, curve, frames[k - 1].parameter, frames[k].parameter, pieces);
      worst = std::max(worst, std::abs(frames[k].s - reference));
    }
    EXPECT_LT(worst, 1e-12 * reference) << stations << " stations, length " << reference;
    EXPECT_NEAR(path.length(), reference, 1e-12 * reference);
  }
}

}  // namespace
}  // namespace talus
