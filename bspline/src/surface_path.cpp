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
  return f;
}

namespace {

ArcLengthTable make_table(const BPatch& surface, const Curve2& curve) {
  // Quadrature pieces end at the curve's knots and are at most half a terrain
  // cell long: the speed |P'| is smooth inside a curve span only as long as
  // the point stays inside one bicubic cell, and Gauss–Legendre loses its
  // order across a cell edge (8 pieces per span left 3e-6 m errors at 1 m cells).
  std::vector<double> knots;
  for (double k : curve.knots().knots()) {
    if (k < curve.parameter_begin() || k > curve.parameter_end()) continue;
    if (knots.empty() || k > knots.back()) knots.push_back(k);
  }
  std::vector<double> breaks{knots.front()};
  for (std::size_t i = 1; i < knots.size(); ++i) {
    const double a = knots[i - 1], b = knots[i];
    double planar = 0.0;  // polyline length over the span, a cheap bound on its extent
    Vec2 previous = curve.evaluate(a);
    for (int m = 1; m <= 8; ++m) {
      const Vec2 p = curve.evaluate(a + (b - a) * m / 8.0);
      planar += (p - previous).norm();
      previous = p;
    }
    const int pieces = std::max(4, static_cast<int>(std::ceil(2.0 * planar / surface.cellsize())));
    for (int m = 1; m < pieces; ++m) breaks.push_back(a + (b - a) * m / pieces);
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
    : surface_(&surface), curve_(std::move(curve)), arc_length_(make_table(surface, curve_)) {}

double SurfacePath::speed(double sigma) const {
  Curve2::Derivatives d;
  curve_.derivatives(sigma, 1, d);
  const Vec2 d1 = d.col(1);
  return std::hypot(d1.x(), d1.y(), surface_->evaluate(d.col(0)).gradient.dot(d1));
}

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
  PathFrame f = frame_without_arc_length(*surface_, curve_, sigma);
  f.s = arc_length_.arc_length(sigma, speed_function());
  return f;
}

PathFrame SurfacePath::frame_at_arc_length(double s) const {
  PathFrame f =
      frame_without_arc_length(*surface_, curve_, arc_length_.parameter(s, speed_function()));
  f.s = s;
  return f;
}

void SurfacePath::sample_uniform_parameter(std::size_t stations,
                                           std::vector<PathFrame>& frames) const {
  if (stations < 2) throw InputError("a path needs at least 2 stations");
  frames.resize(stations);
  const double begin = curve_.parameter_begin(), end = curve_.parameter_end();
  const double step = (end - begin) / static_cast<double>(stations - 1);
  // Coarser than the arc-length table: the table's quadrature is the accurate choice.
  const bool coarse = stations - 1 < arc_length_.pieces();
  for (std::size_t k = 0; k < stations; ++k) {
    const double sigma = (k + 1 == stations) ? end : begin + step * static_cast<double>(k);
    PathFrame& f = frames[k];
    f = frame_without_arc_length(*surface_, curve_, sigma);
    if (k == 0) {
      f.s = 0.0;
    } else if (coarse || k + 1 == stations) {
      f.s = arc_length_.arc_length(sigma, speed_function());
    } else {
      const PathFrame& prev = frames[k - 1];
      f.s = prev.s + 0.5 * step * (prev.speed + f.speed) +
            step * step / 12.0 * (prev.speed_rate - f.speed_rate);
    }
  }
}

std::vector<PathFrame> SurfacePath::sample(std::size_t stations) const {
  if (stations < 2) throw InputError("a path needs at least 2 stations");
  std::vector<PathFrame> frames;
  frames.reserve(stations);
  const double total = length();
  for (std::size_t k = 0; k < stations; ++k) {
    const double s = (k + 1 == stations) ? total : total * static_cast<double>(k) / (stations - 1);
    frames.push_back(frame_at_arc_length(s));
  }
  return frames;
}

}  // namespace talus
