#pragma once
/// @file
/// Terrain rasters in and out: read_terrain() loads a DEM from any file GDAL
/// reads (GeoTIFF, SRTM .hgt, ...) or, for `.asc`, with the strict ESRI ASCII
/// reader (esri_ascii.hpp), and write_geotiff() writes layered float32
/// GeoTIFFs on a grid's nodes.
///
/// GDAL is optional for the library: built without it (CMake option
/// TALUS_WITH_GDAL=OFF), read_terrain() reads `.asc` only and the writers throw
/// InputError saying so. gdal_available() tells which build this is.
///
/// What a GDAL raster must be to load (anything else is an InputError naming
/// the file and the reason, never a silent reinterpretation):
/// - north-up (geotransform rotation terms 0), west to east columns; rows north
///   to south or south to north;
/// - square pixels (|pixel width| = |pixel height| to 1e-9 relative);
/// - a metric CRS (a projected CRS in metres, or no CRS at all, read as a
///   local metric frame). A geographic CRS (degrees) is refused unless
///   options.reproject is kAuto: then it is warped (bilinear, GDALWarp) to
///   the UTM zone of the raster's centre (WGS 84, EPSG:326zz north, 327zz
///   south) on square pixels of GDAL's suggested size; nodes outside the
///   source footprint become NODATA. A projected CRS in other units (feet) is
///   refused;
/// - at least 2 × 2 pixels, values finite and |z| <= kMaxElevationMagnitude
///   except the band's NODATA value; NaN pixels are NODATA too;
/// - one band of real numbers (or the band chosen by options.band); the
///   band's scale and offset are applied (z = raw × scale + offset, the
///   NODATA test on the raw value), and its unit converted to metres (none,
///   "m", "metre", "meter", "metres", "meters"; "ft", "foot", "feet" × 0.3048;
///   "US survey foot", "ftUS" × 1200/3937; any other unit is refused). A
///   scaled band is not warped (--reproject auto): unscale it first.
/// Pixel (column c, row r from the north) is node (c, nrows - 1 - r) at the
/// pixel's centre, as for ESRI grids.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/georeference.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// True if this build of Talus reads and writes rasters through GDAL.
bool gdal_available();

/// Which reader read_terrain() uses.
enum class TerrainFormat {
  kAuto,       ///< `.asc` (any case): the strict ESRI ASCII reader; anything else: GDAL
  kEsriAscii,  ///< the strict ESRI ASCII reader, whatever the extension
  kGdal,       ///< GDAL, whatever the extension (`.asc` then goes through GDAL's AAIGrid)
};

/// What read_terrain() does with a geographic (degrees) raster.
enum class Reprojection {
  kNone,  ///< refuse it (InputError naming the CRS and `--reproject auto`)
  kAuto,  ///< warp it to the UTM zone of its centre
};
/// "none" or "auto".
std::string_view to_string(Reprojection reprojection);
/// Parses "none" or "auto"; InputError naming `option` otherwise.
Reprojection parse_reprojection(const std::string& text, const std::string& option = "--reproject");

struct TerrainReadOptions {
  TerrainFormat format = TerrainFormat::kAuto;
  Reprojection reproject = Reprojection::kNone;
  /// The band holding the elevations (1-based), GDAL rasters only; 0 = the raster's only
  /// band (a raster of several bands is then an InputError: which one holds elevations?).
  int band = 0;
  /// Memory the caller will need per node once the grid is read [bytes] (>= 0, finite; a
  /// B-patch fit: BPatch::kInterpolationBytesPerNode): counted with the read's own in its
  /// memory budget check, so a command that could not hold its work refuses before reading a
  /// pixel (GDAL rasters, whose size is known before their pixels are read).
  double bytes_per_node_after = 0.0;
  /// Throws InputError if band < 0 or bytes_per_node_after is negative or not finite.
  void validate() const;
};

