#include "talus/kinematic/hait/potential_bitmap.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>

#include "talus/core/error.hpp"
#include "talus/core/graph_search.hpp"
#include "talus/core/memory_budget.hpp"

namespace talus {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Offset {
  int di, dj;
};

// Lattice offsets within distance `radius` [m] of a node (the node included).
std::vector<Offset> disc_offsets(double radius, double h) {
  const int r = static_cast<int>(std::floor(radius / h + 1e-9));
  std::vector<Offset> out;
  for (int dj = -r; dj <= r; ++dj)
    for (int di = -r; di <= r; ++di)
      if ((di * di + dj * dj) * h * h <= radius * radius * (1.0 + 1e-12)) out.push_back({di, dj});
  return out;
}

}  // namespace

void PotentialBitmapOptions::validate() const {
  const auto fail = [](const char* field, const char* rule, double v) {
    std::ostringstream msg;
    msg << "PotentialBitmapOptions." << field << " must be " << rule << ", got " << v;
    throw InputError(msg.str());
  };
  if (!(robot_radius > 0.0) || !std::isfinite(robot_radius))
    fail("robot_radius", "positive and finite", robot_radius);
  if (!(max_slope > 0.0 && max_slope < std::numbers::pi / 2))
    fail("max_slope", "in (0, pi/2)", max_slope);
  if (!(max_roughness > 0.0) || !std::isfinite(max_roughness))
    fail("max_roughness", "positive and finite", max_roughness);
  if (!(slope_weight >= 0.0) || !std::isfinite(slope_weight))
    fail("slope_weight", ">= 0 and finite", slope_weight);
  if (!(roughness_weight >= 0.0) || !std::isfinite(roughness_weight))
    fail("roughness_weight", ">= 0 and finite", roughness_weight);
  if (!(position_uncertainty >= 0.0) || !std::isfinite(position_uncertainty))
    fail("position_uncertainty", ">= 0 and finite", position_uncertainty);
  if (connectivity != 8 && connectivity != 16) fail("connectivity", "8 or 16", connectivity);
}

