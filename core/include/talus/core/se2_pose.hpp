#pragma once
/// @file
/// A planar configuration of a vehicle: position and heading. The kinematic
/// planners' paths are sequences of them (talus/kinematic/configuration_space.hpp),
/// and the optimal layer drives such paths at their time-optimal profile
/// (talus/optimal/driven_path_time.hpp).
#include "talus/core/types.hpp"

namespace talus {

/// A configuration q = (x, y, θ): position [m] and heading [rad] (θ = 0 faces
/// east, counter-clockwise positive).
struct SE2Pose {
  double x = 0.0;      ///< [m]
  double y = 0.0;      ///< [m]
  double theta = 0.0;  ///< heading [rad], any value (compared modulo 2π)
  Vec2 position() const { return {x, y}; }
};

}  // namespace talus
