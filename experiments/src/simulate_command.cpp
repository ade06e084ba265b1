#include "simulate_command.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "cli_values.hpp"
#include "limits_command.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/output_folder.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/progress_line.hpp"
#include "terrain_input.hpp"

namespace talus::experiments {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

bool parse_double(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE;
}

std::string trace_csv(const TrackingResult& r) {
  std::string csv = kTraceCsvHeader;
  csv += '\n';
  const auto& trace = r.simulation.trace;
  for (std::size_t k = 0; k < trace.size(); ++k) {
    const VehicleSample& s = trace[k];
    const TrackingSample& t = r.tracking[k];
    double min_load = s.wheels[0].normal_load, max_slip = 0.0;
    for (const WheelContact& w : s.wheels) {
      min_load = std::min(min_load, w.normal_load);
      if (w.normal_load > 0.0) max_slip = std::max(max_slip, std::abs(w.slip_angle));
    }
    for (const double value :
         {s.t, s.state.position.x(), s.state.position.y(), s.state.position.z(), s.state.roll,
          s.state.pitch, s.state.yaw, s.speed, t.desired_speed, s.controls.steering,
          s.controls.drive_force, t.s, t.cross_track, s.lateral_load_ratio, s.side_slip,
          min_load}) {
      append_csv_number(csv, value);
      csv += ',';
    }
    append_csv_number(csv, max_slip);
    csv += '\n';
  }
  return csv;
}

}  // namespace

ReferenceTrajectory read_trajectory_csv(const std::string& path) {
  const std::string source = printable(path, 200);
  std::string text = read_input_file(path, kMaxPathFileBytes);
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) throw InputError(source + ": empty file (expected a header)");
  const std::vector<std::string> header = split(line);
  int ix = -1, iy = -1, iv = -1;
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (header[c] == "x") ix = static_cast<int>(c);
    if (header[c] == "y") iy = static_cast<int>(c);
    if (header[c] == "v") iv = static_cast<int>(c);
  }
  if (ix < 0 || iy < 0 || iv < 0)
    throw InputError(source + ":1: the header must name the columns x, y and v (as the " +
                     "trajectory.csv of talus plan), got '" + printable(trim(line), 120) + "'");
  ReferenceTrajectory r;
  std::size_t number = 1;
  bool blank_seen = false;
  while (std::getline(in, line)) {
    ++number;
    if (trim(line).empty()) {
      blank_seen = true;
      continue;
    }
    const std::string where = source + ":" + std::to_string(number) + ": ";
    if (blank_seen) throw InputError(where + "a row after a blank line");
    const std::vector<std::string> cells = split(line);
    if (cells.size() != header.size())
      throw InputError(where + "expected " + std::to_string(header.size()) + " columns, got " +
                       std::to_string(cells.size()));
    double x = 0.0, y = 0.0, v = 0.0;
    for (const auto& [index, value, name] :
         {std::tuple{ix, &x, "x"}, std::tuple{iy, &y, "y"}, std::tuple{iv, &v, "v"}}) {
      const std::string& cell = cells[static_cast<std::size_t>(index)];
      if (!parse_double(cell, *value) || !std::isfinite(*value))
        throw InputError(where + "column " + name + " must be a finite number, got '" +
                         printable(cell) + "'");
    }
    if (v < 0.0) throw InputError(where + "speed v must be >= 0, got " + format_number(v));
    const Vec2 p(x, y);
    if (!r.points.empty() && r.points.back() == p) {
      r.speed.back() = std::max(r.speed.back(), v);  // repeated station: keep one
      continue;
    }
    r.points.push_back(p);
    r.speed.push_back(v);
  }
  if (r.points.size() < 2)
    throw InputError(source + ": a trajectory needs at least 2 distinct points, got " +
                     std::to_string(r.points.size()));
  return r;
}

