#pragma once
// The geometry of one station of a lifted planar curve and its derivatives
// with respect to the planar curve's position and first and second
// parameter derivatives there, shared by both local-stage formulations
// (path_time_objective.cpp, simultaneous_path_solver.cpp).
#include <Eigen/Core>

#include "talus/bspline/bpatch.hpp"

namespace talus::detail {

/// Rows (values and Jacobian): κ_n [1/m], κ_g [1/m], k_t, k_q, k_r, speed =
/// ds/dσ [m], speed_rate = d²s/dσ² [m]. Jacobian columns: x, y, x', y', x'',
/// y'' of the planar curve at the station.
struct StationDerivatives {
  Eigen::Matrix<double, 7, 1> value;
  Eigen::Matrix<double, 7, 6> jacobian;
};

/// At the planar curve's (position, first, second derivative) `planar`,
/// whose first derivative is non-zero and whose position is in the terrain's
/// domain: Eigen AutoDiff through lifted_geometry(), including the B-patch's
/// third derivatives.
StationDerivatives station_derivatives(const BPatch& terrain,
                                       const Eigen::Matrix<double, 2, 3>& planar);

}  // namespace talus::detail
