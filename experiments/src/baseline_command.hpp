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
inline constexpr const char* kBaselineOutputHelp =
    "Angles in radians, counter-clockwise from east. Writes, in --out DIR (created if needed): "
    "path.csv (columns x,y,theta,control: every configuration of the path from start to goal, "
    "control = the motion reaching it as the planner names it, e.g. forward, forward-left, "
    "reverse-right, or none on the first row), summary.json (status found | no_path | "
    "start_invalid | goal_invalid | budget_exceeded, message, the planner's counters, "
    "preprocessing_seconds, search_seconds, length_m, the planner's settings such as robot and "
    "options, ...; also printed) and path.png (the path over shaded relief). dacre-wright also "
    "writes "
    "voxels.csv (columns level,x_min,x_max,y_min,y_max,theta_min,theta_max,status: every voxel "
    "whose state was decided, analysed or combined from its sons above p0, status FREE or "
    "MIXED), channel.csv (columns step,voxel: the channel from the start's voxel to the goal's, "
    "voxel = 0-based data row of voxels.csv), octree.png (FREE voxels at four headings of the "
    "path, the channel and the path) and the summary keys voxels_analysed_per_level, "
    "free_volume_fraction, voxels_decided, free_leaves, reference_level. eldershaw-yim also "
    "writes prm_points.csv (point,ix,iy,itheta,x,y,theta), prm_edges.csv "
    "(new_point,old_point), steps.csv (the foot plan: step,move,cg_x,cg_y,cg_theta then "
    "foot_x_i,foot_y_i,foot_z_i,contact_i per leg i), cgmap.png (the footmap and the CGmap of "
    "the start's heading slice, the route and its footprints) and the summary keys "
    "footmap_invalid_nodes, cgmap_cells, foot_plan_status, feedback_cells. Exit code 0 when a "
    "path is found; 2 when none exists, the start or goal configuration is invalid or the "
    "budget ran out (summary still written); 1 on bad input: malformed numbers or options, "
    "missing or bad files, a start or goal off the map or on NODATA (one line on stderr, "
    "nothing written)";

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
