#include "talus/bspline/surface_path.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "talus/bspline/lifted_geometry.hpp"
#include "talus/core/error.hpp"

namespace talus {

PathFrame lift_to_surface(const Vec2& position, const SurfacePoint& surface, const Vec2& d1,
                          const Vec2& d2) {
  if (!(d1.norm() > 0.0)) throw InputError("path has zero velocity: its frame is undefined");
  const LiftedGeometry<double> g =
      lifted_geometry<double>(surface.gradient, surface.hessian, d1, d2);
  PathFrame f;
  f.point = Vec3(position.x(), position.y(), surface.z);
  f.speed = g.speed;
  f.speed_rate = g.speed_rate;
  f.tangent = g.tangent;
  f.lateral = g.lateral;
  f.normal = g.normal;
  f.kappa_n = g.kappa_n;
  f.kappa_g = g.kappa_g;
  f.k_t = g.k_t;
  f.k_q = g.k_q;
  f.k_r = g.k_r;
  const double d1_norm = d1.norm();
  f.kappa_planar = (d1.x() * d2.y() - d1.y() * d2.x()) / (d1_norm * d1_norm * d1_norm);
  return f;
}

namespace {

/// Parameters in (a, b) where the planar curve crosses a grid line of the
/// surface (x = x_min + i h or y = y_min + j h), appended to `out`. The span
/// is scanned at steps of at most h / 8 of planar length and each change of
/// cell index is bracketed and solved (safeguarded regula falsi); a curve that
/// dips across a line and back within one step is not seen, which only
/// costs the arc-length table a few extra refinements there.
void add_cell_crossings(const BPatch& surface, const Curve2& curve, double a, double b,
                        double planar, std::vector<double>& out) {
  const double h = surface.cellsize();
  const int steps = std::max(8, static_cast<int>(std::ceil(8.0 * planar / h)));
  const auto cell = [&](double value, double origin) {
    return static_cast<long>(std::floor((value - origin) / h));
  };
  const auto solve = [&](int axis, double line, double lo, double hi) {
    double g_lo = curve.evaluate(lo)[axis] - line, g_hi = curve.evaluate(hi)[axis] - line;
    for (int iteration = 0; iteration < 100 && hi - lo > 1e-15 * (std::abs(lo) + std::abs(hi));
         ++iteration) {
      // Regula falsi, falling back to bisection when it does not shrink the bracket.
      double mid = (g_hi != g_lo) ? lo - g_lo * (hi - lo) / (g_hi - g_lo) : 0.5 * (lo + hi);
      if (!(mid > lo + 0.01 * (hi - lo) && mid < hi - 0.01 * (hi - lo))) mid = 0.5 * (lo + hi);
      const double g = curve.evaluate(mid)[axis] - line;
      if (g == 0.0) return mid;
      if ((g < 0.0) == (g_lo < 0.0)) {
        lo = mid;
        g_lo = g;
      } else {
        hi = mid;
        g_hi = g;
      }
    }
    return 0.5 * (lo + hi);
  };
  const double origin[2] = {surface.x_min(), surface.y_min()};
  double previous_sigma = a;
  Vec2 previous = curve.evaluate(a);
  for (int m = 1; m <= steps; ++m) {
    const double sigma = (m == steps) ? b : a + (b - a) * m / steps;
    const Vec2 p = curve.evaluate(sigma);
    for (int axis = 0; axis < 2; ++axis) {
      const long c0 = cell(previous[axis], origin[axis]), c1 = cell(p[axis], origin[axis]);
      for (long line = std::min(c0, c1) + 1; line <= std::max(c0, c1); ++line)
        out.push_back(
            solve(axis, origin[axis] + h * static_cast<double>(line), previous_sigma, sigma));
    }
    previous_sigma = sigma;
    previous = p;
  }
}

ArcLengthTable make_table(const BPatch& surface, const Curve2& curve) {
  // Breakpoints where the speed |P'| is not analytic: the curve's knots and
  // the surface's cell edges (the bicubic pieces meet with a jump in the
  // third derivative). Between them the table's Chebyshev series converge
  // geometrically and it refines each piece to about 1e-14 relative.
  std::vector<double> knots;
  for (double k : curve.knots().knots()) {
    if (k < curve.parameter_begin() || k > curve.parameter_end()) continue;
    if (knots.empty() || k > knots.back()) knots.push_back(k);
  }
  std::vector<double> breaks{knots.front()};
  std::vector<double> crossings;
  for (std::size_t i = 1; i < knots.size(); ++i) {
    const double a = knots[i - 1], b = knots[i];
    double planar = 0.0;  // polyline length over the span, a cheap bound on its extent
    Vec2 previous = curve.evaluate(a);
    for (int m = 1; m <= 8; ++m) {
      const Vec2 p = curve.evaluate(a + (b - a) * m / 8.0);
      planar += (p - previous).norm();
      previous = p;
    }
    crossings.clear();
    add_cell_crossings(surface, curve, a, b, planar, crossings);
    std::sort(crossings.begin(), crossings.end());
    const double min_gap = 1e-9 * (b - a);
    for (const double c : crossings) {
      if (c - breaks.back() > min_gap && b - c > min_gap) breaks.push_back(c);
    }
    breaks.push_back(b);
  }
  const auto speed = [&surface, &curve](double sigma) {
    Curve2::Derivatives d;
    curve.derivatives(sigma, 1, d);
    const Vec2 p = d.col(0), d1 = d.col(1);
    try {
      const SurfacePoint sp = surface.evaluate(p);
      return std::hypot(d1.x(), d1.y(), sp.gradient.dot(d1));
    } catch (const InputError& e) {
      std::ostringstream msg;
      msg << "path leaves the terrain at curve parameter " << sigma << ": " << e.what();
      throw InputError(msg.str());
    }
  };
  return ArcLengthTable(breaks, 1, speed);
}

}  // namespace

SurfacePath::SurfacePath(const BPatch& surface, Curve2 curve)
    : surface_(surface), curve_(std::move(curve)), arc_length_(make_table(surface, curve_)) {}

namespace {

/// Frame at σ without its arc length.
PathFrame frame_without_arc_length(const BPatch& surface, const Curve2& curve, double sigma) {
  Curve2::Derivatives d;
  curve.derivatives(sigma, 2, d);
  PathFrame f = lift_to_surface(d.col(0), surface.evaluate(d.col(0)), d.col(1), d.col(2));
  f.parameter = sigma;
  return f;
}

}  // namespace

PathFrame SurfacePath::frame_at_parameter(double sigma) const {
  PathFrame f = frame_without_arc_length(surface_, curve_, sigma);
  f.s = arc_length_.arc_length(sigma);
  return f;
}

PathFrame SurfacePath::frame_at_arc_length(double s) const {
  PathFrame f = frame_without_arc_length(surface_, curve_, arc_length_.parameter(s));
  f.s = s;
  return f;
}

void SurfacePath::sample_uniform_parameter(std::size_t stations,
                                           std::vector<PathFrame>& frames) const {
  if (stations < 2) throw InputError("a path needs at least 2 stations");
  frames.resize(stations);
  const double begin = curve_.parameter_begin(), end = curve_.parameter_end();
  const double step = (end - begin) / static_cast<double>(stations - 1);
  // s from the arc-length table's series: one Clenshaw sum per station, the
  // piece found from the previous station's.
  std::size_t piece = 0;
  for (std::size_t k = 0; k < stations; ++k) {
    const double sigma = (k + 1 == stations) ? end : begin + step * static_cast<double>(k);
    PathFrame& f = frames[k];
    f = frame_without_arc_length(surface_, curve_, sigma);
    f.s = (k == 0) ? 0.0 : arc_length_.arc_length(sigma, piece);
  }
}

std::vector<PathFrame> SurfacePath::sample(std::size_t stations) const {
  if (stations < 2) throw InputError("a path needs at least 2 stations");
  std::vector<PathFrame> frames;
  frames.reserve(stations);
  const double total = length();
  std::size_t piece = 0;  // the inverse map's bracket, carried from station to station
  for (std::size_t k = 0; k < stations; ++k) {
    const double s = (k + 1 == stations) ? total : total * static_cast<double>(k) / (stations - 1);
    PathFrame f = frame_without_arc_length(surface_, curve_, arc_length_.parameter(s, piece));
    f.s = s;
    frames.push_back(f);
  }
  return frames;
}

}  // namespace talus
