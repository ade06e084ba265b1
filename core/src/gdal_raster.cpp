// The GDAL half of raster_io.hpp (compiled only with TALUS_WITH_GDAL).
#include "gdal_raster.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <gdal_utils.h>
#include <ogr_srs_api.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/memory_budget.hpp"

namespace talus::detail {
namespace {

/// Largest raster read [nodes]: 8 bytes a node twice (read buffer and grid).
constexpr double kMaxRasterNodes = 2.5e8;
/// How many times its own pixel count a raster may grow by --reproject auto: a DEM warped to
/// its UTM zone keeps about its count (1-2x); a strip round a pole squares it.
constexpr double kMaxWarpGrowth = 16.0;

void register_drivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

/// GDAL's errors go quiet while it lives (this thread only); last() is the
/// last message GDAL raised, for InputError texts.
class QuietErrors {
 public:
  QuietErrors() {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietErrors() { CPLPopErrorHandler(); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
  static std::string last() {
    const char* message = CPLGetLastErrorMsg();
    return message && *message ? printable(message, 300) : std::string("no reason given");
  }
};

/// No .aux.xml side files: a temporary file is renamed after writing, and a
/// reader must not leave files beside a user's DEM.
class NoSideFiles {
 public:
  NoSideFiles() { CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO"); }
  ~NoSideFiles() { CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", nullptr); }
  NoSideFiles(const NoSideFiles&) = delete;
  NoSideFiles& operator=(const NoSideFiles&) = delete;
};

struct DatasetCloser {
  void operator()(void* h) const {
    if (h) GDALClose(h);
  }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;

struct SrsDeleter {
  void operator()(void* h) const {
    if (h) OSRDestroySpatialReference(h);
  }
};
using Srs = std::unique_ptr<void, SrsDeleter>;

struct TransformDeleter {
  void operator()(void* h) const {
    if (h) OCTDestroyCoordinateTransformation(h);
  }
};

std::string take_cpl_string(char* s) {
  std::string out = s ? s : "";
  CPLFree(s);
  return out;
}

std::optional<int> epsg_of(OGRSpatialReferenceH srs) {
  const auto code = [](OGRSpatialReferenceH h) -> std::optional<int> {
    const char* authority = OSRGetAuthorityName(h, nullptr);
    const char* code = OSRGetAuthorityCode(h, nullptr);
    if (authority && code && std::string(authority) == "EPSG") return std::atoi(code);
    return std::nullopt;
  };
  if (auto c = code(srs)) return c;
  Srs clone(OSRClone(srs));
  if (clone && OSRAutoIdentifyEPSG(clone.get()) == OGRERR_NONE) return code(clone.get());
  return std::nullopt;
}

GeoReference describe(OGRSpatialReferenceH srs) {
  GeoReference g;
  char* wkt = nullptr;
  if (OSRExportToWkt(srs, &wkt) == OGRERR_NONE) g.wkt = take_cpl_string(wkt);
  if (g.wkt.empty()) {  // some CRSs have WKT2 only
    const char* options[] = {"FORMAT=WKT2_2018", nullptr};
    wkt = nullptr;
    if (OSRExportToWktEx(srs, &wkt, options) == OGRERR_NONE) g.wkt = take_cpl_string(wkt);
  }
  if (const char* name = OSRGetName(srs)) g.name = name;
  g.epsg = epsg_of(srs);
  return g;
}

/// The dataset's CRS, or null for none.
Srs dataset_srs(GDALDatasetH ds) {
  OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
  if (!srs) return Srs(nullptr);
  Srs clone(OSRClone(srs));
  OSRSetAxisMappingStrategy(clone.get(), OAMS_TRADITIONAL_GIS_ORDER);
  return clone;
}

std::string format(double v) {
  std::ostringstream out;
  out.precision(12);
  out << v;
  return out.str();
}

/// The EPSG code of the WGS 84 UTM zone holding the centre of `ds` (whose CRS is `srs`).
int utm_zone_epsg(GDALDatasetH ds, OGRSpatialReferenceH srs, const std::string& source) {
  double gt[6];
  GDALGetGeoTransform(ds, gt);
  const double cx = 0.5 * GDALGetRasterXSize(ds), cy = 0.5 * GDALGetRasterYSize(ds);
  double x = gt[0] + gt[1] * cx + gt[2] * cy;
  double y = gt[3] + gt[4] * cx + gt[5] * cy;
  Srs wgs84(OSRNewSpatialReference(nullptr));
  OSRImportFromEPSG(wgs84.get(), 4326);
  OSRSetAxisMappingStrategy(wgs84.get(), OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<void, TransformDeleter> transform(
      OCTNewCoordinateTransformation(srs, wgs84.get()));
  if (!transform || !OCTTransform(transform.get(), 1, &x, &y, nullptr) || !std::isfinite(x) ||
      !(std::abs(y) <= 90.0)) {
    throw InputError(source +
                     ": --reproject auto cannot place the raster's centre in longitude and "
                     "latitude (" +
                     QuietErrors::last() + ")");
  }
  const double lon = std::remainder(x, 360.0);  // in [-180, 180]
  int zone = static_cast<int>(std::floor((lon + 180.0) / 6.0)) + 1;
  zone = std::min(std::max(zone, 1), 60);
  return (y >= 0.0 ? 32600 : 32700) + zone;
}

/// The size GDALWarp will give `ds` warped to `target` (its suggested output), refused
/// beyond the raster node limit or the memory budget before any pixel is warped: a narrow
/// strip near a pole can warp to a square many times its own size.
void require_warp_fits(GDALDatasetH ds, const std::string& target, const std::string& source,
                       double bytes_per_node_after) {
  Srs srs(OSRNewSpatialReference(nullptr));
  char* wkt = nullptr;
  if (OSRSetFromUserInput(srs.get(), target.c_str()) != OGRERR_NONE ||
      OSRExportToWkt(srs.get(), &wkt) != OGRERR_NONE) {
    CPLFree(wkt);
    throw InputError(source + ": --reproject auto cannot describe " + target);
  }
  void* transformer =
      GDALCreateGenImgProjTransformer(ds, GDALGetProjectionRef(ds), nullptr, wkt, FALSE, 0.0, 1);
  CPLFree(wkt);
  if (transformer == nullptr) {
    throw InputError(source + ": --reproject auto cannot transform the raster to " + target + " (" +
                     QuietErrors::last() + ")");
  }
  double gt[6];
  int nx = 0, ny = 0;
  const CPLErr err =
      GDALSuggestedWarpOutput(ds, GDALGenImgProjTransform, transformer, gt, &nx, &ny);
  GDALDestroyGenImgProjTransformer(transformer);
  if (err != CE_None) {
    throw InputError(source + ": --reproject auto cannot size the warped raster (" +
                     QuietErrors::last() + ")");
  }
  const double nodes = static_cast<double>(nx) * static_cast<double>(ny);
  const double source_nodes =
      static_cast<double>(GDALGetRasterXSize(ds)) * static_cast<double>(GDALGetRasterYSize(ds));
  if (nodes > kMaxWarpGrowth * std::max(source_nodes, 1e4)) {
    throw InputError(source + ": warped to " + target + " the raster would grow from " +
                     format(source_nodes) + " to " + std::to_string(nx) + " x " +
                     std::to_string(ny) + " pixels (a strip along a pole or a meridian?); " +
                     "warp it yourself at the resolution you want (gdalwarp -t_srs -tr)");
  }
  if (nodes > kMaxRasterNodes) {
    throw InputError(source + ": warped to " + target + " the raster would have " +
                     std::to_string(nx) + " x " + std::to_string(ny) +
                     " pixels, more than Talus reads (" + format(kMaxRasterNodes) +
                     "); crop it first (gdal_translate -projwin) or warp it yourself");
  }
  // The warped band (float64), then grid_of's pixels, values and mask, then the caller's work.
  require_memory((25.0 + bytes_per_node_after) * nodes,
                 source + " warped to " + target + " (" + std::to_string(nx) + " x " +
                     std::to_string(ny) + " pixels)",
                 "crop the raster first (gdal_translate -projwin) or warp it yourself (gdalwarp "
                 "-tr)");
}

/// GDALWarp of `ds` to EPSG:`epsg` (bilinear, float64, NODATA NaN), in memory.
Dataset warp_to(GDALDatasetH ds, int epsg, const std::string& source, double bytes_per_node_after) {
  const std::string target = "EPSG:" + std::to_string(epsg);
  require_warp_fits(ds, target, source, bytes_per_node_after);
  const char* argv[] = {"-of", "MEM",     "-t_srs",     target.c_str(), "-r",   "bilinear",
                        "-ot", "Float64", "-dstnodata", "nan",          nullptr};
  GDALWarpAppOptions* options = GDALWarpAppOptionsNew(const_cast<char**>(argv), nullptr);
  int usage_error = 0;
  GDALDatasetH sources[] = {ds};
  Dataset out(GDALWarp("", nullptr, 1, sources, options, &usage_error));
  GDALWarpAppOptionsFree(options);
  if (!out) {
    throw InputError(source + ": --reproject auto could not warp the raster to " + target + " (" +
                     QuietErrors::last() + ")");
  }
  return out;
}

/// The 1-based index of the elevation band: `requested`, or with 0 the raster's only band.
int elevation_band(GDALDatasetH ds, int requested, const std::string& source) {
  const int count = GDALGetRasterCount(ds);
  if (requested == 0 && count != 1) {
    throw InputError(source + ": the raster has " + std::to_string(count) +
                     " bands; Talus reads one band of elevations: extract it first "
                     "(gdal_translate -b N) or choose it (TerrainReadOptions::band)");
  }
  const int index = requested == 0 ? 1 : requested;
  if (index > count) {
    throw InputError(source + ": band " + std::to_string(index) + " requested, the raster has " +
                     std::to_string(count));
  }
  return index;
}

/// raw → metres: the band's scale and offset, then its unit.
struct ElevationScale {
  double scale = 1.0, offset = 0.0, metres_per_unit = 1.0;
  double operator()(double raw) const { return (raw * scale + offset) * metres_per_unit; }
  bool identity() const { return scale == 1.0 && offset == 0.0 && metres_per_unit == 1.0; }
};

/// The band's scale, offset and unit (raster_io.hpp's file comment); InputError for a complex
/// band, a scale or offset that is not finite (or a zero scale), or a unit that is not a length.
ElevationScale elevation_scale(GDALRasterBandH band, const std::string& source) {
  if (GDALDataTypeIsComplex(GDALGetRasterDataType(band))) {
    throw InputError(source + ": the elevation band holds complex numbers (" +
                     GDALGetDataTypeName(GDALGetRasterDataType(band)) +
                     "); Talus needs real elevations");
  }
  ElevationScale out;
  int has_scale = 0, has_offset = 0;
  out.scale = GDALGetRasterScale(band, &has_scale);
  out.offset = GDALGetRasterOffset(band, &has_offset);
  if (!has_scale) out.scale = 1.0;
  if (!has_offset) out.offset = 0.0;
  if (!std::isfinite(out.scale) || out.scale == 0.0 || !std::isfinite(out.offset)) {
    throw InputError(source + ": the elevation band's scale " + format(out.scale) + " and offset " +
                     format(out.offset) +
                     " do not map its values to elevations (a finite, non-zero scale and a "
                     "finite offset)");
  }
  const char* unit_type = GDALGetRasterUnitType(band);
  std::string unit = unit_type ? unit_type : "";
  for (char& c : unit) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" ||
      unit == "meters") {
    out.metres_per_unit = 1.0;
  } else if (unit == "ft" || unit == "foot" || unit == "feet") {
    out.metres_per_unit = 0.3048;
  } else if (unit == "us survey foot" || unit == "ftus" || unit == "us-ft") {
    out.metres_per_unit = 1200.0 / 3937.0;
  } else {
    throw InputError(source + ": the elevation band's unit is '" + printable(unit_type, 40) +
                     "', not a length Talus knows (metres or feet); convert the band to metres "
                     "first");
  }
  return out;
}

/// ElevationGrid from band `band_index` of `ds`, after every geometric check.
ElevationGrid grid_of(GDALDatasetH ds, int band_index, const std::string& source,
                      double bytes_per_node_after) {
  const int nx = GDALGetRasterXSize(ds), ny = GDALGetRasterYSize(ds);
  if (nx < 2 || ny < 2) {
    throw InputError(source + ": the raster has " + std::to_string(nx) + " x " +
                     std::to_string(ny) + " pixels; Talus needs at least 2 x 2");
  }
  if (static_cast<double>(nx) * static_cast<double>(ny) > kMaxRasterNodes) {
    throw InputError(source + ": the raster has " + std::to_string(nx) + " x " +
                     std::to_string(ny) + " pixels, more than Talus reads (" +
                     format(kMaxRasterNodes) + "); crop it first (gdal_translate -srcwin)");
  }
  // The pixels as doubles, the grid's values and its mask, then the caller's work.
  require_memory((17.0 + bytes_per_node_after) * static_cast<double>(nx) * static_cast<double>(ny),
                 source + " (" + std::to_string(nx) + " x " + std::to_string(ny) + " pixels" +
                     (bytes_per_node_after > 0.0 ? ", read and fitted" : "") + ")",
                 "crop or resample the raster first (gdal_translate -srcwin, gdalwarp -tr)");
  double gt[6];
  if (GDALGetGeoTransform(ds, gt) != CE_None) {
    throw InputError(source +
                     ": the raster has no geotransform (pixel size and origin); Talus needs a "
                     "georeferenced north-up raster with square pixels in metres");
  }
  if (gt[2] != 0.0 || gt[4] != 0.0) {
    throw InputError(source + ": the raster is rotated (geotransform rotation terms " +
                     format(gt[2]) + ", " + format(gt[4]) +
                     "); Talus needs a north-up raster: warp it first (gdalwarp)");
  }
  if (!(gt[1] > 0.0) || gt[5] == 0.0 || !std::isfinite(gt[1]) || !std::isfinite(gt[5]) ||
      !std::isfinite(gt[0]) || !std::isfinite(gt[3])) {
    throw InputError(source + ": the raster's pixel size " + format(gt[1]) + " x " + format(gt[5]) +
                     " is not usable (columns must run west to east with a positive, finite "
                     "pixel width)");
  }
  const double h = gt[1];
  if (std::abs(std::abs(gt[5]) - h) > 1e-9 * h) {
    throw InputError(source + ": the raster has non-square pixels (" + format(h) + " x " +
                     format(std::abs(gt[5])) +
                     "); Talus needs square pixels: resample it first (gdalwarp -tr H H)");
  }
  GDALRasterBandH band = GDALGetRasterBand(ds, elevation_band(ds, band_index, source));
  const ElevationScale to_metres = elevation_scale(band, source);
  int has_nodata = 0;
  const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
  const std::size_t w = static_cast<std::size_t>(nx), rows = static_cast<std::size_t>(ny);
  std::vector<double> pixels(w * rows);
  if (GDALRasterIO(band, GF_Read, 0, 0, nx, ny, pixels.data(), nx, ny, GDT_Float64, 0, 0) !=
      CE_None) {
    throw InputError(source + ": cannot read the raster's pixels (" + QuietErrors::last() + ")");
  }
  const bool north_up = gt[5] < 0.0;
  const double x_min = gt[0] + 0.5 * h;
  const double y_min =
      north_up ? gt[3] + static_cast<double>(ny) * gt[5] + 0.5 * h : gt[3] + 0.5 * h;
  ElevationGrid grid(w, rows, h, x_min, y_min);
  for (std::size_t r = 0; r < rows; ++r) {
    const std::size_t j = north_up ? rows - 1 - r : r;
    for (std::size_t i = 0; i < w; ++i) {
      const double raw = pixels[r * w + i];
      if (std::isnan(raw) || (has_nodata && raw == nodata)) {
        grid.set_void(i, j);
        continue;
      }
      const double z = to_metres(raw);
      if (!(std::abs(z) <= kMaxElevationMagnitude)) {
        throw InputError(source + ": pixel (column " + std::to_string(i) + ", row " +
                         std::to_string(r) + " from the north) is " + format(z) +
                         ", beyond the supported elevation magnitude of 1e9 m (a void? declare "
                         "it as the band's NODATA value)");
      }
      grid.at(i, j) = z;
    }
  }
  return grid;
}

/// The GDAL drivers a terrain may be read with: rasters of elevations in
/// files. Everything else (WMS and tile services, databases, the network
/// drivers, formats that describe other datasets) is refused at open.
const char* const kTerrainDrivers[] = {"GTiff", "COG",  "AAIGrid", "SRTMHGT", "VRT",
                                       "HFA",   "EHdr", "ENVI",    "USGSDEM", nullptr};

/// The minimal XML text decoding a VRT file name needs.
std::string xml_text(std::string text) {
  const std::pair<const char*, const char*> entities[] = {
      {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}, {"&amp;", "&"}};
  for (const auto& [entity, plain] : entities) {
    for (std::size_t at = text.find(entity); at != std::string::npos;
         at = text.find(entity, at + 1))
      text.replace(at, std::strlen(entity), plain);
  }
  return text;
}

/// A GDAL VRT reaches other files: before GDAL opens it (which can open its
/// sources, and a FIFO among them blocks), every source it names must be a
/// regular file within the grid size limit, not a GDAL virtual path
/// (/vsigzip/, /vsicurl/...) or a URL, and no band may be a raw band (which
/// reads any file at any offset). Nested VRTs are checked the same way, at
/// most four deep. `path` is a regular file already.
void check_vrt_sources(const std::string& path, int depth = 0) {
  const std::string source = printable(path, 200);
  std::ifstream probe(path, std::ios::binary);
  char head[256] = {};
  probe.read(head, sizeof head - 1);
  if (std::string(head).find("<VRTDataset") == std::string::npos) return;
  if (depth > 4) throw InputError(source + ": VRTs nested more than four deep");
  const std::string text = read_input_file(path, kMaxConfigFileBytes);
  if (text.find("VRTRawRasterBand") != std::string::npos) {
    throw InputError(source +
                     ": a VRT raw raster band (it reads any file at any offset) is not "
                     "accepted; give the raster itself");
  }
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  for (const char* tag : {"SourceFilename", "SourceDataset"}) {
    const std::string open = std::string("<") + tag, close = std::string("</") + tag + ">";
    for (std::size_t at = text.find(open); at != std::string::npos; at = text.find(open, at + 1)) {
      const std::size_t body = text.find('>', at);
      const std::size_t end = body == std::string::npos ? body : text.find(close, body);
      if (end == std::string::npos) throw InputError(source + ": a malformed VRT");
      const std::string attributes = text.substr(at, body - at);
      const std::string name = xml_text(text.substr(body + 1, end - body - 1));
      if (name.rfind("/vsi", 0) == 0 || name.find("://") != std::string::npos) {
        throw InputError(source + ": its source " + printable(name, 200) +
                         " is a GDAL virtual path or a URL; Talus reads terrains from files only");
      }
      const bool relative = attributes.find("relativeToVRT=\"1\"") != std::string::npos;
      const std::string resolved = relative ? (folder / name).string() : name;
      std::error_code ec;
      const auto status = std::filesystem::status(resolved, ec);
      if (!std::filesystem::is_regular_file(status)) {
        throw InputError(source + ": its source " + printable(resolved, 200) +
                         (std::filesystem::exists(status)
                              ? " is not a regular file (a device, FIFO, socket or folder)"
                              : " does not exist"));
      }
      if (std::filesystem::file_size(resolved, ec) > kMaxGridFileBytes) {
        throw InputError(source + ": its source " + printable(resolved, 200) +
                         " is larger than the grid file limit");
      }
      check_vrt_sources(resolved, depth + 1);
    }
  }
}

/// The files beside the DEM `path` that describe it, whether or not GDAL used them (an
/// internal geotransform outranks a world file, which GDAL then does not list): world files
/// (.wld, .<first and last letter of the extension>w such as .tfw, .<extension>w), .prj,
/// .aux.xml, .ovr and .msk. Those that exist as regular files.
std::vector<std::string> sidecar_files(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path dem(path);
  std::string ext = dem.extension().string();  // ".tif"
  std::vector<fs::path> candidates;
  for (const char* replaced : {".wld", ".prj"})
    candidates.push_back(fs::path(dem).replace_extension(replaced));
  if (ext.size() >= 3) {
    candidates.push_back(
        fs::path(dem).replace_extension(std::string(".") + ext[1] + ext.back() + "w"));  // .tfw
    candidates.push_back(fs::path(dem).replace_extension(ext + "w"));                    // .tifw
  }
  for (const char* appended : {".aux.xml", ".ovr", ".msk"})
    candidates.push_back(fs::path(path + appended));
  std::vector<std::string> out;
  for (const fs::path& c : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(c, ec)) out.push_back(c.string());
  }
  return out;
}

}  // namespace

TerrainRaster gdal_read_terrain(const std::string& path, const TerrainReadOptions& options) {
  register_drivers();
  const std::string source = printable(path, 200);
  // As read_input_file: nothing that is not a regular file reaches GDAL (a FIFO
  // would block, /dev/zero never end), and no GDAL virtual path (/vsicurl/...).
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw InputError(source + ": no such file");
  if (std::filesystem::is_directory(status)) throw InputError(source + ": is a folder, not a file");
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(source +
                     ": is not a regular file (a device, FIFO or socket); give a file's path");
  }
  check_vrt_sources(path);
  QuietErrors quiet;
  NoSideFiles no_side_files;
  Dataset ds(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, kTerrainDrivers, nullptr,
                        nullptr));
  if (!ds) {
    throw InputError(source + ": not a raster GDAL can read (" + QuietErrors::last() + ")");
  }
  TerrainRaster out;
  if (char** files = GDALGetFileList(ds.get())) {
    for (char** f = files; *f != nullptr; ++f) out.files.emplace_back(*f);
    CSLDestroy(files);
  }
  if (out.files.empty()) out.files.push_back(path);
  for (std::string& sidecar : sidecar_files(path)) out.files.push_back(std::move(sidecar));
  if (GDALDriverH driver = GDALGetDatasetDriver(ds.get())) {
    out.driver = GDALGetDriverShortName(driver);
  }
  Srs srs = dataset_srs(ds.get());
  if (srs) out.source_crs = describe(srs.get());
  if (srs && !OSRIsProjected(srs.get()) && !OSRIsLocal(srs.get())) {
    const bool geographic = OSRIsGeographic(srs.get()) != 0;
    if (!geographic) {
      throw InputError(source + ": the raster's CRS " + out.source_crs.label() +
                       " is neither projected nor geographic; Talus needs a metric CRS");
    }
    const int epsg = utm_zone_epsg(ds.get(), srs.get(), source);
    if (options.reproject == Reprojection::kNone) {
      throw InputError(source + ": the raster's CRS " + out.source_crs.label() +
                       " is geographic (degrees), not metres; pass --reproject auto to warp it "
                       "to the UTM zone of its centre (EPSG:" +
                       std::to_string(epsg) + "), or reproject it first (gdalwarp -t_srs)");
    }
    const ElevationScale band_scale = elevation_scale(
        GDALGetRasterBand(ds.get(), elevation_band(ds.get(), options.band, source)), source);
    if (!band_scale.identity()) {
      throw InputError(source +
                       ": the band has a scale, an offset or a unit other than metres, which "
                       "--reproject auto does not carry through the warp; unscale it first "
                       "(gdal_translate -unscale -ot Float64) or reproject it yourself");
    }
    ds = warp_to(ds.get(), epsg, source, options.bytes_per_node_after);
    srs = dataset_srs(ds.get());
    out.reprojected = true;
  }
  if (srs) {
    char* unit = nullptr;  // owned by the SRS
    const double to_metres = OSRGetLinearUnits(srs.get(), &unit);
    if (std::abs(to_metres - 1.0) > 1e-12) {
      throw InputError(source + ": the raster's CRS " + describe(srs.get()).label() + " is in " +
                       (unit ? std::string(unit) : std::string("unknown units")) + " (" +
                       format(to_metres) +
                       " m), not metres; reproject it to a metric CRS first (gdalwarp -t_srs)");
    }
    out.crs = describe(srs.get());
  }
  if (!out.reprojected) out.source_crs = out.crs;
  out.grid = grid_of(ds.get(), options.band, source, options.bytes_per_node_after);
  return out;
}

std::optional<GeoReference> gdal_read_prj(const std::string& prj_path) {
  register_drivers();
  QuietErrors quiet;
  std::string text;
  try {
    text = read_input_file(prj_path, kMaxConfigFileBytes);
  } catch (const InputError&) {
    return std::nullopt;
  }
  Srs srs(OSRNewSpatialReference(nullptr));
  if (OSRSetFromUserInput(srs.get(), text.c_str()) != OGRERR_NONE) return std::nullopt;
  return describe(srs.get());
}

void gdal_write_geotiff(const RasterLayers& layers, const std::string& file,
                        const std::string& path) {
  register_drivers();
  QuietErrors quiet;
  NoSideFiles no_side_files;
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  if (!driver) throw InputError(path + ": GDAL has no GTiff driver");
  const int nx = static_cast<int>(layers.ncols), ny = static_cast<int>(layers.nrows);
  const char* create_options[] = {"COMPRESS=DEFLATE", "INTERLEAVE=BAND", nullptr};
  Dataset ds(GDALCreate(driver, file.c_str(), nx, ny, static_cast<int>(layers.bands.size()),
                        GDT_Float32, const_cast<char**>(create_options)));
  if (!ds) throw InputError(path + ": cannot create the GeoTIFF (" + QuietErrors::last() + ")");
  const double h = layers.cellsize;
  double gt[6] = {
      layers.x_min - 0.5 * h, h, 0.0, layers.y_min + (static_cast<double>(ny) - 0.5) * h, 0.0, -h};
  if (GDALSetGeoTransform(ds.get(), gt) != CE_None ||
      (layers.crs.known() && GDALSetProjection(ds.get(), layers.crs.wkt.c_str()) != CE_None)) {
    throw InputError(path + ": cannot georeference the GeoTIFF (" + QuietErrors::last() + ")");
  }
  const std::size_t w = layers.ncols, rows = layers.nrows;
  std::vector<float> pixels(w * rows);
  const float nodata = static_cast<float>(layers.nodata);
  for (std::size_t b = 0; b < layers.bands.size(); ++b) {
    const RasterBand& layer = layers.bands[b];
    GDALRasterBandH band = GDALGetRasterBand(ds.get(), static_cast<int>(b + 1));
    GDALSetDescription(band, layer.name.c_str());
    GDALSetRasterNoDataValue(band, static_cast<double>(nodata));
    if (!layer.unit.empty()) GDALSetRasterUnitType(band, layer.unit.c_str());
    for (const auto& [key, value] : layer.metadata) {
      GDALSetMetadataItem(band, key.c_str(), value.c_str(), nullptr);
    }
    for (std::size_t r = 0; r < rows; ++r) {
      const std::size_t j = rows - 1 - r;
      for (std::size_t i = 0; i < w; ++i) {
        const double v = layer.values[j * w + i];
        pixels[r * w + i] = std::isnan(v) ? nodata : static_cast<float>(v);
      }
    }
    if (GDALRasterIO(band, GF_Write, 0, 0, nx, ny, pixels.data(), nx, ny, GDT_Float32, 0, 0) !=
        CE_None) {
      throw InputError(path + ": cannot write band '" + layer.name + "' (" + QuietErrors::last() +
                       ")");
    }
  }
  CPLErrorReset();
  ds.reset();  // flushes and closes
  if (CPLGetLastErrorType() >= CE_Failure) {
    throw InputError(path + ": writing the GeoTIFF failed (" + QuietErrors::last() + ")");
  }
}

void gdal_write_png(const RgbaImage& image, const std::string& file, const std::string& path) {
  register_drivers();
  QuietErrors quiet;
  NoSideFiles no_side_files;
  GDALDriverH mem = GDALGetDriverByName("MEM");
  GDALDriverH png = GDALGetDriverByName("PNG");
  if (!mem || !png) throw InputError(path + ": GDAL has no MEM or PNG driver");
  const int w = static_cast<int>(image.width), h = static_cast<int>(image.height);
  Dataset ds(GDALCreate(mem, "", w, h, 4, GDT_Byte, nullptr));
  if (!ds) throw InputError(path + ": cannot create the image (" + QuietErrors::last() + ")");
  for (int c = 0; c < 4; ++c) {
    // Pixel stride 4 bytes, line stride 4 w bytes: band c reads every fourth byte.
    if (GDALRasterIO(GDALGetRasterBand(ds.get(), c + 1), GF_Write, 0, 0, w, h,
                     const_cast<std::uint8_t*>(image.rgba.data()) + c, w, h, GDT_Byte, 4,
                     4 * w) != CE_None) {
      throw InputError(path + ": cannot fill the image (" + QuietErrors::last() + ")");
    }
  }
  GDALSetRasterColorInterpretation(GDALGetRasterBand(ds.get(), 4), GCI_AlphaBand);
  Dataset out(GDALCreateCopy(png, file.c_str(), ds.get(), FALSE, nullptr, nullptr, nullptr));
  if (!out) throw InputError(path + ": cannot write the PNG (" + QuietErrors::last() + ")");
  CPLErrorReset();
  out.reset();
  if (CPLGetLastErrorType() >= CE_Failure) {
    throw InputError(path + ": writing the PNG failed (" + QuietErrors::last() + ")");
  }
}

std::vector<Vec2> gdal_to_longitude_latitude(const GeoReference& crs,
                                             const std::vector<Vec2>& points) {
  const QuietErrors quiet;
  Srs from(OSRNewSpatialReference(nullptr));
  if (OSRSetFromUserInput(from.get(), crs.wkt.c_str()) != OGRERR_NONE)
    throw InputError("cannot read the CRS " + crs.label() + " (" + QuietErrors::last() + ")");
  OSRSetAxisMappingStrategy(from.get(), OAMS_TRADITIONAL_GIS_ORDER);
  Srs wgs84(OSRNewSpatialReference(nullptr));
  OSRImportFromEPSG(wgs84.get(), 4326);
  OSRSetAxisMappingStrategy(wgs84.get(), OAMS_TRADITIONAL_GIS_ORDER);  // longitude first
  std::unique_ptr<void, TransformDeleter> transform(
      OCTNewCoordinateTransformation(from.get(), wgs84.get()));
  if (!transform)
    throw InputError("cannot transform " + crs.label() + " to WGS 84 (" + QuietErrors::last() +
                     ")");
  std::vector<double> x(points.size()), y(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    x[k] = points[k].x();
    y[k] = points[k].y();
  }
  std::vector<int> ok(points.size(), 0);
  OCTTransformEx(transform.get(), static_cast<int>(points.size()), x.data(), y.data(), nullptr,
                 ok.data());
  std::vector<Vec2> out(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!ok[k] || !std::isfinite(x[k]) || !(std::abs(y[k]) <= 90.0))
      throw InputError("cannot transform the point (" + format(points[k].x()) + ", " +
                       format(points[k].y()) + ") of " + crs.label() + " to WGS 84");
    out[k] = Vec2(x[k], y[k]);
  }
  return out;
}

}  // namespace talus::detail
