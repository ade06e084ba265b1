// The pure relief and plotting helpers behind the terrain gallery: hillshade
// geometry, colour ramp, "nice number" choices and gnuplot quoting.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "talus/bspline/relief.hpp"
#include "talus/core/error.hpp"
#include "talus/report/plot.hpp"

namespace talus::experiments {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Hillshade, FlatGroundGetsSineOfAltitude) {
  EXPECT_NEAR(hillshade(0.0, 0.0, {315.0, 45.0}), std::sin(45.0 * kDeg), 1e-15);
  EXPECT_NEAR(hillshade(0.0, 0.0, {90.0, 30.0}), 0.5, 1e-15);
  // Exaggeration does not change flat ground.
  EXPECT_NEAR(hillshade(0.0, 0.0, {315.0, 45.0}, 10.0), std::sin(45.0 * kDeg), 1e-15);
}

TEST(Hillshade, FaceNormalToTheSunIsFullyLit) {
  // Sun in the north-west at 45°: a plane rising towards the south-east with
  // a 45° slope faces it exactly. Its gradient points uphill (south-east).
  const double g = std::tan(45.0 * kDeg) / std::sqrt(2.0);
  EXPECT_NEAR(hillshade(g, -g, {315.0, 45.0}), 1.0, 1e-12);
  // The opposite face is tilted by 90° away from the sun: grazing light.
  EXPECT_NEAR(hillshade(-g, g, {315.0, 45.0}), 0.0, 1e-12);
  // Steeper than that, it is in self-shadow and clamped at 0.
  EXPECT_EQ(hillshade(-3.0 * g, 3.0 * g, {315.0, 45.0}), 0.0);
}

TEST(Hillshade, AzimuthIsClockwiseFromNorth) {
  // Sun from the east (90°): a slope rising to the west (z_x < 0) faces it.
  const SunPosition east{90.0, 45.0};
  EXPECT_GT(hillshade(-0.5, 0.0, east), hillshade(0.0, 0.0, east));
  EXPECT_LT(hillshade(0.5, 0.0, east), hillshade(0.0, 0.0, east));
  // Sun from the north (0°): a slope rising to the south (z_y < 0) faces it.
  const SunPosition north{0.0, 45.0};
  EXPECT_GT(hillshade(0.0, -0.5, north), hillshade(0.0, 0.5, north));
}

TEST(Hillshade, MatchesTheGisSlopeAspectFormula) {
  // cos(zenith) cos(slope) + sin(zenith) sin(slope) cos(azimuth - aspect),
  // with the aspect as the compass bearing of the downhill direction.
  const SunPosition sun{315.0, 45.0};
  const double zenith = (90.0 - sun.altitude_deg) * kDeg;
  for (const auto& [zx, zy] : {std::pair{0.3, -0.2}, {-1.2, 0.4}, {0.05, 0.9}, {-0.7, -0.7}}) {
    const double slope = std::atan(std::hypot(zx, zy));
    const double aspect = std::atan2(-zx, -zy);  // bearing of (-zx, -zy): x east, y north
    const double expected = std::max(
        0.0, std::cos(zenith) * std::cos(slope) +
                 std::sin(zenith) * std::sin(slope) * std::cos(sun.azimuth_deg * kDeg - aspect));
    EXPECT_NEAR(hillshade(zx, zy, sun), expected, 1e-12) << zx << ", " << zy;
  }
}

TEST(Hillshade, ExaggerationScalesTheGradient) {
  EXPECT_NEAR(hillshade(0.1, -0.05, {}, 5.0), hillshade(0.5, -0.25, {}, 1.0), 1e-15);
  EXPECT_THROW(hillshade(0.0, 0.0, {}, 0.0), InputError);
  EXPECT_THROW(hillshade(0.0, 0.0, {}, std::nan("")), InputError);
}

TEST(ColourRamp, EndpointsClampingAndContinuity) {
  const auto stops = hypsometric_stops();
  ASSERT_GE(stops.size(), 2u);
  EXPECT_EQ(stops.front().t, 0.0);
  EXPECT_EQ(stops.back().t, 1.0);
  const Rgb low = hypsometric_colour(0.0), high = hypsometric_colour(1.0);
  EXPECT_EQ(low.g, stops.front().colour.g);
  EXPECT_EQ(high.r, stops.back().colour.r);
  EXPECT_EQ(hypsometric_colour(-3.0).g, low.g);
  EXPECT_EQ(hypsometric_colour(7.0).b, high.b);
  EXPECT_EQ(hypsometric_colour(std::nan("")).r, low.r);
  // Piecewise linear: tiny steps in t give tiny steps in colour.
  for (double t = 0.0; t < 1.0; t += 0.001) {
    const Rgb a = hypsometric_colour(t), b = hypsometric_colour(t + 0.001);
    EXPECT_LT(std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b), 0.02) << t;
    for (const double c : {a.r, a.g, a.b}) {
      EXPECT_GE(c, 0.0);
      EXPECT_LE(c, 1.0);
    }
  }
}

