#include "talus/report/relief_raster.hpp"

#include <algorithm>
#include <fstream>
#include <ostream>
#include <tuple>

#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"

namespace talus {
namespace {

/// Writes `header`, then "x y VALUES" per sample (`values` writes VALUES of
/// sample k), a blank line after each raster row.
template <typename Values>
void write_raster_file(const ReliefRaster& raster, const std::string& header,
                       const std::filesystem::path& file, const Values& values) {
  std::ofstream out = open_output_file(file);
  out << header;
  for (std::size_t b = 0; b < raster.size.ny; ++b) {
    for (std::size_t a = 0; a < raster.size.nx; ++a) {
      const std::size_t k = b * raster.size.nx + a;
      out << fmt("%.7g", raster.offsets[k].x()) << ' ' << fmt("%.7g", raster.offsets[k].y()) << ' ';
      values(out, k);
      out << '\n';
    }
    out << '\n';
  }
  close_output_file(out, file);
}

/// Element floor(0.95 n) of the slopes in ascending order.
double slope_p95(const ReliefRaster& raster) {
  std::vector<double> slopes = raster.slopes;
  const auto p95 = slopes.begin() + static_cast<long>(0.95 * static_cast<double>(slopes.size()));
  std::nth_element(slopes.begin(), p95, slopes.end());
  return *p95;
}

Rgb relief_colour(const SurfacePoint& sample, const ReliefColouring& colouring) {
  const double relief = colouring.zmax - colouring.zmin;
  const double t = relief > 0.0 ? (sample.z - colouring.zmin) / relief : 0.5;
  const Rgb colour =
      shade_colour(hypsometric_colour(t), hillshade(sample, colouring.sun, colouring.exaggeration),
                   colouring.ambient);
  if (!colouring.washed) return colour;
  return {0.55 * colour.r + 0.45, 0.55 * colour.g + 0.45, 0.55 * colour.b + 0.45};
}

void write_relief_rgb(const ReliefRaster& raster, const ReliefColouring& colouring,
                      const std::string& header, const std::filesystem::path& file) {
  write_raster_file(raster, header, file, [&](std::ostream& out, std::size_t k) {
    const Rgb colour = relief_colour(raster.samples[k], colouring);
    out << to_byte(colour.r) << ' ' << to_byte(colour.g) << ' ' << to_byte(colour.b);
  });
}

}  // namespace

void write_elevation_raster(const ReliefRaster& raster, const std::string& header,
                            const std::filesystem::path& file) {
  write_raster_file(raster, header, file, [&](std::ostream& out, std::size_t k) {
    out << fmt("%.7g", raster.samples[k].z);
  });
}

ReliefImage write_relief_image(const BPatch& surface, const MapFrame& frame,
                               const std::string& what, const std::filesystem::path& file,
                               std::size_t max_samples,
                               std::optional<std::pair<double, double>> z_range, bool washed,
                               const SunPosition& sun) {
  ReliefImage image{
      sample_surface_raster(surface, frame.origin(), frame.width(), frame.height(), max_samples),
      {}};
  ReliefColouring& colouring = image.colouring;
  if (z_range) {
    std::tie(colouring.zmin, colouring.zmax) = *z_range;
  } else {
    const auto [low, high] =
        std::minmax_element(image.raster.samples.begin(), image.raster.samples.end(),
                            [](const SurfacePoint& a, const SurfacePoint& b) { return a.z < b.z; });
    colouring.zmin = low->z;
    colouring.zmax = high->z;
  }
  colouring.sun = sun;
  colouring.exaggeration = hillshade_exaggeration(slope_p95(image.raster));
  colouring.washed = washed;
  const std::string header =
      "# " + what + ": hypsometric colour x hillshade (azimuth " + fmt("%g", sun.azimuth_deg) +
      " deg, altitude " + fmt("%g", sun.altitude_deg) + " deg, exaggeration " +
      fmt("%g", colouring.exaggeration) + ")" + (washed ? ", washed 45 % towards white" : "") +
      "\n# x - x_min [m], y - y_min [m], red, green, blue [0-255]\n";
  write_relief_rgb(image.raster, colouring, header, file);
  return image;
}

}  // namespace talus
