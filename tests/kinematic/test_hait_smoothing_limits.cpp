// The pair limits of the Haït smoothing (§4.4): the paper's hint, pairs
// limited by the number of controls they span, and the invariants every run
// keeps (never longer, never more controls, ends fixed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/hait/hait_smoothing.hpp"
#include "talus/kinematic/reeds_shepp.hpp"

namespace talus {
namespace {

/// A wiggle: `runs` arcs of 0.4 m (0.4 rad at radius 1 m) alternately left
/// and right, forward, sampled every 0.1 m: `runs` controls.
std::vector<PathPoint> wiggle(int runs) {
  std::vector<PathPoint> path{{{0.0, 0.0, 0.0}, Control{}}};
  for (int r = 0; r < runs; ++r) {
    const Control u{1, r % 2 == 0 ? 1 : -1};
    const SE2Pose from = path.back().pose;
    for (int k = 1; k <= 4; ++k) path.push_back({apply_control(from, u, 0.1 * k, 1.0), u});
  }
  return path;
}

ConfigurationCheck always_valid(const SE2Pose&) {
  return {true, 1.0, 1};
}

HaitSmoothingOptions pairs(std::size_t max_controls, bool within) {
  HaitSmoothingOptions o;
  o.iterations = 3000;
  o.max_span = 0.0;
  o.max_span_controls = max_controls;
  o.draw_within_span = within;
  o.seed = 5;
  return o;
}

TEST(HaitSmoothingLimits, ControlsAreControlChangesPlusOne) {
  const std::vector<PathPoint> path = wiggle(12);
  ASSERT_EQ(control_changes(path), 11u);
  HaitSmoothingReport r;
  smooth_path(path, always_valid, ReedsShepp(1.0), pairs(0, true), &r);
  EXPECT_EQ(r.controls_before(), 12u);
  EXPECT_EQ(r.controls_after(), r.control_changes_after + 1);
}

TEST(HaitSmoothingLimits, OneControlPairsCannotChangeAWiggle) {
  // A portion inside one arc of 0.4 rad is already the shortest curve of bounded curvature
  // between its ends, so pairs that span one control replace nothing; without the limit the
  // same pairs straighten the wiggle.
  const std::vector<PathPoint> path = wiggle(12);
  const ReedsShepp curves(1.0);
  for (const bool within : {true, false}) {
    HaitSmoothingReport one, free;
    const std::vector<PathPoint> same =
        smooth_path(path, always_valid, curves, pairs(1, within), &one);
    smooth_path(path, always_valid, curves, pairs(0, within), &free);
    EXPECT_EQ(one.replacements, 0u) << within;
    EXPECT_EQ(one.controls_after(), 12u);
    EXPECT_EQ(same.size(), path.size());
    EXPECT_GT(free.replacements, 0u);
    EXPECT_LE(free.controls_after(), 5u);  // about one Reeds–Shepp curve end to end
  }
}

TEST(HaitSmoothingLimits, EveryPairLimitKeepsTheInvariants) {
  // Invariants for every limit: never more controls, never longer, the ends fixed.
  const std::vector<PathPoint> path = wiggle(16);
  const ReedsShepp curves(1.0);
  const double before = path_length(path, 1.0);
  for (const std::size_t n : {1u, 2u, 3u, 4u, 6u, 10u, 0u}) {
    HaitSmoothingReport r;
    const std::vector<PathPoint> out = smooth_path(path, always_valid, curves, pairs(n, true), &r);
    EXPECT_LE(r.controls_after(), r.controls_before()) << n;
    EXPECT_LE(r.length_after, before + 1e-12) << n;
    EXPECT_NEAR(path_length(out, 1.0), r.length_after, 1e-12);
    EXPECT_EQ(out.front().pose.x, path.front().pose.x);
    EXPECT_EQ(out.back().pose.x, path.back().pose.x);
    EXPECT_EQ(out.back().pose.y, path.back().pose.y);
    EXPECT_EQ(out.back().pose.theta, path.back().pose.theta);
  }
}

}  // namespace
}  // namespace talus
