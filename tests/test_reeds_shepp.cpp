#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "talus/core/error.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/reeds_shepp.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

/// Uniform in [lo, hi) from raw mt19937_64 bits (platform-independent).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

SE2Pose random_pose(std::mt19937_64& rng) {
  return {uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -kPi, kPi)};
}

TEST(ConfigurationSpace, ApplyControlFollowsExactArcs) {
  // A quarter circle to the left of radius 2 from the origin facing east.
  const SE2Pose q = apply_control({0, 0, 0}, {1, 1}, kPi, 2.0);
  EXPECT_NEAR(q.x, 2.0, 1e-12);
  EXPECT_NEAR(q.y, 2.0, 1e-12);
  EXPECT_NEAR(q.theta, kPi / 2, 1e-12);
  // Reversing with the wheels steered left turns clockwise, backing onto the left circle.
  const SE2Pose r = apply_control({0, 0, 0}, {-1, -1}, kPi, 2.0);
  EXPECT_NEAR(r.x, -2.0, 1e-12);
  EXPECT_NEAR(r.y, 2.0, 1e-12);
  EXPECT_NEAR(r.theta, -kPi / 2, 1e-12);
  EXPECT_EQ(control_name({-1, -1}), "reverse-left");
  EXPECT_EQ(control_name({1, -1}), "forward-right");
  EXPECT_EQ(control_name({}), "none");
  // Driving forward then back the same way returns to the start.
  const SE2Pose back =
      apply_control(apply_control({1, 2, 0.3}, {1, -1}, 0.7, 1.5), {-1, 1}, 0.7, 1.5);
  EXPECT_NEAR(back.x, 1.0, 1e-12);
  EXPECT_NEAR(back.y, 2.0, 1e-12);
  EXPECT_NEAR(back.theta, 0.3, 1e-12);
}

TEST(ConfigurationSpace, ControlChangesCountSwitchesOnly) {
  std::vector<PathPoint> p{{{}, {}}, {{}, {1, 0}}, {{}, {1, 0}}, {{}, {1, 1}}, {{}, {-1, 1}}};
  EXPECT_EQ(control_changes(p), 2u);
  p.resize(3);
  EXPECT_EQ(control_changes(p), 0u);
}

TEST(ReedsShepp, StraightTranslationDistanceIsItsLength) {
  const ReedsShepp rs(1.0);
  EXPECT_NEAR(rs.distance({0, 0, 0}, {3, 0, 0}), 3.0, 1e-9);
  EXPECT_NEAR(rs.distance({1, 1, kPi / 4}, {3, 3, kPi / 4}), std::sqrt(8.0), 1e-9);
  // Straight back: reverse.
  EXPECT_NEAR(rs.distance({0, 0, 0}, {-2, 0, 0}), 2.0, 1e-9);
  const auto fwd = rs.segments({0, 0, 0}, {3, 0, 0});
  ASSERT_EQ(fwd.size(), 1u);
  EXPECT_EQ(fwd[0].control, (Control{1, 0}));
  const auto rev = rs.segments({0, 0, 0}, {-2, 0, 0});
  ASSERT_EQ(rev.size(), 1u);
  EXPECT_EQ(rev[0].control, (Control{-1, 0}));
  EXPECT_NEAR(rev[0].length, 2.0, 1e-9);
}

TEST(ReedsShepp, QuarterTurnIsOneArc) {
  const double r = 1.5;
  const ReedsShepp rs(r);
  EXPECT_NEAR(rs.distance({0, 0, 0}, {r, r, kPi / 2}), r * kPi / 2, 1e-9);
  const auto segs = rs.segments({0, 0, 0}, {r, r, kPi / 2});
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].control, (Control{1, 1}));
}

TEST(ReedsShepp, DistanceIsASymmetricMetric) {
  const ReedsShepp rs(0.8);
  std::mt19937_64 rng(7);
  for (int k = 0; k < 200; ++k) {
    const SE2Pose a = random_pose(rng), b = random_pose(rng), c = random_pose(rng);
    const double ab = rs.distance(a, b);
    EXPECT_NEAR(ab, rs.distance(b, a), 1e-9);
    EXPECT_GE(ab + 1e-9, std::hypot(a.x - b.x, a.y - b.y));  // never below the straight line
    EXPECT_LE(rs.distance(a, c), ab + rs.distance(b, c) + 1e-9);
  }
  EXPECT_NEAR(rs.distance({1, 2, 3}, {1, 2, 3}), 0.0, 1e-12);
}

TEST(ReedsShepp, SamplerMatchesOmplAndEndsAtTheGoal) {
  const ReedsShepp rs(1.2);
  std::mt19937_64 rng(11);
  for (int k = 0; k < 100; ++k) {
    const SE2Pose a = random_pose(rng), b = random_pose(rng);
    const double spacing = 0.1;
    const std::vector<PathPoint> pts = rs.sample(a, b, spacing);
    const double total = rs.distance(a, b);
    ASSERT_GE(pts.size(), 2u);
    EXPECT_EQ(pts.front().control, Control{});
    EXPECT_DOUBLE_EQ(pts.back().pose.x, b.x);
    EXPECT_DOUBLE_EQ(pts.back().pose.y, b.y);
    EXPECT_NEAR(path_length(pts, 1.2), total, 1e-6);
    double s = 0.0;
    for (std::size_t i = 1; i < pts.size(); ++i) {
      const std::span<const PathPoint> piece(pts.data() + i - 1, 2);
      const double ds = path_length(piece, 1.2);
      EXPECT_LE(ds, spacing + 1e-9);
      s += ds;
      // OMPL's interpolation at the same fraction of the curve lands on our sample.
      const SE2Pose o = rs.ompl_interpolate(a, b, s / total);
      EXPECT_NEAR(o.x, pts[i].pose.x, 1e-6);
      EXPECT_NEAR(o.y, pts[i].pose.y, 1e-6);
      EXPECT_NEAR(wrap_angle(o.theta - pts[i].pose.theta), 0.0, 1e-6);
    }
    EXPECT_LE(control_changes(pts), 4u);  // at most five segments
  }
}

TEST(ReedsShepp, RejectsBadInput) {
  EXPECT_THROW(ReedsShepp(0.0), InputError);
  EXPECT_THROW(ReedsShepp(-1.0), InputError);
  const ReedsShepp rs(1.0);
  EXPECT_THROW(rs.sample({0, 0, 0}, {1, 0, 0}, 0.0), InputError);
  EXPECT_THROW(rs.distance({NAN, 0, 0}, {1, 0, 0}), InputError);
}

}  // namespace
}  // namespace talus
