#include "talus/bspline/surface_raster.hpp"

#include <algorithm>
#include <cmath>

#include "talus/core/error.hpp"

namespace talus {

RasterSize raster_for_extent(double width, double height, std::size_t max_samples) {
  if (!(width > 0.0) || !std::isfinite(width) || !(height > 0.0) || !std::isfinite(height)) {
    throw InputError("raster_for_extent: width and height must be positive and finite");
  }
  if (max_samples < 2) throw InputError("raster_for_extent: max_samples must be >= 2");
  RasterSize size;
  size.spacing = std::max(width, height) / static_cast<double>(max_samples - 1);
  // The slack absorbs rounding when a side is an exact multiple of the
  // spacing (always the case for the longer side).
  const auto count = [&](double side) {
    const auto n = static_cast<std::size_t>(std::floor(side / size.spacing * (1.0 + 1e-12))) + 1;
    return std::clamp<std::size_t>(n, 2, max_samples);
  };
  size.nx = count(width);
  size.ny = count(height);
  return size;
}

SurfaceRaster sample_surface_raster(const BPatch& patch, const Vec2& origin, double width,
                                    double height, std::size_t max_samples) {
  SurfaceRaster raster;
  raster.size = raster_for_extent(width, height, max_samples);
  const RasterSize& size = raster.size;
  raster.offsets.resize(size.nx * size.ny);
  raster.samples.resize(size.nx * size.ny);
  raster.slopes.resize(size.nx * size.ny);
  for (std::size_t b = 0; b < size.ny; ++b)
    for (std::size_t a = 0; a < size.nx; ++a) {
      const double dx = std::min(static_cast<double>(a) * size.spacing, width);
      const double dy = std::min(static_cast<double>(b) * size.spacing, height);
      const std::size_t k = b * size.nx + a;
      raster.offsets[k] = Vec2(dx, dy);
      raster.samples[k] = patch.evaluate(origin + raster.offsets[k]);
      raster.slopes[k] = raster.samples[k].gradient.norm();
    }
  return raster;
}

}  // namespace talus
