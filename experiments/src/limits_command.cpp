#include "limits_command.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "cli_values.hpp"
#include "plot.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/bspline/surface_path_from_points.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/path_csv.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"

namespace talus::experiments {

void append_csv_number(std::string& out, double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void check_path_options(const std::optional<long long>& stations,
                        const std::optional<double>& smoothing, const std::string& output) {
  if (stations && *stations < 2) {
    throw InputError("--stations must be at least 2, got " + std::to_string(*stations));
  }
  if (stations && *stations > kMaxStations) {
    throw InputError("--stations must be at most " + std::to_string(kMaxStations) + ", got " +
                     std::to_string(*stations));
  }
  if (smoothing && !(std::isfinite(*smoothing) && *smoothing > 0.0)) {
    std::ostringstream msg;
    msg << "--smoothing must be a positive finite number (lambda), got " << *smoothing;
    throw InputError(msg.str());
  }
  if (output.empty()) throw InputError("no output file given (-o OUT.csv)");
}

TerrainPath build_terrain_path(const std::string& terrain_file, const std::string& path_file,
                               const std::optional<double>& smoothing) {
  const PathPointSource source{path_file, terrain_file};
  const std::vector<Vec2> points = read_path_csv(path_file);
  check_no_reversal(points, source);  // before the terrain is read, as it always was
  return surface_path_from_points(points, read_esri_ascii(terrain_file), smoothing, source);
}

std::size_t default_station_count(double planar_length) {
  if (!(planar_length >= 0.0)) return kMinDefaultStations;
  const double n = std::ceil(planar_length) + 1.0;
  if (n >= static_cast<double>(kMaxDefaultStations)) return kMaxDefaultStations;
  return std::max(kMinDefaultStations, static_cast<std::size_t>(n));
}

nlohmann::json limits(const LimitsRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  check_path_options(request.stations, request.smoothing, request.output);
  check_output_is_not_an_input(
      "-o", request.output,
      {{"--terrain", request.terrain}, {"--path", request.path}, {"--vehicle", request.vehicle}});

  const Vehicle vehicle = load_vehicle(request.vehicle);
  const TerrainPath terrain_path =
      build_terrain_path(request.terrain, request.path, request.smoothing);
  const SurfacePath& path = *terrain_path.path;

  const std::size_t stations = request.stations ? static_cast<std::size_t>(*request.stations)
                                                : default_station_count(terrain_path.planar_length);
  const VelocityLimits limits(vehicle, path, stations);

  // The CSV, and the summary on the way.
  std::string csv = kLimitsCsvHeader;
  csv += '\n';
  std::map<std::string, std::size_t> binding_counts;
  for (const Constraint c : {Constraint::kSliding, Constraint::kTipover, Constraint::kContact,
                             Constraint::kMaxSpeed, Constraint::kNone}) {
    binding_counts[std::string(to_string(c))] = 0;
  }
  double min_v_max = std::numeric_limits<double>::infinity();
  double min_v_max_s = 0.0;
  std::size_t untraversable = 0;
  for (std::size_t k = 0; k < limits.size(); ++k) {
    const PathFrame& f = limits.frame(k);
    const SpeedLimits& l = limits.limits(k);
    const double v_max = l.traversable ? l.v_max : 0.0;
    const double v_min = l.traversable ? l.v_min : 0.0;
    const std::string binding(to_string(l.upper_binding));
    ++binding_counts[binding];
    if (!l.traversable) ++untraversable;
    if (v_max < min_v_max) {
      min_v_max = v_max;
      min_v_max_s = f.s;
    }
    for (const double value : {f.s, f.point.x(), f.point.y(), f.point.z(), v_min, v_max}) {
      append_csv_number(csv, value);
      csv += ',';
    }
    csv += binding;
    for (const double value : {f.k_t, f.k_q, f.k_r, f.kappa_n, f.kappa_g}) {
      csv += ',';
      append_csv_number(csv, value);
    }
    csv += '\n';
  }

  write_text_file(request.output, csv);

  nlohmann::json summary;
  summary["stations"] = limits.size();
  summary["length_m"] = path.length();
  summary["min_v_max"] =
      std::isinf(min_v_max) ? nlohmann::json(nullptr) : nlohmann::json(min_v_max);
  summary["min_v_max_s"] =
      std::isinf(min_v_max) ? nlohmann::json(nullptr) : nlohmann::json(min_v_max_s);
  summary["untraversable_stations"] = untraversable;
  summary["binding_counts"] = binding_counts;
  summary["fit"] = request.smoothing ? "smoothing" : "interpolating";
  summary["smoothing"] =
      request.smoothing ? nlohmann::json(*request.smoothing) : nlohmann::json(nullptr);
  summary["output"] = request.output;
  summary["seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace talus::experiments
