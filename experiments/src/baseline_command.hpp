#pragma once
/// @file
/// The `talus baseline hait` command's work, separate from argument parsing:
/// the Haït–Siméon–Taïx kinematic planner (talus::plan_hait) on a terrain file
/// for a robot file, writing the path, a JSON summary and a map.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "talus/kinematic/configuration_space.hpp"

namespace talus::experiments {

/// `talus baseline hait --terrain T.asc --robot R.yaml --start X,Y,THETA
/// --goal X,Y,THETA [--heuristic euclidean|potential|potential-rs] [--smooth]
/// [--terrain-uncertainty DZ] [--position-uncertainty RHO,DTHETA] --out DIR`.
struct BaselineHaitRequest {
  std::string terrain;                     ///< ESRI ASCII grid
  std::string robot;                       ///< robot YAML (load_robot, data/robots/README.md)
  std::string start;                       ///< "X,Y,THETA": [m], [m], heading [rad]
  std::string goal;                        ///< "X,Y,THETA"
  std::string heuristic = "potential-rs";  ///< parse_heuristic()
  bool smooth = false;                     ///< Reeds–Shepp smoothing of the found path (§4.4)
  double terrain_uncertainty = 0.0;        ///< δz [m] (>= 0)
  std::string position_uncertainty;        ///< "RHO,DTHETA" [m], [rad]; empty = none
  std::string output_dir;                  ///< --out: created if needed
};

/// Exit code of `talus baseline hait` when no path exists or the start or
/// goal configuration is not valid for the robot (the summary is still written).
inline constexpr int kBaselineNoPathExitCode = 2;

/// The columns of DIR/path.csv.
inline constexpr const char* kBaselinePathCsvHeader = "x,y,theta,control";

/// Parses "X,Y,THETA" (three finite numbers, spaces allowed around them) given
/// to `option`; anything else is an InputError naming the option and the text.
SE2Pose parse_pose(const std::string& option, const std::string& text);

/// What `baseline_hait` returns: the summary (also DIR/summary.json) and
/// whether a path was found.
struct BaselineOutcome {
  nlohmann::json summary;
  bool found = false;
};

/// Checks the options, reads the terrain and the robot, runs plan_hait with
/// the default HaitOptions except for the request's heuristic, smoothing and
/// uncertainties, and writes in request.output_dir:
/// - path.csv: kBaselinePathCsvHeader, the dense configurations of the path
///   (start first; control = the one reaching the row, "none" on the first
///   row); header only when no path was found;
/// - summary.json: status (found | no_path | start_invalid | goal_invalid |
///   node_limit), message, nodes_created, nodes_developed, placements,
///   preprocessing_seconds, search_seconds, smoothing_seconds, length_m,
///   control_changes, control_changes_before_smoothing, connected_to_goal,
///   path_points, robot {kind, name}, terrain {file, ncols, nrows, cellsize},
///   start, goal, options {...}, files, seconds;
/// - path.png: the path over the terrain's shaded relief (when a path exists
///   and gnuplot is installed).
/// Bad input (options, malformed numbers, missing or bad files, a start or
/// goal off the map or on NODATA) throws InputError and writes nothing.
BaselineOutcome baseline_hait(const BaselineHaitRequest& request);

}  // namespace talus::experiments
