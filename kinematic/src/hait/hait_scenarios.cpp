#include "talus/kinematic/hait/hait_scenarios.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {
namespace {

/// Uniform in [lo, hi) from the top 53 bits (platform independent).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

}  // namespace

void add_hills(ElevationGrid& grid, std::span<const GaussianHill> hills) {
  for (const GaussianHill& hill : hills) {
    for (std::size_t j = 0; j < grid.nrows(); ++j) {
      for (std::size_t i = 0; i < grid.ncols(); ++i) {
        const double d2 = (grid.node_position(i, j) - hill.centre).squaredNorm();
        grid.at(i, j) += hill.height * std::exp(-d2 / (2.0 * hill.sigma * hill.sigma));
      }
    }
  }
}

ElevationGrid hait_fractal_base(std::size_t ncols, std::size_t nrows, double spacing,
                                double height_scale, std::uint64_t seed) {
  FractalTerrainOptions f;
  f.shape = {ncols, nrows, spacing, 0.0, 0.0};
  f.fractal_dimension = 2.2;
  f.height_scale = height_scale;
  f.seed = seed;
  return generate_fractal_terrain(f);
}

ElevationGrid hait_rough_terrain(std::size_t ncols, std::size_t nrows, double spacing,
                                 std::size_t hills, std::uint64_t seed) {
  const double extent = spacing * static_cast<double>(std::max(ncols, nrows) - 1);
  // fBm with H = 0.8: the range grows as extent^H; 1.2 m at 35 m.
  ElevationGrid g =
      hait_fractal_base(ncols, nrows, spacing, 1.2 * std::pow(extent / 35.0, 0.8), seed);
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ULL);
  const double w = spacing * static_cast<double>(ncols - 1);
  const double h = spacing * static_cast<double>(nrows - 1);
  std::vector<GaussianHill> placed;
  for (std::size_t k = 0; k < hills; ++k) {
    // The two draws are arguments of one call, so their order is the
    // compiler's (kept as it was: the terrains of earlier runs stay the same).
    placed.push_back({Vec2(uniform(rng, 0.0, w), uniform(rng, 0.0, h)), 1.8, 1.4});
  }
  add_hills(g, placed);
  return g;
}

HaitScenario hait_heuristics_scenario(bool quick) {
  const std::size_t n = quick ? 61 : 141;
  const double spacing = 0.25;
  const double size = spacing * static_cast<double>(n - 1);
  HaitScenario s;
  s.grid = hait_fractal_base(n, n, spacing, quick ? 0.5 : 1.2, 7);
  // The crescent: hills on an arc of radius r around c, opening towards the start.
  const Vec2 c(0.55 * size, 0.55 * size);
  const double r = 0.22 * size;
  const int hills = quick ? 7 : 11;
  const double pi = std::acos(-1.0);
  for (int k = 0; k < hills; ++k) {
    const double a = pi / 4.0 - 0.6 * pi + 1.2 * pi * k / (hills - 1);  // facing north-east
    s.hills.push_back({c + r * Vec2(std::cos(a), std::sin(a)), 2.0, quick ? 0.7 : 1.0});
  }
  add_hills(s.grid, s.hills);
  s.start = {0.12 * size, 0.12 * size, pi / 4.0};
  s.goal = {0.88 * size, 0.88 * size, pi / 2.0};
  s.description =
      std::to_string(n) + " x " + std::to_string(n) + " nodes at 0.25 m (" + std::to_string(n * n) +
      " nodes; the paper's terrains: 0.25 m, about 20000 nodes): a fractional Brownian "
      "surface (D = 2.2, seed 7) plus a crescent of " +
      std::to_string(hills) +
      " steep Gaussian hills (2 m high) that cups the straight line from the start (south-west) "
      "to the goal (north-east), heading north at the goal.";
  return s;
}

