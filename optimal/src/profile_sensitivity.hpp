#pragma once
// Adjoint sensitivity of the time-optimal travel time to the path geometry.
//
// The discrete time-optimal profile x_k = ṡ_k² is pinned by the constraints
// it touches: a station on the limit curve satisfies a speed condition in x_k
// alone; a step on a maximum- or minimum-acceleration arc satisfies a control
// condition in (x_j, x_{j+1}); a step whose line x = y0 + β u touches a
// station's friction ellipse tangentially (the discrete limit curve: states
// just below the continuous one where the two ends of a step admit a single
// common control) adds the double-root condition on its control. Together
// these equations E(x, θ) = 0 in the interior states (θ: the stations'
// geometry and step lengths) are consistent and, off degenerate profiles,
// determine dx/dθ; by the implicit-function theorem
//     dT/dθ = ∂T/∂θ − λᵀ ∂E/∂θ,   λ = J (JᵀJ)⁻¹ (∂T/∂x)ᵀ,   J = ∂E/∂x,
// one sparse factorisation for all of θ (least squares, exact for a
// consistent system with more touched constraints than states). The
// constraint functions are differentiated with Eigen's AutoDiff, from the
// same formulas as the profile solver's. T is piecewise smooth: where the set
// of touched constraints changes (a switching point crossing a station) only
// one-sided derivatives exist, and this is the gradient of the active set
// found at this profile.
#include <array>
#include <cstddef>
#include <vector>

#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"

namespace talus::detail {

/// dT/d(κ_n, κ_g, k_t, k_q, k_r, κ_w) at each station and dT/dΔs for each step.
struct TravelTimeSensitivity {
  std::vector<std::array<double, 6>> geometry;
  std::vector<double> step_length;
};

/// Sensitivity of T = Σ 2 Δs_j / (ṡ_j + ṡ_{j+1}) for the time-optimal
/// profile with station speeds `speeds` along stations with geometry
/// `geometry` at arc lengths `s` (strictly increasing), start and end speeds
/// fixed. Returns false when the touched constraints do not determine the
/// states (rank-deficient system; the caller then falls back to finite
/// differences).
bool travel_time_sensitivity(const Vehicle& vehicle, const std::vector<StationGeometry>& geometry,
                             const std::vector<double>& s, const std::vector<double>& speeds,
                             TravelTimeSensitivity& out);

}  // namespace talus::detail
