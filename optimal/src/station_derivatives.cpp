#include "station_derivatives.hpp"

#include <unsupported/Eigen/AutoDiff>

#include "talus/bspline/lifted_geometry.hpp"

namespace talus::detail {

StationDerivatives station_derivatives(const BPatch& terrain,
                                       const Eigen::Matrix<double, 2, 3>& planar) {
  using Derivative = Eigen::Matrix<double, 6, 1>;
  using Local = Eigen::AutoDiffScalar<Derivative>;
  using LocalVector2 = Eigen::Matrix<Local, 2, 1>;
  const Vec2 position = planar.col(0);
  const SurfacePoint sp = terrain.evaluate(position);
  const Eigen::Vector4d third = terrain.third_derivatives(position);  // xxx, xxy, xyy, yyy
  const auto along_position = [](double dx, double dy) {
    Derivative d = Derivative::Zero();
    d[0] = dx;
    d[1] = dy;
    return d;
  };
  const Mat2& H = sp.hessian;
  LocalVector2 gradient(Local(sp.gradient.x(), along_position(H(0, 0), H(0, 1))),
                        Local(sp.gradient.y(), along_position(H(1, 0), H(1, 1))));
  Eigen::Matrix<Local, 2, 2> hessian;
  hessian(0, 0) = Local(H(0, 0), along_position(third[0], third[1]));
  hessian(0, 1) = hessian(1, 0) = Local(H(0, 1), along_position(third[1], third[2]));
  hessian(1, 1) = Local(H(1, 1), along_position(third[2], third[3]));
  LocalVector2 d1(Local(planar(0, 1), 6, 2), Local(planar(1, 1), 6, 3));
  LocalVector2 d2(Local(planar(0, 2), 6, 4), Local(planar(1, 2), 6, 5));
  const LiftedGeometry<Local> g = lifted_geometry<Local>(gradient, hessian, d1, d2);
  StationDerivatives out;
  const Local* outputs[7] = {&g.kappa_n, &g.kappa_g, &g.k_t,       &g.k_q,
                             &g.k_r,     &g.speed,   &g.speed_rate};
  for (int r = 0; r < 7; ++r) {
    out.value[r] = outputs[r]->value();
    out.jacobian.row(r) = outputs[r]->derivatives().transpose();
  }
  return out;
}

}  // namespace talus::detail
