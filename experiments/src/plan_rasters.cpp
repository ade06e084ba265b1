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
  // Each feature's planar points in the DEM's CRS, transformed together once.
  struct Line {
    std::vector<Vec2> points;
    std::vector<double> z;  // empty for a candidate's lattice path
    nlohmann::json properties;
  };
  std::vector<Line> lines;
  if (const Trajectory* best = result.best()) {
    const VelocityLimits& limits = *best->limits;
    constexpr std::size_t kMaxPoints = 5000;
    const std::size_t stride =
        std::max<std::size_t>(1, (limits.size() + kMaxPoints - 1) / kMaxPoints);
    Line line;
    const auto add = [&](std::size_t k) {
      const Vec3& p = limits.frame(k).point;
      line.points.emplace_back(p.x(), p.y());
      line.z.push_back(p.z());
    };
    for (std::size_t k = 0; k < limits.size(); k += stride) add(k);
    if ((limits.size() - 1) % stride != 0) add(limits.size() - 1);
    line.properties = {{"kind", "trajectory"},
                       {"travel_time", finite_or_null(best->travel_time())}};
    lines.push_back(std::move(line));
  }
  for (std::size_t c = 0; c < result.global.candidates.size(); ++c) {
    const CandidatePath& path = result.global.candidates[c];
    lines.push_back({path.vertices,
                     {},
                     {{"kind", "candidate"},
                      {"candidate", c},
                      {"cost_seconds", finite_or_null(path.cost_seconds)},
                      {"length_m", finite_or_null(path.length_m)}}});
  }
  const bool geographic = crs.known() && gdal_available();
  std::vector<Vec2> shown;
  for (const Line& line : lines) shown.insert(shown.end(), line.points.begin(), line.points.end());
  if (geographic) shown = to_longitude_latitude(crs, shown);
  nlohmann::json features = nlohmann::json::array();
  std::size_t at = 0;  // the line's first point in `shown`
  for (Line& line : lines) {
    nlohmann::json coordinates = nlohmann::json::array(), projected = nlohmann::json::array();
    for (std::size_t k = 0; k < line.points.size(); ++k, ++at) {
      nlohmann::json point = {shown[at].x(), shown[at].y()},
                     own = {line.points[k].x(), line.points[k].y()};
      if (!line.z.empty()) {
        point.push_back(line.z[k]);
        own.push_back(line.z[k]);
      }
      coordinates.push_back(std::move(point));
      projected.push_back(std::move(own));
    }
    if (geographic) line.properties["projected_coordinates"] = std::move(projected);
    features.push_back({{"type", "Feature"},
                        {"properties", std::move(line.properties)},
                        {"geometry", {{"type", "LineString"}, {"coordinates", coordinates}}}});
  }
  nlohmann::json out = {{"type", "FeatureCollection"}, {"features", std::move(features)}};
  if (geographic) {
    out["projected_crs"] = crs.label();
  } else {
    out["coordinates_note"] =
        "the DEM's own x, y [m], not RFC 7946 longitude and latitude: its CRS is unknown";
  }
  return out.dump(1) + "\n";
}

}  // namespace talus::experiments
