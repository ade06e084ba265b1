// driven_path_time: a path of configurations driven at its time-optimal profile along its own
// segments and arcs, split at cusps. Checked against the bang-coast-bang closed form on flat
// ground, against the same motion described with the opposite heading (a point mass does not
// care which way it faces), against its mirror image, and for its status and input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/optimal/driven_path_time.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace {

using namespace talus;
using talus::terrain_test::gaussian_hill;
using talus::terrain_test::grid_around_origin;

/// Top speed 2 m/s, drive and brake 1 m/s²: a rest-to-rest run of length L >= 4 m on flat
/// ground takes L / 2 + 2 s (2 s and 2 m to reach 2 m/s, the same to stop: 1 s more than
/// covering those 4 m at the top speed, twice).
Vehicle slow_rover(double mu = 0.7) {
  Vehicle v = talus::vehicle_test::point_mass_rover(mu);
  v.max_speed = 2.0;
  v.max_accel = 1.0;
  v.max_decel = 1.0;
  return v;
}

BPatch flat() {
  return BPatch::interpolate(grid_around_origin([](double, double) { return 0.0; }, 10.0, 1.0));
}

/// Configurations every 0.1 m from x0 to x1 along y = 0, all with heading `theta`.
std::vector<SE2Pose> along_x(double x0, double x1, double theta) {
  std::vector<SE2Pose> poses;
  const int n = static_cast<int>(std::lround(std::abs(x1 - x0) / 0.1));
  for (int k = 0; k <= n; ++k) poses.push_back({x0 + (x1 - x0) * k / n, 0.0, theta});
  return poses;
}

/// A counter-clockwise arc of radius `r` about the origin from angle a0 to a1, heading along
/// travel (+ `offset`, e.g. π to describe the same motion in reverse), at 0.1 rad steps.
std::vector<SE2Pose> arc(double r, double a0, double a1, double offset = 0.0) {
  std::vector<SE2Pose> poses;
  const int n = static_cast<int>(std::lround((a1 - a0) / 0.05));
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + (a1 - a0) * k / n;
    poses.push_back({r * std::cos(a), r * std::sin(a), a + 0.5 * std::numbers::pi + offset});
  }
  return poses;
}

TEST(DrivenPathTime, StraightRunOnFlatGroundIsTheBangCoastBangTime) {
  const DrivenPathResult r = driven_path_time(flat(), slow_rover(), along_x(-5.0, 5.0, 0.0));
  ASSERT_EQ(r.status, DrivenPathStatus::kOk) << r.message;
  ASSERT_EQ(r.pieces.size(), 1u);
  EXPECT_EQ(r.pieces[0].direction, 1);
  EXPECT_EQ(r.pieces[0].stations, 101u);
  EXPECT_NEAR(r.length, 10.0, 1e-12);
  EXPECT_NEAR(r.travel_time, 10.0 / 2.0 + 2.0, 1e-9);
}

TEST(DrivenPathTime, ACuspSplitsThePathIntoTwoRestToRestPieces) {
  std::vector<SE2Pose> path = along_x(-5.0, 0.0, 0.0);
  const std::vector<SE2Pose> back = along_x(0.0, -5.0, 0.0);  // reversing, facing east
  path.insert(path.end(), back.begin() + 1, back.end());
  const DrivenPathResult r = driven_path_time(flat(), slow_rover(), path);
  ASSERT_EQ(r.status, DrivenPathStatus::kOk) << r.message;
  ASSERT_EQ(r.pieces.size(), 2u);
  EXPECT_EQ(r.pieces[0].direction, 1);
  EXPECT_EQ(r.pieces[1].direction, -1);
  EXPECT_EQ(r.pieces[0].last, r.pieces[1].first);
  EXPECT_EQ(r.pieces[1].last, path.size() - 1);
  EXPECT_NEAR(r.pieces[0].travel_time, 5.0 / 2.0 + 2.0, 1e-9);
  EXPECT_NEAR(r.pieces[1].travel_time, 5.0 / 2.0 + 2.0, 1e-9);
  EXPECT_NEAR(r.travel_time, 9.0, 1e-9);
}

TEST(DrivenPathTime, ArcsHaveTheirExactLength) {
  const double r = 3.0;
  const DrivenPathResult d = driven_path_time(flat(), slow_rover(), arc(r, 0.0, 2.0));
  ASSERT_EQ(d.status, DrivenPathStatus::kOk) << d.message;
  EXPECT_NEAR(d.planar_length, r * 2.0, 1e-12);
  EXPECT_NEAR(d.length, r * 2.0, 1e-9);  // flat: the 3-D length is the planar one
  // The turn cannot be faster than its length at the top speed plus the start and stop.
  EXPECT_GE(d.travel_time, r * 2.0 / 2.0 + 2.0 - 1e-9);
}

