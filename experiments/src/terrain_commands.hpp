#pragma once
/// @file
/// The `talus terrain` subcommands' work, separate from argument parsing.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace talus::experiments {

/// `talus terrain info FILE [--reproject none|auto]`: size, node-domain
/// bounds, elevation range, number of NODATA nodes, and the CRS (crs: label,
/// epsg, name, wkt; null fields when unknown), the reader (driver) and
/// whether it was reprojected (source_crs then names the file's own).
nlohmann::json terrain_info(const std::string& path, const std::string& reproject = "none",
                            int band = 0);

/// `talus terrain fit FILE [--smoothing LAMBDA] [--fill nearest] [--reproject R]`.
struct TerrainFitRequest {
  std::string path;
  std::optional<double> smoothing;  ///< lambda of the smoothing fit; none = interpolating fit
  bool fill_nearest = false;        ///< fill NODATA by the nearest valid node before fitting
  std::string reproject = "none";   ///< load_terrain
  int band = 0;                     ///< --band: the DEM's elevation band (0 = its only band)
};
nlohmann::json terrain_fit(const TerrainFitRequest& request);

/// `talus terrain traversability --terrain T --vehicle V [--headings N]
/// [--smoothing LAMBDA] [--reproject R] -o OUT.tif`.
struct TraversabilityRequest {
  std::string terrain;              ///< DEM (load_terrain)
  std::string vehicle;              ///< vehicle YAML/JSON (load_vehicle)
  std::string output;               ///< the GeoTIFF; the preview is OUT with extension .png
  std::string reproject = "none";   ///< load_terrain
  int band = 0;                     ///< --band: the DEM's elevation band (0 = its only band)
  long long headings = 16;          ///< TraversabilityOptions::headings (1 to 360)
  std::optional<double> smoothing;  ///< lambda of the smoothing fit; none = interpolating fit
};

/// Band names of the traversability GeoTIFF: kSpeedLimitBandPrefix + the
/// heading index (3 digits, heading 2π k / N counter-clockwise from east),
/// then the three summary bands.
inline constexpr const char* kSpeedLimitBandPrefix = "speed_limit_heading_";
inline constexpr const char* kSpeedLimitMinBand = "speed_limit_min";
inline constexpr const char* kBindingBand = "binding_constraint";
inline constexpr const char* kUntraversableBand = "untraversable";
/// NODATA of the written rasters (float32; every band declares it).
inline constexpr double kRasterNodata = -9999.0;

/// Loads the terrain and vehicle, fits the B-patch (interpolating; with
/// NODATA nodes the interpolation of fill_voids(nearest) and those nodes
/// NODATA in every band; or the smoothing fit), computes
/// talus::traversability_map and writes OUT (float32 GeoTIFF in the DEM's
/// CRS and grid, one band per heading [m/s] then speed_limit_min [m/s],
/// binding_constraint (codes of talus::binding_code: 0 none, 1 sliding,
/// 2 tipover, 3 contact, 4 max_speed, 5 pitchover, 6 drive, 7 brake) and
/// untraversable (1/0), NODATA kRasterNodata) and the preview PNG (speed_limit_min,
/// red = 0 to green = the largest finite value, untraversable dark red,
/// NODATA transparent; at most 512 pixels a side). Returns the JSON summary.
/// Bad input throws InputError before anything is written; the two files
/// are each written atomically and the PNG is removed if the GeoTIFF fails.
nlohmann::json terrain_traversability(const TraversabilityRequest& request);

}  // namespace talus::experiments
