#include "baseline_profile.hpp"

#include <chrono>
#include <cmath>

#include "talus/bspline/bpatch.hpp"
#include "talus/optimal/driven_path_time.hpp"
#include "talus/optimal/polyline_travel_time.hpp"

namespace talus::experiments {

void add_baseline_profile(nlohmann::json& summary, const ElevationGrid& grid,
                          const std::vector<SE2Pose>& path, bool found, const Vehicle& vehicle,
                          const std::string& vehicle_file) {
  summary["vehicle"] = vehicle_file;
  summary["profile_status"] = "no_path";
  summary["profile_travel_time"] = nullptr;
  summary["profile_length_m"] = nullptr;
  summary["profile_pieces"] = 0;
  summary["profile_seconds"] = 0.0;
  if (!found || path.size() < 2) return;
  const BPatch surface = BPatch::interpolate(grid);
  const DrivenPathResult driven = driven_path_time(surface, vehicle, path);
  if (driven.status != DrivenPathStatus::kNotTangent) {
    summary["profile_method"] = "own_arcs";
    summary["profile_status"] = to_string(driven.status);
    if (driven.status == DrivenPathStatus::kOk) {
      summary["profile_travel_time"] = driven.travel_time;
    }
    summary["profile_length_m"] = driven.length;
    summary["profile_pieces"] = driven.pieces.size();
    summary["profile_seconds"] = driven.seconds;
    return;
  }
  // No driving direction (the path moves sideways): a clamped cubic fitted to its positions.
  const auto started = std::chrono::steady_clock::now();
  std::vector<Vec2> points;
  for (const SE2Pose& q : path) points.push_back(q.position());
  const double time = polyline_travel_time(surface, vehicle, points);
  summary["profile_method"] = "fitted_cubic";
  summary["profile_status"] = std::isfinite(time) ? "ok" : "infeasible";
  if (std::isfinite(time)) summary["profile_travel_time"] = time;
  summary["profile_pieces"] = 1;
  summary["profile_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

}  // namespace talus::experiments