namespace {

/// InputError unless the terrain uncertainty grid has the terrain's shape and finite,
/// non-negative values.
void require_valid_uncertainty(const ElevationGrid& dz, std::size_t ncols, std::size_t nrows) {
  if (dz.ncols() != ncols || dz.nrows() != nrows) {
    throw InputError("terrain uncertainty grid shape differs from the terrain's");
  }
  for (std::size_t j = 0; j < nrows; ++j)
    for (std::size_t i = 0; i < ncols; ++i)
      if (dz.valid(i, j) && !(dz.at(i, j) >= 0.0 && std::isfinite(dz.at(i, j)))) {
        std::ostringstream msg;
        msg << "terrain uncertainty at node (" << i << ", " << j << ") must be finite and >= 0";
        throw InputError(msg.str());
      }
}

/// Slope, roughness and cost of every node (+inf: an obstacle).
struct CostBitmap {
  std::vector<double> slope, roughness, cost;
};

/// The cost bitmap: a plane fitted over each node's disc of the robot's radius (file
/// comment); a disc with a void is an obstacle.
CostBitmap cost_bitmap(const ElevationGrid& g, const ElevationGrid* dz,
                       const PotentialBitmapOptions& options, const std::vector<Offset>& disc) {
  const std::size_t ncols = g.ncols(), nrows = g.nrows(), n = ncols * nrows;
  const double h = g.cellsize();
  CostBitmap out{std::vector<double>(n, kInf), std::vector<double>(n, kInf),
                 std::vector<double>(n, kInf)};
  // Normal matrix of a disc with every node present: the same for all inner nodes.
  const auto normal_matrix = [&](auto&& present) {
    Mat3 a = Mat3::Zero();
    for (const Offset& o : disc) {
      if (!present(o)) continue;
      const Vec3 row(1.0, o.di * h, o.dj * h);
      a += row * row.transpose();
    }
    return a;
  };
  const Mat3 full_inverse = normal_matrix([](const Offset&) { return true; }).inverse();
  for (std::size_t j = 0; j < nrows; ++j) {
    for (std::size_t i = 0; i < ncols; ++i) {
      const auto inside = [&](const Offset& o) {
        const long ii = static_cast<long>(i) + o.di, jj = static_cast<long>(j) + o.dj;
        return ii >= 0 && jj >= 0 && ii < static_cast<long>(ncols) && jj < static_cast<long>(nrows);
      };
      bool full = true, voids = false;
      double dz_max = 0.0;
      Vec3 rhs = Vec3::Zero();
      const double z0 = g.at(i, j);
      for (const Offset& o : disc) {
        if (!inside(o)) {
          full = false;
          continue;
        }
        const std::size_t ii = i + o.di, jj = j + o.dj;
        if (!g.valid(ii, jj)) {
          voids = true;
          break;
        }
        if (dz && dz->valid(ii, jj)) dz_max = std::max(dz_max, dz->at(ii, jj));
        rhs += Vec3(1.0, o.di * h, o.dj * h) * (g.at(ii, jj) - z0);
      }
      if (voids) continue;  // unknown terrain in the disc: obstacle
      const Vec3 coef =
          full ? Vec3(full_inverse * rhs) : Vec3(normal_matrix(inside).ldlt().solve(rhs));
      const double inv_norm = 1.0 / std::sqrt(1.0 + coef.tail<2>().squaredNorm());
      double dmin = kInf, dmax = -kInf;
      for (const Offset& o : disc) {
        if (!inside(o)) continue;
        const double z = g.at(i + o.di, j + o.dj) - z0;
        const double d = (z - coef.x() - coef.y() * o.di * h - coef.z() * o.dj * h) * inv_norm;
        dmin = std::min(dmin, d);
        dmax = std::max(dmax, d);
      }
      const std::size_t k = j * ncols + i;
      out.slope[k] = std::atan(coef.tail<2>().norm());
      out.roughness[k] = (dmax - dmin) + 2.0 * dz_max;
      if (out.slope[k] <= options.max_slope && out.roughness[k] <= options.max_roughness) {
        out.cost[k] = 1.0 + options.slope_weight * out.slope[k] / options.max_slope +
                      options.roughness_weight * out.roughness[k] / options.max_roughness;
      }
    }
  }
  return out;
}

/// Growing by rho (§5.3.1): the largest cost within distance `radius` of each node.
std::vector<double> grown_cost(const std::vector<double>& cost, std::size_t ncols,
                               std::size_t nrows, double h, double radius) {
  require_memory(std::numbers::pi * std::pow(radius / h + 1.0, 2.0) * sizeof(Offset),
                 "growing the potential bitmap by the position uncertainty",
                 "use a smaller position uncertainty or a coarser terrain");
  const std::vector<Offset> grow = disc_offsets(radius, h);
  std::vector<double> grown(ncols * nrows);
  for (std::size_t j = 0; j < nrows; ++j)
    for (std::size_t i = 0; i < ncols; ++i) {
      double c = 0.0;
      for (const Offset& o : grow) {
        const long ii = static_cast<long>(i) + o.di, jj = static_cast<long>(j) + o.dj;
        if (ii < 0 || jj < 0 || ii >= static_cast<long>(ncols) || jj >= static_cast<long>(nrows))
          continue;
        c = std::max(c, cost[static_cast<std::size_t>(jj) * ncols + static_cast<std::size_t>(ii)]);
      }
      grown[j * ncols + i] = c;
    }
  return grown;
}

/// The wave from `goal_index` over `wave_cost`: 8 (king) or 16 (also knight) moves, a move
/// costing its length times the mean cost of the nodes it touches.
ShortestPathTree propagate_wave(const std::vector<double>& wave_cost, std::size_t ncols,
                                std::size_t nrows, double h, int connectivity,
                                std::size_t goal_index) {
  struct Move {
    int di, dj;
    double length;
    int m1i, m1j, m2i, m2j;  // the two nodes beside a knight move's midpoint
    bool knight;
  };
  std::vector<Move> moves;
  for (int dj = -2; dj <= 2; ++dj) {
    for (int di = -2; di <= 2; ++di) {
      const int ai = std::abs(di), aj = std::abs(dj);
      const bool king = std::max(ai, aj) == 1;
      const bool knight = (ai == 2 && aj == 1) || (ai == 1 && aj == 2);
      if (!king && !(knight && connectivity == 16)) continue;
      Move m{di, dj, h * std::hypot(di, dj), 0, 0, 0, 0, knight};
      if (ai == 2) m = {di, dj, m.length, di / 2, 0, di / 2, dj, true};
      if (aj == 2) m = {di, dj, m.length, 0, dj / 2, di, dj / 2, true};
      moves.push_back(m);
    }
  }
  const auto nc = static_cast<long>(ncols), nr = static_cast<long>(nrows);
  const auto edges = [&](std::uint32_t node, auto&& emit) {
    const long i = node % ncols, j = node / ncols;
    const double c0 = wave_cost[node];
    for (const Move& m : moves) {
      const long ii = i + m.di, jj = j + m.dj;
      if (ii < 0 || jj < 0 || ii >= nc || jj >= nr) continue;
      const std::size_t next = static_cast<std::size_t>(jj * nc + ii);
      const double c1 = wave_cost[next];
      if (!(c1 < kInf)) continue;
      double c = 0.5 * (c0 + c1);
      if (m.knight) {
        const double a = wave_cost[static_cast<std::size_t>((j + m.m1j) * nc + i + m.m1i)];
        const double b = wave_cost[static_cast<std::size_t>((j + m.m2j) * nc + i + m.m2i)];
        if (!(a < kInf) || !(b < kInf)) continue;
        c = 0.25 * (c0 + c1 + a + b);
      }
      emit(static_cast<std::uint32_t>(next), m.length * c);
    }
  };
  const std::size_t n = ncols * nrows;
  if (n > std::numeric_limits<std::uint32_t>::max() - 1) {
    throw InputError("terrain too large for the potential bitmap's 32-bit node ids");
  }
  return shortest_paths(n, static_cast<std::uint32_t>(goal_index), edges);
}

}  // namespace

