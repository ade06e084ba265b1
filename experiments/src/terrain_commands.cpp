#include "terrain_commands.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <system_error>

#include "cli_values.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/raster_io.hpp"
#include "talus/dynamics/traversability_map.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "terrain_input.hpp"

namespace talus::experiments {
namespace {

nlohmann::json crs_json(const GeoReference& crs) {
  if (!crs.known()) return nullptr;
  return {{"label", crs.label()},
          {"epsg", crs.epsg ? nlohmann::json(*crs.epsg) : nlohmann::json(nullptr)},
          {"name", crs.name},
          {"wkt", crs.wkt}};
}

/// Colour of a speed limit v in [0, top] on the preview: red, yellow, green.
std::array<std::uint8_t, 4> speed_colour(double v, double top) {
  const double t = std::isinf(v) ? 1.0 : std::clamp(top > 0.0 ? v / top : 1.0, 0.0, 1.0);
  const double r = t < 0.5 ? 1.0 : 2.0 * (1.0 - t);
  const double g = t < 0.5 ? 2.0 * t : 1.0;
  return {static_cast<std::uint8_t>(std::lround(215.0 * r + 20.0)),
          static_cast<std::uint8_t>(std::lround(190.0 * g + 20.0)), 40, 255};
}

/// The preview of speed_limit_min: at most kMaxPreview pixels a side, nearest node.
RgbaImage preview(const TraversabilityMap& map) {
  constexpr std::size_t kMaxPreview = 512;
  const std::size_t longer = std::max(map.ncols, map.nrows);
  const double step =
      longer > kMaxPreview ? static_cast<double>(longer - 1) / (kMaxPreview - 1) : 1.0;
  RgbaImage image;
  image.width = std::max<std::size_t>(
      2, static_cast<std::size_t>(std::floor(static_cast<double>(map.ncols - 1) / step)) + 1);
  image.height = std::max<std::size_t>(
      2, static_cast<std::size_t>(std::floor(static_cast<double>(map.nrows - 1) / step)) + 1);
  double top = 0.0;
  for (const double v : map.speed_limit_min) {
    if (std::isfinite(v)) top = std::max(top, v);
  }
  image.rgba.assign(4 * image.width * image.height, 0);
  for (std::size_t r = 0; r < image.height; ++r) {
    const std::size_t j =
        map.nrows - 1 -
        std::min(map.nrows - 1,
                 static_cast<std::size_t>(std::lround(static_cast<double>(r) * step)));
    for (std::size_t c = 0; c < image.width; ++c) {
      const std::size_t i = std::min(
          map.ncols - 1, static_cast<std::size_t>(std::lround(static_cast<double>(c) * step)));
      const std::size_t node = j * map.ncols + i;
      std::array<std::uint8_t, 4> colour{0, 0, 0, 0};  // NODATA: transparent
      if (map.untraversable[node] == 1.0) {
        colour = {110, 0, 0, 255};
      } else if (!std::isnan(map.speed_limit_min[node])) {
        colour = speed_colour(map.speed_limit_min[node], top);
      }
      std::copy(colour.begin(), colour.end(), image.rgba.begin() + 4 * (r * image.width + c));
    }
  }
  return image;
}

std::string heading_band_name(std::size_t k) {
  std::string digits = std::to_string(k);
  while (digits.size() < 3) digits.insert(digits.begin(), '0');
  return kSpeedLimitBandPrefix + digits;
}

}  // namespace

nlohmann::json terrain_info(const std::string& path, const std::string& reproject, int band) {
  const TerrainRaster terrain = load_terrain(path, reproject, band, /*fits_surface=*/false);
  const ElevationGrid& grid = terrain.grid;
  const auto range = grid.elevation_range();
  nlohmann::json out;
  out["ncols"] = grid.ncols();
  out["nrows"] = grid.nrows();
  out["cellsize"] = grid.cellsize();
  out["xmin"] = grid.x_min();
  out["xmax"] = grid.x_max();
  out["ymin"] = grid.y_min();
  out["ymax"] = grid.y_max();
  out["zmin"] = range ? nlohmann::json(range->first) : nlohmann::json(nullptr);
  out["zmax"] = range ? nlohmann::json(range->second) : nlohmann::json(nullptr);
  out["voids"] = grid.void_count();
  out["crs"] = crs_json(terrain.crs);
  out["driver"] = terrain.driver;
  out["reprojected"] = terrain.reprojected;
  out["source_crs"] = crs_json(terrain.source_crs);
  return out;
}

nlohmann::json terrain_fit(const TerrainFitRequest& request) {
  ElevationGrid grid = load_terrain(request.path, request.reproject, request.band).grid;
  if (request.fill_nearest) grid = fill_voids(grid, VoidFill::kNearest);
  const auto start = std::chrono::steady_clock::now();
  const BPatch patch = request.smoothing ? BPatch::fit_smoothing(grid, *request.smoothing)
                                         : BPatch::interpolate(grid);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const BPatchFitReport report = patch.residuals(grid);
  nlohmann::json out;
  out["method"] = request.smoothing ? "smoothing" : "interpolating";
  out["smoothing"] = request.smoothing ? nlohmann::json(*request.smoothing) : nlohmann::json(0.0);
  out["max_node_residual"] = report.max_node_residual;
  out["rms_residual"] = report.rms_residual;
  out["fit_seconds"] = seconds;
  out["patches"] = patch.patches();
  out["voids"] = report.voids;
  return out;
}

nlohmann::json terrain_traversability(const TraversabilityRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  if (request.output.empty()) throw InputError("no output file given (-o OUT.tif)");
  std::filesystem::path preview_path(request.output);
  if (preview_path.extension() == ".png") {
    throw InputError("-o " + request.output +
                     ": the GeoTIFF must not be a .png (the preview is written as OUT.png)");
  }
  preview_path.replace_extension(".png");
  check_output_is_not_an_input("-o", request.output,
                               {{"--terrain", request.terrain}, {"--vehicle", request.vehicle}});
  check_output_is_not_an_input("-o (its preview)", preview_path.string(),
                               {{"--terrain", request.terrain}, {"--vehicle", request.vehicle}});
  if (request.headings < 1 || request.headings > 360) {
    throw InputError("--headings must be between 1 and 360, got " +
                     std::to_string(request.headings));
  }
  if (request.smoothing && !(std::isfinite(*request.smoothing) && *request.smoothing > 0.0)) {
    throw InputError("--smoothing must be a positive finite number (lambda), got " +
                     format_number(*request.smoothing));
  }
  const Vehicle vehicle = load_vehicle(request.vehicle);
  const TerrainRaster terrain = load_terrain(request.terrain, request.reproject, request.band);
  const ElevationGrid& grid = terrain.grid;
  const BPatch surface = [&] {
    try {
      if (request.smoothing) return BPatch::fit_smoothing(grid, *request.smoothing);
      return grid.void_count() ? BPatch::interpolate(fill_voids(grid, VoidFill::kNearest))
                               : BPatch::interpolate(grid);
    } catch (const InputError& e) {
      throw InputError(request.terrain + ": " + e.what());
    }
  }();
  TraversabilityOptions options;
  options.headings = static_cast<std::size_t>(request.headings);
  const TraversabilityMap map = traversability_map(surface, grid, vehicle, options);

  RasterLayers layers = RasterLayers::on_grid_of(grid, terrain.crs);
  layers.nodata = kRasterNodata;
  nlohmann::json bands = nlohmann::json::array();
  nlohmann::json headings = nlohmann::json::array();
  for (std::size_t k = 0; k < map.headings.size(); ++k) {
    // 360 k / N, without the rounding of the radians' round trip (202.49999999999997).
    const double degrees = std::round(map.headings[k] * 180.0 / std::numbers::pi * 1e9) / 1e9;
    layers.bands.push_back({heading_band_name(k),
                            map.speed_limit[k],
                            "m/s",
                            {{"heading_rad", format_number(map.headings[k])},
                             {"heading_deg", format_number(degrees)}}});
    headings.push_back(degrees);
  }
  layers.bands.push_back({kSpeedLimitMinBand, map.speed_limit_min, "m/s", {}});
  layers.bands.push_back({kBindingBand,
                          map.binding,
                          "",
                          {{"codes",
                            "0 none, 1 sliding, 2 tipover, 3 contact, 4 max_speed, 5 pitchover, "
                            "6 drive, 7 brake"}}});
  layers.bands.push_back({kUntraversableBand, map.untraversable, "", {}});
  for (const RasterBand& band : layers.bands) bands.push_back(band.name);

  write_png(preview(map), preview_path.string());
  try {
    write_geotiff(layers, request.output);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(preview_path, ignored);
    throw;
  }

  double lowest = std::numeric_limits<double>::infinity();
  for (const double v : map.speed_limit_min) {
    if (!std::isnan(v)) lowest = std::min(lowest, v);
  }
  nlohmann::json out;
  out["status"] = std::string(to_string(map.status));
  out["output"] = request.output;
  out["preview"] = preview_path.string();
  out["bands"] = std::move(bands);
  out["headings_deg"] = std::move(headings);
  out["ncols"] = grid.ncols();
  out["nrows"] = grid.nrows();
  out["cellsize"] = grid.cellsize();
  out["crs"] = crs_json(terrain.crs);
  out["reprojected"] = terrain.reprojected;
  out["nodata"] = kRasterNodata;
  out["nodata_nodes"] = map.nodata_nodes;
  out["untraversable_nodes"] = map.untraversable_nodes;
  out["blocked_nodes"] = map.blocked_nodes;
  out["min_speed_limit"] = std::isfinite(lowest) ? nlohmann::json(lowest) : nullptr;
  out["binding_codes"] = {"none",      "sliding", "tipover", "contact", "max_speed",
                          "pitchover", "drive",   "brake",   "steering"};
  out["fit"] = request.smoothing ? "smoothing" : "interpolating";
  out["map_seconds"] = map.seconds;
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace talus::experiments
