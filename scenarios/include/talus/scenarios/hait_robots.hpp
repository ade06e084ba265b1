#pragma once
/// @file
/// The robots shared by the Haït–Siméon–Taïx reproductions (hait-heuristics,
/// hait-smoothing, hait-uncertainty, hait-preprocessing, dynamic-vs-kinematic)
/// and by bench_hait, read from the bundled data folder. The terrains and
/// queries are the library's (talus/kinematic/hait/hait_scenarios.hpp).
#include <filesystem>

#include "talus/kinematic/hait/hait_scenarios.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus::scenarios {

/// The robot of the reproductions: data/robots/marsokhod_chassis.yaml (the
/// paper's results are for the articulated chassis of LAAS's Lama).
Robot load_hait_chassis(const std::filesystem::path& data_dir);
/// data/robots/rover4_sprung.yaml, the sprung rigid body.
Robot load_hait_wheeled(const std::filesystem::path& data_dir);

}  // namespace talus::scenarios
