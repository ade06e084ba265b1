#include "baseline_command.hpp"

#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <system_error>
#include <variant>
#include <vector>

#include "cli_values.hpp"
#include "hait_figures.hpp"
#include "limits_command.hpp"
#include "number_format.hpp"
#include "plot.hpp"
#include "stopwatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/hait/robot.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"

namespace talus::experiments {
namespace {

std::string robot_kind(const Robot& robot) {
  return std::holds_alternative<WheeledRobot>(robot) ? "wheeled" : "articulated_chassis";
}

std::string robot_name(const Robot& robot) {
  return std::visit([](const auto& r) { return r.name; }, robot);
}

nlohmann::json pose_json(const SE2Pose& q) {
  return {{"x", q.x}, {"y", q.y}, {"theta", q.theta}};
}

/// A pose the planner will reject as input (off the map or on NODATA), as
/// the one-line message of the CLI's bad-input contract.
void check_on_map(const char* option, const SE2Pose& q, const RuledTerrain& terrain,
                  const std::string& terrain_file) {
  const ElevationGrid& g = terrain.grid();
  if (!terrain.contains(q.position())) {
    throw InputError(std::string(option) + " (" + format_number(q.x) + ", " + format_number(q.y) +
                     ") is off the terrain " + terrain_file + ", whose domain is [" +
                     format_number(g.x_min()) + ", " + format_number(g.x_max()) + "] x [" +
                     format_number(g.y_min()) + ", " + format_number(g.y_max()) + "]");
  }
  if (!terrain.has_data(q.position())) {
    throw InputError(std::string(option) + " (" + format_number(q.x) + ", " + format_number(q.y) +
                     ") lies on NODATA in " + terrain_file);
  }
}

}  // namespace

SE2Pose parse_pose(const std::string& option, const std::string& text) {
  if (const auto v = parse_numbers(text, 3)) return {(*v)[0], (*v)[1], (*v)[2]};
  throw InputError(option +
                   " must be X,Y,THETA: three finite numbers separated by commas (x, y [m], "
                   "heading [rad] counter-clockwise from east), got '" +
                   text + "'");
}

BaselineOutcome baseline_hait(const BaselineHaitRequest& request) {
  const auto start_time = Clock::now();
  HaitOptions options;
  try {
    options.heuristic = parse_heuristic(request.heuristic);
  } catch (const InputError& e) {
    throw InputError(std::string("--heuristic: ") + e.what());
  }
  options.smooth = request.smooth;
  if (!(std::isfinite(request.terrain_uncertainty) && request.terrain_uncertainty >= 0.0)) {
    throw InputError("--terrain-uncertainty must be a finite number >= 0 [m], got " +
                     format_number(request.terrain_uncertainty));
  }
  options.terrain_uncertainty = request.terrain_uncertainty;
  if (!request.position_uncertainty.empty()) {
    const auto v = parse_numbers(request.position_uncertainty, 2);
    if (!v || (*v)[0] < 0.0 || (*v)[1] < 0.0 || (*v)[1] >= std::numbers::pi) {
      throw InputError(
          "--position-uncertainty must be RHO,DTHETA: rho >= 0 [m] and 0 <= dtheta < pi "
          "[rad], got '" +
          request.position_uncertainty + "'");
    }
    options.position_uncertainty = (*v)[0];
    options.heading_uncertainty = (*v)[1];
  }
  options.validate();
  const SE2Pose start = parse_pose("--start", request.start);
  const SE2Pose goal = parse_pose("--goal", request.goal);
  if (request.output_dir.empty()) throw InputError("no output folder given (--out DIR)");
  std::error_code error;
  if (std::filesystem::exists(request.output_dir, error) &&
      !std::filesystem::is_directory(request.output_dir, error)) {
    throw InputError("--out " + request.output_dir + " exists and is not a folder");
  }

  const Robot robot = load_robot(request.robot);
  const RuledTerrain terrain(read_esri_ascii(request.terrain));
  if (terrain.grid().ncols() < 2 || terrain.grid().nrows() < 2) {
    throw InputError(request.terrain + ": the planner needs at least 2 x 2 nodes");
  }
  check_on_map("--start", start, terrain, request.terrain);
  check_on_map("--goal", goal, terrain, request.terrain);

  const HaitResult result = plan_hait(terrain, robot, start, goal, options);
  const bool found = result.status == HaitStatus::kFound;

  const std::filesystem::path dir(request.output_dir);
  std::filesystem::create_directories(dir, error);
  if (error) {
    throw InputError("--out " + request.output_dir + ": cannot create the folder (" +
                     error.message() + ")");
  }
  const std::string path_file = (dir / "path.csv").string();
  const std::string summary_file = (dir / "summary.json").string();
  const std::filesystem::path png = dir / "path.png";
  write_text_file(path_file, hait_path_csv(result.path));

  const auto plot_start = Clock::now();
  std::filesystem::remove(png, error);  // never leave a stale figure
  const bool plots = found && gnuplot_available();
  if (plots) {
    HaitMapData map;
    map.grid = &terrain.grid();
    if (options.smooth) {
      map.routes.push_back({result.unsmoothed_path, "searched path", "#2c7fb8"});
    }
    map.routes.push_back({result.path,
                          (options.smooth ? "smoothed path, " : "path, ") + sig3(result.length_m) +
                              " m, " + std::to_string(result.control_changes) + " control changes",
                          "#e6550d"});
    map.start = start;
    map.goal = goal;
    map.title = "talus baseline hait (" + heuristic_name(options.heuristic) +
                "): " + std::filesystem::path(request.terrain).filename().string() + ", " +
                robot_name(robot) + ", " + std::to_string(result.nodes_created) +
                " nodes created, " + std::to_string(result.placements) + " placements";
    render_hait_map(dir, "path", map);
  }

  nlohmann::json summary;
  summary["status"] = status_name(result.status);
  summary["message"] = result.message;
  summary["nodes_created"] = result.nodes_created;
  summary["nodes_developed"] = result.nodes_developed;
  summary["placements"] = result.placements;
  summary["preprocessing_seconds"] = result.preprocessing_seconds;
  summary["search_seconds"] = result.search_seconds;
  summary["smoothing_seconds"] = result.smoothing_seconds;
  summary["length_m"] = found ? nlohmann::json(result.length_m) : nlohmann::json(nullptr);
  summary["control_changes"] = found ? nlohmann::json(result.control_changes) : nullptr;
  summary["control_changes_before_smoothing"] =
      found ? nlohmann::json(result.control_changes_unsmoothed) : nullptr;
  summary["connected_to_goal"] = result.connected_to_goal;
  summary["path_points"] = result.path.size();
  summary["robot"] = {
      {"file", request.robot}, {"kind", robot_kind(robot)}, {"name", robot_name(robot)}};
  const ElevationGrid& g = terrain.grid();
  summary["terrain"] = {{"file", request.terrain},
                        {"ncols", g.ncols()},
                        {"nrows", g.nrows()},
                        {"cellsize", g.cellsize()}};
  summary["start"] = pose_json(start);
  summary["goal"] = pose_json(goal);
  summary["options"] = {{"heuristic", heuristic_name(options.heuristic)},
                        {"smooth", options.smooth},
                        {"terrain_uncertainty", options.terrain_uncertainty},
                        {"position_uncertainty", options.position_uncertainty},
                        {"heading_uncertainty", options.heading_uncertainty},
                        {"cell_size", options.cell_size},
                        {"theta_bins", options.theta_bins},
                        {"step", options.step},
                        {"turning_radius", options.turning_radius},
                        {"check_spacing", options.check_spacing},
                        {"margin_weight", options.margin_weight},
                        {"max_nodes", options.max_nodes},
                        {"connect_goal", options.connect_goal},
                        {"smoothing_iterations", options.smoothing.iterations},
                        {"smoothing_seed", options.smoothing.seed}};
  summary["files"] = {{"path", path_file},
                      {"summary", summary_file},
                      {"path_png", plots ? nlohmann::json(png.string()) : nullptr}};
  summary["plot_seconds"] = seconds_since(plot_start);
  summary["seconds"] = seconds_since(start_time);
  write_text_file(summary_file, summary.dump(2) + "\n");
  return {std::move(summary), found};
}

}  // namespace talus::experiments
