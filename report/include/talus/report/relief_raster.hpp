#pragma once
/// @file
/// A fitted surface sampled on a relief raster, and the gnuplot data files
/// drawn from it: the shaded-relief image ("x y r g b", for `with rgbimage`)
/// and the elevation raster ("x y z", for tracing contours). Every map of the
/// experiments sits on these.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <optional>
#include <utility>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/relief.hpp"
#include "talus/bspline/surface_raster.hpp"
#include "talus/report/map_frame.hpp"

namespace talus {

/// A B-patch sampled once on the relief raster (sample_surface_raster). The
/// elevation and the gradient are kept because a hillshade's exaggeration
/// depends on the slope distribution, which must be known before any colour
/// is computed.
using ReliefRaster = SurfaceRaster;

/// How a sample is coloured: the hypsometric tint of its elevation over
/// [zmin, zmax] (mid-ramp if that is empty) times a hillshade.
struct ReliefColouring {
  double zmin = 0.0, zmax = 0.0;
  SunPosition sun;
  double exaggeration = 1.0;  ///< vertical exaggeration of the hillshade
  double ambient = 0.35;      ///< shade_colour()'s floor
  /// Washed 45 % towards white, so that routes and overlays read on top.
  bool washed = false;
};

/// Writes `header` and then "x y z" per sample (offsets and elevation [m]), a
/// blank line after each raster row: the input gnuplot traces contours on.
void write_elevation_raster(const ReliefRaster& raster, const std::string& header,
                            const std::filesystem::path& file);

/// A relief image as written, with what its colouring used.
struct ReliefImage {
  ReliefRaster raster;
  ReliefColouring colouring;
};

/// Samples `surface` over the frame's rectangle (`max_samples` along the
/// longer side; the last row and column clamped onto the domain) and writes
/// the shaded-relief image "x y r g b" (offsets [m], channels 0–255, a blank
/// line after each raster row: gnuplot's `with rgbimage` input) to `file`, `what` naming the
/// surface in its header. The tint spans `z_range` (the raster's own range if empty); the
/// hillshade's exaggeration follows the 95th-percentile slope (hillshade_exaggeration).
ReliefImage write_relief_image(const BPatch& surface, const MapFrame& frame,
                               const std::string& what, const std::filesystem::path& file,
                               std::size_t max_samples = 500,
                               std::optional<std::pair<double, double>> z_range = {},
                               bool washed = true, const SunPosition& sun = {});

}  // namespace talus
