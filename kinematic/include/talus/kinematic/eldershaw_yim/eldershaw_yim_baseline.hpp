#pragma once
/// @file
/// The Eldershaw–Yim CG path planner (eldershaw_yim_planner.hpp) as a
/// BaselinePlanner, and its registry entry "eldershaw-yim". Its path is the
/// CG path. Text options:
///
/// | key | default | meaning |
/// |---|---|---|
/// | robot | (required) | legged robot YAML (load_legged_robot, data/robots/README.md) |
/// | theta-slices | 16 | n_θ: 1 or 8..1024 |
/// | direct | false | one A* over the whole CGspace instead of the tree-PRM (§4.2) |
/// | prm-points | 200 | random PRM points (>= 0) |
/// | connect-radius | 0 | [m] PRM neighbours tried; 0 = 40 foot prints |
/// | connect-attempts | 3 | members of one tree tried per new point (>= 1) |
/// | local-margin | 4 | least extra cells around the local planner's box (>= 0) |
/// | seed | 1 | of the PRM's random points |
/// | foot-budget | 20000 | foot-planner search nodes along a found path; 0 = no foot plan |
/// | feedback-rounds | 3 | §3.3 replans after a failed foot plan (0..1000) |
/// | workers | 1 | threads of the local-planner calls (1..256); same plan for any count |
/// | budget | 50000000 | CG cells evaluated + A* expansions (>= 1) |
///
/// Results: counters cg_cells_materialised, cg_blocks_materialised, cg_cells,
/// prm_points, prm_edges, prm_trees, local_planner_calls,
/// local_planner_successes, recreate_calls, expansions, samples_drawn,
/// foot_planner_nodes, foot_plan_steps, feedback_events; stage seconds footmap, materialise,
/// sample, connect, recreate, foot_planner; flags direct, foot_plan_found.
/// The status is the CG path's: a foot plan that fails does not change it.
/// validity() is the CG-cell rule of cg_space.hpp for the cell holding the
/// pose (evaluated without caching, so the returned function is thread-safe).
#include <string>
#include <vector>

#include "talus/kinematic/baseline_planner.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/kinematic/eldershaw_yim/eldershaw_yim_planner.hpp"

namespace talus {

/// plan_eldershaw_yim() for one robot and one set of options.
class EldershawYimBaseline final : public BaselinePlanner {
 public:
  /// Throws InputError for an invalid robot or invalid options.
  EldershawYimBaseline(LeggedRobot robot, EldershawYimPlannerOptions options,
                       std::string robot_file = "");

  std::string name() const override { return "eldershaw-yim"; }
  std::vector<BaselineSetting> settings() const override;
  ValidityFunction validity(const RuledTerrain& terrain) const override;

  const LeggedRobot& robot() const { return robot_; }
  const EldershawYimPlannerOptions& options() const { return options_; }
  /// The full result (cells, PRM points and edges), for the CLI; `ranks`
  /// share the local-planner calls (EldershawYimPlannerOptions::ranks).
  EldershawYimResult plan_full(const RuledTerrain& terrain, const SE2Pose& start,
                               const SE2Pose& goal, const CgRankGroup* ranks = nullptr) const;

 protected:
  BaselineResult solve(const RuledTerrain& terrain, const SE2Pose& start,
                       const SE2Pose& goal) const override;

 private:
  LeggedRobot robot_;
  EldershawYimPlannerOptions options_;
  std::string robot_file_;
};

/// The BaselineResult of a plan_eldershaw_yim() result (what solve() returns).
BaselineResult to_baseline_result(const EldershawYimResult& result, bool direct);

/// The registry entry "eldershaw-yim" (options in the file comment).
BaselineEntry eldershaw_yim_baseline_entry();

}  // namespace talus
