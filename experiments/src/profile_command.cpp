#include "profile_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "cli_values.hpp"
#include "limits_command.hpp"
#include "talus/core/error.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"
#include "talus/optimal/time_optimal_profile.hpp"
#include "talus/optimal/trajectory.hpp"
#include "talus/report/plot.hpp"

namespace talus::experiments {
namespace {

void check_speed_option(const char* option, double speed) {
  if (!(std::isfinite(speed) && speed >= 0.0)) {
    std::ostringstream msg;
    msg << option << " must be a finite speed >= 0 [m/s], got " << speed;
    throw InputError(msg.str());
  }
}

nlohmann::json or_null(bool present, double value) {
  return present ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

std::size_t default_profile_station_count(double length) {
  if (!(length >= 0.0)) return kMinDefaultProfileStations;
  if (!(length / kDefaultStationSpacing < static_cast<double>(kMaxDefaultProfileStations))) {
    return kMaxDefaultProfileStations;
  }
  return std::clamp(station_count(length), kMinDefaultProfileStations, kMaxDefaultProfileStations);
}

std::string default_profile_stations_text() {
  std::ostringstream text;
  text << "ceil(length_m / " << kDefaultStationSpacing
       << ") + 1 with length_m the path's 3-D length on the terrain (a station every "
       << kDefaultStationSpacing << " m on average), clamped to [" << kMinDefaultProfileStations
       << ", " << kMaxDefaultProfileStations << "]";
  return text.str();
}

ProfileOutcome profile(const ProfileRequest& request) {
  const auto start = Clock::now();
  check_path_options(request.stations, request.smoothing, request.output);
  check_output_is_not_an_input(
      "-o", request.output,
      {{"--terrain", request.terrain}, {"--path", request.path}, {"--vehicle", request.vehicle}});
  check_speed_option("--v0", request.start_speed);
  check_speed_option("--v1", request.end_speed);

  const Vehicle vehicle = load_vehicle(request.vehicle);
  const TerrainPath terrain_path = build_terrain_path(
      request.terrain, request.path, request.smoothing, request.reproject, request.band);
  const SurfacePath& path = *terrain_path.path;
  const std::size_t stations = request.stations ? static_cast<std::size_t>(*request.stations)
                                                : default_profile_station_count(path.length());

  const auto limits_start = Clock::now();
  const VelocityLimits limits(vehicle, path, stations);
  const double limits_seconds = seconds_since(limits_start);

  ProfileOptions options;
  options.start_speed = request.start_speed;
  options.end_speed = request.end_speed;
  TimeOptimalProfileSolver solver;
  const auto solve_start = Clock::now();
  const TimeOptimalProfile result = solver.solve(limits, options);
  const double solve_seconds = seconds_since(solve_start);
  const bool feasible = result.status == ProfileStatus::kOk;

  // The CSV. Without a profile, v and a are 0 and t is inf (never arrives).
  std::string csv = kProfileCsvHeader;
  csv += '\n';
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  double peak_speed = 0.0;
  for (std::size_t k = 0; k < limits.size(); ++k) {
    const PathFrame& f = limits.frame(k);
    const SpeedLimits& l = limits.limits(k);
    const double v = feasible ? result.v[k] : 0.0;
    const double a = feasible ? result.a[k] : 0.0;
    const double t = feasible ? result.t[k] : kInfinity;
    const double v_max = l.traversable ? l.v_max : 0.0;
    peak_speed = std::max(peak_speed, v);
    for (const double value : {f.s, f.point.x(), f.point.y(), f.point.z(), v, a, t, v_max}) {
      append_csv_number(csv, value);
      csv += ',';
    }
    csv += to_string(l.upper_binding);
    csv += '\n';
  }
  write_text_file(request.output, csv);

  nlohmann::json switching = nlohmann::json::array();
  for (const SwitchingPoint& p : result.switching_points) {
    switching.push_back({{"station", p.station},
                         {"s", p.s},
                         {"from", std::string(to_string(p.from))},
                         {"to", std::string(to_string(p.to))}});
  }

  nlohmann::json summary;
  summary["status"] = feasible ? "ok" : "infeasible";
  summary["travel_time"] = or_null(feasible, result.travel_time);
  summary["stations"] = limits.size();
  summary["length_m"] = path.length();
  summary["start_speed"] = request.start_speed;
  summary["end_speed"] = request.end_speed;
  summary["peak_speed"] = or_null(feasible, peak_speed);
  summary["switching_points"] = std::move(switching);
  summary["merged_stations"] = result.merged_stations;
  // Stations far apart make the conservative discretisation infeasible where
  // the continuous profile is not: say so rather than let "infeasible" stand alone.
  const double spacing = path.length() / static_cast<double>(limits.size() - 1);
  const std::string hint =
      spacing > 10.0 * kDefaultStationSpacing
          ? " (stations are " + format_number(spacing) +
                " m apart; the discrete profile is conservative, so try more --stations, e.g. "
                "the default)"
          : "";
  summary["message"] = feasible ? nlohmann::json(nullptr) : nlohmann::json(result.message + hint);
  summary["infeasible_station"] =
      feasible ? nlohmann::json(nullptr) : nlohmann::json(result.infeasible_station);
  summary["infeasible_s"] =
      or_null(!feasible, feasible ? 0.0 : result.s[result.infeasible_station]);
  summary["infeasible_binding"] =
      feasible ? nlohmann::json(nullptr)
               : nlohmann::json(std::string(to_string(result.infeasible_binding)));
  summary["fit"] = request.smoothing ? "smoothing" : "interpolating";
  summary["smoothing"] =
      request.smoothing ? nlohmann::json(*request.smoothing) : nlohmann::json(nullptr);
  summary["output"] = request.output;
  summary["limits_seconds"] = limits_seconds;
  summary["solve_seconds"] = solve_seconds;
  summary["seconds"] = seconds_since(start);
  return {std::move(summary), feasible};
}

}  // namespace talus::experiments