PotentialBitmap::PotentialBitmap(const RuledTerrain& terrain, const Vec2& goal,
                                 const PotentialBitmapOptions& options, const ElevationGrid* dz)
    : options_(options) {
  options_.validate();
  const ElevationGrid& g = terrain.grid();
  ncols_ = g.ncols();
  nrows_ = g.nrows();
  spacing_ = g.cellsize();
  origin_ = {g.x_min(), g.y_min()};
  const double h = spacing_;
  if (!goal.allFinite() || !terrain.contains(goal)) {
    std::ostringstream msg;
    msg << "goal (" << goal.x() << ", " << goal.y() << ") is off the terrain [" << g.x_min() << ", "
        << g.x_max() << "] x [" << g.y_min() << ", " << g.y_max() << "]";
    throw InputError(msg.str());
  }
  if (dz) require_valid_uncertainty(*dz, ncols_, nrows_);
  const std::vector<Offset> disc = disc_offsets(std::max(options_.robot_radius, h), h);
  stats_.disc_nodes = disc.size();
  CostBitmap bitmap = cost_bitmap(g, dz, options_, disc);
  slope_ = std::move(bitmap.slope);
  roughness_ = std::move(bitmap.roughness);
  cost_ = std::move(bitmap.cost);
  if (options_.position_uncertainty > 0.0) {
    // No offset reaches past the map's diagonal: a larger rho grows by the
    // whole map, and its disc (O(rho^2) offsets) must not be built.
    const double diagonal =
        h * std::hypot(static_cast<double>(ncols_), static_cast<double>(nrows_));
    cost_ = grown_cost(cost_, ncols_, nrows_, h, std::min(options_.position_uncertainty, diagonal));
  }
  for (double c : cost_) stats_.obstacles += !(c < kInf);

  // Wave propagation from the goal node.
  const auto gi = static_cast<std::size_t>(std::lround((goal.x() - origin_.x()) / h));
  const auto gj = static_cast<std::size_t>(std::lround((goal.y() - origin_.y()) / h));
  goal_node_ = g.node_position(gi, gj);
  const std::size_t goal_index = gj * ncols_ + gi;
  std::vector<double> wave_cost = cost_;
  if (!(wave_cost[goal_index] < kInf)) {
    stats_.goal_on_obstacle = true;
    wave_cost[goal_index] = 1.0 + options_.slope_weight + options_.roughness_weight;
  }
  ShortestPathTree tree =
      propagate_wave(wave_cost, ncols_, nrows_, h, options_.connectivity, goal_index);
  potential_ = std::move(tree.cost);
  stats_.expanded = tree.expanded;
  for (double p : potential_) stats_.reached += (p < kInf);
}

double PotentialBitmap::potential(const Vec2& p) const {
  const double u = (p.x() - origin_.x()) / spacing_, v = (p.y() - origin_.y()) / spacing_;
  if (!p.allFinite() || u < 0.0 || v < 0.0 || u > static_cast<double>(ncols_ - 1) ||
      v > static_cast<double>(nrows_ - 1)) {
    std::ostringstream msg;
    msg << "potential asked at (" << p.x() << ", " << p.y() << "), off the terrain";
    throw InputError(msg.str());
  }
  const auto i = std::min(static_cast<std::size_t>(u), ncols_ - 2);
  const auto j = std::min(static_cast<std::size_t>(v), nrows_ - 2);
  const double a = u - static_cast<double>(i), b = v - static_cast<double>(j);
  const double p00 = potential_at(i, j), p10 = potential_at(i + 1, j);
  const double p01 = potential_at(i, j + 1), p11 = potential_at(i + 1, j + 1);
  if (p00 < kInf && p10 < kInf && p01 < kInf && p11 < kInf) {
    return (1 - a) * (1 - b) * p00 + a * (1 - b) * p10 + (1 - a) * b * p01 + a * b * p11;
  }
  return potential_at(static_cast<std::size_t>(std::lround(u)),
                      static_cast<std::size_t>(std::lround(v)));
}

bool PotentialBitmap::reachable(const Vec2& p) const {
  return potential(p) < kInf;
}

}  // namespace talus
