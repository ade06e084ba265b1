#pragma once
/// @file
/// Strict reader and writer for ESRI ASCII grids (`.asc`).
///
/// Accepted header keys (case-insensitive, any order, any whitespace): ncols,
/// nrows, cellsize, one of xllcorner/xllcenter, one of yllcorner/yllcenter,
/// and optionally NODATA_value. Then nrows × ncols numbers, rows north to
/// south. Every deviation — missing or repeated key, wrong count, non-numeric
/// token, NaN or Inf, non-positive cell size — throws InputError naming the
/// file and line.
#include <iosfwd>
#include <string>

#include "talus/core/elevation_grid.hpp"

namespace talus {

/// Reads an ESRI ASCII grid from `path`.
ElevationGrid read_esri_ascii(const std::string& path);
/// Reads from a stream; `source_name` is used in error messages.
ElevationGrid read_esri_ascii(std::istream& in, const std::string& source_name);

/// Writes `grid` with an `xllcorner` header; NODATA nodes get `nodata_value`.
/// Values are written with enough digits to round-trip exactly.
void write_esri_ascii(const ElevationGrid& grid, const std::string& path,
                      double nodata_value = -9999.0);
void write_esri_ascii(const ElevationGrid& grid, std::ostream& out, double nodata_value = -9999.0);

}  // namespace talus
