#pragma once
// Private to talus_core: the GDAL half of raster_io.hpp, compiled only when
// TALUS_WITH_GDAL is on (gdal_raster.cpp). raster_io.cpp dispatches to it.
#include <optional>
#include <string>

#include "talus/core/raster_io.hpp"

namespace talus::detail {

/// read_terrain() through GDAL (options already validated).
TerrainRaster gdal_read_terrain(const std::string& path, const TerrainReadOptions& options);
/// The CRS in an ESRI `.prj` file; nullopt if GDAL cannot parse it.
std::optional<GeoReference> gdal_read_prj(const std::string& prj_path);
/// write_geotiff() and write_png() into `file` (not atomic: the caller
/// renames it); messages name `path`, where it will be.
void gdal_write_geotiff(const RasterLayers& layers, const std::string& file,
                        const std::string& path);
void gdal_write_png(const RgbaImage& image, const std::string& file, const std::string& path);
/// to_longitude_latitude() through GDAL (crs known).
std::vector<Vec2> gdal_to_longitude_latitude(const GeoReference& crs,
                                             const std::vector<Vec2>& points);

}  // namespace talus::detail
