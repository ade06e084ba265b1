#pragma once
/// @file
/// The search guidance of Haït, Siméon and Taïx 2002, §4.2.2 and §5.3.1: a
/// cost bitmap rating how hard it is for the robot to cross the terrain around
/// each grid node, and the potential bitmap obtained from it by wave
/// propagation from the goal, an estimate of the cost-to-goal everywhere.
///
/// The paper names the ingredients but not the formulas; the choices made here:
/// - Local terrain (§4.2.2 "slope and roughness of a circular domain centred at
///   this point with a radius related to the size of the robot"): the
///   least-squares plane z = c + g·(p − p_0) through the valid nodes within
///   distance R of the node (R = max(robot_radius, grid spacing), so that the
///   disc always holds a plane's worth of nodes; discs are cut at the map's
///   border). slope = atan |g|; roughness = peak-to-peak orthogonal distance of
///   the disc's nodes to that plane (the slab thickness of the collision
///   quadtree, i.e. the largest bump a chassis over the disc must clear).
/// - cost = 1 + w_s·slope/slope_max + w_r·roughness/roughness_max, and an
///   obstacle (cost +∞) where slope > slope_max, roughness > roughness_max, or
///   the disc holds a NODATA node. Cost ≥ 1 is dimensionless, so the potential
///   is a length [m] inflated by difficulty and never below the lattice
///   distance to the goal.
/// - Terrain uncertainty (§5.3.1, "elevation variation Δz is now considered to
///   compute the local slope and roughness"): roughness grows by 2·max δz over
///   the disc, the worst-case spread of terrains between T_min and T_max.
/// - Position uncertainty (§5.3.1): the cost bitmap is grown by ρ, every node
///   taking the largest cost within distance ρ (so obstacles dilate by ρ).
/// - Wave propagation (§4.2.2, "in priority for the pixels whose cost +
///   potential is the lowest"): Dijkstra from the goal node over the node
///   lattice with 8 or 16 neighbours; a move of length L costs L times the mean
///   cost of the nodes it touches (both ends, plus for a knight move (2, 1) the
///   two nodes beside its midpoint), and every one of them must be passable.
///   On flat ground (cost 1) the 16-neighbour potential is the exact lattice
///   distance, within a factor 1/cos(atan(1/2)/2) ≈ 1.0275 of the Euclidean
///   distance (8 neighbours: 1/cos(π/8) ≈ 1.0824).
#include <cstddef>
#include <vector>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// Options of PotentialBitmap (see the file comment for the formulas).
struct PotentialBitmapOptions {
  double robot_radius = 0.5;          ///< radius R of the evaluation disc [m] (> 0)
  double max_slope = 0.5;             ///< slope_max [rad] in (0, π/2): steeper is an obstacle
  double max_roughness = 0.2;         ///< roughness_max [m] (> 0): rougher is an obstacle
  double slope_weight = 1.0;          ///< w_s (>= 0)
  double roughness_weight = 1.0;      ///< w_r (>= 0)
  double position_uncertainty = 0.0;  ///< ρ [m] (>= 0): grow the cost bitmap by ρ (§5.3.1)
  int connectivity = 16;              ///< 8 or 16 neighbours in the wave propagation
  /// Throws InputError naming the offending field.
  void validate() const;
};

/// Work counters and facts of one bitmap.
struct PotentialBitmapStats {
  std::size_t obstacles = 0;      ///< nodes of infinite cost (after growing)
  std::size_t reached = 0;        ///< nodes with a finite potential
  std::size_t expanded = 0;       ///< nodes taken off the propagation queue
  bool goal_on_obstacle = false;  ///< the goal node was an obstacle (see PotentialBitmap)
  /// Lattice nodes in the evaluation disc of radius max(robot_radius, spacing): the cost
  /// bitmap fits a plane to this many nodes around every node, ≈ π (R / h)².
  std::size_t disc_nodes = 0;
};

/// Cost and potential bitmaps over the nodes of a ruled terrain for one goal.
class PotentialBitmap {
 public:
  /// Builds both bitmaps for `goal` [m]. `dz`, if given, is the per-node
  /// terrain uncertainty δz [m] (same shape as the terrain's grid, >= 0,
  /// NODATA = 0). The goal snaps to its nearest node; if that node is an
  /// obstacle it is still the source of the wave, at the largest finite cost
  /// 1 + w_s + w_r, so that a rough goal does not leave the whole map
  /// unreachable (stats().goal_on_obstacle says so). Throws InputError if the
  /// goal is off the map, on bad options or a bad `dz`.
  PotentialBitmap(const RuledTerrain& terrain, const Vec2& goal,
                  const PotentialBitmapOptions& options = {}, const ElevationGrid* dz = nullptr);

  /// Estimated cost-to-goal at p [m of difficulty-weighted length]: bilinear in
  /// the four surrounding nodes' potentials when all are finite, else the
  /// nearest node's value (+∞ where unreachable). Throws InputError off the map.
  double potential(const Vec2& p) const;
  /// True if potential(p) is finite.
  bool reachable(const Vec2& p) const;

  /// Node values, row-major as ElevationGrid (row j from the south after row j−1).
  const std::vector<double>& costs() const { return cost_; }
  const std::vector<double>& potentials() const { return potential_; }
  /// Local slope [rad] and roughness [m] per node (before growing by ρ).
  const std::vector<double>& slopes() const { return slope_; }
  const std::vector<double>& roughness() const { return roughness_; }
  double cost_at(std::size_t i, std::size_t j) const { return cost_[j * ncols_ + i]; }
  double potential_at(std::size_t i, std::size_t j) const { return potential_[j * ncols_ + i]; }

  std::size_t ncols() const { return ncols_; }
  std::size_t nrows() const { return nrows_; }
  /// The goal node's position [m].
  const Vec2& goal_node() const { return goal_node_; }
  const PotentialBitmapOptions& options() const { return options_; }
  const PotentialBitmapStats& stats() const { return stats_; }

 private:
  PotentialBitmapOptions options_;
  PotentialBitmapStats stats_;
  std::size_t ncols_ = 0, nrows_ = 0;
  double spacing_ = 1.0;
  Vec2 origin_ = Vec2::Zero();
  Vec2 goal_node_ = Vec2::Zero();
  std::vector<double> slope_, roughness_, cost_, potential_;
};

}  // namespace talus
