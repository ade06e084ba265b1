// Planar polyline geometry (talus/core/polyline.hpp) against hand-computed
// distances, crossings and compass points.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/polyline.hpp"

namespace talus {
namespace {

// An L: east 4 m, then north 3 m.
const std::vector<Vec2> kEll{{0.0, 0.0}, {4.0, 0.0}, {4.0, 3.0}};

TEST(Polyline, DistanceToPolylineOfPointsNearEachPart) {
  EXPECT_DOUBLE_EQ(distance_to_polyline({2.0, 1.0}, kEll), 1.0);  // above the first leg
  EXPECT_DOUBLE_EQ(distance_to_polyline({6.0, 1.5}, kEll), 2.0);  // east of the second leg
  EXPECT_DOUBLE_EQ(distance_to_polyline({5.0, 5.0}, kEll), std::sqrt(5.0));  // past the end
  EXPECT_DOUBLE_EQ(distance_to_polyline({-3.0, -4.0}, kEll), 5.0);           // before the start
  EXPECT_DOUBLE_EQ(distance_to_polyline({3.0, 1.0}, kEll), 1.0);  // inside the corner: both legs
  EXPECT_EQ(distance_to_polyline({4.0, 2.0}, kEll), 0.0);         // on the line
  // One vertex is a point; a repeated vertex is a zero-length segment.
  EXPECT_DOUBLE_EQ(distance_to_polyline({3.0, 4.0}, std::vector<Vec2>{{0.0, 0.0}}), 5.0);
  EXPECT_DOUBLE_EQ(
      distance_to_polyline({1.0, 1.0}, std::vector<Vec2>{{0.0, 0.0}, {0.0, 0.0}, {2.0, 0.0}}), 1.0);
  EXPECT_THROW(distance_to_polyline({0.0, 0.0}, std::vector<Vec2>{}), InputError);
}

TEST(Polyline, HausdorffDistanceIsSymmetricAndTakesTheWorseDirection) {
  const std::vector<Vec2> base{{0.0, 0.0}, {10.0, 0.0}};
  const std::vector<Vec2> parallel{{0.0, 2.0}, {10.0, 2.0}};
  EXPECT_DOUBLE_EQ(hausdorff_distance(base, parallel), 2.0);
  // A bulge 3 m off the base: base's vertices lie on it, its apex is 3 m away.
  const std::vector<Vec2> bulge{{0.0, 0.0}, {5.0, 3.0}, {10.0, 0.0}};
  EXPECT_DOUBLE_EQ(hausdorff_distance(base, bulge), 3.0);
  EXPECT_DOUBLE_EQ(hausdorff_distance(bulge, base), 3.0);
  // A longer line contains the base: only its far end counts.
  const std::vector<Vec2> longer{{0.0, 0.0}, {20.0, 0.0}};
  EXPECT_DOUBLE_EQ(hausdorff_distance(base, longer), 10.0);
  EXPECT_DOUBLE_EQ(hausdorff_distance(longer, base), 10.0);
  EXPECT_EQ(hausdorff_distance(kEll, kEll), 0.0);
  EXPECT_THROW(hausdorff_distance(base, std::vector<Vec2>{}), InputError);
}

TEST(Polyline, ShareWithinCountsVerticesStrictlyCloserThanTheDistance) {
  const std::vector<Vec2> axis{{-1.0, 0.0}, {1.0, 0.0}};
  const std::vector<Vec2> points{{0.0, 1.0}, {0.0, 3.0}, {0.0, 0.5}, {0.0, 5.0}, {0.0, 2.0}};
  EXPECT_DOUBLE_EQ(share_within(points, axis, 2.0), 2.0 / 5.0);  // (0, 2) is at 2: not within
  EXPECT_DOUBLE_EQ(share_within(points, axis, 10.0), 1.0);
  EXPECT_DOUBLE_EQ(share_within(points, axis, 0.0), 0.0);
  EXPECT_THROW(share_within(std::vector<Vec2>{}, axis, 1.0), InputError);
}

TEST(Polyline, AxisCrossingInterpolatesTheFirstSegmentThatReachesTheTarget) {
  const std::vector<Vec2> tent{{0.0, 0.0}, {2.0, 2.0}, {4.0, 0.0}};
  const Vec2 east(1.0, 0.0);
  // The line x = 3 cuts the second segment at y = 1.
  const Vec2 p = axis_crossing(tent, Vec2::Zero(), east, {3.0, 10.0});
  EXPECT_DOUBLE_EQ(p.x(), 3.0);
  EXPECT_DOUBLE_EQ(p.y(), 1.0);
  // A vertex on the line is the crossing.
  EXPECT_EQ(axis_crossing(tent, Vec2::Zero(), east, {2.0, -7.0}), Vec2(2.0, 2.0));
  // An oblique axis: projection on (1, 1)/√2 of the target (1, 1) is √2, reached
  // half way along the first segment from (0, 0) to (2, 2) ... at (1, 1).
  const Vec2 q = axis_crossing(tent, Vec2::Zero(), Vec2(1.0, 1.0).normalized(), Vec2(2.0, 0.0));
  EXPECT_NEAR(q.x(), 1.0, 1e-15);
  EXPECT_NEAR(q.y(), 1.0, 1e-15);
  // Never reached: the vertex nearest to the target.
  EXPECT_EQ(axis_crossing(tent, Vec2::Zero(), east, {10.0, 1.0}), Vec2(4.0, 0.0));
  // A segment perpendicular to the axis cannot be interpolated and is skipped.
  const std::vector<Vec2> hook{{0.0, 0.0}, {0.0, 5.0}, {2.0, 5.0}};
  EXPECT_EQ(axis_crossing(hook, Vec2::Zero(), east, {0.0, 1.0}), Vec2(0.0, 5.0));
  EXPECT_THROW(axis_crossing(tent, Vec2::Zero(), Vec2(2.0, 0.0), Vec2::Zero()), InputError);
  EXPECT_THROW(axis_crossing(std::vector<Vec2>{}, Vec2::Zero(), east, Vec2::Zero()), InputError);
}

TEST(Polyline, CompassPointsOfTheEightDirectionsAndTheirSectors) {
  EXPECT_EQ(compass_point({1.0, 0.0}), "east");
  EXPECT_EQ(compass_point({1.0, 1.0}), "north-east");
  EXPECT_EQ(compass_point({0.0, 2.0}), "north");
  EXPECT_EQ(compass_point({-1.0, 1.0}), "north-west");
  EXPECT_EQ(compass_point({-3.0, 0.0}), "west");
  EXPECT_EQ(compass_point({-1.0, -1.0}), "south-west");
  EXPECT_EQ(compass_point({0.0, -1.0}), "south");
  EXPECT_EQ(compass_point({1.0, -1.0}), "south-east");
  // Sector edges at ±22.5°: 20° is still east, 25° north-east.
  const double deg = std::acos(-1.0) / 180.0;
  EXPECT_EQ(compass_point({std::cos(20 * deg), std::sin(20 * deg)}), "east");
  EXPECT_EQ(compass_point({std::cos(25 * deg), std::sin(25 * deg)}), "north-east");
  EXPECT_EQ(compass_point({std::cos(-160 * deg), std::sin(-160 * deg)}), "west");
  EXPECT_EQ(compass_point({-1.0, -1e-9}), "west");  // just below the ±180° seam
  EXPECT_THROW(compass_point(Vec2::Zero()), InputError);
  EXPECT_THROW(compass_point({std::nan(""), 1.0}), InputError);
  EXPECT_THROW(compass_point({std::numeric_limits<double>::infinity(), 1.0}), InputError);
}

}  // namespace
}  // namespace talus
