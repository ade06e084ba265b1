#include "talus/navigation/hazard_detection.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <string>

#include "talus/core/error.hpp"

namespace talus {

void HazardDetectionOptions::validate() const {
  if (!(sensor_radius > 0.0) || !std::isfinite(sensor_radius))
    throw InputError("HazardDetectionOptions.sensor_radius must be > 0 [m]");
  if (!(max_slope >= 0.0 && max_slope < std::numbers::pi / 2))
    throw InputError("HazardDetectionOptions.max_slope must be in [0, pi/2) [rad] (0 = derived)");
  if (!(max_step >= 0.0) || !std::isfinite(max_step))
    throw InputError("HazardDetectionOptions.max_step must be >= 0 [m] (0 = derived)");
}

namespace {

/// The hazard flags of the grid nodes [i0, i1] x [j0, j1] (a window already
/// clipped to the grid), row-major in the window: 1 where a node on the data
/// that `considered(p)` accepts is too steep or has too much 3 x 3 relief
/// (the file comment's test; the relief over the node's neighbours inside
/// the window, which holds all of them unless the grid ends there).
template <typename Considered>
std::vector<unsigned char> hazard_window(const BPatch& surface, const Vehicle& vehicle,
                                         const HazardDetectionOptions& options, long i0, long j0,
                                         long i1, long j1, Considered considered) {
  const double slope_limit =
      std::tan(options.max_slope > 0.0
                   ? options.max_slope
                   : std::atan(std::min(vehicle.friction, vehicle.half_track / vehicle.cg_height)));
  const double step_limit = options.max_step > 0.0
                                ? options.max_step
                                : (vehicle.body ? vehicle.body->wheel_radius : vehicle.cg_height);
  const double h = surface.cellsize();
  const long w = i1 - i0 + 1, rows = j1 - j0 + 1;
  const auto node = [&](long i, long j) {
    return Vec2(surface.x_min() + static_cast<double>(i) * h,
                surface.y_min() + static_cast<double>(j) * h);
  };
  std::vector<double> z(static_cast<std::size_t>(w * rows));
  std::vector<unsigned char> hazard(z.size(), 0);
  const auto at = [w](long a, long b) { return static_cast<std::size_t>(b * w + a); };
  for (long b = 0; b < rows; ++b)
    for (long a = 0; a < w; ++a) z[at(a, b)] = surface.elevation(node(i0 + a, j0 + b));
  for (long b = 0; b < rows; ++b)
    for (long a = 0; a < w; ++a) {
      const Vec2 p = node(i0 + a, j0 + b);
      if (!considered(p) || !surface.on_data(p)) continue;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (long db = -1; db <= 1; ++db)
        for (long da = -1; da <= 1; ++da) {
          const long x = a + da, y = b + db;
          if (x < 0 || y < 0 || x >= w || y >= rows) continue;
          lo = std::min(lo, z[at(x, y)]);
          hi = std::max(hi, z[at(x, y)]);
        }
      const bool steep = surface.evaluate(p).gradient.norm() > slope_limit;
      hazard[at(a, b)] = steep || hi - lo > step_limit ? 1 : 0;
    }
  return hazard;
}

}  // namespace

std::vector<unsigned char> hazard_node_mask(const BPatch& surface, const Vehicle& vehicle,
                                            const HazardDetectionOptions& options) {
  options.validate();
  return hazard_window(surface, vehicle, options, 0, 0, static_cast<long>(surface.ncols()) - 1,
                       static_cast<long>(surface.nrows()) - 1, [](const Vec2&) { return true; });
}

std::vector<DiscHazard> detect_hazards(const BPatch& surface, const Vehicle& vehicle,
                                       const Vec2& position,
                                       const HazardDetectionOptions& options) {
  options.validate();
  if (!position.allFinite()) throw InputError("detect_hazards: the position must be finite");
  // The nodes of the sensor's bounding box, one node of margin for the 3 x 3 relief.
  const double h = surface.cellsize();
  const auto index = [h](double value, double origin) {
    return static_cast<long>(std::floor((value - origin) / h));
  };
  const long nc = static_cast<long>(surface.ncols()), nr = static_cast<long>(surface.nrows());
  const long i0 = std::max(0L, index(position.x() - options.sensor_radius, surface.x_min()) - 1);
  const long j0 = std::max(0L, index(position.y() - options.sensor_radius, surface.y_min()) - 1);
  const long i1 =
      std::min(nc - 1, index(position.x() + options.sensor_radius, surface.x_min()) + 2);
  const long j1 =
      std::min(nr - 1, index(position.y() + options.sensor_radius, surface.y_min()) + 2);
  if (i0 > i1 || j0 > j1) return {};
  const long w = i1 - i0 + 1, rows = j1 - j0 + 1;
  const auto node = [&](long i, long j) {
    return Vec2(surface.x_min() + static_cast<double>(i) * h,
                surface.y_min() + static_cast<double>(j) * h);
  };
  const std::vector<unsigned char> hazard =
      hazard_window(surface, vehicle, options, i0, j0, i1, j1,
                    [&](const Vec2& p) { return (p - position).norm() <= options.sensor_radius; });
  std::vector<unsigned char> seen(hazard.size(), 0);
  const auto at = [w](long a, long b) { return static_cast<std::size_t>(b * w + a); };
  // 8-connected groups, each as the disc round its centroid.
  std::vector<DiscHazard> out;
  std::vector<std::size_t> stack, group;
  for (std::size_t first = 0; first < hazard.size(); ++first) {
    if (!hazard[first] || seen[first]) continue;
    stack = {first};
    group.clear();
    seen[first] = 1;
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      group.push_back(k);
      const long a = static_cast<long>(k) % w, b = static_cast<long>(k) / w;
      for (long db = -1; db <= 1; ++db)
        for (long da = -1; da <= 1; ++da) {
          const long x = a + da, y = b + db;
          if (x < 0 || y < 0 || x >= w || y >= rows) continue;
          const std::size_t n = at(x, y);
          if (hazard[n] && !seen[n]) {
            seen[n] = 1;
            stack.push_back(n);
          }
        }
    }
    Vec2 centre = Vec2::Zero();
    const auto position_of = [&](std::size_t k) {
      return node(i0 + static_cast<long>(k) % w, j0 + static_cast<long>(k) / w);
    };
    for (const std::size_t k : group) centre += position_of(k);
    centre /= static_cast<double>(group.size());
    double radius = 0.0;
    for (const std::size_t k : group) radius = std::max(radius, (position_of(k) - centre).norm());
    out.push_back({centre, radius + 0.5 * h});
  }
  return out;
}

}  // namespace talus
