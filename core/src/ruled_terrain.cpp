#include "talus/core/ruled_terrain.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "talus/core/error.hpp"

namespace talus {

RuledTerrain::RuledTerrain(ElevationGrid grid) : grid_(std::move(grid)) {
  // A default-constructed grid has 0 x 0 nodes and no patch at all.
  if (grid_.ncols() < 2 || grid_.nrows() < 2) {
    throw InputError("ruled terrain needs a grid of at least 2 x 2 nodes");
  }
}

bool RuledTerrain::patch_has_data(std::size_t i, std::size_t j) const {
  return grid_.valid(i, j) && grid_.valid(i + 1, j) && grid_.valid(i, j + 1) &&
         grid_.valid(i + 1, j + 1);
}

bool RuledTerrain::has_data(const Vec2& p) const {
  if (!contains(p)) return false;
  const PatchLocation loc = locate(p);
  return patch_has_data(loc.i, loc.j);
}

PatchLocation RuledTerrain::locate(const Vec2& p) const {
  if (!contains(p)) {
    std::ostringstream msg;
    msg << "point (" << p.x() << ", " << p.y() << ") is off the terrain [" << grid_.x_min() << ", "
        << grid_.x_max() << "] x [" << grid_.y_min() << ", " << grid_.y_max() << "]";
    throw InputError(msg.str());
  }
  const double h = grid_.cellsize();
  const double u = (p.x() - grid_.x_min()) / h;
  const double v = (p.y() - grid_.y_min()) / h;
  PatchLocation loc;
  loc.i = std::min(static_cast<std::size_t>(u), grid_.ncols() - 2);
  loc.j = std::min(static_cast<std::size_t>(v), grid_.nrows() - 2);
  loc.a = u - static_cast<double>(loc.i);
  loc.b = v - static_cast<double>(loc.j);
  return loc;
}

void RuledTerrain::require_data(const Vec2& p, const PatchLocation& loc) const {
  if (!patch_has_data(loc.i, loc.j)) {
    std::ostringstream msg;
    msg << "point (" << p.x() << ", " << p.y() << ") lies on patch (" << loc.i << ", " << loc.j
        << "), which touches a NODATA node";
    throw InputError(msg.str());
  }
}

double RuledTerrain::elevation(const Vec2& p) const {
  const PatchLocation loc = locate(p);
  require_data(p, loc);
  const double z00 = grid_.at(loc.i, loc.j), z10 = grid_.at(loc.i + 1, loc.j);
  const double z01 = grid_.at(loc.i, loc.j + 1), z11 = grid_.at(loc.i + 1, loc.j + 1);
  const double a = loc.a, b = loc.b;
  return (1 - a) * (1 - b) * z00 + a * (1 - b) * z10 + (1 - a) * b * z01 + a * b * z11;
}

Vec2 RuledTerrain::gradient(const Vec2& p) const {
  const PatchLocation loc = locate(p);
  require_data(p, loc);
  const double z00 = grid_.at(loc.i, loc.j), z10 = grid_.at(loc.i + 1, loc.j);
  const double z01 = grid_.at(loc.i, loc.j + 1), z11 = grid_.at(loc.i + 1, loc.j + 1);
  const double h = grid_.cellsize();
  // dz/da and dz/db of the bilinear form, then the chain rule a = (x - x_i) / h.
  const double dza = (1 - loc.b) * (z10 - z00) + loc.b * (z11 - z01);
  const double dzb = (1 - loc.a) * (z01 - z00) + loc.a * (z11 - z10);
  return {dza / h, dzb / h};
}

RuledTerrain RuledTerrain::shifted(double dz, double sign) const {
  if (!(dz >= 0.0) || !std::isfinite(dz)) {
    throw InputError("terrain uncertainty dz must be finite and >= 0, got " + std::to_string(dz));
  }
  ElevationGrid g = grid_;
  for (std::size_t j = 0; j < g.nrows(); ++j)
    for (std::size_t i = 0; i < g.ncols(); ++i)
      if (g.valid(i, j)) g.at(i, j) += sign * dz;
  return RuledTerrain(std::move(g));
}

RuledTerrain RuledTerrain::shifted(const ElevationGrid& dz, double sign) const {
  if (dz.ncols() != grid_.ncols() || dz.nrows() != grid_.nrows()) {
    std::ostringstream msg;
    msg << "terrain uncertainty grid is " << dz.ncols() << " x " << dz.nrows()
        << " nodes, the terrain " << grid_.ncols() << " x " << grid_.nrows();
    throw InputError(msg.str());
  }
  ElevationGrid g = grid_;
  for (std::size_t j = 0; j < g.nrows(); ++j) {
    for (std::size_t i = 0; i < g.ncols(); ++i) {
      if (!dz.valid(i, j)) continue;
      const double d = dz.at(i, j);
      if (!(d >= 0.0) || !std::isfinite(d)) {
        std::ostringstream msg;
        msg << "terrain uncertainty at node (" << i << ", " << j
            << ") must be finite and >= 0, got " << d;
        throw InputError(msg.str());
      }
      if (g.valid(i, j)) g.at(i, j) += sign * d;
    }
  }
  return RuledTerrain(std::move(g));
}

RuledTerrain RuledTerrain::lower_envelope(double dz) const {
  return shifted(dz, -1.0);
}
RuledTerrain RuledTerrain::upper_envelope(double dz) const {
  return shifted(dz, +1.0);
}
RuledTerrain RuledTerrain::lower_envelope(const ElevationGrid& dz) const {
  return shifted(dz, -1.0);
}
RuledTerrain RuledTerrain::upper_envelope(const ElevationGrid& dz) const {
  return shifted(dz, +1.0);
}

}  // namespace talus
