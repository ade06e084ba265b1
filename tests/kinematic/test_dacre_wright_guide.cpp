// The Dacre-Wright voxel channel as a guide for the Haït search
// (HaitOptions::allowed_region filled by dacre_wright_channel_region): the
// region's membership against the channel boxes, the guided search expanding
// fewer nodes and keeping every configuration of its path in the region, and a
// start outside the region reported as such.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/dacre_wright/channel_region.hpp"
#include "talus/kinematic/dacre_wright/dacre_wright_planner.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

const WheeledRobot& six_wheel() {
  static const WheeledRobot r =
      load_dacre_wright_robot(TALUS_DATA_DIR "/robots/dacre_wright_six_wheel.yaml");
  return r;
}

/// The dacre-wright-octree experiment's map: 64 x 64 at 0.25 m, fractal, seed 1993.
const RuledTerrain& map64() {
  static const RuledTerrain t = [] {
    FractalTerrainOptions f;
    f.shape = {64, 64, 0.25, 0.0, 0.0};
    f.height_scale = 0.6;
    f.seed = 1993;
    return RuledTerrain(generate_fractal_terrain(f));
  }();
  return t;
}

/// q in box b grown by m (x, y) and t (θ), θ compared up to whole turns.
bool in_grown_box(const CsBox& b, const SE2Pose& q, double m, double t) {
  if (q.x < b.x1 - m || q.x > b.x2 + m || q.y < b.y1 - m || q.y > b.y2 + m) return false;
  for (int turns = -3; turns <= 3; ++turns) {
    const double th = q.theta + 2 * kPi * turns;
    if (th >= b.theta1 - t && th <= b.theta2 + t) return true;
  }
  return false;
}

TEST(DacreWrightGuide, RegionIsTheUnionOfTheGrownChannelBoxes) {
  DacreWrightResult r;
  r.channel_boxes = {{1, 2, 1, 2, 0, 0.5}, {2, 3, 1, 2, 6.0, 2 * kPi}};
  const auto exact = dacre_wright_channel_region(r);
  EXPECT_TRUE(exact({1.5, 1.5, 0.25}));
  EXPECT_TRUE(exact({1.5, 1.5, 0.25 + 4 * kPi}));  // whole turns
  EXPECT_TRUE(exact({2.0, 1.0, 0.5}));             // the closed box's corner
  EXPECT_FALSE(exact({1.5, 1.5, 0.6}));
  EXPECT_TRUE(exact({2.5, 1.5, -0.1}));  // -0.1 + 2π in [6, 2π]
  EXPECT_FALSE(exact({2.5, 1.5, 0.25}));
  EXPECT_FALSE(exact({3.1, 1.5, 6.1}));
  const auto grown = dacre_wright_channel_region(r, {0.2, 0.3});
  EXPECT_TRUE(grown({3.1, 1.5, 6.1}));
  EXPECT_TRUE(grown({1.5, 1.5, 0.75}));
  EXPECT_TRUE(grown({2.5, 1.5, 0.25}));  // 2π + 0.3 wraps past 0
  EXPECT_FALSE(grown({3.3, 1.5, 6.1}));
  EXPECT_FALSE(dacre_wright_channel_region(DacreWrightResult{})({1.5, 1.5, 0.25}));
  EXPECT_THROW(dacre_wright_channel_region(r, {-0.1, 0.0}), InputError);
  EXPECT_THROW(dacre_wright_channel_region(r, {0.0, std::nan("")}), InputError);
}

TEST(DacreWrightGuide, TheChannelPrunesTheHaitSearchAndHoldsItsPath) {
  const SE2Pose start{3.0, 3.0, 0.0}, goal{12.5, 12.5, 1.5};
  DacreWrightOptions dw;
  dw.octree.max_level = 6;
  const DacreWrightResult channel = plan_dacre_wright(map64(), six_wheel(), start, goal, dw);
  ASSERT_TRUE(channel.found()) << channel.brief_report();

  HaitOptions o;
  o.heuristic = HaitHeuristic::kEuclidean;
  const HaitResult free = plan_hait(map64(), Robot(six_wheel()), start, goal, o);
  ASSERT_EQ(free.status, HaitStatus::kFound) << free.message;
  // Grown by one Haït cell in x, y and θ (the exact channel is narrower than the arcs).
  const double m = o.cell_size, t = 2 * kPi / o.theta_bins;
  o.allowed_region = dacre_wright_channel_region(channel, {m, t});
  const HaitResult guided = plan_hait(map64(), Robot(six_wheel()), start, goal, o);
  ASSERT_EQ(guided.status, HaitStatus::kFound) << guided.message;
  EXPECT_LT(guided.nodes_developed, free.nodes_developed);
  EXPECT_LT(guided.placements, free.placements);
  // Every configuration of the guided path lies in a grown channel box, and
  // the unguided path leaves them (so the restriction is not vacuous).
  for (const PathPoint& p : guided.path) {
    bool inside = false;
    for (const CsBox& b : channel.channel_boxes) inside = inside || in_grown_box(b, p.pose, m, t);
    EXPECT_TRUE(inside) << p.pose.x << " " << p.pose.y << " " << p.pose.theta;
  }
  std::size_t outside = 0;
  for (const PathPoint& p : free.path) {
    bool inside = false;
    for (const CsBox& b : channel.channel_boxes) inside = inside || in_grown_box(b, p.pose, m, t);
    outside += inside ? 0 : 1;
  }
  EXPECT_GT(outside, 0u);
}

TEST(DacreWrightGuide, AStartOutsideTheRegionIsInvalidWithTheReason) {
  const SE2Pose start{3.0, 3.0, 0.0}, goal{12.5, 12.5, 1.5};
  HaitOptions o;
  o.allowed_region = [](const SE2Pose& q) { return q.x > 5.0; };
  const HaitResult r = plan_hait(map64(), Robot(six_wheel()), start, goal, o);
  EXPECT_EQ(r.status, HaitStatus::kStartInvalid);
  EXPECT_NE(r.message.find("outside the allowed region"), std::string::npos) << r.message;
  o.allowed_region = [](const SE2Pose& q) { return q.x < 5.0; };
  const HaitResult g = plan_hait(map64(), Robot(six_wheel()), start, goal, o);
  EXPECT_EQ(g.status, HaitStatus::kGoalInvalid);
  EXPECT_NE(g.message.find("outside the allowed region"), std::string::npos) << g.message;
}

}  // namespace
}  // namespace talus
