#include "station_derivatives.hpp"

#include <unsupported/Eigen/AutoDiff>

#include "talus/bspline/lifted_geometry.hpp"

namespace talus::detail {
namespace {

using Derivative = Eigen::Matrix<double, 6, 1>;
using Local = Eigen::AutoDiffScalar<Derivative>;
using LocalVector2 = Eigen::Matrix<Local, 2, 1>;
using LocalMatrix2 = Eigen::Matrix<Local, 2, 2>;

/// The surface's gradient and Hessian at a point that moves with the
/// station's inputs as `point` does: values there, derivatives by the chain
/// rule through the Hessian and the third derivatives.
void surface_at(const BPatch& terrain, const LocalVector2& point, LocalVector2& gradient,
                LocalMatrix2& hessian) {
  const Vec2 at(point.x().value(), point.y().value());
  const SurfacePoint sp = terrain.evaluate(at);
  const Eigen::Vector4d third = terrain.third_derivatives(at);  // xxx, xxy, xyy, yyy
  const Derivative& dx = point.x().derivatives();
  const Derivative& dy = point.y().derivatives();
  const Mat2& H = sp.hessian;
  gradient = LocalVector2(Local(sp.gradient.x(), H(0, 0) * dx + H(0, 1) * dy),
                          Local(sp.gradient.y(), H(1, 0) * dx + H(1, 1) * dy));
  hessian(0, 0) = Local(H(0, 0), third[0] * dx + third[1] * dy);
  hessian(0, 1) = hessian(1, 0) = Local(H(0, 1), third[1] * dx + third[2] * dy);
  hessian(1, 1) = Local(H(1, 1), third[2] * dx + third[3] * dy);
}

}  // namespace

StationDerivatives station_derivatives(const BPatch& terrain,
                                       const Eigen::Matrix<double, 2, 3>& planar,
                                       const WheelLayout* wheels) {
  const LocalVector2 position(Local(planar(0, 0), 6, 0), Local(planar(1, 0), 6, 1));
  LocalVector2 gradient;
  LocalMatrix2 hessian;
  surface_at(terrain, position, gradient, hessian);
  const LocalVector2 d1(Local(planar(0, 1), 6, 2), Local(planar(1, 1), 6, 3));
  const LocalVector2 d2(Local(planar(0, 2), 6, 4), Local(planar(1, 2), 6, 5));
  const LiftedGeometry<Local> g = lifted_geometry<Local>(gradient, hessian, d1, d2);
  Local kappa_n = g.kappa_n, kappa_wheels = g.kappa_n;
  if (wheels != nullptr) {
    using std::sqrt;
    const Local speed = sqrt(d1.squaredNorm());
    const LocalVector2 heading = d1 / speed;
    const Local kappa_planar = (d1.x() * d2.y() - d1.y() * d2.x()) / (speed * speed * speed);
    const LocalVector2 left(-heading.y(), heading.x());
    // The wheels where wheel_positions() puts them (a clamped coordinate keeps
    // its derivative: the clamp only matters within a wheelbase of the map's edge).
    const std::array<Vec2, 4> at = wheel_positions(terrain, *wheels, planar.col(0),
                                                   Vec2(heading.x().value(), heading.y().value()));
    std::array<LocalVector2, 4> gradients;
    std::array<LocalMatrix2, 4> hessians;
    for (std::size_t j = 0; j < 4; ++j) {
      LocalVector2 p = position + wheels->offsets[j].x() * heading + wheels->offsets[j].y() * left;
      p.x().value() = at[j].x();
      p.y().value() = at[j].y();
      surface_at(terrain, p, gradients[j], hessians[j]);
    }
    const ChassisCurvatures<Local> c =
        chassis_curvatures<Local>(*wheels, heading, kappa_planar, gradient, gradients, hessians);
    kappa_n = c.chassis;
    kappa_wheels = c.wheels;
  }
  StationDerivatives out;
  const Local* outputs[StationDerivatives::kRows] = {
      &kappa_n, &g.kappa_g, &g.k_t, &g.k_q, &g.k_r, &g.speed, &g.speed_rate, &kappa_wheels};
  for (int r = 0; r < StationDerivatives::kRows; ++r) {
    out.value[r] = outputs[r]->value();
    out.jacobian.row(r) = outputs[r]->derivatives().transpose();
  }
  return out;
}

}  // namespace talus::detail
