#pragma once
// The geometry of one station of a lifted planar curve and its derivatives
// with respect to the planar curve's position and first and second
// parameter derivatives there, shared by both local-stage formulations
// (path_time_objective.cpp, simultaneous_path_solver.cpp).
#include <Eigen/Core>

#include "talus/bspline/bpatch.hpp"
#include "talus/dynamics/wheel_contact.hpp"

namespace talus::detail {

/// Rows (values and Jacobian): κ_n [1/m], κ_g [1/m], k_t, k_q, k_r, speed =
/// ds/dσ [m], speed_rate = d²s/dσ² [m], κ_w [1/m] (StationGeometry's
/// kappa_n and kappa_wheels: with wheels, the chassis' and the least-loaded
/// wheel's curvature, wheel_contact.hpp; without, the c.g. point's κ_n
/// twice). Jacobian columns: x, y, x', y', x'', y'' of the planar curve at
/// the station.
struct StationDerivatives {
  static constexpr int kRows = 8;
  Eigen::Matrix<double, kRows, 1> value;
  Eigen::Matrix<double, kRows, 6> jacobian;
};

/// At the planar curve's (position, first, second derivative) `planar`,
/// whose first derivative is non-zero and whose position is in the terrain's
/// domain: Eigen AutoDiff through lifted_geometry() (and chassis_curvatures()
/// with `wheels`, null for the point mass), including the B-patch's third
/// derivatives.
StationDerivatives station_derivatives(const BPatch& terrain,
                                       const Eigen::Matrix<double, 2, 3>& planar,
                                       const WheelLayout* wheels);

}  // namespace talus::detail
