#pragma once
/// @file
/// The small pure functions behind shaded-relief figures: a hypsometric
/// colour ramp and the "nice number" choices for contour intervals and
/// vertical exaggeration. The hillshade (talus/bspline/hillshade.hpp) and the
/// raster geometry (talus/bspline/surface_raster.hpp) live in the library.
/// Kept free of I/O so they can be unit-tested and reused by every experiment
/// that draws a map.
#include <span>

#include "talus/bspline/hillshade.hpp"
#include "talus/bspline/surface_raster.hpp"

namespace talus {

// The hillshade itself and the raster geometry are library computations;
// named here too so that every map-drawing file finds them in one place.
using talus::hillshade;
using talus::raster_for_extent;
using talus::RasterSize;
using talus::SunPosition;

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

}  // namespace talus
