#pragma once
/// @file
/// The `talus baseline NAME` command's work, separate from argument parsing:
/// any registered kinematic baseline (talus::planner_registry(): the kinematic baselines and
/// "talus") on a terrain file, writing the path, a JSON summary and a map.
#include <string>

#include <nlohmann/json.hpp>

#include "talus/kinematic/baseline_options.hpp"
#include "talus/kinematic/configuration_space.hpp"

namespace talus::experiments {

/// `talus baseline NAME --terrain T.asc --start X,Y,THETA --goal X,Y,THETA
/// --out DIR [--KEY VALUE | --FLAG ...]`, the KEYs being the baseline's own
/// options (BaselineEntry::options).
struct BaselineRequest {
  std::string baseline;            ///< registry name, e.g. "hait"
  std::string terrain;             ///< DEM (load_terrain)
  std::string reproject = "none";  ///< --reproject: none | auto (load_terrain)
  int band = 0;                    ///< --band: the DEM's elevation band (0 = its only band)
  std::string start;               ///< "X,Y,THETA": [m], [m], heading [rad]
  std::string goal;                ///< "X,Y,THETA"
  std::string output_dir;          ///< --out: created if needed
  BaselineOptions options;         ///< the baseline's options given on the command line
  std::string vehicle;  ///< --vehicle: drive the path at its profile (baseline_profile.hpp)
};

/// Exit code of `talus baseline NAME` when no path was found: none exists,
/// the start or goal configuration is not valid, or the budget ran out (the
/// summary is still written).
inline constexpr int kBaselineNoPathExitCode = 2;

/// The columns of DIR/path.csv.
inline constexpr const char* kBaselinePathCsvHeader = "x,y,theta,control";

/// What `talus baseline NAME` writes, for its --help.
/// What `talus baseline NAME` writes and how it exits, for NAME's --help: the
/// outputs every planner writes, then NAME's own (dacre-wright's octree
/// files, eldershaw-yim's roadmap and foot plan), then the exit codes.
std::string baseline_output_help(const std::string& name);

/// Parses "X,Y,THETA" (three finite numbers, spaces allowed around them) given
/// to `option`; anything else is an InputError naming the option and the text.
SE2Pose parse_pose(const std::string& option, const std::string& text);

/// What `run_baseline` returns: the summary (also DIR/summary.json) and
/// whether a path was found.
struct BaselineOutcome {
  nlohmann::json summary;  ///< null on an MPI rank other than 0 (it writes nothing)
  bool found = false;
};

/// Checks the request, builds the baseline from the registry with the
/// request's options, reads the terrain, plans, and writes in
/// request.output_dir:
/// - path.csv: kBaselinePathCsvHeader, one row per pose of the path (control
///   = the planner's motion label, "none" when it gives none); header only
///   when no path was found;
/// - summary.json: baseline, status (to_string(BaselineStatus)), message,
///   every counter of the result as a top-level key, preprocessing_seconds,
///   search_seconds, length_m (null unless found), path_points, one object
///   per section of the planner's settings (e.g. robot, options), terrain
///   {file, ncols, nrows, cellsize}, start, goal, files, plot_seconds, seconds;
/// - path.png: the path over the terrain's shaded relief (when a path exists
///   and gnuplot is installed);
/// - for the dacre-wright baseline also voxels.csv, channel.csv
///   (dacre_wright_outputs.hpp), octree.png (when a path exists and gnuplot is
///   installed) and add_dacre_wright_summary()'s keys.
/// - for the eldershaw-yim baseline also prm_points.csv, prm_edges.csv,
///   steps.csv (eldershaw_yim_outputs.hpp), cgmap.png (when gnuplot is
///   installed) and the footmap, CGmap, foot-plan and feedback keys.
/// Bad input (an unknown baseline, bad options, malformed numbers, missing or
/// bad files, a start or goal off the map or on NODATA) throws InputError,
/// naming a bad option as its flag (--KEY), and writes nothing.
BaselineOutcome run_baseline(const BaselineRequest& request);

}  // namespace talus::experiments
