#include "talus/kinematic/eldershaw_yim/footmap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus {

Footmap::Footmap(const RuledTerrain& terrain, const LeggedRobot& robot)
    : terrain_(&terrain), ncols_(terrain.grid().ncols()), nrows_(terrain.grid().nrows()) {
  const ElevationGrid& g = terrain.grid();
  const double h = g.cellsize();
  const double s = 0.5 * std::max(robot.foot_print, h);
  valid_.assign(ncols_ * nrows_, 0);
  slope_.assign(ncols_ * nrows_, std::numeric_limits<double>::quiet_NaN());
  const double limit = robot.max_traction_slope;
  auto sample = [&](double x, double y, double& z) {
    const Vec2 p(std::clamp(x, g.x_min(), g.x_max()), std::clamp(y, g.y_min(), g.y_max()));
    if (!terrain.has_data(p)) return false;
    z = terrain.elevation(p);
    return true;
  };
  for (std::size_t j = 0; j < nrows_; ++j) {
    for (std::size_t i = 0; i < ncols_; ++i) {
      if (!g.valid(i, j)) continue;
      const Vec2 p = g.node_position(i, j);
      double xe = 0, xw = 0, yn = 0, ys = 0;
      if (!sample(p.x() + s, p.y(), xe) || !sample(p.x() - s, p.y(), xw) ||
          !sample(p.x(), p.y() + s, yn) || !sample(p.x(), p.y() - s, ys))
        continue;
      const double dx = std::min(p.x() + s, g.x_max()) - std::max(p.x() - s, g.x_min());
      const double dy = std::min(p.y() + s, g.y_max()) - std::max(p.y() - s, g.y_min());
      const double gx = dx > 0 ? (xe - xw) / dx : 0.0;
      const double gy = dy > 0 ? (yn - ys) / dy : 0.0;
      const double slope = std::atan(std::hypot(gx, gy));
      slope_[j * ncols_ + i] = slope;
      valid_[j * ncols_ + i] = slope <= limit ? 1 : 0;
    }
  }
}

std::size_t Footmap::invalid_count() const {
  return static_cast<std::size_t>(std::count(valid_.begin(), valid_.end(), std::uint8_t{0}));
}

}  // namespace talus
