#include "talus/bspline/relief.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Stops chosen as a conventional elevation tint: greens for lowlands, tans
// and browns for the middle, near-white for the summits. Mid-tones stay light
// enough that the hillshade multiplied on top remains visible, and adjacent
// stops differ in lightness as well as hue so the ramp still reads in grey.
constexpr std::array<ColourStop, 6> kHypsometricStops{{
    {0.00, {0.184, 0.420, 0.227}},  // #2f6b3a dark green
    {0.20, {0.431, 0.604, 0.290}},  // #6e9a4a yellow-green
    {0.40, {0.784, 0.761, 0.478}},  // #c8c27a khaki
    {0.60, {0.725, 0.553, 0.337}},  // #b98d56 tan
    {0.80, {0.549, 0.392, 0.275}},  // #8c6446 brown
    {1.00, {0.949, 0.941, 0.922}},  // #f2f0eb near-white
}};

double clamp01(double value) {
  return std::clamp(value, 0.0, 1.0);
}

}  // namespace

std::span<const ColourStop> hypsometric_stops() {
  return kHypsometricStops;
}

Rgb hypsometric_colour(double t) {
  if (std::isnan(t)) return kHypsometricStops.front().colour;
  t = clamp01(t);
  for (std::size_t k = 1; k < kHypsometricStops.size(); ++k) {
    const ColourStop& lo = kHypsometricStops[k - 1];
    const ColourStop& hi = kHypsometricStops[k];
    if (t <= hi.t) {
      const double w = (t - lo.t) / (hi.t - lo.t);
      return {lo.colour.r + w * (hi.colour.r - lo.colour.r),
              lo.colour.g + w * (hi.colour.g - lo.colour.g),
              lo.colour.b + w * (hi.colour.b - lo.colour.b)};
    }
  }
  return kHypsometricStops.back().colour;
}

Rgb shade_colour(const Rgb& colour, double shade, double ambient) {
  const double factor = ambient + (1.0 - ambient) * clamp01(shade);
  return {clamp01(colour.r * factor), clamp01(colour.g * factor), clamp01(colour.b * factor)};
}

int to_byte(double channel) {
  return static_cast<int>(std::lround(clamp01(channel) * 255.0));
}

double nice_floor(double x) {
  if (!(x > 0.0) || !std::isfinite(x)) {
    throw InputError("nice_floor: argument must be positive and finite, got " + std::to_string(x));
  }
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  // The 1e-9 slack keeps exact inputs such as 2, 50 or 0.5 from dropping a
  // step because log10/pow round the decade a hair above them.
  const double mantissa = x / decade * (1.0 + 1e-9);
  if (mantissa >= 5.0) return 5.0 * decade;
  if (mantissa >= 2.0) return 2.0 * decade;
  return decade;
}

double contour_interval(double range, int target_levels) {
  if (!(range > 0.0) || !std::isfinite(range) || target_levels < 1) return 1.0;
  return nice_floor(range / static_cast<double>(target_levels));
}

double hillshade_exaggeration(double p95_gradient) {
  const double target = std::tan(20.0 * kDegree);
  if (!(p95_gradient > 0.0) || !std::isfinite(p95_gradient) || p95_gradient >= target) return 1.0;
  return std::max(1.0, nice_floor(target / p95_gradient));
}

}  // namespace talus