TEST(DrivenPathTime, TheSameMotionFacingBackwardsTakesTheSameTime) {
  // On a hill, so that slope and curvature both matter: driving forward along the arc, or in
  // reverse along it with the heading turned by π, is the same motion of a point mass.
  const BPatch hill =
      BPatch::interpolate(grid_around_origin(gaussian_hill({1.0, 0.5}, 1.5, 2.0), 10.0, 0.5));
  const DrivenPathResult forward = driven_path_time(hill, slow_rover(), arc(4.0, -1.0, 2.5));
  const DrivenPathResult reverse =
      driven_path_time(hill, slow_rover(), arc(4.0, -1.0, 2.5, std::numbers::pi));
  ASSERT_EQ(forward.status, DrivenPathStatus::kOk) << forward.message;
  ASSERT_EQ(reverse.status, DrivenPathStatus::kOk) << reverse.message;
  ASSERT_EQ(reverse.pieces.size(), 1u);
  EXPECT_EQ(reverse.pieces[0].direction, -1);
  EXPECT_NEAR(reverse.travel_time, forward.travel_time, 1e-9 * forward.travel_time);
  EXPECT_GT(forward.travel_time, 4.0 * 3.5 / 2.0 + 2.0);  // the hill slows it below flat ground
}

TEST(DrivenPathTime, MirrorImagesTakeTheSameTimeOnFlatGround) {
  std::vector<SE2Pose> left = arc(2.0, -1.5, 1.5), right;
  for (const SE2Pose& q : left) right.push_back({q.x, -q.y, -q.theta});
  const DrivenPathResult l = driven_path_time(flat(), slow_rover(0.3), left);
  const DrivenPathResult r = driven_path_time(flat(), slow_rover(0.3), right);
  ASSERT_EQ(l.status, DrivenPathStatus::kOk) << l.message;
  EXPECT_NEAR(l.travel_time, r.travel_time, 1e-9 * l.travel_time);
  // With mu 0.3 the sliding limit sqrt(mu g r) = 2.43 m/s is above the top speed; with 0.05 it
  // is 0.99 m/s, so the turn must be slower.
  const DrivenPathResult slippery = driven_path_time(flat(), slow_rover(0.05), left);
  EXPECT_GT(slippery.travel_time, l.travel_time);
}

TEST(DrivenPathTime, ASlopeTooSteepForTheFrictionIsInfeasible) {
  const BPatch ramp =
      BPatch::interpolate(grid_around_origin([](double x, double) { return x; }, 10.0, 1.0));
  const DrivenPathResult r = driven_path_time(ramp, slow_rover(0.5), along_x(-5.0, 5.0, 0.0));
  EXPECT_EQ(r.status, DrivenPathStatus::kInfeasible);
  EXPECT_TRUE(std::isinf(r.travel_time));
  EXPECT_FALSE(r.message.empty());
  EXPECT_NE(r.brief_report().find("infeasible"), std::string::npos);
}

TEST(DrivenPathTime, RepeatedConfigurationsCountAsOneAndAStandingPathTakesNoTime) {
  std::vector<SE2Pose> path = along_x(-5.0, 5.0, 0.0);
  path.insert(path.begin() + 30, path[30]);
  const DrivenPathResult r = driven_path_time(flat(), slow_rover(), path);
  EXPECT_EQ(r.pieces.at(0).stations, 101u);
  EXPECT_NEAR(r.travel_time, 7.0, 1e-9);
  const std::vector<SE2Pose> standing(3, SE2Pose{1.0, 1.0, 0.3});
  const DrivenPathResult s = driven_path_time(flat(), slow_rover(), standing);
  EXPECT_EQ(s.status, DrivenPathStatus::kOk);
  EXPECT_EQ(s.travel_time, 0.0);
  EXPECT_TRUE(s.pieces.empty());
}

TEST(DrivenPathTime, APathThatMovesSidewaysHasNoDrivingDirection) {
  // Facing north-east while moving east: no segment or arc along the heading joins these.
  const DrivenPathResult r =
      driven_path_time(flat(), slow_rover(), along_x(-5.0, 5.0, 0.25 * std::numbers::pi));
  EXPECT_EQ(r.status, DrivenPathStatus::kNotTangent);
  EXPECT_TRUE(std::isinf(r.travel_time));
  EXPECT_TRUE(r.pieces.empty());
  EXPECT_NE(r.message.find("configuration 0 to 1"), std::string::npos) << r.message;
}

TEST(DrivenPathTime, BadInputIsAnInputError) {
  const BPatch surface = flat();
  const std::vector<SE2Pose> one = {{0.0, 0.0, 0.0}};
  EXPECT_THROW(driven_path_time(surface, slow_rover(), one), InputError);
  const std::vector<SE2Pose> nan = {{0.0, 0.0, 0.0},
                                    {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}};
  EXPECT_THROW(driven_path_time(surface, slow_rover(), nan), InputError);
  const std::vector<SE2Pose> off = {{0.0, 0.0, 0.0}, {50.0, 0.0, 0.0}};
  EXPECT_THROW(driven_path_time(surface, slow_rover(), off), InputError);
  DrivenPathOptions options;
  options.cusp_speed = -1.0;
  EXPECT_THROW(driven_path_time(surface, slow_rover(), along_x(0.0, 1.0, 0.0), options),
               InputError);
}

}  // namespace
