// Test vehicles: the rover-scale point mass several suites share.
#pragma once

#include "talus/dynamics/vehicle.hpp"

namespace talus::vehicle_test {

/// A point mass with friction `mu`, centre of mass 0.5 m up, half track
/// 0.6 m (b/h = 1.2) and a top speed of 10 m/s; no drive or brake limit.
inline Vehicle point_mass_rover(double mu = 0.7) {
  Vehicle v;
  v.friction = mu;
  v.cg_height = 0.5;
  v.half_track = 0.6;
  v.max_speed = 10.0;
  return v;
}

}  // namespace talus::vehicle_test
