// hillshade (talus/bspline/hillshade.hpp) and sample_surface_raster
// (talus/bspline/surface_raster.hpp) on planes, where the shade is the cosine
// of the angle between the plane's normal and the sun, in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "talus/bspline/hillshade.hpp"
#include "talus/bspline/surface_raster.hpp"
#include "talus/core/error.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// The GIS formula, written independently of the normal-vector form:
/// cos Z cos S + sin Z sin S cos(A − aspect), Z the sun's zenith angle, S the
/// slope angle, aspect the compass bearing the slope faces (downhill).
double gis_hillshade(double z_x, double z_y, const SunPosition& sun, double k) {
  const double zenith = (90.0 - sun.altitude_deg) * kDeg;
  const double slope = std::atan(k * std::hypot(z_x, z_y));
  const double aspect = std::atan2(-z_x, -z_y);  // bearing of −∇z: x east, y north
  return std::max(
      0.0, std::cos(zenith) * std::cos(slope) +
               std::sin(zenith) * std::sin(slope) * std::cos(sun.azimuth_deg * kDeg - aspect));
}

TEST(Hillshade, PlaneShadeIsTheCosineBetweenNormalAndSun) {
  const double a = 0.3, b = -0.45;
  const ElevationGrid grid = terrain_test::grid_of_nodes(
      [&](double x, double y) { return 10.0 + a * x + b * y; }, 9, 8, 1.5, 20.0, -4.0);
  const BPatch plane = BPatch::interpolate(grid);
  const SurfacePoint p = plane.evaluate({25.2, 1.7});
  for (const SunPosition sun :
       {SunPosition{}, SunPosition{90.0, 30.0}, SunPosition{200.0, 60.0}, SunPosition{10.0, 5.0}}) {
    for (const double k : {1.0, 2.5}) {
      EXPECT_NEAR(hillshade(p, sun, k), gis_hillshade(a, b, sun, k), 1e-12)
          << sun.azimuth_deg << " " << sun.altitude_deg << " " << k;
      EXPECT_EQ(hillshade(p, sun, k), hillshade(p.gradient.x(), p.gradient.y(), sun, k));
    }
  }
}

TEST(Hillshade, FlatGroundSunFacingAndSelfShadowedSlopes) {
  EXPECT_NEAR(hillshade(0.0, 0.0, {123.0, 30.0}), 0.5, 1e-15);  // sin α
  // A slope facing the sun, tilted by its zenith angle, is lit head-on.
  const double g = std::tan(45.0 * kDeg) / std::sqrt(2.0);  // 45° slope facing north-west
  EXPECT_NEAR(hillshade(g, -g, {315.0, 45.0}), 1.0, 1e-12);
  // The opposite slope, steeper than the sun's altitude, is in self-shadow.
  EXPECT_EQ(hillshade(-2.0 * g, 2.0 * g, {315.0, 45.0}), 0.0);
  EXPECT_THROW(hillshade(0.0, 0.0, {}, -1.0), InputError);
  EXPECT_THROW(hillshade(SurfacePoint{}, {}, std::numeric_limits<double>::infinity()), InputError);
}

TEST(SurfaceRaster, SamplesThePatchAtClampedOffsetsRowByRowFromTheSouth) {
  const double a = 0.3, b = -0.4;
  const ElevationGrid grid = terrain_test::grid_of_nodes(
      [&](double x, double y) { return a * x + b * y; }, 11, 7, 1.0, 5.0, 3.0);
  const BPatch plane = BPatch::interpolate(grid);
  const Vec2 origin(5.0, 3.0);
  const SurfaceRaster raster = sample_surface_raster(plane, origin, 10.0, 6.0, 21);
  EXPECT_EQ(raster.size.nx, 21u);
  EXPECT_EQ(raster.size.ny, 13u);
  EXPECT_DOUBLE_EQ(raster.size.spacing, 0.5);
  ASSERT_EQ(raster.samples.size(), 21u * 13u);
  EXPECT_EQ(raster.offsets.back(), Vec2(10.0, 6.0));  // the far corner, on the domain
  EXPECT_EQ(raster.offsets[21], Vec2(0.0, 0.5));      // second row starts at the west edge
  for (std::size_t k = 0; k < raster.samples.size(); ++k) {
    const Vec2 x = origin + raster.offsets[k];
    EXPECT_NEAR(raster.samples[k].z, a * x.x() + b * x.y(), 1e-12);
    EXPECT_NEAR(raster.slopes[k], std::hypot(a, b), 1e-12);
  }
  EXPECT_THROW(sample_surface_raster(plane, origin, 11.0, 6.0, 21), InputError);  // off the domain
  EXPECT_THROW(sample_surface_raster(plane, origin, 10.0, 6.0, 1), InputError);
}

}  // namespace
}  // namespace talus
