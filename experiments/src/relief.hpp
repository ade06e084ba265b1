#pragma once
/// @file
/// The small pure functions behind shaded-relief figures: Lambertian
/// hillshade, a hypsometric colour ramp, and the "nice number" choices for
/// contour intervals, vertical exaggeration and raster sizes. Kept free of I/O
/// so they can be unit-tested and reused by every experiment that draws a map.
#include <cstddef>
#include <span>

namespace talus::experiments {

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

/// A colour with channels in [0, 1].
struct Rgb {
  double r = 0.0, g = 0.0, b = 0.0;
};

/// Hypsometric (elevation-tint) colour ramp: t = 0 (lowest) dark green through
/// yellow-green, tan and brown to near-white at t = 1 (highest). Linear
/// between the stops of hypsometric_stops(); t is clamped to [0, 1], NaN gives
/// the lowest colour.
Rgb hypsometric_colour(double t);

/// One stop of the ramp (position in [0, 1] and colour), exposed so a gnuplot
/// colour key can use exactly the same colours as the image.
struct ColourStop {
  double t;
  Rgb colour;
};
/// The ramp's stops, ordered by t from 0 to 1.
std::span<const ColourStop> hypsometric_stops();

/// Modulates a colour by a hillshade value: colour × (ambient + (1 − ambient) ×
/// shade). The ambient term keeps shadowed slopes tinted rather than black, so
/// the elevation colour stays readable everywhere. Channels clamped to [0, 1].
Rgb shade_colour(const Rgb& colour, double shade, double ambient = 0.35);

/// Channel in [0, 1] as an integer in [0, 255] (rounded), for image files.
int to_byte(double channel);

/// Largest number of the form {1, 2, 5} × 10^k that is <= x (x > 0).
/// Throws InputError if x is not positive and finite.
double nice_floor(double x);

/// A contour interval of the form {1, 2, 5} × 10^k giving at least
/// `target_levels` contour levels over `range` (and fewer than about 2.5 ×
/// that). A non-positive range (flat terrain) gives 1.
double contour_interval(double range, int target_levels = 12);

/// Vertical exaggeration for a hillshade: 1 if the terrain's 95th-percentile
/// gradient magnitude already reaches tan(20°) (its shading is readable as is),
/// else nice_floor(tan(20°) / p95), so gentle terrains (dunes, Mars at 15 km
/// posting) still show their forms. Rounded down so slopes are never
/// exaggerated beyond that target. A non-positive p95 (flat) gives 1.
double hillshade_exaggeration(double p95_gradient);

/// Sample counts of a raster with square pixels over a width × height
/// rectangle, the longer side getting `max_samples` samples (both ends
/// included), the shorter one as many as fit at the same spacing (at least 2).
struct RasterSize {
  std::size_t nx = 2, ny = 2;  ///< samples along x and y
  double spacing = 1.0;        ///< distance between neighbouring samples [same unit as width]
};
/// Throws InputError if a side is not positive and finite or max_samples < 2.
RasterSize raster_for_extent(double width, double height, std::size_t max_samples);

}  // namespace talus::experiments
