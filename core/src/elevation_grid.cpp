#include "talus/core/elevation_grid.hpp"

#include <cmath>
#include <deque>
#include <limits>
#include <sstream>

#include "talus/core/error.hpp"
#include "talus/core/memory_budget.hpp"

namespace talus {

ElevationGrid::ElevationGrid(std::size_t ncols, std::size_t nrows, double cellsize, double x_min,
                             double y_min, double fill)
    : ncols_(ncols), nrows_(nrows), cellsize_(cellsize), x_min_(x_min), y_min_(y_min) {
  if (ncols < 2 || nrows < 2) {
    std::ostringstream msg;
    msg << "elevation grid needs at least 2 x 2 nodes, got " << ncols << " x " << nrows;
    throw InputError(msg.str());
  }
  if (!(cellsize > 0.0) || !std::isfinite(cellsize)) {
    throw InputError("elevation grid cell size must be positive and finite, got " +
                     std::to_string(cellsize));
  }
  if (!std::isfinite(x_min) || !std::isfinite(y_min) || !std::isfinite(fill)) {
    throw InputError("elevation grid origin and fill value must be finite");
  }
  // ncols * nrows may wrap: compare in doubles first.
  require_memory(static_cast<double>(ncols) * static_cast<double>(nrows) * 9.0,
                 "a " + std::to_string(ncols) + " x " + std::to_string(nrows) + " elevation grid",
                 "use fewer nodes (crop or resample the terrain, or smaller --ncols/--nrows)");
  z_.assign(ncols * nrows, fill);
  valid_.assign(ncols * nrows, 1);
}

Vec2 ElevationGrid::node_position(std::size_t i, std::size_t j) const {
  return {x_min_ + static_cast<double>(i) * cellsize_, y_min_ + static_cast<double>(j) * cellsize_};
}

void ElevationGrid::set(std::size_t i, std::size_t j, double z) {
  z_[j * ncols_ + i] = z;
  valid_[j * ncols_ + i] = 1;
}

std::size_t ElevationGrid::void_count() const {
  std::size_t n = 0;
  for (unsigned char v : valid_) n += (v == 0);
  return n;
}

std::optional<std::pair<double, double>> ElevationGrid::elevation_range() const {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (std::size_t k = 0; k < z_.size(); ++k) {
    if (!valid_[k]) continue;
    lo = std::min(lo, z_[k]);
    hi = std::max(hi, z_[k]);
  }
  if (lo > hi) return std::nullopt;
  return std::make_pair(lo, hi);
}

bool ElevationGrid::contains(const Vec2& p) const {
  return p.x() >= x_min_ && p.x() <= x_max() && p.y() >= y_min_ && p.y() <= y_max();
}

double ElevationGrid::bilinear(const Vec2& p) const {
  if (!contains(p)) {
    std::ostringstream msg;
    msg << "point (" << p.x() << ", " << p.y() << ") is outside the grid domain [" << x_min_ << ", "
        << x_max() << "] x [" << y_min_ << ", " << y_max() << "]";
    throw InputError(msg.str());
  }
  const double u = (p.x() - x_min_) / cellsize_;
  const double v = (p.y() - y_min_) / cellsize_;
  const auto i = std::min(static_cast<std::size_t>(u), ncols_ - 2);
  const auto j = std::min(static_cast<std::size_t>(v), nrows_ - 2);
  if (!valid(i, j) || !valid(i + 1, j) || !valid(i, j + 1) || !valid(i + 1, j + 1)) {
    std::ostringstream msg;
    msg << "point (" << p.x() << ", " << p.y() << ") touches a NODATA node";
    throw InputError(msg.str());
  }
  const double a = u - static_cast<double>(i);
  const double b = v - static_cast<double>(j);
  return (1 - a) * (1 - b) * at(i, j) + a * (1 - b) * at(i + 1, j) + (1 - a) * b * at(i, j + 1) +
         a * b * at(i + 1, j + 1);
}

ElevationGrid fill_voids(const ElevationGrid& grid, VoidFill method) {
  if (method != VoidFill::kNearest) throw InputError("unknown void fill method");
  if (!grid.elevation_range()) throw InputError("cannot fill voids: the grid has no valid node");
  // Multi-source breadth-first search over the 8-neighbourhood: each void takes
  // the value of the valid node that reaches it first (Chebyshev distance).
  ElevationGrid out = grid;
  const std::size_t nc = grid.ncols(), nr = grid.nrows();
  std::deque<std::pair<std::size_t, std::size_t>> queue;
  for (std::size_t j = 0; j < nr; ++j)
    for (std::size_t i = 0; i < nc; ++i)
      if (grid.valid(i, j)) queue.emplace_back(i, j);
  while (!queue.empty()) {
    const auto [i, j] = queue.front();
    queue.pop_front();
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        const long ni = static_cast<long>(i) + di, nj = static_cast<long>(j) + dj;
        if (ni < 0 || nj < 0 || ni >= static_cast<long>(nc) || nj >= static_cast<long>(nr))
          continue;
        const auto ui = static_cast<std::size_t>(ni), uj = static_cast<std::size_t>(nj);
        if (out.valid(ui, uj)) continue;
        out.set(ui, uj, out.at(i, j));
        queue.emplace_back(ui, uj);
      }
    }
  }
  return out;
}

}  // namespace talus
