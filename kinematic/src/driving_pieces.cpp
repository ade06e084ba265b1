#include "talus/kinematic/driving_pieces.hpp"

#include <cmath>

namespace talus {

std::vector<DrivingPiece> split_at_cusps(std::span<const SE2Pose> path) {
  std::vector<DrivingPiece> pieces;
  if (path.empty()) return pieces;
  DrivingPiece piece{{path.front().position()}, 0};
  for (std::size_t k = 1; k < path.size(); ++k) {
    const SE2Pose& q = path[k];
    const double along =
        (q.position() - path[k - 1].position()).dot(Vec2(std::cos(q.theta), std::sin(q.theta)));
    const int v = along > 0.0 ? 1 : (along < 0.0 ? -1 : piece.direction);
    if (piece.direction != 0 && v != piece.direction) {  // a cusp: stop, then drive the other way
      const Vec2 cusp = piece.points.back();
      pieces.push_back(std::move(piece));
      piece = DrivingPiece{{cusp}, 0};
    }
    piece.direction = v;
    piece.points.push_back(q.position());
  }
  pieces.push_back(std::move(piece));
  return pieces;
}

}  // namespace talus
