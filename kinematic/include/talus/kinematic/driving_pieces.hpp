#pragma once
/// @file
/// A kinematic path split at its cusps into pieces each driven in one
/// direction (forward or reverse), so that each can be given a velocity
/// profile from rest to rest (path–velocity decomposition).
#include <span>
#include <vector>

#include "talus/core/types.hpp"
#include "talus/kinematic/configuration_space.hpp"

namespace talus {

/// One piece of a path between two cusps (or the path's ends).
struct DrivingPiece {
  std::vector<Vec2> points;  ///< planar positions in order [m]; consecutive pieces share an end
  int direction = 0;         ///< +1 forward, −1 reverse, 0 for a single-pose path
};

/// Splits `path` where the direction of travel reverses. The step from pose
/// k − 1 to pose k is forward if it goes along pose k's heading
/// ((p_k − p_{k−1}) · (cos θ_k, sin θ_k) > 0), reverse if against it, and
/// keeps the previous step's direction if perpendicular (or zero). Every
/// pose's position belongs to a piece; the pose at a cusp ends one piece and
/// starts the next. An empty path gives no piece, a single pose one piece of
/// one point.
std::vector<DrivingPiece> split_at_cusps(std::span<const SE2Pose> path);

}  // namespace talus
