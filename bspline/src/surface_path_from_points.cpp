#include "talus/bspline/surface_path_from_points.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "talus/core/error.hpp"

namespace talus {
namespace {

/// Enough digits for UTM coordinates.
std::string format_number(double value) {
  std::ostringstream out;
  out.precision(15);
  out << value;
  return out.str();
}

/// "(x, y)".
std::string format_point(const Vec2& p) {
  return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ")";
}

/// "[x_min, x_max] x [y_min, y_max]".
std::string format_domain(const ElevationGrid& grid) {
  return "[" + format_number(grid.x_min()) + ", " + format_number(grid.x_max()) + "] x [" +
         format_number(grid.y_min()) + ", " + format_number(grid.y_max()) + "]";
}

/// "path point k (x, y) (P.csv line L)".
std::string describe_point(const std::vector<Vec2>& points, std::size_t k,
                           const PathPointSource& source) {
  return "path point " + std::to_string(k) + " " + format_point(points[k]) + " (" +
         source.path_file + " line " + std::to_string(k + source.first_line) + ")";
}

std::string outside_message(const std::vector<Vec2>& points, std::size_t k,
                            const ElevationGrid& grid, const PathPointSource& source) {
  return describe_point(points, k, source) + " is outside the terrain " + source.terrain_file +
         ", whose domain is " + format_domain(grid);
}

}  // namespace

void check_no_reversal(const std::vector<Vec2>& points, const PathPointSource& source) {
  for (std::size_t k = 1; k + 1 < points.size(); ++k) {
    const Vec2 in = (points[k] - points[k - 1]).normalized();
    const Vec2 out = (points[k + 1] - points[k]).normalized();
    if (in.dot(out) < -0.9999) {
      throw InputError(describe_point(points, k, source) +
                       " turns the path straight back on itself: the spline through it would "
                       "stop there; split the path at this point instead");
    }
  }
}

void check_points_in_domain(const std::vector<Vec2>& points, const ElevationGrid& grid,
                            const PathPointSource& source) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!grid.contains(points[k])) throw InputError(outside_message(points, k, grid, source));
  }
}

void check_points_on_data(const std::vector<Vec2>& points, const BPatch& surface,
                          const ElevationGrid& grid, const PathPointSource& source) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!surface.contains(points[k])) throw InputError(outside_message(points, k, grid, source));
    if (!surface.on_data(points[k])) {
      throw InputError(describe_point(points, k, source) + " lies in a NODATA cell of " +
                       source.terrain_file + " (a corner of its cell has no elevation)");
    }
  }
}

void check_curve_in_domain(const Curve2& curve, const std::vector<Vec2>& points,
                           const BPatch& surface, const ElevationGrid& grid,
                           const PathPointSource& source) {
  if (points.size() < 2) return;
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
        throw InputError("the spline through the path points of " + source.path_file +
                         " leaves the terrain " + source.terrain_file + " between points " +
                         std::to_string(k) + " and " + std::to_string(k + 1) + ", at " +
                         format_point(p) + " (domain " + format_domain(grid) +
                         "): move those points further inside or add points between them");
      }
    }
  }
}

void check_path_on_data(const SurfacePath& path, const PathPointSource& source) {
  const BPatch& surface = path.surface();
  // A station every quarter cell (the count of talus::station_count).
  const double n = std::ceil(path.length() / (0.25 * surface.cellsize())) + 1.0;
  std::vector<PathFrame> frames;
  path.sample_uniform_parameter(std::max<std::size_t>(2, static_cast<std::size_t>(n)), frames);
  for (const PathFrame& f : frames) {
    const Vec2 p = f.point.head<2>();
    if (!surface.on_data(p)) {
      throw InputError(source.path_file + ": the path crosses a NODATA cell of " +
                       source.terrain_file + " at s = " + format_number(f.s) + " m, (" +
                       format_number(p.x()) + ", " + format_number(p.y()) + ")");
    }
  }
}

double planar_polyline_length(const std::vector<Vec2>& points) {
  double length = 0.0;
  for (std::size_t k = 1; k < points.size(); ++k) length += (points[k] - points[k - 1]).norm();
  return length;
}

TerrainPath surface_path_from_points(const std::vector<Vec2>& points, const ElevationGrid& grid,
                                     const std::optional<double>& smoothing,
                                     const PathPointSource& source) {
  check_no_reversal(points, source);
  check_points_in_domain(points, grid, source);
  auto surface = std::make_unique<const BPatch>([&] {
    try {
      return smoothing ? BPatch::fit_smoothing(grid, *smoothing) : BPatch::interpolate(grid);
    } catch (const InputError& e) {
      throw InputError(source.terrain_file + ": " + e.what());
    }
  }());
  check_points_on_data(points, *surface, grid, source);

  Curve2 curve = Curve2::interpolate(points);
  check_curve_in_domain(curve, points, *surface, grid, source);
  auto path = std::make_unique<const SurfacePath>(*surface, std::move(curve));
  check_path_on_data(*path, source);
  return TerrainPath{std::move(surface), std::move(path), planar_polyline_length(points)};
}

}  // namespace talus
