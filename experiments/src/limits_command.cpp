#include "limits_command.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "cli_values.hpp"
#include "plot.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/path_csv.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"
#include "talus/optimal/trajectory.hpp"

namespace talus::experiments {
namespace {

/// "(x, y)" with enough digits for UTM coordinates.
std::string format_point(const Vec2& p) {
  std::ostringstream out;
  out.precision(15);
  out << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

std::string format_domain(const ElevationGrid& grid) {
  std::ostringstream out;
  out.precision(15);
  out << "[" << grid.x_min() << ", " << grid.x_max() << "] x [" << grid.y_min() << ", "
      << grid.y_max() << "]";
  return out.str();
}

/// "point k (x, y) (P.csv line L)": point k is on line k + 2 (read_path_csv).
std::string describe_point(const std::vector<Vec2>& points, std::size_t k,
                           const std::string& path_file) {
  return "path point " + std::to_string(k) + " " + format_point(points[k]) + " (" + path_file +
         " line " + std::to_string(k + 2) + ")";
}

/// A way point where the path turns straight back (A, B, A) makes the
/// interpolating spline stop there, and its frame is undefined: name it.
void check_no_reversal(const std::vector<Vec2>& points, const std::string& path_file) {
  for (std::size_t k = 1; k + 1 < points.size(); ++k) {
    const Vec2 in = (points[k] - points[k - 1]).normalized();
    const Vec2 out = (points[k + 1] - points[k]).normalized();
    if (in.dot(out) < -0.9999) {
      throw InputError(describe_point(points, k, path_file) +
                       " turns the path straight back on itself: the spline through it would "
                       "stop there; split the path at this point instead");
    }
  }
}

/// Every way point must lie on the terrain's domain (checked before the fit).
void check_points_in_domain(const std::vector<Vec2>& points, const ElevationGrid& grid,
                            const std::string& path_file, const std::string& terrain_file) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!grid.contains(points[k])) {
      throw InputError(describe_point(points, k, path_file) + " is outside the terrain " +
                       terrain_file + ", whose domain is " + format_domain(grid));
    }
  }
}

/// Every way point must lie on the surface and on measured data.
void check_points_on_data(const std::vector<Vec2>& points, const BPatch& surface,
                          const ElevationGrid& grid, const std::string& path_file,
                          const std::string& terrain_file) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!surface.contains(points[k])) {
      throw InputError(describe_point(points, k, path_file) + " is outside the terrain " +
                       terrain_file + ", whose domain is " + format_domain(grid));
    }
    if (!surface.on_data(points[k])) {
      throw InputError(describe_point(points, k, path_file) + " lies in a NODATA cell of " +
                       terrain_file + " (a corner of its cell has no elevation)");
    }
  }
}

/// The one NODATA policy of `limits` and `profile` (as `plan`, which treats
/// voids as impassable): a path that crosses a NODATA cell anywhere, not
/// only at a way point, is refused, naming the first place. Sampled at a
/// quarter of the cell size, so no cell the path crosses is skipped.
void check_path_on_data(const SurfacePath& path, const std::string& path_file,
                        const std::string& terrain_file) {
  const BPatch& surface = path.surface();
  std::vector<PathFrame> frames;
  path.sample_uniform_parameter(station_count(path.length(), 0.25 * surface.cellsize()), frames);
  for (const PathFrame& f : frames) {
    const Vec2 p = f.point.head<2>();
    if (!surface.on_data(p)) {
      throw InputError(path_file + ": the path crosses a NODATA cell of " + terrain_file +
                       " at s = " + format_number(f.s) + " m, (" + format_number(p.x()) + ", " +
                       format_number(p.y()) + ")");
    }
  }
}

/// The interpolating spline can swing outside the domain between two way
/// points; name the two points (SurfacePath's own check remains the backstop).
void check_curve_in_domain(const Curve2& curve, const std::vector<Vec2>& points,
                           const BPatch& surface, const std::string& path_file,
                           const std::string& terrain_file, const ElevationGrid& grid) {
  // The way points' chord-length parameters, normalised to the curve's domain.
  std::vector<double> u(points.size(), 0.0);
  for (std::size_t k = 1; k < points.size(); ++k)
    u[k] = u[k - 1] + (points[k] - points[k - 1]).norm();
  const double begin = curve.parameter_begin(), end = curve.parameter_end();
  for (double& value : u) value = begin + (end - begin) * value / u.back();
  constexpr int kSamplesPerSegment = 64;
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    for (int m = 1; m < kSamplesPerSegment; ++m) {
      const double sigma = u[k] + (u[k + 1] - u[k]) * m / kSamplesPerSegment;
      const Vec2 p = curve.evaluate(sigma);
      if (!surface.contains(p)) {
        throw InputError("the spline through the path points of " + path_file +
                         " leaves the terrain " + terrain_file + " between points " +
                         std::to_string(k) + " and " + std::to_string(k + 1) + ", at " +
                         format_point(p) + " (domain " + format_domain(grid) +
                         "): move those points further inside or add points between them");
      }
    }
  }
}

double planar_polyline_length(const std::vector<Vec2>& points) {
  double length = 0.0;
  for (std::size_t k = 1; k < points.size(); ++k) length += (points[k] - points[k - 1]).norm();
  return length;
}

}  // namespace

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
  const std::vector<Vec2> points = read_path_csv(path_file);
  check_no_reversal(points, path_file);
  const ElevationGrid grid = read_esri_ascii(terrain_file);
  check_points_in_domain(points, grid, path_file, terrain_file);

  auto surface = std::make_unique<const BPatch>([&] {
    try {
      return smoothing ? BPatch::fit_smoothing(grid, *smoothing) : BPatch::interpolate(grid);
    } catch (const InputError& e) {
      throw InputError(terrain_file + ": " + e.what());
    }
  }());
  check_points_on_data(points, *surface, grid, path_file, terrain_file);

  Curve2 curve = Curve2::interpolate(points);
  check_curve_in_domain(curve, points, *surface, path_file, terrain_file, grid);
  auto path = std::make_unique<const SurfacePath>(*surface, std::move(curve));
  check_path_on_data(*path, path_file, terrain_file);
  return TerrainPath{std::move(surface), std::move(path), planar_polyline_length(points)};
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
