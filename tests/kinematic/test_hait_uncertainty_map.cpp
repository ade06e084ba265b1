// The per-node terrain uncertainty map of the Haït planner (§5.1: "an interval
// δz associated with each point of the grid"; §5.3.1: the cost bitmap
// penalises high-uncertainty areas): a map holding one value everywhere is the
// constant δz exactly, a local patch changes the checks only near it, and the
// options refuse ambiguous or mis-shaped input.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"
#include "talus/kinematic/hait/hait_robot_validity.hpp"
#include "talus/kinematic/hait/hait_scenarios.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {
namespace {

Robot chassis() {
  return load_robot(std::string(TALUS_DATA_DIR) + "/robots/marsokhod_chassis.yaml");
}

/// A mildly rough 10 m × 10 m plain (41 × 41 nodes at 0.25 m).
ElevationGrid plain() {
  return hait_fractal_base(41, 41, 0.25, 0.15, 11);
}

std::shared_ptr<const ElevationGrid> constant_map(const ElevationGrid& g, double dz) {
  return std::make_shared<const ElevationGrid>(g.ncols(), g.nrows(), g.cellsize(), g.x_min(),
                                               g.y_min(), dz);
}

/// Configurations on a lattice over the map's interior, every heading octant.
std::vector<SE2Pose> probe_poses() {
  std::vector<SE2Pose> poses;
  for (double x = 1.5; x <= 8.5; x += 0.35)
    for (double y = 1.5; y <= 8.5; y += 0.35)
      for (int k = 0; k < 8; ++k) poses.push_back({x, y, k * std::numbers::pi / 4.0});
  return poses;
}

TEST(HaitUncertaintyMap, ConstantMapIsTheConstantDeltaZ) {
  // The plain and a steep hill, so that the probes meet valid and invalid configurations.
  ElevationGrid g = plain();
  const GaussianHill hill{Vec2(6.0, 4.0), 1.2, 0.9};
  add_hills(g, std::span<const GaussianHill>(&hill, 1));
  const RuledTerrain terrain(g);
  for (const bool positional : {false, true}) {
    const double dz = 0.02;
    HaitValidityOptions constant;
    constant.terrain_uncertainty = dz;
    if (positional) {
      constant.position_uncertainty = 0.1;
      constant.heading_uncertainty = 0.15;
    }
    HaitValidityOptions mapped = constant;
    mapped.terrain_uncertainty = 0.0;
    mapped.terrain_uncertainty_map = constant_map(g, dz);
    const HaitRobotValidity a(terrain, chassis(), constant), b(terrain, chassis(), mapped);
    std::size_t valid = 0, invalid = 0;
    for (const SE2Pose& q : probe_poses()) {
      const ConfigurationCheck ca = a.check(q), cb = b.check(q);
      ASSERT_EQ(ca.valid, cb.valid) << q.x << ", " << q.y << ", " << q.theta;
      EXPECT_EQ(ca.margin, cb.margin);
      EXPECT_EQ(ca.placements, cb.placements);
      (ca.valid ? valid : invalid) += 1;
    }
    // The probes see both outcomes, so the comparison can fail.
    EXPECT_GT(valid, 50u) << "positional " << positional;
    EXPECT_GT(invalid, 50u) << "positional " << positional;
  }
}

TEST(HaitUncertaintyMap, ZeroMapIsTheWorstCaseOfTheTerrainItself) {
  // δz = 0 everywhere: the envelopes are the terrain, so the worst-case checks see the nominal
  // placement only and accept exactly what the certain model accepts.
  const ElevationGrid g = plain();
  const RuledTerrain terrain(g);
  HaitValidityOptions mapped;
  mapped.terrain_uncertainty_map = constant_map(g, 0.0);
  const HaitRobotValidity certain(terrain, chassis(), HaitValidityOptions{});
  const HaitRobotValidity zero(terrain, chassis(), mapped);
  for (const SE2Pose& q : probe_poses()) {
    EXPECT_EQ(certain.check(q).valid, zero.check(q).valid) << q.x << ", " << q.y;
  }
}

TEST(HaitUncertaintyMap, PatchActsOnlyNearIt) {
  const ElevationGrid g = plain();
  const RuledTerrain terrain(g);
  const Vec2 centre(5.0, 5.0);
  HaitValidityOptions low, patched;
  low.terrain_uncertainty = 0.01;
  patched.terrain_uncertainty_map =
      std::make_shared<const ElevationGrid>(uncertainty_disc_map(g, 0.01, centre, 1.0, 0.3));
  const HaitRobotValidity a(terrain, chassis(), low), b(terrain, chassis(), patched);
  std::size_t far = 0, inside_invalid = 0, inside = 0;
  for (const SE2Pose& q : probe_poses()) {
    const double d = (q.position() - centre).norm();
    const ConfigurationCheck ca = a.check(q), cb = b.check(q);
    // Beyond the patch + the robot's reach (its footprint's radius) + two cell diagonals (an
    // outer axle's placement is read bilinearly from nodes whose own wheels sit on other cells),
    // nothing changes.
    if (d > 1.0 + a.radius() + 2.0 * std::sqrt(2.0) * 0.25) {
      EXPECT_EQ(ca.valid, cb.valid) << q.x << ", " << q.y << ", " << q.theta;
      if (ca.valid) {
        EXPECT_EQ(ca.margin, cb.margin) << q.x << ", " << q.y << ", " << q.theta << ", d " << d;
      }
      ++far;
    }
    // On the patch, δz = 0.3 m: a wheel pair spread over ±0.3 m gives axle rolls up to
    // atan(0.6 / 0.9) ≈ 0.59 rad beyond the 0.35 rad limit on the roll difference.
    if (d < 0.5) {
      ++inside;
      inside_invalid += cb.valid ? 0 : 1;
      EXPECT_FALSE(cb.valid) << q.x << ", " << q.y << ", " << q.theta;
    }
    // A wider interval never accepts what a narrower one refuses.
    if (!ca.valid) {
      EXPECT_FALSE(cb.valid);
    }
  }
  EXPECT_GT(far, 1000u);
  EXPECT_GT(inside, 0u);
  EXPECT_EQ(inside_invalid, inside);
}

TEST(HaitUncertaintyMap, PlannerWithAConstantMapIsThePlannerWithTheConstant) {
  const ElevationGrid g = plain();
  const RuledTerrain terrain(g);
  HaitOptions constant;
  constant.terrain_uncertainty = 0.03;
  HaitOptions mapped;
  mapped.terrain_uncertainty_map = constant_map(g, 0.03);
  const SE2Pose start{1.5, 2.0, 0.0}, goal{8.5, 8.0, std::numbers::pi / 2.0};
  const HaitResult a = plan_hait(terrain, chassis(), start, goal, constant);
  const HaitResult b = plan_hait(terrain, chassis(), start, goal, mapped);
  ASSERT_EQ(a.status, HaitStatus::kFound) << a.message;
  ASSERT_EQ(b.status, HaitStatus::kFound) << b.message;
  EXPECT_EQ(a.nodes_created, b.nodes_created);
  EXPECT_EQ(a.placements, b.placements);
  EXPECT_EQ(a.length_m, b.length_m);
  ASSERT_EQ(a.path.size(), b.path.size());
  for (std::size_t k = 0; k < a.path.size(); ++k) {
    EXPECT_EQ(a.path[k].pose.x, b.path[k].pose.x);
    EXPECT_EQ(a.path[k].pose.y, b.path[k].pose.y);
  }
}

TEST(HaitUncertaintyMap, PlannerRouteAvoidsAHighUncertaintyPatch) {
  // A patch on the straight line from start to goal, too uncertain to cross: the route keeps its
  // reference point out of it and is no shorter than the route without it.
  const ElevationGrid g = plain();
  const RuledTerrain terrain(g);
  const SE2Pose start{1.5, 5.0, 0.0}, goal{8.5, 5.0, 0.0};
  const Vec2 centre(5.0, 5.0);
  HaitOptions low;
  low.terrain_uncertainty = 0.01;
  HaitOptions patched;
  patched.terrain_uncertainty_map =
      std::make_shared<const ElevationGrid>(uncertainty_disc_map(g, 0.01, centre, 1.0, 0.3));
  const HaitResult a = plan_hait(terrain, chassis(), start, goal, low);
  const HaitResult b = plan_hait(terrain, chassis(), start, goal, patched);
  ASSERT_EQ(a.status, HaitStatus::kFound) << a.message;
  ASSERT_EQ(b.status, HaitStatus::kFound) << b.message;
  EXPECT_GT(length_within_disc(a.path, centre, 1.0), 1.0);  // the straight route crosses it
  EXPECT_EQ(length_within_disc(b.path, centre, 1.0), 0.0);
  EXPECT_GE(b.length_m, a.length_m);
}

TEST(HaitUncertaintyMap, OptionsRefuseAmbiguousOrMisshapedMaps) {
  const ElevationGrid g = plain();
  const RuledTerrain terrain(g);
  HaitValidityOptions both;
  both.terrain_uncertainty = 0.02;
  both.terrain_uncertainty_map = constant_map(g, 0.02);
  EXPECT_THROW(both.validate(), InputError);
  EXPECT_THROW(HaitRobotValidity(terrain, chassis(), both), InputError);
  HaitOptions planner;
  planner.terrain_uncertainty = 0.02;
  planner.terrain_uncertainty_map = constant_map(g, 0.02);
  EXPECT_THROW(planner.validate(), InputError);
  // A map of another shape.
  HaitValidityOptions wrong;
  wrong.terrain_uncertainty_map = std::make_shared<const ElevationGrid>(
      g.ncols() - 1, g.nrows(), g.cellsize(), g.x_min(), g.y_min(), 0.02);
  EXPECT_THROW(HaitRobotValidity(terrain, chassis(), wrong), InputError);
  // A negative δz.
  HaitValidityOptions negative;
  auto bad = std::make_shared<ElevationGrid>(g.ncols(), g.nrows(), g.cellsize(), g.x_min(),
                                             g.y_min(), 0.02);
  bad->at(3, 4) = -0.01;
  negative.terrain_uncertainty_map = bad;
  EXPECT_THROW(HaitRobotValidity(terrain, chassis(), negative), InputError);
}

}  // namespace
}  // namespace talus
