#include "talus/navigation/hazard_route.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/graph_search.hpp"
#include "talus/core/grid_window.hpp"
#include "talus/navigation/hazard_detection.hpp"

namespace talus {
namespace {

constexpr double kClearanceWeight = 10.0;

}  // namespace

std::pair<std::size_t, std::size_t> nearest_grid_node(const ElevationGrid& grid, const Vec2& p) {
  const auto index = [](double value, double origin, double h, std::size_t n) {
    const double k = std::round((value - origin) / h);
    return static_cast<std::size_t>(std::clamp(k, 0.0, static_cast<double>(n - 1)));
  };
  return {index(p.x(), grid.x_min(), grid.cellsize(), grid.ncols()),
          index(p.y(), grid.y_min(), grid.cellsize(), grid.nrows())};
}

HazardRoute plan_hazard_route(const ElevationGrid& grid, const Vehicle& vehicle, const Vec2& start,
                              const Vec2& goal, std::size_t coarse_factor, double clearance) {
  if (coarse_factor == 0) throw InputError("plan_hazard_route: the coarse factor must be >= 1");
  const ElevationGrid coarse = coarse_factor == 1 ? grid : decimate_grid(grid, coarse_factor);
  return plan_hazard_route(coarse, hazard_node_mask(BPatch::interpolate(coarse), vehicle), start,
                           goal, clearance);
}

HazardRoute plan_hazard_route(const ElevationGrid& coarse, const std::vector<unsigned char>& hazard,
                              const Vec2& start, const Vec2& goal, double clearance) {
  if (!(clearance >= 0.0) || !std::isfinite(clearance))
    throw InputError("plan_hazard_route: the clearance must be >= 0 [m]");
  if (hazard.size() != coarse.ncols() * coarse.nrows())
    throw InputError("plan_hazard_route: the hazard mask has " + std::to_string(hazard.size()) +
                     " flags for " + std::to_string(coarse.ncols() * coarse.nrows()) + " nodes");
  const std::size_t nc = coarse.ncols(), nr = coarse.nrows();
  if (nc * nr >= ShortestPathTree::kNone)
    throw InputError("plan_hazard_route: the grid has too many nodes for the search");
  HazardRoute route;
  route.cellsize = coarse.cellsize();
  route.searched_nodes = nc * nr;
  route.hazard_nodes = static_cast<std::size_t>(std::count(hazard.begin(), hazard.end(), 1));
  const auto [si, sj] = nearest_grid_node(coarse, start);
  const auto [gi, gj] = nearest_grid_node(coarse, goal);
  const auto id = [nc](std::size_t i, std::size_t j) {
    return static_cast<std::uint32_t>(j * nc + i);
  };
  const std::uint32_t source = id(si, sj), target = id(gi, gj);
  const auto passable = [&](long i, long j) {
    if (i < 0 || j < 0 || i >= static_cast<long>(nc) || j >= static_cast<long>(nr)) return false;
    const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
    const std::uint32_t n = id(ui, uj);
    if (n == source || n == target) return true;
    return coarse.valid(ui, uj) && hazard[n] == 0;
  };
  const double h = coarse.cellsize();
  // Distance [m] from each node to the nearest hazard node, where below the
  // clearance (`clearance` elsewhere): each hazard node marks the nodes
  // within the clearance around it.
  std::vector<double> distance(nc * nr, clearance);
  if (clearance > 0.0) {
    const long reach = static_cast<long>(std::ceil(clearance / h));
    for (std::size_t n = 0; n < hazard.size(); ++n) {
      if (!hazard[n]) continue;
      const long i = static_cast<long>(n % nc), j = static_cast<long>(n / nc);
      for (long b = std::max(0L, j - reach); b <= std::min<long>(nr - 1, j + reach); ++b)
        for (long a = std::max(0L, i - reach); a <= std::min<long>(nc - 1, i + reach); ++a) {
          const double d = h * std::hypot(static_cast<double>(a - i), static_cast<double>(b - j));
          double& slot = distance[static_cast<std::size_t>(b) * nc + static_cast<std::size_t>(a)];
          slot = std::min(slot, d);
        }
    }
  }
  // A move into a node closer to a hazard than the clearance costs more, up
  // to (1 + kClearanceWeight) times its length next to one.
  const auto weight = [&](std::uint32_t n) {
    return clearance > 0.0 ? 1.0 + kClearanceWeight * (clearance - distance[n]) / clearance : 1.0;
  };
  const auto edges = [&](std::uint32_t node, auto&& emit) {
    const long i = static_cast<long>(node % nc), j = static_cast<long>(node / nc);
    for (long dj = -1; dj <= 1; ++dj)
      for (long di = -1; di <= 1; ++di) {
        if ((di == 0 && dj == 0) || !passable(i + di, j + dj)) continue;
        if (di != 0 && dj != 0 && (!passable(i + di, j) || !passable(i, j + dj))) continue;
        const std::uint32_t next =
            id(static_cast<std::size_t>(i + di), static_cast<std::size_t>(j + dj));
        emit(next, (di != 0 && dj != 0 ? h * std::numbers::sqrt2 : h) * weight(next));
      }
  };
  const Vec2 target_position = coarse.node_position(gi, gj);
  const auto heuristic = [&](std::uint32_t node) {
    return (coarse.node_position(node % nc, node / nc) - target_position).norm();
  };
  const ShortestPathTree tree = shortest_paths(nc * nr, source, edges, target, heuristic);
  route.expansions = tree.expanded;
  const std::vector<std::uint32_t> nodes = tree.path_to(target);
  if (nodes.empty()) return route;
  route.found = true;
  route.route_nodes = nodes.size();
  route.points.push_back(start);
  for (std::size_t k = 1; k + 1 < nodes.size(); ++k)
    route.points.push_back(coarse.node_position(nodes[k] % nc, nodes[k] / nc));
  route.points.push_back(goal);
  return route;
}

ReferenceTrajectory route_waypoints(const std::vector<Vec2>& points, double spacing, double speed) {
  if (points.size() < 2) throw InputError("route_waypoints: needs at least 2 points");
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw InputError("route_waypoints: the spacing must be > 0 [m]");
  if (!(speed >= 0.0) || !std::isfinite(speed))
    throw InputError("route_waypoints: the speed must be >= 0 [m/s]");
  ReferenceTrajectory out;
  double next = spacing;  // arc length of the next waypoint
  double s = 0.0;         // arc length at points[k - 1]
  for (std::size_t k = 1; k < points.size(); ++k) {
    const Vec2 d = points[k] - points[k - 1];
    const double length = d.norm();
    if (!(length > 0.0)) continue;
    while (next < s + length) {
      const Vec2 p = points[k - 1] + ((next - s) / length) * d;
      if (out.points.empty() || (p - out.points.back()).norm() > 0.0) {
        out.points.push_back(p);
        out.speed.push_back(speed);
      }
      next += spacing;
    }
    s += length;
  }
  const Vec2& last = points.back();
  if (!out.points.empty() && (out.points.back() - last).norm() < 1e-9 * std::max(1.0, spacing)) {
    out.points.back() = last;
  } else {
    out.points.push_back(last);
    out.speed.push_back(speed);
  }
  return out;
}

}  // namespace talus
