#include "talus/bspline/surface_path.hpp"

#include <cmath>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {

PathFrame lift_to_surface(const Vec2& position, const SurfacePoint& surface, const Vec2& d1,
                          const Vec2& d2) {
  const double planar_speed = d1.norm();
  if (!(planar_speed > 0.0)) throw InputError("path has zero velocity: its frame is undefined");
  const Vec2& g = surface.gradient;
  const Vec3 p1(d1.x(), d1.y(), g.dot(d1));
  const Vec3 p2(d2.x(), d2.y(), g.dot(d2) + d1.dot(surface.hessian * d1));
  PathFrame f;
  f.point = Vec3(position.x(), position.y(), surface.z);
  f.speed = p1.norm();
  f.tangent = p1 / f.speed;
  const Vec3 curvature = (p2 - p2.dot(f.tangent) * f.tangent) / (f.speed * f.speed);
  f.normal = Vec3(-g.x(), -g.y(), 1.0).normalized();
  f.lateral = f.normal.cross(f.tangent);
  f.kappa_n = curvature.dot(f.normal);
  f.kappa_g = curvature.dot(f.lateral);
  f.k_t = f.tangent.z();
  f.k_q = f.lateral.z();
  f.k_r = f.normal.z();
  return f;
}

namespace {

ArcLengthTable make_table(const BPatch& surface, const Curve2& curve) {
  std::vector<double> breaks;
  for (double k : curve.knots().knots()) {
    if (k < curve.parameter_begin() || k > curve.parameter_end()) continue;
    if (breaks.empty() || k > breaks.back()) breaks.push_back(k);
  }
  auto speed = [&surface, &curve](double sigma) {
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
  return ArcLengthTable(breaks, 8, speed);
}

}  // namespace

SurfacePath::SurfacePath(const BPatch& surface, Curve2 curve)
    : surface_(&surface), curve_(std::move(curve)), arc_length_(make_table(surface, curve_)) {}

PathFrame SurfacePath::frame_at_parameter(double sigma) const {
  Curve2::Derivatives d;
  curve_.derivatives(sigma, 2, d);
  PathFrame f = lift_to_surface(d.col(0), surface_->evaluate(d.col(0)), d.col(1), d.col(2));
  f.parameter = sigma;
  f.s = arc_length_.arc_length(sigma);
  return f;
}

PathFrame SurfacePath::frame_at_arc_length(double s) const {
  PathFrame f = frame_at_parameter(arc_length_.parameter(s));
  f.s = s;
  return f;
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
