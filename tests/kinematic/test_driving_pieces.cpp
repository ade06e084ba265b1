// talus/kinematic/driving_pieces.hpp: a path split at its cusps.
#include <gtest/gtest.h>

#include <vector>

#include "talus/kinematic/driving_pieces.hpp"

namespace talus {
namespace {

std::vector<Vec2> points_of(const DrivingPiece& piece) {
  return piece.points;
}

TEST(DrivingPieces, ForwardReverseForward) {
  // Heading east throughout: east steps are forward, west steps reverse.
  const std::vector<SE2Pose> path{{0, 0, 0}, {1, 0, 0}, {2, 0, 0},   {1, 0.5, 0},
                                  {0, 1, 0}, {1, 1, 0}, {1, 1.5, 0}, {3, 1.5, 0}};
  const std::vector<DrivingPiece> pieces = split_at_cusps(path);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].direction, 1);
  EXPECT_EQ(points_of(pieces[0]), (std::vector<Vec2>{Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)}));
  EXPECT_EQ(pieces[1].direction, -1);
  EXPECT_EQ(points_of(pieces[1]), (std::vector<Vec2>{Vec2(2, 0), Vec2(1, 0.5), Vec2(0, 1)}));
  EXPECT_EQ(pieces[2].direction, 1);
  // The step north (perpendicular to the heading) keeps the forward direction.
  EXPECT_EQ(points_of(pieces[2]),
            (std::vector<Vec2>{Vec2(0, 1), Vec2(1, 1), Vec2(1, 1.5), Vec2(3, 1.5)}));
}

TEST(DrivingPieces, ReverseAloneIsOnePiece) {
  // Heading west while moving east: all reverse, no cusp.
  const double west = 3.141592653589793;
  const std::vector<DrivingPiece> pieces =
      split_at_cusps(std::vector<SE2Pose>{{0, 0, west}, {1, 0, west}, {2, 0, west}});
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].direction, -1);
  EXPECT_EQ(pieces[0].points.size(), 3u);
}

TEST(DrivingPieces, DegeneratePaths) {
  EXPECT_TRUE(split_at_cusps(std::vector<SE2Pose>{}).empty());
  const std::vector<DrivingPiece> one = split_at_cusps(std::vector<SE2Pose>{{4, 5, 1}});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].direction, 0);
  EXPECT_EQ(points_of(one[0]), (std::vector<Vec2>{Vec2(4, 5)}));
}

}  // namespace
}  // namespace talus
