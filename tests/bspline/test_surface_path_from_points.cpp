// talus/bspline/surface_path_from_points.hpp: a path on a terrain from user
// way points, and the message of every check of the user's input.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "talus/bspline/surface_path_from_points.hpp"
#include "talus/core/error.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

const PathPointSource kSource{"P.csv", "T.asc"};

/// 11 x 11 nodes at 1 m from the origin (domain [0, 10] x [0, 10]) holding z = f(x, y).
ElevationGrid square(const terrain_test::HeightFunction& f) {
  return terrain_test::grid_of_nodes(f, 11, 11, 1.0, 0.0, 0.0);
}
ElevationGrid flat_square() {
  return square([](double, double) { return 0.0; });
}

/// The InputError message of `f`, or "" if it throws none.
std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SurfacePathFromPoints, PlaneGivesTheExactLengths) {
  // z = 0.5 x: a straight way along x climbs at slope 1/2.
  const ElevationGrid grid = square([](double x, double) { return 0.5 * x; });
  const std::vector<Vec2> points{Vec2(1, 5), Vec2(5, 5), Vec2(9, 5)};
  const TerrainPath tp = surface_path_from_points(points, grid, std::nullopt, kSource);
  ASSERT_TRUE(tp.surface && tp.path);
  EXPECT_EQ(tp.planar_length, 8.0);
  EXPECT_NEAR(tp.path->length(), 8.0 * std::sqrt(1.25), 1e-9);
  EXPECT_EQ(tp.path->surface().identity(), tp.surface->identity());  // the same surface
  EXPECT_NEAR(tp.surface->evaluate(Vec2(3.3, 7.1)).z, 1.65, 1e-12);  // interpolating fit
  // The smoothing fit reproduces a plane too (its penalty vanishes on it).
  const TerrainPath smooth = surface_path_from_points(points, grid, 1.0, kSource);
  EXPECT_NEAR(smooth.path->length(), 8.0 * std::sqrt(1.25), 1e-6);
}

TEST(SurfacePathFromPoints, PlanarPolylineLength) {
  EXPECT_EQ(planar_polyline_length({}), 0.0);
  EXPECT_EQ(planar_polyline_length({Vec2(1, 1)}), 0.0);
  EXPECT_EQ(planar_polyline_length({Vec2(0, 0), Vec2(3, 4), Vec2(3, 10)}), 11.0);
}

TEST(SurfacePathFromPoints, ReversalIsNamed) {
  const std::vector<Vec2> points{Vec2(1, 1), Vec2(5, 1), Vec2(2, 1)};
  const std::string expected =
      "path point 1 (5, 1) (P.csv line 3) turns the path straight back on itself: the spline "
      "through it would stop there; split the path at this point instead";
  EXPECT_EQ(message_of([&] { check_no_reversal(points, kSource); }), expected);
  EXPECT_EQ(
      message_of([&] { surface_path_from_points(points, flat_square(), std::nullopt, kSource); }),
      expected);
  // A sharp turn that is not a reversal passes; so does a path of two points.
  EXPECT_EQ(message_of([&] {
              check_no_reversal({Vec2(1, 1), Vec2(5, 1), Vec2(1, 1.5)}, kSource);
            }),
            "");
  EXPECT_EQ(message_of([&] { check_no_reversal({Vec2(1, 1), Vec2(5, 1)}, kSource); }), "");
  // first_line shifts the line numbers.
  PathPointSource shifted = kSource;
  shifted.first_line = 7;
  EXPECT_NE(message_of([&] { check_no_reversal(points, shifted); }).find("(P.csv line 8)"),
            std::string::npos);
}

TEST(SurfacePathFromPoints, PointOutsideTheDomainIsNamed) {
  const std::vector<Vec2> points{Vec2(1, 1), Vec2(12.5, 5)};
  const std::string expected =
      "path point 1 (12.5, 5) (P.csv line 3) is outside the terrain T.asc, whose domain is "
      "[0, 10] x [0, 10]";
  EXPECT_EQ(message_of([&] { check_points_in_domain(points, flat_square(), kSource); }), expected);
  EXPECT_EQ(
      message_of([&] { surface_path_from_points(points, flat_square(), std::nullopt, kSource); }),
      expected);
  const BPatch patch = BPatch::interpolate(flat_square());
  EXPECT_EQ(message_of([&] { check_points_on_data(points, patch, flat_square(), kSource); }),
            expected);
}

TEST(SurfacePathFromPoints, PointOnNodataIsNamed) {
  ElevationGrid grid = flat_square();
  grid.set_void(5, 5);
  const std::vector<Vec2> points{Vec2(1, 1), Vec2(5.5, 5.5), Vec2(9, 2)};
  EXPECT_EQ(message_of([&] { surface_path_from_points(points, grid, 1.0, kSource); }),
            "path point 1 (5.5, 5.5) (P.csv line 3) lies in a NODATA cell of T.asc (a corner of "
            "its cell has no elevation)");
}

TEST(SurfacePathFromPoints, FitErrorsNameTheTerrain) {
  ElevationGrid grid = flat_square();
  grid.set_void(5, 5);  // the interpolating fit refuses NODATA
  const std::string message = message_of([&] {
    surface_path_from_points({Vec2(1, 1), Vec2(9, 2)}, grid, std::nullopt, kSource);
  });
  EXPECT_EQ(message.rfind("T.asc: ", 0), 0u) << message;
}

TEST(SurfacePathFromPoints, PathAcrossNodataIsNamed) {
  ElevationGrid grid = flat_square();
  grid.set_void(5, 5);
  // Both way points are on data; the straight way between them crosses the
  // cells around node (5, 5), which span x in [4, 6].
  const std::string message = message_of([&] {
    surface_path_from_points({Vec2(1, 5.5), Vec2(9, 5.5)}, grid, 1.0, kSource);
  });
  const std::string prefix = "P.csv: the path crosses a NODATA cell of T.asc at s = ";
  ASSERT_EQ(message.rfind(prefix, 0), 0u) << message;
  const double s = std::stod(message.substr(prefix.size()));
  EXPECT_GE(s, 3.0 - 0.25);  // x = 1 + s on this flat, straight way, a station every 0.25 m
  EXPECT_LE(s, 3.0 + 0.25);
  // Off the voids, the same way is accepted.
  EXPECT_EQ(message_of([&] {
              surface_path_from_points({Vec2(1, 2.5), Vec2(9, 2.5)}, grid, 1.0, kSource);
            }),
            "");
}

TEST(SurfacePathFromPoints, SplineLeavingTheDomainIsNamed) {
  // Way points 0.05 m inside the west border: coming in from the south-east,
  // the interpolating cubic swings west of them between points 1 and 2.
  const std::vector<Vec2> points{Vec2(5, 0.5), Vec2(0.05, 2), Vec2(0.05, 8), Vec2(5, 9.5)};
  const std::string message =
      message_of([&] { surface_path_from_points(points, flat_square(), std::nullopt, kSource); });
  const std::string prefix =
      "the spline through the path points of P.csv leaves the terrain T.asc between points 1 and "
      "2, at (";
  ASSERT_EQ(message.rfind(prefix, 0), 0u) << message;
  EXPECT_NE(message.find("(domain [0, 10] x [0, 10]): move those points further inside or add "
                         "points between them"),
            std::string::npos)
      << message;
  const Curve2 curve = Curve2::interpolate(points);
  const BPatch patch = BPatch::interpolate(flat_square());
  EXPECT_EQ(
      message_of([&] { check_curve_in_domain(curve, points, patch, flat_square(), kSource); }),
      message);
}

}  // namespace
}  // namespace talus
