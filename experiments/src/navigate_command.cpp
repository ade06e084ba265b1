#include "navigate_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "cli_values.hpp"
#include "json_values.hpp"
#include "limits_command.hpp"
#include "plan_command.hpp"
#include "talus/core/error.hpp"
#include "talus/core/output_folder.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/report/navigation_figures.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/progress_line.hpp"
#include "terrain_input.hpp"

namespace talus::experiments {
namespace {

/// One row per trace sample, with the command and cap of the last control
/// tick at or before it.
std::string trace_csv(const PotentialFieldNavigationResult& r) {
  std::string csv = kNavigateTraceHeader;
  csv += '\n';
  std::size_t tick = 0;
  const std::size_t ticks = r.commands.size();
  for (const VehicleSample& s : r.simulation.trace) {
    while (tick + 1 < ticks && r.command_times[tick + 1] <= s.t + 1e-12) ++tick;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double kappa = ticks > 0 ? r.commands[tick].curvature : nan;
    const double desired = ticks > 0 ? r.commands[tick].speed : nan;
    const double cap = ticks > 0 ? r.lookahead_caps[tick] : nan;
    for (const double value :
         {s.t, s.state.position.x(), s.state.position.y(), s.state.position.z(), s.state.roll,
          s.state.pitch, s.state.yaw, s.speed, kappa, s.side_slip, desired}) {
      append_csv_number(csv, value);
      csv += ',';
    }
    append_csv_number(csv, cap);
    csv += '\n';
  }
  return csv;
}

std::string waypoints_csv(const ReferenceTrajectory& w) {
  std::string csv = "x,y,v\n";
  for (std::size_t k = 0; k < w.points.size(); ++k) {
    append_csv_number(csv, w.points[k].x());
    csv += ',';
    append_csv_number(csv, w.points[k].y());
    csv += ',';
    append_csv_number(csv, w.speed[k]);
    csv += '\n';
  }
  return csv;
}

}  // namespace

NavigateOutcome navigate(const NavigateRequest& request) {
  const auto start_time = Clock::now();
  if (request.coarse_factor < 1)
    throw InputError("--coarse-factor must be >= 1, got " + std::to_string(request.coarse_factor));
  if (!(request.time_limit > 0.0 && std::isfinite(request.time_limit)))
    throw InputError("--time-limit must be a positive number of seconds, got " +
                     format_number(request.time_limit));
  if (!(request.trace_interval > 0.0 && std::isfinite(request.trace_interval)))
    throw InputError("--trace-interval must be a positive number of seconds, got " +
                     format_number(request.trace_interval));
  const Vec2 start = parse_point("--start", request.start);
  const Vec2 goal = parse_point("--goal", request.goal);
  OutputFolder out(request.output_dir);
  const Vehicle vehicle = load_vehicle(request.vehicle);
  if (!vehicle.body)
    throw InputError(request.vehicle +
                     ": navigation simulates the vehicle and needs its body: add at least "
                     "`mass: KG` (data/vehicles/README.md)");
  if (!std::isfinite(vehicle.max_speed))
    throw InputError(request.vehicle + ": the high-level plan needs a finite max_speed");
  const TerrainRaster terrain = load_terrain(request.terrain, request.reproject, request.band);
  for (const auto& [name, p] : {std::pair{"--start", start}, std::pair{"--goal", goal}}) {
    if (!terrain.grid.contains(p))
      throw InputError(std::string(name) + " " + format_number(p.x()) + "," + format_number(p.y()) +
                       " is off the terrain " + request.terrain);
  }
  LayeredNavigationOptions options;
  options.coarse_factor = static_cast<std::size_t>(request.coarse_factor);
  options.navigation.lookahead.enabled = request.lookahead;
  options.navigation.hazards_from_map = request.detect_hazards;
  options.navigation.time_limit = request.time_limit;
  options.navigation.seed = request.seed;
  options.navigation.simulation.output_interval = request.trace_interval;
  ProgressLine line("talus navigate", request.progress);
  options.planner.progress = [&line](const PlannerProgress& p) {
    line.update("planning on the coarse map (" + std::string(to_string(p.stage)) + ")");
    return true;
  };
  const std::size_t limit = static_cast<std::size_t>(std::ceil(request.time_limit));
  options.navigation.simulation.progress = [&line, limit](double t) {
    line.update("navigating, t = " + format_number(std::round(10.0 * t) / 10.0) + " s of at most " +
                    std::to_string(limit) + " s",
                static_cast<std::size_t>(t), limit);
  };
  NavigateOutcome outcome;
  try {
    outcome.result = navigate_layered(terrain.grid, vehicle, start, goal, options);
  } catch (const InputError& e) {
    throw InputError(request.terrain + ": " + e.what());
  }
  const LayeredNavigationResult& r = outcome.result;

  const std::filesystem::path& dir = out.staging();
  nlohmann::json summary;
  summary["status"] = std::string(to_string(r.status));
  summary["failure"] = r.status == LayeredNavigationStatus::kFailed && r.navigation
                           ? nlohmann::json(std::string(to_string(r.navigation->status)))
                           : nlohmann::json(nullptr);
  summary["message"] = r.message.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.message);
  summary["navigation_time"] =
      r.navigation ? nlohmann::json(r.navigation->navigation_time) : nlohmann::json(nullptr);
  summary["optimal_time"] = finite_or_null(r.optimal_time);
  summary["time_increase"] = finite_or_null(r.time_increase());
  summary["plan_status"] = std::string(to_string(r.plan_status));
  summary["lookahead"] = request.lookahead;
  summary["detect_hazards"] = request.detect_hazards;
  summary["coarse_factor"] = request.coarse_factor;
  summary["waypoints"] = r.waypoints.points.size();
  summary["ticks"] = r.navigation ? r.navigation->commands.size() : 0;
  summary["lookahead_caps_applied"] = r.navigation ? r.navigation->lookahead_caps_applied : 0;
  if (r.navigation) {
    const VehicleSimulationDiagnostics& d = r.navigation->simulation.diagnostics;
    summary["margins"] = {{"peak_lateral_load_ratio", d.peak_lateral_load_ratio},
                          {"min_normal_load_ratio", d.min_normal_load_ratio},
                          {"peak_slip_angle", d.peak_slip_angle},
                          {"peak_side_slip", d.peak_side_slip},
                          {"peak_roll", d.peak_roll},
                          {"peak_speed", d.peak_speed}};
    write_text_file(dir / "trace.csv", trace_csv(*r.navigation));
  } else {
    summary["margins"] = nullptr;
    write_text_file(dir / "trace.csv", std::string(kNavigateTraceHeader) + "\n");
  }
  write_text_file(dir / "waypoints.csv", waypoints_csv(r.waypoints));
  const bool plots = request.figures && r.navigation && gnuplot_available();
  if (plots) {
    const BPatch surface = BPatch::interpolate(terrain.grid);
    NavigationFigureData figure;
    figure.surface = surface;
    figure.waypoints = &r.waypoints;
    figure.result = &*r.navigation;
    figure.start = start;
    figure.goal = goal;
    figure.title = std::string(request.lookahead ? "near-optimal" : "standard") +
                   " navigation: " + std::string(to_string(r.status)) +
                   (r.navigation->message.empty() ? "" : " (" + r.navigation->message + ")");
    render_navigation_figures(dir, "navigation", figure);
  }
  summary["inputs"] = {{"terrain", request.terrain},
                       {"vehicle", request.vehicle},
                       {"start", {start.x(), start.y()}},
                       {"goal", {goal.x(), goal.y()}},
                       {"seed", request.seed},
                       {"time_limit", request.time_limit}};
  summary["files"] = {{"trace", out.final_path("trace.csv").string()},
                      {"waypoints", out.final_path("waypoints.csv").string()},
                      {"summary", out.final_path("summary.json").string()}};
  if (plots) {
    for (const char* name : {"map", "speed", "angles"})
      summary["files"][std::string("figure_") + name] =
          out.final_path(std::string("navigation_") + name + ".png").string();
  }
  summary["seconds"] = {{"plan", r.plan_seconds},
                        {"navigation", r.navigation ? r.navigation->simulation.seconds : 0.0},
                        {"total", seconds_since(start_time)}};
  write_text_file(dir / "summary.json", summary.dump(2) + "\n");
  out.commit();
  outcome.summary = std::move(summary);
  return outcome;
}

}  // namespace talus::experiments
