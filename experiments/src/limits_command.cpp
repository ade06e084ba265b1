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
#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/bspline/surface_path_from_points.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/path_csv.hpp"
#include "talus/dynamics/limit_summary.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"
#include "talus/report/plot.hpp"
#include "terrain_input.hpp"

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
                               const std::optional<double>& smoothing, const std::string& reproject,
                               int band) {
  const PathPointSource source{path_file, terrain_file};
  const std::vector<Vec2> points = read_path_csv(path_file);
  check_no_reversal(points, source);  // before the terrain is read, as it always was
  return surface_path_from_points(points, load_terrain(terrain_file, reproject, band).grid,
                                  smoothing, source);
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
  const TerrainPath terrain_path = build_terrain_path(
      request.terrain, request.path, request.smoothing, request.reproject, request.band);
  const SurfacePath& path = *terrain_path.path;

  const std::size_t stations = request.stations ? static_cast<std::size_t>(*request.stations)
                                                : default_station_count(terrain_path.planar_length);
  const VelocityLimits limits(vehicle, path, stations);

  std::string csv = kLimitsCsvHeader;
  csv += '\n';
  for (std::size_t k = 0; k < limits.size(); ++k) {
    const PathFrame& f = limits.frame(k);
    const SpeedLimits& l = limits.limits(k);
    for (const double value : {f.s, f.point.x(), f.point.y(), f.point.z(), l.v_min, l.v_max}) {
      append_csv_number(csv, value);
      csv += ',';
    }
    csv += to_string(l.upper_binding);
    for (const double value : {f.k_t, f.k_q, f.k_r, f.kappa_n, f.kappa_g}) {
      csv += ',';
      append_csv_number(csv, value);
    }
    csv += '\n';
  }

  write_text_file(request.output, csv);

  // An untraversable station has v_min = v_max = 0 (SpeedLimits).
  const LimitSummary sum = summarise_limits(limits);
  std::map<std::string, std::size_t> binding_counts;
  for (std::size_t c = 0; c < kConstraintCount; ++c) {
    const auto constraint = static_cast<Constraint>(c);
    const bool always = constraint == Constraint::kSliding || constraint == Constraint::kTipover ||
                        constraint == Constraint::kContact || constraint == Constraint::kMaxSpeed ||
                        constraint == Constraint::kNone;
    if (always || sum.upper_count(constraint) > 0)
      binding_counts[std::string(to_string(constraint))] = sum.upper_count(constraint);
  }
  const bool bounded = !std::isinf(sum.min_v_max);
  nlohmann::json summary;
  summary["stations"] = limits.size();
  summary["length_m"] = path.length();
  summary["min_v_max"] = bounded ? nlohmann::json(sum.min_v_max) : nlohmann::json(nullptr);
  summary["min_v_max_s"] =
      bounded ? nlohmann::json(limits.frame(sum.min_index).s) : nlohmann::json(nullptr);
  summary["untraversable_stations"] = sum.untraversable;
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
