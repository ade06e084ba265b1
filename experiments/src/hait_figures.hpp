#pragma once
/// @file
/// The map figure of the Haït–Siméon–Taïx experiments and of `talus baseline
/// NAME`: one or more planned (x, y) routes over the terrain's shaded relief,
/// with start and goal. A gnuplot script is saved beside the PNG (plot.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/types.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/scenarios/hait_robots.hpp"

namespace talus::experiments {

/// One route on the map: its configurations, a legend label and a gnuplot colour.
struct HaitRoute {
  std::vector<PathPoint> path;
  std::string label;
  std::string colour = "#e6550d";
};

/// What the map shows; positions in the grid's frame [m], drawn as offsets
/// from its south-west node.
struct HaitMapData {
  const ElevationGrid* grid = nullptr;
  std::vector<HaitRoute> routes;
  SE2Pose start, goal;
  std::string title;
};

/// Writes `stem`_relief.rgb, `stem`_routes.dat and `stem`.gp in `dir` and
/// renders `stem`.png (the relief is the interpolating B-patch of the grid;
/// NODATA is filled by the nearest node for the picture only). Headings are
/// drawn as arrows at start and goal.
void render_hait_map(const std::filesystem::path& dir, const std::string& stem,
                     const HaitMapData& data);

/// render_hait_map() of `routes` on the scenario's grid, from its start to its goal.
void render_hait_map(const std::filesystem::path& dir, const std::string& stem,
                     const HaitScenario& scenario, std::vector<HaitRoute> routes,
                     std::string title);

/// The (x, y, θ, control) rows of a baseline's path as CSV with header
/// `x,y,theta,control`: control = motions[k] (BaselineResult::motions), "none"
/// where `motions` has no label.
std::string baseline_path_csv(const std::vector<SE2Pose>& path,
                              const std::vector<std::string>& motions);

}  // namespace talus::experiments
