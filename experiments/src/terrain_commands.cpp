#include "terrain_commands.hpp"

#include <chrono>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"

namespace talus::experiments {

nlohmann::json terrain_info(const std::string& path) {
  const ElevationGrid grid = read_esri_ascii(path);
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
  return out;
}

nlohmann::json terrain_fit(const TerrainFitRequest& request) {
  ElevationGrid grid = read_esri_ascii(request.path);
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

}  // namespace talus::experiments
