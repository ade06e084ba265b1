#pragma once
// The closed-form heart of the time-optimal profile: the admissible constant
// tangential accelerations u of one step when one end's state is known.
//
// Along the step the state x = ṡ² is affine in u: at the known end it is
// fixed, at the other end it is y0 + beta u (beta = ±2 Δs). The admissible
// set of (x, u) at a station is convex and its intersection with that line
// is one interval of u; the vehicle's AdmissibleSet (dynamics/) computes it,
// for every vehicle model, and this header only names the two questions a
// step asks.

#include "talus/dynamics/admissible_set.hpp"
#include "talus/dynamics/velocity_limits.hpp"

namespace talus::detail {

using ControlInterval = AccelerationInterval;
/// The vehicle as the step solver sees it (the name the step tests use).
using VehicleConstants = AdmissibleSet;

/// The u such that the station with geometry `s`, at state x = y0 + beta u,
/// has (x, u) admissible and x in [x_lower, x_upper].
inline ControlInterval admissible_controls(const AdmissibleSet& set, const StationGeometry& s,
                                           double y0, double beta, double x_lower, double x_upper) {
  return set.accelerations_along(s, y0, beta, x_lower, x_upper);
}

/// The u admissible at a station whose state x is known.
inline ControlInterval known_state_controls(const AdmissibleSet& set, const StationGeometry& s,
                                            double x) {
  return set.accelerations_at(s, x);
}

}  // namespace talus::detail
