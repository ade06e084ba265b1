// Eldershaw and Yim 2001 §3.2, the foot-level planner: along CG paths of the
// high-level planner, every step is checked independently of the planner's
// quadrant rule: the CG lies inside the support polygon (convex hull) of the
// feet in contact, every contact foot is inside its leg's range at that CG
// pose, on a footmap-valid terrain node, at the node's height, and reaches
// below the under-carriage; consecutive steps change one thing only.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "planar_geometry_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/kinematic/eldershaw_yim/eldershaw_yim_planner.hpp"
#include "talus/kinematic/eldershaw_yim/foot_planner.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using geometry_test::convex_hull;
using geometry_test::cross;
using terrain_test::grid_from_function;

/// Signed distance-like margin of p inside the convex hull of `pts`: the
/// smallest cross product over the hull's edges divided by the edge length;
/// >= 0 inside or on the boundary, -inf with < 3 hull points.
double hull_margin(const std::vector<Vec2>& pts, const Vec2& p) {
  const std::vector<Vec2> h = convex_hull(pts);
  if (h.size() < 3) return -std::numeric_limits<double>::infinity();
  double margin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < h.size(); ++i) {
    const Vec2& a = h[i];
    const Vec2& b = h[(i + 1) % h.size()];
    margin = std::min(margin, cross(a, b, p) / (b - a).norm());
  }
  return margin;
}

void expect_sound_plan(const Footmap& fm, const LeggedRobot& robot, const CgLattice& L,
                       const std::vector<CgCell>& cells, const FootPlan& plan) {
  ASSERT_TRUE(plan.found()) << plan.message;
  ASSERT_FALSE(plan.steps.empty());
  EXPECT_EQ(plan.steps.front().move, FootMove::kStart);
  EXPECT_EQ(plan.steps.back().path_index, cells.size() - 1);
  const ElevationGrid& g = fm.terrain().grid();
  std::size_t unstable = 0, out_of_range = 0, off_terrain = 0, too_short = 0, bad_steps = 0;
  std::size_t advances = 0, foot_moves = 0;
  for (std::size_t s = 0; s < plan.steps.size(); ++s) {
    const FootStep& st = plan.steps[s];
    const SE2Pose q = L.centre(cells[st.path_index]);
    EXPECT_EQ(st.cg.x, q.x);
    EXPECT_EQ(st.cg.y, q.y);
    const double c = std::cos(q.theta), sn = std::sin(q.theta);
    const double min_height = cg_min_height(fm, robot, q).value();
    std::vector<Vec2> contact;
    for (std::size_t l = 0; l < st.feet.size(); ++l) {
      const FootState& f = st.feet[l];
      if (!f.contact) continue;
      const Vec3 p = foot_position(fm, f);
      contact.emplace_back(p.x(), p.y());
      const Vec2 d(p.x() - q.x, p.y() - q.y);
      const Vec2 uv(c * d.x() + sn * d.y(), -sn * d.x() + c * d.y());
      out_of_range += robot.legs[l].in_range(uv) ? 0 : 1;
      off_terrain +=
          (fm.valid(f.i, f.j) && p.z() == fm.terrain().elevation({p.x(), p.y()})) ? 0 : 1;
      too_short += p.z() + robot.legs[l].reach.at(uv) > min_height ? 0 : 1;
      (void)g;
    }
    unstable += hull_margin(contact, {q.x, q.y}) >= -1e-12 ? 0 : 1;
    if (s == 0) continue;
    const FootStep& prev = plan.steps[s - 1];
    std::size_t changed = 0;
    for (std::size_t l = 0; l < st.feet.size(); ++l) {
      const FootState &a = prev.feet[l], &b = st.feet[l];
      changed += (a.contact != b.contact || (b.contact && (a.i != b.i || a.j != b.j))) ? 1 : 0;
    }
    if (st.move == FootMove::kAdvanceCg) {
      ++advances;
      bad_steps += (st.path_index == prev.path_index + 1 && changed == 0) ? 0 : 1;
    } else {
      ++foot_moves;
      bad_steps += (st.path_index == prev.path_index && changed == 1 && st.leg >= 0) ? 0 : 1;
    }
  }
  EXPECT_EQ(unstable, 0u);
  EXPECT_EQ(out_of_range, 0u);
  EXPECT_EQ(off_terrain, 0u);
  EXPECT_EQ(too_short, 0u);
  EXPECT_EQ(bad_steps, 0u);
  EXPECT_EQ(advances, cells.size() - 1);
  EXPECT_GT(foot_moves, 0u);  // a walk, not a slide
}

TEST(EldershawYimFeet, FlatGroundEveryStanceIsStableForBothRobots) {
  for (const char* file : {"eldershaw_spider.yaml", "eldershaw_ambler.yaml"}) {
    const LeggedRobot robot = load_legged_robot(std::string(TALUS_DATA_DIR "/robots/") + file);
    const double side = robot.foot_print == 0.25 ? 12.0 : 30.0;
    const RuledTerrain flat(grid_from_function([](double, double) { return 0.0; }, 0, 0, side, side,
                                               robot.foot_print / 2));
    EldershawYimPlannerOptions o;
    o.direct = true;
    o.theta_slices = 8;
    const SE2Pose start{side / 6, side / 2, 0}, goal{5 * side / 6, side / 2, 0};
    const EldershawYimResult r = plan_eldershaw_yim(flat, robot, start, goal, o);
    ASSERT_TRUE(r.found()) << r.brief_report();
    const Footmap fm(flat, robot);
    const CgLattice L(flat.grid(), robot.foot_print, 8);
    const FootPlan plan = plan_footsteps(fm, robot, L, r.cells);
    expect_sound_plan(fm, robot, L, r.cells, plan);
  }
}

