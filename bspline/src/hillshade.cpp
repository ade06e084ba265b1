#include "talus/bspline/hillshade.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "talus/core/error.hpp"

namespace talus {

double hillshade(double z_x, double z_y, const SunPosition& sun, double exaggeration) {
  if (!(exaggeration > 0.0) || !std::isfinite(exaggeration)) {
    throw InputError("hillshade: vertical exaggeration must be positive and finite, got " +
                     std::to_string(exaggeration));
  }
  constexpr double kDegree = std::numbers::pi / 180.0;
  const double azimuth = sun.azimuth_deg * kDegree;
  const double altitude = sun.altitude_deg * kDegree;
  // Compass azimuth A (clockwise from north) in an x-east, y-north frame:
  // the horizontal direction towards the sun is (sin A, cos A).
  const double s_x = std::cos(altitude) * std::sin(azimuth);
  const double s_y = std::cos(altitude) * std::cos(azimuth);
  const double s_z = std::sin(altitude);
  const double g_x = exaggeration * z_x;
  const double g_y = exaggeration * z_y;
  // The upward normal of z = f(x, y) is (-f_x, -f_y, 1), normalised.
  const double dot = (-g_x * s_x - g_y * s_y + s_z) / std::sqrt(1.0 + g_x * g_x + g_y * g_y);
  return std::max(0.0, dot);
}

double hillshade(const SurfacePoint& point, const SunPosition& sun, double exaggeration) {
  return hillshade(point.gradient.x(), point.gradient.y(), sun, exaggeration);
}

}  // namespace talus
