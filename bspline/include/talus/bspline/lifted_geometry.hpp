#pragma once
/// @file
/// The differential geometry of a planar curve lifted onto a surface z(x, y),
/// written once as a template on the scalar type: lift_to_surface()
/// instantiates it with double, and the path optimiser with Eigen's
/// AutoDiffScalar to differentiate the curvatures with respect to the curve.
/// Conventions are those of surface_path.hpp.
#include <Eigen/Core>

namespace talus {

/// Arc-length rate, frame and curvatures of a lifted curve at one point.
template <typename Scalar>
struct LiftedGeometry {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  Scalar speed;       ///< ds/dσ
  Scalar speed_rate;  ///< d²s/dσ²
  Vector3 tangent, lateral, normal;
  Scalar kappa_n, kappa_g;  ///< normal and geodesic curvature [1/m]
  Scalar k_t, k_q, k_r;     ///< the vertical unit vector in (t, q, r)
};

/// Geometry of the lifted curve where the surface has `gradient` and
/// `hessian` and the planar curve has derivatives d1 = (x', y') and
/// d2 = (x'', y'') with respect to its parameter. d1 must be non-zero (the
/// caller checks).
template <typename Scalar>
LiftedGeometry<Scalar> lifted_geometry(const Eigen::Matrix<Scalar, 2, 1>& gradient,
                                       const Eigen::Matrix<Scalar, 2, 2>& hessian,
                                       const Eigen::Matrix<Scalar, 2, 1>& d1,
                                       const Eigen::Matrix<Scalar, 2, 1>& d2) {
  using std::sqrt;
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  // Velocity and acceleration of P(σ) = (x, y, z(x, y)).
  const Vector3 p1(d1.x(), d1.y(), gradient.dot(d1));
  const Vector3 p2(d2.x(), d2.y(), gradient.dot(d2) + d1.dot(hessian * d1));
  LiftedGeometry<Scalar> out;
  out.speed = sqrt(p1.squaredNorm());
  out.speed_rate = p1.dot(p2) / out.speed;
  out.tangent = p1 / out.speed;
  // d²P/ds² is the part of P'' normal to the tangent, over speed².
  const Vector3 curvature = (p2 - p2.dot(out.tangent) * out.tangent) / (out.speed * out.speed);
  const Vector3 up_normal(-gradient.x(), -gradient.y(), Scalar(1.0));
  out.normal = up_normal / sqrt(up_normal.squaredNorm());
  out.lateral = out.normal.cross(out.tangent);
  out.kappa_n = curvature.dot(out.normal);
  out.kappa_g = curvature.dot(out.lateral);
  out.k_t = out.tangent.z();
  out.k_q = out.lateral.z();
  out.k_r = out.normal.z();
  return out;
}

}  // namespace talus