TEST(EldershawYimFeet, TheSpiderWalksOverAHillAndTheReachingRobotOverTheRidge) {
  const LeggedRobot spider = load_legged_robot(TALUS_DATA_DIR "/robots/eldershaw_spider.yaml");
  // A Gaussian hill 0.4 m high (sigma 1.5 m) in the way: feet stand at many heights.
  const RuledTerrain hill(grid_from_function(
      [](double x, double y) {
        return 0.4 * std::exp(-((x - 6) * (x - 6) + (y - 6.3) * (y - 6.3)) / 4.5);
      },
      0, 0, 12, 12, 0.125));
  EldershawYimPlannerOptions o;
  o.direct = true;
  o.theta_slices = 16;
  const EldershawYimResult r = plan_eldershaw_yim(hill, spider, {2, 6, 0}, {10, 6, 0}, o);
  ASSERT_TRUE(r.found()) << r.brief_report();
  const Footmap fm(hill, spider);
  const CgLattice L(hill.grid(), 0.25, 16);
  const FootPlan plan = plan_footsteps(fm, spider, L, r.cells);
  expect_sound_plan(fm, spider, L, r.cells, plan);
  double z_max = 0.0;
  for (const FootStep& st : plan.steps)
    for (const FootState& f : st.feet) z_max = std::max(z_max, foot_position(fm, f).z());
  EXPECT_GT(z_max, 0.3);  // it walked over the hill's top

  // A ridge 0.3 m high and 0.25 m wide across the map; eight legs reaching 0.5 m with feet
  // 0.3..1.0 m fore and aft: it steps over without touching the ridge's flanks.
  const RuledTerrain ridge(grid_from_function(
      [](double x, double) { return std::abs(x - 6) <= 0.125 + 1e-9 ? 0.3 : 0.0; }, 0, 0, 12, 8,
      0.125));
  LeggedRobot box;
  box.max_traction_slope = 0.6;
  box.foot_print = 0.25;
  // Two legs per quadrant: under the quadrant rule a foot can only be lifted while another
  // holds its quadrant, so one leg per quadrant could never step.
  for (int su : {1, 1, -1, -1}) {
    for (int sv : {1, -1}) {
      Leg leg;
      std::vector<Vec2> b{
          {0.3 * su, 0.05 * sv}, {1.0 * su, 0.05 * sv}, {1.0 * su, 0.4 * sv}, {0.3 * su, 0.4 * sv}};
      if (su * sv < 0) std::reverse(b.begin(), b.end());
      leg.range = b;
      leg.reach.constant = 0.5;
      box.legs.push_back(leg);
    }
  }
  box.under_carriage.depth = {0.0, Vec2(-0.25, -0.25), 0.25, 3, 3, std::vector<double>(9, 0.1)};
  o.theta_slices = 1;
  const EldershawYimResult rr = plan_eldershaw_yim(ridge, box, {3, 4, 0}, {9, 4, 0}, o);
  ASSERT_TRUE(rr.found()) << rr.brief_report();
  const Footmap fr(ridge, box);
  const CgLattice Lr(ridge.grid(), 0.25, 1);
  const FootPlan pr = plan_footsteps(fr, box, Lr, rr.cells);
  expect_sound_plan(fr, box, Lr, rr.cells, pr);
}

TEST(EldershawYimFeet, BudgetAndOptions) {
  const LeggedRobot spider = load_legged_robot(TALUS_DATA_DIR "/robots/eldershaw_spider.yaml");
  const RuledTerrain flat(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 8, 8, 0.125));
  EldershawYimPlannerOptions o;
  o.direct = true;
  o.theta_slices = 8;
  const EldershawYimResult r = plan_eldershaw_yim(flat, spider, {2, 4, 0}, {6, 4, 0}, o);
  ASSERT_TRUE(r.found());
  const Footmap fm(flat, spider);
  const CgLattice L(flat.grid(), 0.25, 8);
  FootPlannerOptions f;
  f.budget = 3;
  const FootPlan p = plan_footsteps(fm, spider, L, r.cells, f);
  EXPECT_EQ(p.status, FootPlanStatus::kBudgetExceeded) << p.message;
  EXPECT_EQ(p.nodes, 3u);
  f.budget = 0;
  EXPECT_THROW(plan_footsteps(fm, spider, L, r.cells, f), InputError);
  // Reruns are identical.
  const FootPlan a = plan_footsteps(fm, spider, L, r.cells),
                 b = plan_footsteps(fm, spider, L, r.cells);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(a.steps[k].move, b.steps[k].move);
    EXPECT_EQ(a.steps[k].leg, b.steps[k].leg);
    for (std::size_t l = 0; l < a.steps[k].feet.size(); ++l) {
      EXPECT_EQ(a.steps[k].feet[l].i, b.steps[k].feet[l].i);
      EXPECT_EQ(a.steps[k].feet[l].j, b.steps[k].feet[l].j);
    }
  }
}

}  // namespace
}  // namespace talus