SimulateOutcome simulate(const SimulateRequest& request) {
  const auto start_time = Clock::now();
  if (!(request.speed_scale > 0.0 && std::isfinite(request.speed_scale)))
    throw InputError("--speed-scale must be a positive number, got " +
                     format_number(request.speed_scale));
  if (!(request.trace_interval > 0.0 && std::isfinite(request.trace_interval)))
    throw InputError("--trace-interval must be a positive number of seconds, got " +
                     format_number(request.trace_interval));
  OutputFolder out(request.output_dir);
  const Vehicle vehicle = load_vehicle(request.vehicle);
  if (!vehicle.body)
    throw InputError(request.vehicle +
                     ": the simulation needs the vehicle's body: add at least `mass: KG` "
                     "(and optionally inertia, suspension and tyre keys, data/vehicles/README.md)");
  const ReferenceTrajectory reference = read_trajectory_csv(request.trajectory);
  const TerrainRaster terrain = load_terrain(request.terrain, request.reproject, request.band);
  const ElevationGrid& grid = terrain.grid;
  for (std::size_t i : {std::size_t{0}, reference.points.size() - 1}) {
    if (!grid.contains(reference.points[i]))
      throw InputError(request.trajectory + ": its " + (i == 0 ? "first" : "last") +
                       " point is off the terrain " + request.terrain);
  }
  const auto fit_start = Clock::now();
  const BPatch surface = [&] {
    try {
      return request.smoothing ? BPatch::fit_smoothing(grid, *request.smoothing)
                               : BPatch::interpolate(grid);
    } catch (const InputError& e) {
      throw InputError(request.terrain + ": " + e.what());
    }
  }();
  const double fit_seconds = seconds_since(fit_start);

  TrackingOptions options;
  options.speed_scale = request.speed_scale;
  options.steering_law = parse_steering_law(request.steering_law);
  options.simulation.output_interval = request.trace_interval;
  ProgressLine line("talus simulate", request.progress);
  options.simulation.progress = [&line](double t) {
    line.update("driving the trajectory, t = " + format_number(std::round(10.0 * t) / 10.0) +
                " s simulated");
  };
  SimulateOutcome outcome;
  outcome.result = track_trajectory(surface, vehicle, reference, options);
  const TrackingResult& r = outcome.result;
  const VehicleSimulationDiagnostics& d = r.simulation.diagnostics;
  outcome.reached = r.status == TrackingStatus::kReachedGoal;

  const std::filesystem::path& dir = out.staging();
  write_text_file(dir / "trace.csv", trace_csv(r));
  nlohmann::json summary;
  summary["status"] = std::string(to_string(r.status));
  summary["failure"] =
      outcome.reached ? nlohmann::json(nullptr) : nlohmann::json(std::string(to_string(r.status)));
  summary["message"] = r.message.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.message);
  summary["progress"] = r.progress;
  summary["path_length"] = r.path_length;
  summary["travel_time"] = r.travel_time;
  summary["planned_time"] = r.planned_time;
  summary["speed_scale"] = request.speed_scale;
  summary["steering_law"] = std::string(to_string(options.steering_law));
  summary["margins"] = {{"peak_lateral_load_ratio", d.peak_lateral_load_ratio},
                        {"min_normal_load", d.min_normal_load},
                        {"min_normal_load_ratio", d.min_normal_load_ratio},
                        {"peak_slip_angle", d.peak_slip_angle},
                        {"peak_side_slip", d.peak_side_slip},
                        {"peak_roll", d.peak_roll},
                        {"peak_speed", d.peak_speed}};
  summary["tracking"] = {{"max_cross_track", r.max_cross_track},
                         {"rms_cross_track", r.rms_cross_track},
                         {"max_speed_excess", r.max_speed_excess}};
  summary["solver"] = {{"method", "CVODE BDF, dense Newton"},
                       {"steps", d.steps},
                       {"rhs_evaluations", d.rhs_evaluations},
                       {"jacobian_evaluations", d.jacobian_evaluations},
                       {"error_test_failures", d.error_test_failures},
                       {"nonlinear_failures", d.nonlinear_failures}};
  summary["real_time_factor"] = r.simulation.real_time_factor();
  summary["inputs"] = {{"terrain", request.terrain},
                       {"vehicle", request.vehicle},
                       {"trajectory", request.trajectory},
                       {"points", reference.points.size()},
                       {"smoothing", request.smoothing ? nlohmann::json(*request.smoothing)
                                                       : nlohmann::json(nullptr)}};
  summary["files"] = {{"trace", out.final_path("trace.csv").string()},
                      {"summary", out.final_path("summary.json").string()}};
  summary["seconds"] = {
      {"fit", fit_seconds}, {"simulation", r.seconds}, {"total", seconds_since(start_time)}};
  write_text_file(dir / "summary.json", summary.dump(2) + "\n");
  out.commit();
  outcome.summary = std::move(summary);
  return outcome;
}

}  // namespace talus::experiments
