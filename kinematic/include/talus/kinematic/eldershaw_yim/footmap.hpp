#pragma once
/// @file
/// The footmap of Eldershaw and Yim 2001 §3.1: per terrain node, whether a
/// foot of the robot can keep traction there. A node is valid iff the terrain
/// slope at the footprint scale is at most the robot's max_traction_slope.
///
/// Slope at the footprint scale (the paper names the slope, not how it is
/// measured): the gradient by central differences of the bilinear terrain
/// (RuledTerrain) over one foot print, g = ((z(x+s, y) − z(x−s, y)) / 2s,
/// (z(x, y+s) − z(x, y−s)) / 2s) with s = max(foot_print, spacing) / 2, the
/// sample points clamped into the map (one-sided at the border); slope =
/// atan |g|. A node whose samples touch NODATA, or which is NODATA itself, is
/// invalid. Feet stand on terrain nodes: the foot's height is the node's.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/eldershaw_yim/legged_robot.hpp"

namespace talus {

/// The footmap of one robot on one terrain, computed eagerly (one pass over
/// the nodes; cheap next to CG space).
class Footmap {
 public:
  /// `terrain` must outlive the footmap.
  Footmap(const RuledTerrain& terrain, const LeggedRobot& robot);

  const RuledTerrain& terrain() const { return *terrain_; }
  std::size_t ncols() const { return ncols_; }
  std::size_t nrows() const { return nrows_; }
  /// Foot traction at node (i, j) (column from the west, row from the south).
  bool valid(std::size_t i, std::size_t j) const { return valid_[j * ncols_ + i] != 0; }
  /// Slope at node (i, j) [rad] (NaN where NODATA is involved).
  double slope(std::size_t i, std::size_t j) const { return slope_[j * ncols_ + i]; }
  /// Nodes where a foot has no traction.
  std::size_t invalid_count() const;

 private:
  const RuledTerrain* terrain_;
  std::size_t ncols_ = 0, nrows_ = 0;
  std::vector<std::uint8_t> valid_;
  std::vector<double> slope_;
};

}  // namespace talus