/// A loaded DEM: the grid in its CRS's metres, the CRS, and how it was read.
struct TerrainRaster {
  ElevationGrid grid;
  GeoReference crs;          ///< of grid; unknown for an .asc without .prj
  std::string driver;        ///< "esri-ascii" (Talus's reader) or GDAL's driver name ("GTiff", ...)
  bool reprojected = false;  ///< true if warped from a geographic CRS (options.reproject)
  GeoReference source_crs;   ///< the file's own CRS (equal to crs unless reprojected)
  /// Every file the read reached: the DEM, its .prj, and what GDAL lists for
  /// the dataset (world files, .aux.xml, a VRT's sources). A command protects
  /// them from its outputs (protect_from_outputs, output_file.hpp).
  std::vector<std::string> files;
  /// One line: size, cell size, CRS, driver, reprojection, voids.
  std::string brief_report() const;
};

/// Reads the DEM at `path` (see the file comment). Throws InputError, naming
/// the file, for a missing or unreadable file, a format neither reader takes,
/// a rotated, non-square or geographic raster (without kAuto), a band out of
/// range, or bad values; and, without GDAL, for anything but `.asc`.
///
/// An `.asc` read by the strict reader takes its CRS from a `.prj` beside it
/// (the same name with `.prj`) when GDAL is available and the file exists.
TerrainRaster read_terrain(const std::string& path, const TerrainReadOptions& options = {});

/// One band of a layered raster on a grid's nodes.
struct RasterBand {
  std::string name;  ///< band description (grid_map-style layer name, e.g. "speed_limit_min")
  /// ncols × nrows values, row-major from the south (as ElevationGrid::values());
  /// NaN = NODATA.
  std::vector<double> values;
  std::string unit;  ///< GDAL unit type of the values, e.g. "m/s"; empty = none
  /// Extra band metadata (GDAL metadata items, default domain), e.g. {"heading_deg", "22.5"}.
  std::vector<std::pair<std::string, std::string>> metadata;
};

/// A layered raster: bands on the nodes of a grid with a CRS.
struct RasterLayers {
  std::size_t ncols = 0, nrows = 0;
  double cellsize = 1.0, x_min = 0.0, y_min = 0.0;  ///< node geometry, as ElevationGrid
  GeoReference crs;
  std::vector<RasterBand> bands;
  /// The NODATA value written for NaN values (and declared on every band).
  double nodata = -9999.0;
  /// Empty layers on `grid`'s nodes.
  static RasterLayers on_grid_of(const ElevationGrid& grid, const GeoReference& crs);
  /// Throws InputError for sizes < 2, a bad cell size, no band, a band of the
  /// wrong size or with an empty name, or a valid value equal to nodata.
  void validate() const;
};

/// Writes `layers` as a float32 GeoTIFF (one band per layer, in order, with
/// its name as the band description, NODATA declared, DEFLATE compressed,
/// the CRS's WKT) at `path`, atomically: into a temporary file beside it,
/// renamed over `path` once complete, so a failure leaves no partial file.
/// Throws InputError (validate(), or a write failure naming the file; without
/// GDAL, always).
void write_geotiff(const RasterLayers& layers, const std::string& path);

/// An 8-bit RGBA image, rows from the north (image order), pixel (c, r) at
/// 4 (r width + c).
struct RgbaImage {
  std::size_t width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};
/// Writes `image` as a PNG at `path` (atomically, as write_geotiff). Throws
/// InputError for an empty or mis-sized image or a write failure; without
/// GDAL, always.
void write_png(const RgbaImage& image, const std::string& path);

/// `points` (x, y in `crs`) as WGS 84 (longitude, latitude) [degrees], in
/// that order (RFC 7946's), through GDAL's transformation. Throws InputError
/// when `crs` is unknown, GDAL cannot transform it or a point, or (without
/// GDAL) always.
std::vector<Vec2> to_longitude_latitude(const GeoReference& crs, const std::vector<Vec2>& points);

}  // namespace talus
