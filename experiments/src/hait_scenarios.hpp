#pragma once
/// @file
/// The terrains, robots and queries shared by the Haït–Siméon–Taïx
/// reproductions (hait-heuristics, hait-smoothing, hait-uncertainty,
/// hait-preprocessing, dynamic-vs-kinematic) and by bench_hait. The paper's
/// terrains are not published; ours are generated with a seed at the paper's
/// scale (0.25 m spacing, about 20000 nodes), so every run is reproducible.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "talus/core/elevation_grid.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus::experiments {

/// A planning query on a generated terrain.
struct HaitScenario {
  ElevationGrid grid;
  SE2Pose start, goal;
  std::string description;  ///< one paragraph for the reports (how the terrain was made)
  /// hait_gorge_scenario: the gorge's centre, the ridge's x–half-thickness [m]
  /// and the y where the ridge ends (north); unused elsewhere.
  Vec2 gorge = Vec2::Zero();
  double ridge_half_thickness = 0.0;
  double ridge_end_y = 0.0;
};

/// A rough rover-scale terrain of `ncols` × `nrows` nodes at `spacing` [m]
/// (south-west node at the origin): a fractional Brownian surface (D = 2.2,
/// 1.2 m peak to peak over the whole map, scaled with the map's extent so
/// that the slope statistics do not depend on its size) plus `hills` steep
/// Gaussian hills (1.8 m high, σ = 1.4 m) at seeded positions. The terrain of
/// hait-preprocessing.
ElevationGrid hait_rough_terrain(std::size_t ncols, std::size_t nrows, double spacing,
                                 std::size_t hills, std::uint64_t seed);

/// The hait-heuristics problem (also hait-smoothing, dynamic-vs-kinematic and
/// bench_hait): 141 × 141 nodes at 0.25 m (19881 nodes, 35 m × 35 m; `quick`:
/// 61 × 61), a rough fractal base and a crescent of steep hills that cups the
/// straight line from the start to the goal, the trap that misleads a
/// straight-line heuristic (the paper's Fig. 18 problem is of that kind).
HaitScenario hait_heuristics_scenario(bool quick);

/// The hait-uncertainty problem: a mildly rough plain crossed by a steep
/// ridge with one narrow gorge on the straight line from start to goal and a
/// long way round its end (the paper's Fig. 27). `quick` uses a smaller map.
HaitScenario hait_gorge_scenario(bool quick);

/// The robot of the reproductions: data/robots/marsokhod_chassis.yaml (the
/// paper's results are for the articulated chassis of LAAS's Lama).
Robot load_hait_chassis(const std::filesystem::path& data_dir);
/// data/robots/rover4_sprung.yaml, the sprung rigid body.
Robot load_hait_wheeled(const std::filesystem::path& data_dir);

}  // namespace talus::experiments
