#include "talus/core/raster_io.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <system_error>

#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/output_file.hpp"

#ifdef TALUS_WITH_GDAL
#include "gdal_raster.hpp"
#endif

namespace talus {
namespace {

bool has_asc_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".asc";
}

#ifndef TALUS_WITH_GDAL
[[noreturn]] void no_gdal(const std::string& what) {
  throw InputError(what +
                   ": this build of Talus has no GDAL (configured with TALUS_WITH_GDAL=OFF); it "
                   "reads ESRI ASCII grids (.asc) only");
}

#endif

}  // namespace

std::string GeoReference::label() const {
  if (epsg) return "EPSG:" + std::to_string(*epsg) + (name.empty() ? "" : " (" + name + ")");
  if (!name.empty()) return name;
  return known() ? "unnamed CRS" : "unknown";
}

bool gdal_available() {
#ifdef TALUS_WITH_GDAL
  return true;
#else
  return false;
#endif
}

std::string_view to_string(Reprojection reprojection) {
  switch (reprojection) {
    case Reprojection::kNone:
      return "none";
    case Reprojection::kAuto:
      return "auto";
  }
  return "unknown";
}

Reprojection parse_reprojection(const std::string& text, const std::string& option) {
  if (text == "none") return Reprojection::kNone;
  if (text == "auto") return Reprojection::kAuto;
  throw InputError(option + " must be none or auto (the UTM zone of the raster's centre), got '" +
                   printable(text) + "'");
}

void TerrainReadOptions::validate() const {
  if (band < 0)
    throw InputError(
        "terrain band must be >= 1 (bands count from 1), or 0 for a raster's only "
        "band, got " +
        std::to_string(band));
  if (!(bytes_per_node_after >= 0.0) || !std::isfinite(bytes_per_node_after))
    throw InputError("TerrainReadOptions.bytes_per_node_after must be finite and >= 0, got " +
                     std::to_string(bytes_per_node_after));
}

std::string TerrainRaster::brief_report() const {
  std::ostringstream out;
  out << grid.ncols() << " x " << grid.nrows() << " nodes, cell " << grid.cellsize() << " m, CRS "
      << crs.label() << ", read by " << driver;
  if (reprojected) out << ", reprojected from " << source_crs.label();
  out << ", " << grid.void_count() << " NODATA nodes";
  return out.str();
}

TerrainRaster read_terrain(const std::string& path, const TerrainReadOptions& options) {
  options.validate();
  require_file_name(path);
  const bool strict = options.format == TerrainFormat::kEsriAscii ||
                      (options.format == TerrainFormat::kAuto && has_asc_extension(path));
  if (strict) {
    TerrainRaster out;
    out.grid = read_esri_ascii(path);
    out.driver = "esri-ascii";
    out.files.push_back(path);
#ifdef TALUS_WITH_GDAL
    const std::filesystem::path prj = std::filesystem::path(path).replace_extension(".prj");
    std::error_code ec;
    if (std::filesystem::is_regular_file(prj, ec)) {
      const auto crs = detail::gdal_read_prj(prj.string());
      if (!crs) {
        throw InputError(printable(prj.string(), 200) +
                         ": not a coordinate reference system GDAL can parse (the .prj beside " +
                         printable(path, 200) + ")");
      }
      out.crs = *crs;
      out.files.push_back(prj.string());
    }
#endif
    out.source_crs = out.crs;
    return out;
  }
#ifdef TALUS_WITH_GDAL
  return detail::gdal_read_terrain(path, options);
#else
  no_gdal(printable(path, 200));
#endif
}

RasterLayers RasterLayers::on_grid_of(const ElevationGrid& grid, const GeoReference& crs) {
  RasterLayers layers;
  layers.ncols = grid.ncols();
  layers.nrows = grid.nrows();
  layers.cellsize = grid.cellsize();
  layers.x_min = grid.x_min();
  layers.y_min = grid.y_min();
  layers.crs = crs;
  return layers;
}

void RasterLayers::validate() const {
  if (ncols < 2 || nrows < 2) {
    throw InputError("raster layers need at least 2 x 2 nodes, got " + std::to_string(ncols) +
                     " x " + std::to_string(nrows));
  }
  if (!(cellsize > 0.0) || !std::isfinite(cellsize) || !std::isfinite(x_min) ||
      !std::isfinite(y_min)) {
    throw InputError("raster layers need a positive finite cell size and a finite origin");
  }
  if (bands.empty()) throw InputError("raster layers have no band");
  if (!std::isfinite(nodata)) throw InputError("raster layers' NODATA value must be finite");
  const float nodata32 = static_cast<float>(nodata);
  for (const RasterBand& band : bands) {
    if (band.name.empty()) throw InputError("a raster band has no name");
    if (band.values.size() != ncols * nrows) {
      throw InputError("raster band '" + band.name + "' has " + std::to_string(band.values.size()) +
                       " values, expected ncols x nrows = " + std::to_string(ncols * nrows));
    }
    for (const double v : band.values) {
      if (!std::isnan(v) && static_cast<float>(v) == nodata32) {
        throw InputError("raster band '" + band.name + "' has a value equal to the NODATA value " +
                         std::to_string(nodata));
      }
    }
  }
}

void write_geotiff(const RasterLayers& layers, const std::string& path) {
  layers.validate();
#ifdef TALUS_WITH_GDAL
  write_file_atomically(path, [&](const std::filesystem::path& file) {
    detail::gdal_write_geotiff(layers, file.string(), path);
  });
#else
  no_gdal(printable(path, 200) + ": cannot write a GeoTIFF");
#endif
}

std::vector<Vec2> to_longitude_latitude(const GeoReference& crs, const std::vector<Vec2>& points) {
  if (!crs.known())
    throw InputError("cannot give longitude and latitude: the coordinates' CRS is unknown");
#ifdef TALUS_WITH_GDAL
  return detail::gdal_to_longitude_latitude(crs, points);
#else
  no_gdal("longitude and latitude");
#endif
}

void write_png(const RgbaImage& image, const std::string& path) {
  if (image.width == 0 || image.height == 0 ||
      image.rgba.size() != 4 * image.width * image.height) {
    throw InputError(printable(path, 200) + ": the image is empty or its pixels do not match " +
                     std::to_string(image.width) + " x " + std::to_string(image.height));
  }
#ifdef TALUS_WITH_GDAL
  write_file_atomically(path, [&](const std::filesystem::path& file) {
    detail::gdal_write_png(image, file.string(), path);
  });
#else
  no_gdal(printable(path, 200) + ": cannot write a PNG");
#endif
}

}  // namespace talus
