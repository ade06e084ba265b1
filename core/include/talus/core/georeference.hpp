#pragma once
/// @file
/// GeoReference: the coordinate reference system (CRS) an elevation grid's x
/// and y are in. Talus computes in the grid's own metric frame (x east, y
/// north, metres; see elevation_grid.hpp); the CRS is carried alongside so
/// that raster and vector outputs land where the input DEM was.
#include <optional>
#include <string>

namespace talus {

/// The CRS of a grid, as the file declared it. An ESRI ASCII grid without a
/// `.prj` beside it has none (unknown(): a local metric frame).
struct GeoReference {
  /// OGC WKT of the CRS (as GDAL exports it); empty = unknown.
  std::string wkt;
  /// EPSG code of the CRS when it has one (e.g. 32613 for WGS 84 / UTM zone 13N).
  std::optional<int> epsg;
  /// Human-readable name of the CRS, e.g. "WGS 84 / UTM zone 13N"; empty if unknown.
  std::string name;

  bool known() const { return !wkt.empty(); }
  /// "EPSG:32613 (WGS 84 / UTM zone 13N)", the name alone without a code, or "unknown".
  std::string label() const;
};

}  // namespace talus