HaitScenario hait_gorge_scenario(bool quick) {
  const std::size_t nx = quick ? 81 : 141, ny = quick ? 81 : 141;
  const double spacing = 0.25;
  const double w = spacing * static_cast<double>(nx - 1), h = spacing * static_cast<double>(ny - 1);
  HaitScenario s;
  s.grid = hait_fractal_base(nx, ny, spacing, 0.15, 11);
  // A north-south ridge at x = w/2 from the south border to 60 % of the
  // height, 2.5 m high and 3 m thick, cut by a gorge at y = 0.35 h whose
  // floor is 2 floor_half wide with walls `wall` wide.
  const double xc = 0.5 * w, yc = 0.35 * h, ridge_end = 0.6 * h;
  const double height = 2.5, half_thickness = 1.5, floor_half = 0.9, wall = 0.35;
  for (std::size_t j = 0; j < ny; ++j) {
    for (std::size_t i = 0; i < nx; ++i) {
      const Vec2 p = s.grid.node_position(i, j);
      const double across = std::abs(p.x() - xc) / half_thickness;
      double ridge = across < 1.0 ? 0.5 * (1.0 + std::cos(std::acos(-1.0) * across)) : 0.0;
      if (p.y() > ridge_end) {
        ridge *= std::exp(-std::pow((p.y() - ridge_end) / 0.6, 2));
      }
      const double off = std::abs(p.y() - yc);
      const double cut = off < floor_half ? 0.0
                         : off < floor_half + wall
                             ? 0.5 * (1.0 - std::cos(std::acos(-1.0) * (off - floor_half) / wall))
                             : 1.0;
      s.grid.at(i, j) += height * ridge * cut;
    }
  }
  s.gorge = Vec2(xc, yc);
  s.ridge_half_thickness = half_thickness;
  s.ridge_end_y = ridge_end;
  s.gorge_half_width = floor_half + wall;
  s.start = {0.15 * w, yc, 0.0};
  s.goal = {0.85 * w, yc, 0.0};
  s.description =
      std::to_string(nx) + " x " + std::to_string(ny) +
      " nodes at 0.25 m: a mildly rough fractal plain (D = 2.2, 0.15 m peak to peak, seed 11) "
      "crossed from the south border by a north-south ridge 2.5 m high and 3 m thick, cut on the "
      "straight line from start to goal by a gorge with a 1.8 m flat floor and 0.35 m walls; "
      "the way round is past the ridge's north end.";
  return s;
}

double first_crossing_y(std::span<const PathPoint> path, double x) {
  for (std::size_t k = 1; k < path.size(); ++k) {
    const double a = path[k - 1].pose.x - x, b = path[k].pose.x - x;
    if ((a <= 0.0) != (b <= 0.0)) {
      const double t = a / (a - b);
      return path[k - 1].pose.y + t * (path[k].pose.y - path[k - 1].pose.y);
    }
  }
  return std::nan("");
}

bool passes_through_gorge(std::span<const PathPoint> path, const HaitScenario& gorge_scenario) {
  const double y = first_crossing_y(path, gorge_scenario.gorge.x());
  return std::isfinite(y) &&
         std::abs(y - gorge_scenario.gorge.y()) < gorge_scenario.gorge_half_width;
}

ElevationGrid uncertainty_disc_map(const ElevationGrid& grid, double base, const Vec2& centre,
                                   double radius, double high) {
  for (const double v : {base, high, radius}) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      std::ostringstream msg;
      msg << "uncertainty_disc_map: base, high and radius must be finite and >= 0, got " << base
          << ", " << high << ", " << radius;
      throw InputError(msg.str());
    }
  }
  ElevationGrid dz(grid.ncols(), grid.nrows(), grid.cellsize(), grid.x_min(), grid.y_min(), base);
  for (std::size_t j = 0; j < grid.nrows(); ++j) {
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      if ((grid.node_position(i, j) - centre).norm() <= radius) dz.at(i, j) = high;
    }
  }
  return dz;
}

double length_within_disc(std::span<const PathPoint> path, const Vec2& centre, double radius) {
  double inside = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Vec2 a = path[k - 1].pose.position() - centre, b = path[k].pose.position() - centre;
    const Vec2 d = b - a;
    const double dd = d.squaredNorm();
    if (dd == 0.0) continue;
    // |a + t d|^2 = r^2: t = (-a.d ± sqrt((a.d)^2 - dd (|a|^2 - r^2))) / dd, clipped to [0, 1].
    const double ad = a.dot(d);
    const double disc = ad * ad - dd * (a.squaredNorm() - radius * radius);
    if (disc <= 0.0) continue;
    const double root = std::sqrt(disc);
    const double t0 = std::max(0.0, (-ad - root) / dd), t1 = std::min(1.0, (-ad + root) / dd);
    if (t1 > t0) inside += (t1 - t0) * std::sqrt(dd);
  }
  return inside;
}

}  // namespace talus
