#pragma once
/// @file
/// The one place the `talus` commands load a terrain (--terrain, terrain
/// FILE): talus::read_terrain (core/raster_io.hpp) with the --reproject
/// choice, so every command accepts the same files.
#include <string>

#include "talus/core/raster_io.hpp"

namespace talus::experiments {

/// Help text of every --terrain option.
inline constexpr const char* kTerrainHelp =
    "DEM: an ESRI ASCII grid (.asc, Talus's strict reader) or any raster GDAL reads (GeoTIFF, "
    "SRTM .hgt, ...): north-up, square pixels, elevations in metres, a metric CRS (see "
    "--reproject)";
/// Help text of every --reproject option.
inline constexpr const char* kReprojectHelp =
    "what to do with a geographic (degrees) DEM: none = refuse it; auto = warp it (bilinear) to "
    "the WGS 84 UTM zone of its centre on square pixels";

/// Help text of every --band option.
inline constexpr const char* kBandHelp =
    "the DEM's band of elevations (1-based) when it has several; by default a DEM must have "
    "one band";

/// read_terrain(path) with Reprojection parse_reprojection(reproject) and `band` (0: the
/// DEM's only band). `fits_surface`: the command fits a B-patch to the grid, whose memory
/// the read budgets first (TerrainReadOptions::bytes_per_node_after), so a DEM too large
/// to fit is refused before its pixels are read.
TerrainRaster load_terrain(const std::string& path, const std::string& reproject = "none",
                           int band = 0, bool fits_surface = true);

}  // namespace talus::experiments
