#pragma once
// The curvature of the planar path at one station and its derivatives: the
// steering limit as a smooth constraint of both local-stage formulations
// (path_time_objective.cpp, simultaneous_path_solver.cpp).
#include <cmath>

#include <Eigen/Core>

namespace talus::detail {

/// κ = (x' y'' − y' x'') / |c'|³ [1/m] (> 0 turning left) of a planar curve
/// at a station given as (position, c', c'') with c' ≠ 0, and its
/// derivatives with respect to (x, y, x', y', x'', y''): the columns of
/// StationDerivatives. κ is what AdmissibleSet compares with the vehicle's
/// steering limit (StationGeometry::kappa_planar).
struct PlanarCurvature {
  double value = 0.0;
  Eigen::Matrix<double, 1, 6> jacobian = Eigen::Matrix<double, 1, 6>::Zero();
};

inline PlanarCurvature planar_curvature(const Eigen::Matrix<double, 2, 3>& planar) {
  const double x1 = planar(0, 1), y1 = planar(1, 1), x2 = planar(0, 2), y2 = planar(1, 2);
  const double cross = x1 * y2 - y1 * x2;
  const double speed2 = x1 * x1 + y1 * y1;
  const double speed = std::sqrt(speed2);
  const double speed3 = speed2 * speed;
  PlanarCurvature out;
  out.value = cross / speed3;
  // d(cross/|c'|³) = dcross/|c'|³ − 3 cross (c'·dc')/|c'|⁵.
  const double along = 3.0 * cross / (speed3 * speed2);
  out.jacobian << 0.0, 0.0, y2 / speed3 - along * x1, -x2 / speed3 - along * y1, -y1 / speed3,
      x1 / speed3;
  return out;
}

}  // namespace talus::detail
