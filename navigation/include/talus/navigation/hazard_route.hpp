#pragma once
/// @file
/// The high-level layer of the Iagnemma–Shimoda–Shiller baseline
/// (iagnemma_baseline.hpp): a shortest route over the grid nodes that are not
/// hazards, and the waypoints along it that the potential-field navigator
/// (potential_field_navigation.hpp) drives through.
///
/// The paper's high-level layer is the time-optimal planner of Section II on
/// coarse map data; in Talus that planner is in optimal/, which the kinematic
/// layer cannot use (core ← bspline ← dynamics ← optimal / kinematic). This
/// route is the documented stand-in (`talus navigate`,
/// navigation/layered_navigation.hpp, is the paper's layered scheme with Talus's
/// own planner):
/// - the map: the terrain's grid, decimated by `coarse_factor` (every k-th
///   node, decimate_grid: the coarse data of the paper) and interpolated as a
///   B-patch;
/// - a node is passable when it is on the data and not a hazard by the
///   navigator's own test (hazard_node_mask: slope above atan(min(μ, b/h)) or
///   3 × 3 relief above the wheel radius, on the coarse surface); the nodes
///   nearest the start and the goal are passable whatever they are (the
///   baseline checks the start and the goal on the fine map first);
/// - A* (core's shortest_paths) with 8-connected moves costing their planar
///   length times 1 + 10 (c − d) / c for a move into a node at distance
///   d < c from the nearest hazard node (c = `clearance`; 1 with c = 0), so
///   the route keeps the clearance where it can and comes closer only where
///   it must; a diagonal move only where both nodes beside it are passable
///   (no corner cutting between two hazards); the Euclidean distance to the
///   goal node as the heuristic (admissible: no move costs less than its
///   length);
/// - the route: the start, the route's nodes after the start's node and
///   before the goal's, the goal; waypoints every `spacing` metres of its
///   planar length and its last point (the goal), all at one speed.
#include <cstddef>
#include <utility>
#include <vector>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/trajectory_tracking.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus {

/// A hazard-free route over the (coarse) grid.
struct HazardRoute {
  bool found = false;
  /// Planar points from the start to the goal (both included); empty unless found.
  std::vector<Vec2> points;
  std::size_t route_nodes = 0;     ///< grid nodes of the route (start and goal nodes included)
  std::size_t expansions = 0;      ///< A* nodes expanded
  std::size_t hazard_nodes = 0;    ///< hazards among the searched grid's nodes
  std::size_t searched_nodes = 0;  ///< nodes of the searched (coarse) grid
  double cellsize = 0.0;           ///< of the searched grid [m]
};

/// The node (column, row) of `grid` nearest `p`, clamped to the grid.
std::pair<std::size_t, std::size_t> nearest_grid_node(const ElevationGrid& grid, const Vec2& p);

/// The route of the file comment from `start` to `goal` (both inside
/// `grid`'s domain) for `vehicle`, keeping `clearance` [m] (>= 0) from
/// hazards where it can. `coarse_factor` >= 1 (1 = the grid itself).
/// InputError for a factor of 0 or one that leaves fewer than 2 × 2 nodes,
/// or a negative clearance.
HazardRoute plan_hazard_route(const ElevationGrid& grid, const Vehicle& vehicle, const Vec2& start,
                              const Vec2& goal, std::size_t coarse_factor, double clearance);

/// The same search on `grid` itself, given its hazard_node_mask() (row-major,
/// one flag per node), for a caller that has the mask already. InputError
/// for a mask of another size or a negative clearance.
HazardRoute plan_hazard_route(const ElevationGrid& grid, const std::vector<unsigned char>& hazard,
                              const Vec2& start, const Vec2& goal, double clearance);

/// Waypoints every `spacing` (> 0) metres of planar length along `points`
/// (at least 2), then its last point, each at `speed` (>= 0) [m/s].
/// Consecutive points that coincide are skipped. InputError for bad input.
ReferenceTrajectory route_waypoints(const std::vector<Vec2>& points, double spacing, double speed);

}  // namespace talus