TEST(ColourRamp, ShadingAndBytes) {
  const Rgb c{0.8, 0.4, 0.2};
  const Rgb lit = shade_colour(c, 1.0, 0.35);
  EXPECT_DOUBLE_EQ(lit.r, 0.8);
  const Rgb dark = shade_colour(c, 0.0, 0.35);
  EXPECT_DOUBLE_EQ(dark.g, 0.4 * 0.35);
  EXPECT_EQ(to_byte(0.0), 0);
  EXPECT_EQ(to_byte(1.0), 255);
  EXPECT_EQ(to_byte(2.0), 255);
  EXPECT_EQ(to_byte(0.5), 128);
}

TEST(NiceNumbers, FloorAndContourInterval) {
  EXPECT_DOUBLE_EQ(nice_floor(1.0), 1.0);
  EXPECT_DOUBLE_EQ(nice_floor(2.0), 2.0);
  EXPECT_DOUBLE_EQ(nice_floor(4.99), 2.0);
  EXPECT_DOUBLE_EQ(nice_floor(50.0), 50.0);
  EXPECT_DOUBLE_EQ(nice_floor(0.5), 0.5);
  EXPECT_DOUBLE_EQ(nice_floor(0.0123), 0.01);
  EXPECT_DOUBLE_EQ(nice_floor(9999.0), 5000.0);
  EXPECT_THROW(nice_floor(0.0), InputError);
  // 1525 m of relief and >= 12 levels: 100 m (15 levels).
  EXPECT_DOUBLE_EQ(contour_interval(1525.0, 12), 100.0);
  EXPECT_DOUBLE_EQ(contour_interval(4.2, 12), 0.2);
  EXPECT_DOUBLE_EQ(contour_interval(0.0, 12), 1.0);
  for (const double range : {0.37, 4.2, 117.0, 1525.0, 11051.0}) {
    const double levels = range / contour_interval(range, 12);
    EXPECT_GE(levels, 12.0);
    EXPECT_LT(levels, 30.0);
  }
}

TEST(NiceNumbers, HillshadeExaggeration) {
  EXPECT_EQ(hillshade_exaggeration(std::tan(25.0 * kDeg)), 1.0);
  EXPECT_EQ(hillshade_exaggeration(0.0), 1.0);
  // p95 slope 2.3° (Mars at 15 km): tan 20° / tan 2.3° ≈ 9 -> 5.
  EXPECT_EQ(hillshade_exaggeration(std::tan(2.3 * kDeg)), 5.0);
  EXPECT_EQ(hillshade_exaggeration(std::tan(8.0 * kDeg)), 2.0);
}

TEST(Raster, SquarePixelsLongerSideGetsMaxSamples) {
  const RasterSize square = raster_for_extent(15330.0, 15330.0, 400);
  EXPECT_EQ(square.nx, 400u);
  EXPECT_EQ(square.ny, 400u);
  EXPECT_DOUBLE_EQ(square.spacing, 15330.0 / 399.0);
  const RasterSize tall = raster_for_extent(9480.0, 13770.0, 400);
  EXPECT_EQ(tall.ny, 400u);
  EXPECT_EQ(tall.nx, static_cast<std::size_t>(std::floor(9480.0 / tall.spacing)) + 1);
  EXPECT_LE(static_cast<double>(tall.nx - 1) * tall.spacing, 9480.0);
  const RasterSize sliver = raster_for_extent(1000.0, 1.0, 400);
  EXPECT_EQ(sliver.ny, 2u);
  EXPECT_THROW(raster_for_extent(0.0, 1.0, 400), InputError);
  EXPECT_THROW(raster_for_extent(1.0, 1.0, 1), InputError);
}

TEST(GnuplotQuoting, StringsAndEnhancedText) {
  EXPECT_EQ(gnuplot_string("a.png"), "'a.png'");
  EXPECT_EQ(gnuplot_string("it's"), "'it''s'");
  EXPECT_EQ(gnuplot_string("x_{min}"), "'x_{min}'");
  EXPECT_EQ(gnuplot_plain_text("big_tujunga"), "'big\\_tujunga'");
  EXPECT_EQ(gnuplot_plain_text("a^b{c}"), "'a\\^b\\{c\\}'");
  EXPECT_EQ(gnuplot_string("one\ntwo"), "'one'.\"\\n\".'two'");
}

TEST(Gnuplot, MissingScriptIsAnError) {
  EXPECT_THROW(run_gnuplot("/nonexistent/folder/plot.gp"), Error);
}

}  // namespace
}  // namespace talus::experiments
