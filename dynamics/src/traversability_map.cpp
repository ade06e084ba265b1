#include "talus/dynamics/traversability_map.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/admissible_set.hpp"

namespace talus {

void TraversabilityOptions::validate() const {
  if (headings < 1 || headings > 360) {
    throw InputError("headings must be between 1 and 360, got " + std::to_string(headings));
  }
}

std::string_view to_string(TraversabilityStatus status) {
  switch (status) {
    case TraversabilityStatus::kOk:
      return "ok";
    case TraversabilityStatus::kNoData:
      return "no_data";
  }
  return "unknown";
}

std::string TraversabilityMap::brief_report() const {
  std::ostringstream out;
  out << to_string(status) << ": " << ncols << " x " << nrows << " nodes, " << headings.size()
      << " headings, " << untraversable_nodes << " untraversable, " << blocked_nodes
      << " blocked in some heading, " << nodata_nodes << " NODATA, " << seconds << " s";
  if (!message.empty()) out << " (" << message << ")";
  return out.str();
}

TraversabilityMap traversability_map(const BPatch& surface, const ElevationGrid& grid,
                                     const Vehicle& vehicle, const TraversabilityOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.validate();
  vehicle.validate();
  const AdmissibleSet set(vehicle);
  const std::size_t n = grid.ncols() * grid.nrows();
  const std::size_t m = options.headings;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();

  TraversabilityMap map;
  map.ncols = grid.ncols();
  map.nrows = grid.nrows();
  std::vector<Vec2> directions(m);
  for (std::size_t k = 0; k < m; ++k) {
    const double theta = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(m);
    map.headings.push_back(theta);
    directions[k] = Vec2(std::cos(theta), std::sin(theta));
  }
  map.speed_limit.assign(m, std::vector<double>(n, kNaN));
  map.speed_limit_min.assign(n, kNaN);
  map.binding.assign(n, kNaN);
  map.untraversable.assign(n, kNaN);

  for (std::size_t j = 0; j < grid.nrows(); ++j) {
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const std::size_t node = j * grid.ncols() + i;
      if (!grid.valid(i, j)) {
        ++map.nodata_nodes;
        continue;
      }
      const Vec2 p = grid.node_position(i, j);
      const SurfacePoint point = surface.evaluate(p);  // throws off the domain
      double lowest = kInf;
      Constraint binding = Constraint::kNone;
      bool any_traversable = false;
      for (std::size_t k = 0; k < m; ++k) {
        const PathFrame frame = lift_to_surface(p, point, directions[k], Vec2::Zero());
        const SpeedLimits limits = set.speed_limits(station_geometry(frame, surface, set.wheels()));
        map.speed_limit[k][node] = limits.v_max;
        any_traversable = any_traversable || limits.traversable;
        if (limits.v_max < lowest || k == 0) {
          lowest = limits.v_max;
          binding = limits.upper_binding;
        }
      }
      map.speed_limit_min[node] = lowest;
      map.binding[node] = binding_code(binding);
      map.untraversable[node] = any_traversable ? 0.0 : 1.0;
      if (!any_traversable) ++map.untraversable_nodes;
      if (lowest == 0.0) ++map.blocked_nodes;
    }
  }
  if (map.nodata_nodes == n) {
    map.status = TraversabilityStatus::kNoData;
    map.message = "every node of the grid is NODATA";
  }
  map.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return map;
}

}  // namespace talus
