#include "plan_rasters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

namespace talus::experiments {
namespace {

/// JSON has no infinity: null.
nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

RasterLayers cost_to_go_layers(const GlobalSearchResult& result, const GeoReference& crs) {
  RasterLayers layers;
  layers.ncols = result.nx;
  layers.nrows = result.ny;
  layers.cellsize = result.spacing;
  layers.x_min = result.origin.x();
  layers.y_min = result.origin.y();
  layers.crs = crs;
  const std::size_t n = result.nx * result.ny;
  const auto field = [n](const std::vector<double>& values) {
    return values.size() == n ? values
                              : std::vector<double>(n, std::numeric_limits<double>::quiet_NaN());
  };
  std::vector<double> from_start = field(result.cost_from_start);
  std::vector<double> unreachable(n);
  for (std::size_t k = 0; k < n; ++k) {
    unreachable[k] = std::isnan(from_start[k])   ? std::numeric_limits<double>::quiet_NaN()
                     : std::isinf(from_start[k]) ? 1.0
                                                 : 0.0;
  }
  layers.bands.push_back({kCostFromStartBand, std::move(from_start), "s", {}});
  layers.bands.push_back({kCostToGoalBand, field(result.cost_to_goal), "s", {}});
  layers.bands.push_back({kUnreachableBand, std::move(unreachable), "", {}});
  return layers;
}

std::string plan_geojson(const PlannerResult& result, const GeoReference& crs) {
  nlohmann::json features = nlohmann::json::array();
  if (const Trajectory* best = result.best()) {
    const VelocityLimits& limits = *best->limits;
    constexpr std::size_t kMaxPoints = 5000;
    const std::size_t stride =
        std::max<std::size_t>(1, (limits.size() + kMaxPoints - 1) / kMaxPoints);
    nlohmann::json coordinates = nlohmann::json::array();
    for (std::size_t k = 0; k < limits.size(); k += stride) {
      const Vec3& p = limits.frame(k).point;
      coordinates.push_back({p.x(), p.y(), p.z()});
    }
    if ((limits.size() - 1) % stride != 0) {
      const Vec3& p = limits.frame(limits.size() - 1).point;
      coordinates.push_back({p.x(), p.y(), p.z()});
    }
    features.push_back(
        {{"type", "Feature"},
         {"properties",
          {{"kind", "trajectory"}, {"travel_time", finite_or_null(best->travel_time())}}},
         {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coordinates)}}}});
  }
  for (std::size_t c = 0; c < result.global.candidates.size(); ++c) {
    const CandidatePath& path = result.global.candidates[c];
    nlohmann::json coordinates = nlohmann::json::array();
    for (const Vec2& v : path.vertices) coordinates.push_back({v.x(), v.y()});
    features.push_back({{"type", "Feature"},
                        {"properties",
                         {{"kind", "candidate"},
                          {"candidate", c},
                          {"cost_seconds", finite_or_null(path.cost_seconds)},
                          {"length_m", finite_or_null(path.length_m)}}},
                        {"geometry", {{"type", "LineString"}, {"coordinates", coordinates}}}});
  }
  nlohmann::json out = {{"type", "FeatureCollection"}, {"features", std::move(features)}};
  if (crs.epsg) {
    out["crs"] = {{"type", "name"},
                  {"properties", {{"name", "urn:ogc:def:crs:EPSG::" + std::to_string(*crs.epsg)}}}};
  }
  return out.dump(1) + "\n";
}

}  // namespace talus::experiments
