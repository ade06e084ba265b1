#pragma once
/// @file
/// Lambertian hillshade: how brightly a sun at a given position lights a
/// surface with a given gradient, the basis of shaded-relief maps.
#include "talus/bspline/bpatch.hpp"

namespace talus {

/// Direction of the light for a hillshade. The cartographic default (light
/// from the north-west, 45° above the horizon) makes slopes facing the reader
/// look lit and avoids the "relief inversion" illusion of light from the south.
struct SunPosition {
  double azimuth_deg = 315.0;  ///< compass bearing the light comes from, clockwise from north
  double altitude_deg = 45.0;  ///< angle above the horizon, in (0, 90]
};

/// Lambertian hillshade of a surface with gradient (z_x, z_y) (x east, y
/// north, dimensionless slopes), in [0, 1]:
///
///   shade = max(0, n · s),
///   n = (-k z_x, -k z_y, 1) / sqrt(1 + k² (z_x² + z_y²))   (unit surface normal)
///   s = (cos α sin A, cos α cos A, sin α)                  (unit vector towards the sun)
///
/// with A the sun's azimuth (clockwise from north), α its altitude and k the
/// vertical exaggeration. This equals the usual GIS formula
/// cos(zenith) cos(slope) + sin(zenith) sin(slope) cos(azimuth - aspect);
/// flat ground gets sin α (0.707 for α = 45°), and faces turned away from the
/// sun by more than 90° get 0 (self-shadow; cast shadows are not traced).
/// Throws InputError if the exaggeration is not positive and finite.
double hillshade(double z_x, double z_y, const SunPosition& sun = {}, double exaggeration = 1.0);

/// The hillshade of a B-patch at a point it was evaluated at (its gradient).
double hillshade(const SurfacePoint& point, const SunPosition& sun = {}, double exaggeration = 1.0);

}  // namespace talus
