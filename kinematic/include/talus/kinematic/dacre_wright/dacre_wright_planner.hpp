#pragma once
/// @file
/// The incremental path search of Dacre-Wright and Siméon 1993 §4.3 over the
/// configuration octree (configuration_octree.hpp): the largest FREE voxels
/// V_s, V_g holding the start and the goal, A* over largest FREE voxels whose
/// expansion is ConfigurationOctree::free_neighbours (6 face directions, θ
/// periodic), and a path of configurations through the resulting voxel
/// channel.
///
/// A* costs (the paper names A* without a cost): the distance between voxel
/// centres in the metric √(Δx² + Δy² + (ρ Δθ)²), Δθ the periodic difference
/// and ρ = heading_weight [m/rad]; the heuristic is that distance to V_g's
/// centre (consistent). Ties go to the smaller VoxelKey::code(), so results
/// are deterministic.
///
/// The path: start, then on each face shared by consecutive channel voxels the
/// point of that face nearest the goal (clamping), then the goal; straight
/// segments between them lie in one voxel each (voxels are convex), sampled
/// every check_spacing metres / heading_spacing radians. θ is continuous along
/// the path (not wrapped), so the last θ may differ from the goal's by 2πm.
#include <cstddef>
#include <string>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/dacre_wright/configuration_octree.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {

/// Options of plan_dacre_wright.
struct DacreWrightOptions {
  OctreeOptions octree;           ///< p_max, p0, the analysis budget, the box analysis
  bool full = false;              ///< build the whole octree first (§4.2) instead of incrementally
  double heading_weight = -1.0;   ///< ρ [m/rad] of the A* metric; < 0 = the largest wheel radius
                                  ///< |(u_i, v_i)| (how far a wheel moves per radian)
  double check_spacing = 0.1;     ///< [m] most xy distance between consecutive path poses (> 0)
  double heading_spacing = 0.05;  ///< [rad] most heading change between them (> 0)
  /// Throws InputError naming the field.
  void validate() const;
};

/// How a query ended.
enum class DacreWrightStatus {
  kFound,           ///< a voxel channel and a path
  kNoPath,          ///< the FREE voxels reachable from V_s do not hold the goal
  kStartInvalid,    ///< the start fails the placement test (Definition 2)
  kGoalInvalid,     ///< the goal fails it
  kStartUncovered,  ///< the start is admissible but in no FREE voxel down to p_max
  kGoalUncovered,   ///< the same for the goal
  kBudgetExceeded,  ///< OctreeOptions::budget voxel analyses were spent
};
/// "found", "no_path", "start_invalid", "goal_invalid", "start_uncovered",
/// "goal_uncovered", "budget_exceeded".
const char* to_string(DacreWrightStatus status);

/// One decided voxel of a query, with its box (for output and figures).
struct DecidedVoxel {
  VoxelKey key;
  CsBox box;  ///< θ in [0, 2π]
  VoxelStatus status = VoxelStatus::kUnknown;
  bool from_sons = false;  ///< above p0: combined from its sons, not analysed
};

/// Result of one query.
struct DacreWrightResult {
  DacreWrightStatus status = DacreWrightStatus::kNoPath;
  std::string message = "plan_dacre_wright was not called";
  std::vector<VoxelKey> channel;     ///< V_s … V_g, consecutive ones sharing a face
  std::vector<CsBox> channel_boxes;  ///< their boxes (θ in [0, 2π])
  std::vector<SE2Pose> path;         ///< start … goal, every pose inside a channel voxel
  double length_m = 0.0;             ///< xy length of `path` [m]
  /// Every voxel whose state was decided, in order of decision: analysed
  /// (analyse_box) or, for levels above p0, combined from its sons.
  std::vector<DecidedVoxel> voxels;
  /// channel[k] is voxels[channel_indices[k]] (empty unless found).
  std::vector<std::size_t> channel_indices;
  /// The FREE leaves of what was built (FREE voxels with no FREE ancestor), as
  /// indices into `voxels`, in increasing order.
  std::vector<std::size_t> free_leaf_indices;
  std::vector<std::size_t> analyses_per_level;  ///< analyse_box calls per level
  int reference_level = 0;                      ///< p0 used
  double free_volume_fraction = 0.0;            ///< FREE leaves / root volume of what was built
  std::size_t expansions = 0;                   ///< A* nodes expanded
  double preprocessing_seconds = 0.0;           ///< build_full (0 when incremental) [s]
  double search_seconds = 0.0;                  ///< the incremental search and the path [s]
  bool found() const { return status == DacreWrightStatus::kFound; }
  /// analyse_box calls in all (the sum of analyses_per_level).
  std::size_t voxels_analysed() const;
  /// One line: status, channel and path sizes, analyses, times, message.
  std::string brief_report() const;
};

/// The placement test at one configuration: place_robot and Definition 2.
bool dacre_wright_admissible(const WheeledRobot& robot, const RuledTerrain& terrain,
                             const SE2Pose& q);

/// §4.3 on `terrain` for `robot` (valid and symmetric, else InputError).
/// Throws InputError for invalid options or a non-finite start / goal.
DacreWrightResult plan_dacre_wright(const RuledTerrain& terrain, const WheeledRobot& robot,
                                    const SE2Pose& start, const SE2Pose& goal,
                                    const DacreWrightOptions& options = {});

}  // namespace talus
