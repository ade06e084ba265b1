#pragma once
/// @file
/// Fixed-size Eigen aliases for the geometry used throughout Talus. All
/// lengths are metres; frames are x east, y north, z up.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace talus {

using Vec2 = Eigen::Vector2d;  ///< planar point or direction (x, y) [m]
using Vec3 = Eigen::Vector3d;  ///< spatial point or direction (x, y, z) [m]
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

}  // namespace talus
