#pragma once
/// @file
/// The Dacre-Wright–Siméon free-space structuring (dacre_wright_planner.hpp)
/// as a BaselinePlanner, and its registry entry "dacre-wright". Text options:
///
/// | key | default | meaning |
/// |---|---|---|
/// | robot | (required) | wheeled robot YAML with a symmetric layout (load_dacre_wright_robot) |
/// | max-level | 6 | p_max, 1..8 |
/// | reference-level | auto | p0 in 0..p_max, or auto (voxel side nearest the wheelbase) |
/// | full | false | build the whole octree before the search (§4.2) |
/// | refinements | 1 | extra passes of the box analysis with the narrowed Δr (>= 0) |
/// | check-spacing | 0.1 | [m] most xy step between path poses |
/// | budget | 1000000 | OctreeOptions::budget, voxel analyses (>= 1) |
///
/// Results: counters voxels_analysed, voxels_analysed_level_P (P = 0..p_max),
/// channel_voxels, expansions; flag full_octree. start/goal "uncovered"
/// (admissible but in no FREE voxel) are reported as no_path with that message.
/// validity() is the placement test of Definition 2 (place_robot, |l_i| <
/// L_max, |φ| < max_roll, |ψ| < max_pitch): the paper has no collision test.
#include <string>
#include <vector>

#include "talus/kinematic/baseline_planner.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/kinematic/dacre_wright/dacre_wright_planner.hpp"

namespace talus {

/// plan_dacre_wright() for one robot and one set of options.
class DacreWrightBaseline final : public BaselinePlanner {
 public:
  /// Throws InputError for an invalid or asymmetric robot or invalid options.
  DacreWrightBaseline(WheeledRobot robot, DacreWrightOptions options, std::string robot_file = "");

  std::string name() const override { return "dacre-wright"; }
  std::vector<BaselineSetting> settings() const override;
  ValidityFunction validity(const RuledTerrain& terrain) const override;

  const WheeledRobot& robot() const { return robot_; }
  const DacreWrightOptions& options() const { return options_; }
  /// The full result of the last kind of query (channel, voxels), for the CLI.
  DacreWrightResult plan_full(const RuledTerrain& terrain, const SE2Pose& start,
                              const SE2Pose& goal) const;

 protected:
  BaselineResult solve(const RuledTerrain& terrain, const SE2Pose& start,
                       const SE2Pose& goal) const override;

 private:
  WheeledRobot robot_;
  DacreWrightOptions options_;
  std::string robot_file_;
};

/// The BaselineResult of a plan_dacre_wright() result (what solve() returns):
/// status mapped as in the file comment, path and length when found, times,
/// the counters and the flag full_octree = `full`.
BaselineResult to_baseline_result(const DacreWrightResult& result, bool full);

/// The registry entry "dacre-wright" (options in the file comment).
BaselineEntry dacre_wright_baseline_entry();

}  // namespace talus
