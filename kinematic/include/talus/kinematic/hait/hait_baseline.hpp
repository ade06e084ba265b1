#pragma once
/// @file
/// The Haït–Siméon–Taïx planner (hait_planner.hpp) as a BaselinePlanner, and
/// its registry entry "hait". The typed constructor is the C++ API; the entry
/// reads the text options below into a Robot and HaitOptions:
///
/// | key | default | meaning |
/// |---|---|---|
/// | robot | (required) | robot YAML file (load_robot, data/robots/README.md) |
/// | heuristic | potential-rs | euclidean, potential or potential-rs (parse_heuristic) |
/// | smooth | false | Reeds–Shepp smoothing of the found path (§4.4) |
/// | terrain-uncertainty | 0 | δz >= 0 [m] |
/// | position-uncertainty | (none) | "RHO,DTHETA": ρ >= 0 [m], 0 <= Δθ < π [rad] |
/// | budget | 2000000 | HaitOptions::max_nodes, search nodes created (>= 1) |
///
/// Every other HaitOptions field keeps its default. Results: the path's
/// motions are control_name() of each configuration's control; search_seconds
/// is the A* plus the smoothing (stage_seconds "smoothing" the latter);
/// counters nodes_created, nodes_developed, placements, control_changes and
/// control_changes_before_smoothing; flag connected_to_goal (the path ends
/// with a Reeds–Shepp curve to the exact goal). validity() is HaitRobotValidity with the options'
/// uncertainties, the oracle the search uses.
#include <string>
#include <vector>

#include "talus/kinematic/baseline_planner.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {

/// plan_hait() for one robot and one set of options.
class HaitBaseline final : public BaselinePlanner {
 public:
  /// Throws InputError for an invalid robot or options. `robot_file` is only
  /// reported (settings(), section "robot").
  HaitBaseline(Robot robot, HaitOptions options, std::string robot_file = "");

  std::string name() const override { return "hait"; }
  std::vector<BaselineSetting> settings() const override;
  ValidityFunction validity(const RuledTerrain& terrain) const override;

  const Robot& robot() const { return robot_; }
  const HaitOptions& options() const { return options_; }

 protected:
  BaselineResult solve(const RuledTerrain& terrain, const SE2Pose& start,
                       const SE2Pose& goal) const override;

 private:
  Robot robot_;
  HaitOptions options_;
  std::string robot_file_;
};

/// The registry entry "hait" (options in the file comment).
BaselineEntry hait_baseline_entry();

}  // namespace talus
