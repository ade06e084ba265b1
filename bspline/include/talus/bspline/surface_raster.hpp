#pragma once
/// @file
/// A B-patch sampled on a raster of square pixels over a rectangle: the
/// samples behind shaded-relief images, elevation rasters for contouring and
/// slope distributions.
#include <cstddef>
#include <vector>

#include "talus/bspline/bpatch.hpp"

namespace talus {

/// Sample counts of a raster with square pixels over a width × height
/// rectangle, the longer side getting `max_samples` samples (both ends
/// included), the shorter one as many as fit at the same spacing (at least 2).
struct RasterSize {
  std::size_t nx = 2, ny = 2;  ///< samples along x and y
  double spacing = 1.0;        ///< distance between neighbouring samples [same unit as width]
};
/// Throws InputError if a side is not positive and finite or max_samples < 2.
RasterSize raster_for_extent(double width, double height, std::size_t max_samples);

/// A surface sampled on raster_for_extent(width, height, max_samples) over
/// [origin, origin + (width, height)], row by row from the south: sample
/// (a, b) at index b nx + a, at offset (min(a h, width), min(b h, height))
/// from the origin (the clamp keeps the last row and column on the
/// rectangle whatever the rounding).
struct SurfaceRaster {
  RasterSize size;
  std::vector<Vec2> offsets;          ///< sample position − origin [m]
  std::vector<SurfacePoint> samples;  ///< the patch at each sample
  std::vector<double> slopes;         ///< gradient magnitude |∇z| at each sample [-]
};

/// Samples `patch`; throws InputError as raster_for_extent() does, or if the
/// rectangle leaves the patch's domain.
SurfaceRaster sample_surface_raster(const BPatch& patch, const Vec2& origin, double width,
                                    double height, std::size_t max_samples);

}  // namespace talus
