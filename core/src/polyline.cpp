#include "talus/core/polyline.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "talus/core/error.hpp"

namespace talus {
namespace {

void require_vertices(std::span<const Vec2> line, const char* what) {
  if (line.empty()) throw InputError(std::string(what) + ": the polyline has no vertex");
}

}  // namespace

double distance_to_polyline(const Vec2& p, std::span<const Vec2> line) {
  require_vertices(line, "distance_to_polyline");
  double best = (p - line.front()).norm();
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const Vec2 d = line[k + 1] - line[k];
    // A zero-length segment projects onto its first end.
    const double t = std::clamp((p - line[k]).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (p - (line[k] + t * d)).norm());
  }
  return best;
}

double hausdorff_distance(std::span<const Vec2> a, std::span<const Vec2> b) {
  require_vertices(a, "hausdorff_distance");
  require_vertices(b, "hausdorff_distance");
  double h = 0.0;
  for (const Vec2& p : a) h = std::max(h, distance_to_polyline(p, b));
  for (const Vec2& p : b) h = std::max(h, distance_to_polyline(p, a));
  return h;
}

double share_within(std::span<const Vec2> points, std::span<const Vec2> line, double distance) {
  require_vertices(points, "share_within");
  require_vertices(line, "share_within");
  std::size_t near = 0;
  for (const Vec2& p : points)
    if (distance_to_polyline(p, line) < distance) ++near;
  return static_cast<double>(near) / static_cast<double>(points.size());
}

Vec2 axis_crossing(std::span<const Vec2> line, const Vec2& origin, const Vec2& axis,
                   const Vec2& target) {
  require_vertices(line, "axis_crossing");
  if (!(std::abs(axis.norm() - 1.0) <= 1e-9)) {
    throw InputError("axis_crossing: the axis must be a unit vector");
  }
  const double t_target = (target - origin).dot(axis);
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const double t0 = (line[k] - origin).dot(axis), t1 = (line[k + 1] - origin).dot(axis);
    if ((t0 - t_target) * (t1 - t_target) <= 0.0 && t0 != t1) {
      const double f = (t_target - t0) / (t1 - t0);
      return line[k] + f * (line[k + 1] - line[k]);
    }
  }
  Vec2 best = line.front();
  for (const Vec2& p : line)
    if ((p - target).norm() < (best - target).norm()) best = p;
  return best;
}

std::string compass_point(const Vec2& direction) {
  if (!direction.allFinite() || direction.isZero(0.0)) {
    throw InputError("compass_point: the direction must be non-zero and finite");
  }
  static constexpr const char* kNames[] = {"east", "north-east", "north", "north-west",
                                           "west", "south-west", "south", "south-east"};
  const double angle = std::atan2(direction.y(), direction.x());  // from east, counter-clockwise
  const int sector = static_cast<int>(std::lround(angle / (std::numbers::pi / 4.0)) + 8) % 8;
  return kNames[sector];
}

}  // namespace talus
