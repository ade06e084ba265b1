#include "talus/optimal/candidate_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/polyline.hpp"
#include "talus/dynamics/velocity_limits.hpp"

namespace talus {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double degrees(double radians) {
  return radians * 180.0 / std::numbers::pi;
}

}  // namespace

double terrain_slope_degrees(const SurfacePoint& point) {
  return degrees(std::atan(point.gradient.norm()));
}

CandidateMetrics measure_candidate(const BPatch& terrain, const Vehicle& vehicle,
                                   const CandidatePath& path, double spacing) {
  const std::vector<Vec2>& v = path.vertices;
  if (v.empty()) throw InputError("measure_candidate: the path has no vertex");
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    throw InputError("measure_candidate: the lattice spacing must be positive and finite");
  }
  CandidateMetrics m;
  const double steep = degrees(std::atan(vehicle.friction));
  double s = 0.0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const SurfacePoint p = terrain.evaluate(v[k]);
    if (k > 0) {
      const Vec2 a = v[k - 1], b = v[k];
      const int stations = edge_stations((b - a).norm(), spacing);
      const EdgeCost e = edge_cost(terrain, vehicle, a, b, stations);
      s += e.length;
      m.recomputed_cost += e.forward;
      m.edge_speed.push_back(e.length / e.forward);
      m.min_edge_speed = std::min(m.min_edge_speed, m.edge_speed.back());
      // The steepest slope anywhere on the edge, at the search's own stations,
      // and whether the vehicle could stand still where it exceeds atan μ.
      for (int q = 0; q < stations; ++q) {
        const double tau = static_cast<double>(q) / (stations - 1);
        const Vec2 x = a + tau * (b - a);
        const SurfacePoint sp = terrain.evaluate(x);
        const double slope = terrain_slope_degrees(sp);
        m.max_slope = std::max(m.max_slope, slope);
        if (slope <= steep) continue;
        ++m.steep_stations;
        const StationGeometry g =
            StationGeometry::from(lift_to_surface(x, sp, b - a, Vec2::Zero()));
        const AccelerationBounds rest = acceleration_bounds(vehicle, g, 0.0);
        if (!rest.feasible || rest.a_max < 0.0 || rest.a_min > 0.0) {
          ++m.speed_only_stations;
          if (g.kappa_n > 0.0) ++m.concave_speed_only;
        }
      }
      m.climb += std::max(0.0, p.z - m.z.back());
    }
    m.s.push_back(s);
    m.z.push_back(p.z);
    m.slope.push_back(terrain_slope_degrees(p));
    m.max_z = std::max(m.max_z, p.z);
  }
  for (std::size_t a = 0; a < v.size() && !m.revisits; ++a)
    for (std::size_t b = a + 1; b < v.size() && !m.revisits; ++b)
      m.revisits = (v[a] - v[b]).norm() < 1e-6 * spacing;
  return m;
}

LandmarkPassage landmark_passage(std::span<const Vec2> route, const Vec2& start, const Vec2& goal,
                                 const Vec2& landmark) {
  if (route.empty()) throw InputError("landmark_passage: the route has no vertex");
  if (start == goal) throw InputError("landmark_passage: start and goal coincide");
  const Vec2 axis = (goal - start).normalized();
  LandmarkPassage passage;
  passage.point = axis_crossing(route, start, axis, landmark);
  passage.distance = (passage.point - landmark).norm();
  if (passage.distance > 0.0) passage.side = compass_point(passage.point - landmark);
  return passage;
}

CorridorOverlap corridor_overlap(std::span<const Vec2> route, std::span<const Vec2> reference,
                                 double near) {
  return {hausdorff_distance(route, reference), share_within(route, reference, near)};
}

double default_separation(const GlobalSearchResult& result) {
  return default_candidate_separation(result.start_node, result.goal_node, result.spacing);
}

Vec2 lattice_node_position(const GlobalSearchResult& result, std::size_t n) {
  return result.origin + result.spacing * Vec2(static_cast<double>(n % result.nx),
                                               static_cast<double>(n / result.nx));
}

LatticeCensus lattice_census(const BPatch& terrain, const GlobalSearchResult& result,
                             double friction) {
  if (result.cost_from_start.size() != result.nx * result.ny) {
    throw InputError(
        "lattice_census: the search result carries no cost field "
        "(run it with cost_fields = true)");
  }
  LatticeCensus census;
  const double steep = degrees(std::atan(friction));
  for (std::size_t n = 0; n < result.nx * result.ny; ++n) {
    if (terrain_slope_degrees(terrain.evaluate(lattice_node_position(result, n))) > steep)
      ++census.steep_nodes;
    if (!(result.cost_from_start[n] < kInf)) ++census.unreachable_nodes;
  }
  return census;
}

}  // namespace talus
