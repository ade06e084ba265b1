// Eldershaw and Yim 2001: the legged-robot files and their errors, the
// footmap on planes of known slope, CG-cell validity on flat ground, the
// MinHeight/reach rule on a cliff (mesa) and a narrow ridge, the A* local
// planner's exact cost and theta wrap, the tree-PRM's forest invariant and
// seeded reproducibility. Every path is re-checked cell by cell with
// evaluate_cg_pose, independently of the planner's cache.
#include <gtest/gtest.h>

#include <barrier>
#include <mutex>
#include <thread>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/kinematic/eldershaw_yim/cg_local_planner.hpp"
#include "talus/kinematic/eldershaw_yim/cg_space.hpp"
#include "talus/kinematic/eldershaw_yim/eldershaw_yim_planner.hpp"
#include "talus/kinematic/eldershaw_yim/footmap.hpp"
#include "talus/kinematic/eldershaw_yim/legged_robot.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;
using terrain_test::grid_from_function;

const LeggedRobot& spider() {
  static const LeggedRobot r = load_legged_robot(TALUS_DATA_DIR "/robots/eldershaw_spider.yaml");
  return r;
}

/// Four legs, one per body quadrant: feet at |u| in [inner, outer], |v| in
/// [0.05, 0.4]; a 0.5 m x 0.5 m under-carriage `depth` below the zero plane;
/// foot print 0.25 m; traction up to 0.6 rad.
LeggedRobot box_robot(double reach, double inner, double outer, double depth = 0.1) {
  LeggedRobot r;
  r.name = "box";
  r.max_traction_slope = 0.6;
  r.foot_print = 0.25;
  for (int su : {1, -1}) {
    for (int sv : {1, -1}) {
      Leg leg;
      leg.attachment = Vec2(0.25 * su, 0.25 * sv);
      std::vector<Vec2> box{{inner * su, 0.05 * sv},
                            {outer * su, 0.05 * sv},
                            {outer * su, 0.4 * sv},
                            {inner * su, 0.4 * sv}};
      if (su * sv < 0) std::reverse(box.begin(), box.end());  // keep counter-clockwise
      leg.range = box;
      leg.reach.constant = reach;
      r.legs.push_back(leg);
    }
  }
  BodyField& d = r.under_carriage.depth;
  d.origin = Vec2(-0.25, -0.25);
  d.spacing = 0.25;
  d.nu = d.nv = 3;
  d.values.assign(9, depth);
  r.validate();
  return r;
}

/// Every consecutive pair of cells differs by one unit step along one axis
/// (θ modulo n_θ) and every cell passes the rule, evaluated afresh.
void expect_sound_cells(const Footmap& footmap, const LeggedRobot& robot, const CgLattice& L,
                        const std::vector<CgCell>& cells) {
  ASSERT_FALSE(cells.empty());
  std::size_t bad_steps = 0, invalid = 0;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (evaluate_cg_pose(footmap, robot, L.centre(cells[k])) != CgState::kValid) ++invalid;
    if (k == 0) continue;
    const int dx = std::abs(cells[k].ix - cells[k - 1].ix);
    const int dy = std::abs(cells[k].iy - cells[k - 1].iy);
    const int dt0 = std::abs(cells[k].it - cells[k - 1].it);
    const int dt = std::min(dt0, L.ntheta() - dt0);
    if (dx + dy + dt != 1) ++bad_steps;
  }
  EXPECT_EQ(bad_steps, 0u);
  EXPECT_EQ(invalid, 0u) << "of " << cells.size();
}

// --- robot files -------------------------------------------------------------

TEST(EldershawYimRobot, BundledRobotsLoad) {
  const LeggedRobot& s = spider();
  EXPECT_EQ(s.legs.size(), 8u);
  EXPECT_EQ(s.foot_print, 0.25);
  EXPECT_NEAR(s.outer_radius(), 0.9, 1e-3);
  // Two legs' ranges in each body quadrant.
  int per_quadrant[4] = {0, 0, 0, 0};
  for (const Leg& leg : s.legs) {
    Vec2 mean = Vec2::Zero();
    for (const Vec2& p : leg.range) mean += p / static_cast<double>(leg.range.size());
    ++per_quadrant[(mean.x() < 0 ? 1 : 0) + (mean.y() < 0 ? 2 : 0)];
    EXPECT_TRUE(leg.in_range(mean));
    EXPECT_FALSE(leg.in_range(Vec2::Zero()));
  }
  for (int q : per_quadrant) EXPECT_EQ(q, 2);

  const LeggedRobot a = load_legged_robot(TALUS_DATA_DIR "/robots/eldershaw_ambler.yaml");
  EXPECT_EQ(a.legs.size(), 6u);
  ASSERT_TRUE(a.legs[0].reach.is_grid());
  // The reach grid: 2.2 m next to the body, 1.8 m at the outer edge, bilinear between.
  EXPECT_DOUBLE_EQ(a.legs[0].reach.at({0.0, 1.2}), 2.2);
  EXPECT_DOUBLE_EQ(a.legs[0].reach.at({0.0, 3.0}), 1.8);
  EXPECT_NEAR(a.legs[0].reach.at({0.0, 1.65}), 2.1, 1e-12);
  EXPECT_DOUBLE_EQ(a.max_reach(), 2.2);
  // The three legs of a side share one range (overlapping completely).
  EXPECT_TRUE(a.legs[0].in_range({0.0, 2.0}) && a.legs[1].in_range({0.0, 2.0}) &&
              a.legs[2].in_range({0.0, 2.0}));
}

const char* kGoodRobot = R"(type: legged
max_traction_slope: 0.5
foot_print: 0.25
under_carriage: {origin: [-0.2, -0.2], spacing: 0.4, depth: [[0.1, 0.1], [0.1, 0.1]]}
legs:
  - {attachment: [0.2, 0.2], range: [[0.3, 0.1], [0.8, 0.1], [0.8, 0.5], [0.3, 0.5]], reach: 0.3}
  - {attachment: [-0.2, 0.2], range: [[-0.8, 0.1], [-0.3, 0.1], [-0.3, 0.5], [-0.8, 0.5]], reach: 0.3}
  - {attachment: [0, -0.2], range: [[-0.8, -0.5], [0.8, -0.5], [0.8, -0.1], [-0.8, -0.1]], reach: 0.3}
)";

std::string robot_error(const std::string& text) {
  try {
    parse_legged_robot(text, "bad.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(EldershawYimRobot, BadFilesGiveClearErrors) {
  EXPECT_NO_THROW(parse_legged_robot(kGoodRobot, "good.yaml"));
  const std::string good = kGoodRobot;
  struct Case {
    std::string text, expect;
  };
  const std::vector<Case> cases{
      {replaced(good, "type: legged", "type: wheeled"), "key 'type' must be legged"},
      {replaced(good, "foot_print: 0.25", "foot_print: 0.25\ncolour: red"), "unknown key 'colour'"},
      {replaced(good, "foot_print: 0.25\n", ""), "missing required key 'foot_print'"},
      {replaced(good, "foot_print: 0.25", "foot_print: small"),
       "key 'foot_print' must be a number"},
      {replaced(good, "foot_print: 0.25", "foot_print: 0"), "foot_print must be a positive"},
      {replaced(good, "max_traction_slope: 0.5", "max_traction_slope: 2"),
       "max_traction_slope must be in (0, pi/2)"},
      {replaced(good, "reach: 0.3}\n  - {attachment: [-0.2", "reach: -1}\n  - {attachment: [-0.2"),
       "legs[0].reach must be > 0"},
      {replaced(good, "[[0.3, 0.1], [0.8, 0.1], [0.8, 0.5], [0.3, 0.5]]",
                "[[0.3, 0.5], [0.8, 0.5], [0.8, 0.1], [0.3, 0.1]]"),
       "legs[0].range must be listed counter-clockwise"},
      {replaced(good, "[[0.3, 0.1], [0.8, 0.1], [0.8, 0.5], [0.3, 0.5]]",
                "[[0.3, 0.1], [0.8, 0.5], [0.8, 0.1], [0.3, 0.5], [0.2, 0.3]]"),
       "legs[0].range must be"},
      {replaced(good, "[[0.3, 0.1], [0.8, 0.1], [0.8, 0.5], [0.3, 0.5]]", "[[0.3, 0.1], [0.8]]"),
       "legs[0].range"},
      {replaced(good, "reach: 0.3}\n  - {attachment: [-0.2",
                "reach: {origin: [0.3, 0.1], spacing: 0.1, values: [[1, 1], [1, 1]]}}\n  - "
                "{attachment: [-0.2"),
       "legs[0].reach: the grid does not cover range vertex"},
      {replaced(good, "depth: [[0.1, 0.1], [0.1, 0.1]]", "depth: [[0.1, 0.1], [0.1]]"),
       "under_carriage.depth[1]"},
      {replaced(good, "spacing: 0.4", "spacing: 0.4, spacing: 0.5"), "spacing"},
      {replaced(good, "reach: 0.3}\n  - {attachment: [0, -0.2]",
                "reach: 0.3}\n  - {attachment: [0]"),
       "legs[2].attachment' must be a pair"},
  };
  for (const Case& c : cases) {
    const std::string what = robot_error(c.text);
    EXPECT_NE(what.find("bad.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find(c.expect), std::string::npos)
        << "expected '" << c.expect << "' in: " << what;
  }
  // Two legs only.
  const std::string two = good.substr(0, good.rfind("  - {attachment: [0, -0.2]"));
  EXPECT_NE(robot_error(two).find("legs must list 3 to 16 legs"), std::string::npos)
      << robot_error(two);
}

// --- footmap -----------------------------------------------------------------

TEST(EldershawYimFootmap, SlopeOfAPlaneIsExactEverywhere) {
  for (const double alpha : {0.3, 0.7}) {
    const double t = std::tan(alpha);
    const RuledTerrain terrain(grid_from_function(
        [t](double x, double y) { return t * (0.6 * x + 0.8 * y); }, 0, 0, 4, 4, 0.125));
    const Footmap fm(terrain, spider());  // limit 0.6 rad
    std::size_t wrong = 0;
    for (std::size_t j = 0; j < fm.nrows(); ++j)
      for (std::size_t i = 0; i < fm.ncols(); ++i)
        wrong += std::abs(fm.slope(i, j) - alpha) > 1e-9 ? 1 : 0;
    EXPECT_EQ(wrong, 0u) << alpha;
    EXPECT_EQ(fm.invalid_count(), alpha > 0.6 ? fm.ncols() * fm.nrows() : 0u);
  }
}

TEST(EldershawYimFootmap, ASpikeInvalidatesTheNodesWithinOneFootPrint) {
  // One node raised 1 m: nodes whose footprint-scale differences see it are invalid.
  ElevationGrid g(33, 33, 0.125, 0, 0, 0.0);
  g.at(16, 16) = 1.0;
  const RuledTerrain terrain(g);
  const Footmap fm(terrain, spider());  // s = 0.125 m: the four neighbours and the spike's own
  EXPECT_TRUE(fm.valid(16, 16));        // differences across the spike are symmetric: flat
  EXPECT_FALSE(fm.valid(15, 16));
  EXPECT_FALSE(fm.valid(17, 16));
  EXPECT_FALSE(fm.valid(16, 15));
  EXPECT_FALSE(fm.valid(16, 17));
  EXPECT_TRUE(fm.valid(15, 15));
  EXPECT_EQ(fm.invalid_count(), 4u);
}

// --- CG space ----------------------------------------------------------------

TEST(EldershawYimCgSpace, LatticeRoundTripsAndRefusesTwoToSevenSlices) {
  const ElevationGrid g(41, 21, 0.1, 3.0, -1.0, 0.0);
  const CgLattice L(g, 0.25, 16);
  EXPECT_EQ(L.nx(), 17);
  EXPECT_EQ(L.ny(), 9);
  for (std::size_t k = 0; k < L.size(); k += 37) {
    const CgCell c = L.cell(k);
    EXPECT_EQ(L.index(c), k);
    EXPECT_EQ(L.cell_of(L.centre(c)), c);
  }
  EXPECT_EQ(L.cell_of({3.0, -1.0, -0.01}).it, 0);
  EXPECT_EQ(L.cell_of({3.0, -1.0, 2 * kPi - 0.3}).it, 15);
  for (int n : {0, 2, 7, 2000}) EXPECT_THROW(CgLattice(g, 0.25, n), InputError) << n;
  EXPECT_NO_THROW(CgLattice(g, 0.25, 1));
  EXPECT_NO_THROW(CgLattice(g, 0.25, 8));
}

TEST(EldershawYimCgSpace, FlatGroundEveryInnerCellIsValid) {
  const RuledTerrain flat(grid_from_function([](double, double) { return 0.0; }, 0, 0, 6, 6, 0.25));
  const Footmap fm(flat, spider());
  EXPECT_EQ(fm.invalid_count(), 0u);
  CgSpace space(fm, spider(), 8, 8);
  const CgLattice& L = space.lattice();
  std::size_t inner = 0, invalid_inner = 0, off = 0;
  for (std::size_t k = 0; k < L.size(); ++k) {
    const CgCell c = L.cell(k);
    const SE2Pose q = L.centre(c);
    const double border = std::min({q.x, q.y, 6 - q.x, 6 - q.y});
    const CgState s = space.state(c);
    if (border >= spider().outer_radius()) {
      ++inner;
      invalid_inner += s == CgState::kValid ? 0 : 1;
    }
    // Only the under-carriage leaving the map (0.25 m, or 0.354 m turned) makes a cell invalid.
    if (border < 0.25 - 1e-9) {
      EXPECT_EQ(s, CgState::kOffData) << q.x << " " << q.y;
      ++off;
    }
  }
  EXPECT_GT(inner, 0u);
  EXPECT_EQ(invalid_inner, 0u);
  EXPECT_GT(off, 0u);
  EXPECT_EQ(space.cells_materialised(), L.size());
  EXPECT_EQ(space.blocks_materialised(), 16u);  // 25 x 25 cells in blocks of 8: 4 x 4
}

TEST(EldershawYimCgSpace, BlocksAreMaterialisedOnDemand) {
  const RuledTerrain flat(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 20, 20, 0.25));
  const Footmap fm(flat, spider());
  CgSpace space(fm, spider(), 8, 16);
  EXPECT_EQ(space.peek({20, 20, 3}), CgState::kUnknown);
  EXPECT_TRUE(space.valid({20, 20, 3}));
  EXPECT_EQ(space.blocks_materialised(), 1u);
  EXPECT_EQ(space.cells_materialised(), 16u * 16u * 8u);
  EXPECT_EQ(space.peek({31, 31, 7}), CgState::kValid);    // same block
  EXPECT_EQ(space.peek({32, 20, 0}), CgState::kUnknown);  // the next one
}

TEST(EldershawYimCgSpace, OverlaysCountTheirOwnBlocksAndAreAbsorbedOnce) {
  const RuledTerrain flat(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 20, 20, 0.25));
  const Footmap fm(flat, spider());
  CgSpace space(fm, spider(), 8, 16);
  ASSERT_EQ(space.lattice().nx(), 81);  // the last block column is one cell wide
  EXPECT_TRUE(space.valid({20, 20, 3}));
  space.mark_invalid({21, 20, 3});
  CgSpace a(CgSpace::OverlayOn{}, space), b(CgSpace::OverlayOn{}, space);
  EXPECT_EQ(a.state({21, 20, 3}), CgState::kFeedback);  // the base's mark
  EXPECT_EQ(a.cells_materialised(), 0u);                // the base's block
  EXPECT_TRUE(a.valid({40, 20, 0}));
  EXPECT_EQ(b.state({80, 20, 0}), CgState::kOffData);  // the east edge: under-carriage off data
  EXPECT_TRUE(b.valid({40, 20, 0}));
  EXPECT_EQ(a.cells_materialised(), 16u * 16u * 8u);
  EXPECT_EQ(b.cells_materialised(), 2u * 16u * 16u * 8u - 15u * 16u * 8u);
  EXPECT_EQ(space.peek({40, 20, 0}), CgState::kUnknown);  // the base is unchanged
  space.absorb(std::move(a));
  space.absorb(std::move(b));
  EXPECT_EQ(space.blocks_materialised(), 3u);
  EXPECT_EQ(space.cells_materialised(), 2u * 16u * 16u * 8u + 16u * 8u);
  EXPECT_EQ(space.peek({40, 20, 0}), CgState::kValid);
  CgSpace other(fm, spider(), 8, 16);
  EXPECT_THROW(space.absorb(std::move(other)), InputError);
}

// --- local planner -----------------------------------------------------------

TEST(EldershawYimLocalPlanner, FlatCostIsTheL1DistanceAndThetaWraps) {
  const RuledTerrain flat(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 10, 10, 0.25));
  const Footmap fm(flat, spider());
  CgSpace space(fm, spider(), 16, 16);
  CgLocalPlannerOptions o;
  o.heading_weight = 0.5;
  std::size_t work = 0;
  // 12 cells east, 5 north, from slice 1 to slice 15: two steps through 0.
  const CgLocalPath p = cg_local_plan(space, {10, 10, 1}, {22, 15, 15}, o, work, 1u << 30);
  ASSERT_TRUE(p.found);
  EXPECT_NEAR(p.cost, 0.25 * 17 + 0.5 * 2 * (2 * kPi / 16), 1e-12);
  EXPECT_EQ(p.cells.size(), 17u + 2u + 1u);
  EXPECT_EQ(p.cells.front(), (CgCell{10, 10, 1}));
  EXPECT_EQ(p.cells.back(), (CgCell{22, 15, 15}));
  bool through_zero = false;
  for (const CgCell& c : p.cells) through_zero = through_zero || c.it == 0;
  EXPECT_TRUE(through_zero);
  expect_sound_cells(fm, spider(), space.lattice(), p.cells);
  EXPECT_EQ(work, p.expansions);
}

// --- planner -----------------------------------------------------------------

TEST(EldershawYimPlanner, FlatGroundStraightPathBothModes) {
  const RuledTerrain flat(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 12, 12, 0.25));
  for (const bool direct : {false, true}) {
    EldershawYimPlannerOptions o;
    o.direct = direct;
    const EldershawYimResult r = plan_eldershaw_yim(flat, spider(), {2, 6, 0}, {10, 6, 0}, o);
    ASSERT_TRUE(r.found()) << r.brief_report();
    EXPECT_DOUBLE_EQ(r.length_m, 8.0);
    ASSERT_EQ(r.cells.size(), 33u);
    for (const CgCell& c : r.cells) {
      EXPECT_EQ(c.iy, 24);
      EXPECT_EQ(c.it, 0);
    }
    const Footmap fm(flat, spider());
    expect_sound_cells(fm, spider(), CgLattice(flat.grid(), 0.25, 16), r.cells);
    EXPECT_EQ(r.local_planner_calls, 1u) << r.brief_report();
  }
}

/// 20 m x 20 m at 0.25 m: a mesa 1 m high over x >= 8, 4 <= y <= 12, with
/// cliffs to the west and south; to the north a ramp down to 0 at y = 16.
RuledTerrain mesa() {
  return RuledTerrain(grid_from_function(
      [](double x, double y) {
        if (x < 8 || y < 4) return 0.0;
        if (y <= 12) return 1.0;
        return std::max(0.0, (16 - y) / 4);
      },
      0, 0, 20, 20, 0.25));
}

TEST(EldershawYimPlanner, ACliffHigherThanEveryReachIsGoneRound) {
  const RuledTerrain t = mesa();
  const SE2Pose start{4, 8, 0}, goal{12, 8, 0};
  EldershawYimPlannerOptions o;
  o.direct = true;
  o.theta_slices = 8;
  o.plan_feet = false;  // the CG level only (test_eldershaw_yim_feet.cpp plans feet)
  // The spider: reach 0.3 m < cliff 1 m + under-carriage 0.1 m. The only way up is the ramp.
  const EldershawYimResult r = plan_eldershaw_yim(t, spider(), start, goal, o);
  ASSERT_TRUE(r.found()) << r.brief_report();
  const Footmap fm(t, spider());
  const CgLattice L(t.grid(), 0.25, 8);
  expect_sound_cells(fm, spider(), L, r.cells);
  double y_max = 0.0;
  for (const SE2Pose& q : r.path) y_max = std::max(y_max, q.y);
  EXPECT_GT(y_max, 12.0) << "the route must climb the ramp north of the mesa";
  EXPECT_GT(r.length_m, 8.0 + 2 * 4.0) << r.brief_report();
  // Where the under-carriage straddles the west cliff (x = 8), or the rear feet have only the
  // cliff's foot to stand on, the spider's legs are too short; clear of it, it stands.
  for (const double x : {7.75, 8.0, 8.25})
    EXPECT_EQ(evaluate_cg_pose(fm, spider(), {x, 8, 0}), CgState::kTooShort) << x;
  for (const double x : {7.0, 9.0})
    EXPECT_EQ(evaluate_cg_pose(fm, spider(), {x, 8, 0}), CgState::kValid) << x;

  // Legs reaching 1.5 m (> 1 m + 0.1 m) climb the cliff where they stand: a straight route.
  LeggedRobot tall = spider();
  for (Leg& leg : tall.legs) leg.reach.constant = 1.5;
  const EldershawYimResult s = plan_eldershaw_yim(t, tall, start, goal, o);
  ASSERT_TRUE(s.found()) << s.brief_report();
  EXPECT_DOUBLE_EQ(s.length_m, 8.0);
  const Footmap fm_tall(t, tall);
  expect_sound_cells(fm_tall, tall, L, s.cells);
}

/// 12 m x 8 m at 0.125 m: a ridge 0.3 m high and 0.25 m wide along x = 6 across the whole map.
RuledTerrain ridge() {
  return RuledTerrain(grid_from_function(
      [](double x, double) { return std::abs(x - 6) <= 0.125 + 1e-9 ? 0.3 : 0.0; }, 0, 0, 12, 8,
      0.125));
}

TEST(EldershawYimPlanner, ARidgeIsCrossedOnlyIfLegsReachBothSides) {
  const RuledTerrain t = ridge();
  const SE2Pose start{3, 4, 0}, goal{9, 4, 0};
  EldershawYimPlannerOptions o;
  o.direct = true;
  o.theta_slices = 1;   // no rotation: see the end for a robot that turns its wide side across
  o.plan_feet = false;  // the CG level only
  // Ridge 0.3 m + under-carriage 0.1 m = MinHeight 0.4 m over the ridge.
  const LeggedRobot reaching = box_robot(0.5, 0.4, 0.9);  // 0.5 > 0.4, feet beyond the ridge
  const EldershawYimResult a = plan_eldershaw_yim(t, reaching, start, goal, o);
  ASSERT_TRUE(a.found()) << a.brief_report();
  EXPECT_DOUBLE_EQ(a.length_m, 6.0);
  expect_sound_cells(Footmap(t, reaching), reaching, CgLattice(t.grid(), 0.25, 8), a.cells);

  const LeggedRobot short_legs = box_robot(0.35, 0.4, 0.9);  // 0.35 < 0.4: the body would touch
  const EldershawYimResult b = plan_eldershaw_yim(t, short_legs, start, goal, o);
  EXPECT_EQ(b.status, EldershawYimStatus::kNoPath) << b.brief_report();
  EXPECT_EQ(evaluate_cg_pose(Footmap(t, short_legs), short_legs, {6, 4, 0}), CgState::kTooShort);

  const LeggedRobot close_feet = box_robot(0.5, 0.05, 0.2);  // long legs, feet kept near the body
  const EldershawYimResult c = plan_eldershaw_yim(t, close_feet, start, goal, o);
  EXPECT_EQ(c.status, EldershawYimStatus::kNoPath) << c.brief_report();
  EXPECT_EQ(evaluate_cg_pose(Footmap(t, close_feet), close_feet, {6, 4, 0}), CgState::kNoSupport);
}

TEST(EldershawYimPlanner, TreePrmIsAForestAndASeedReproducesItBitForBit) {
  const RuledTerrain t = mesa();
  const SE2Pose start{4, 8, 0}, goal{12, 8, 0};
  EldershawYimPlannerOptions o;
  o.theta_slices = 8;
  o.prm_points = 300;
  o.connect_radius = 5.0;
  o.seed = 7;
  o.feet.budget = 2000;
  o.feedback_rounds = 0;  // one roadmap (feedback replans are tested below)
  const EldershawYimResult a = plan_eldershaw_yim(t, spider(), start, goal, o);
  ASSERT_TRUE(a.found()) << a.brief_report();
  // Each edge joined two trees: edges = points - trees.
  EXPECT_EQ(a.prm_edges.size(), a.prm_points.size() - a.prm_trees);
  EXPECT_EQ(a.local_planner_successes, a.prm_edges.size());
  EXPECT_GE(a.recreate_calls, 2u);
  EXPECT_LT(a.cells_materialised, a.cg_cells);
  const Footmap fm(t, spider());
  expect_sound_cells(fm, spider(), CgLattice(t.grid(), 0.25, 8), a.cells);
  EXPECT_EQ(a.cells.front(), CgLattice(t.grid(), 0.25, 8).cell_of(start));

  const EldershawYimResult b = plan_eldershaw_yim(t, spider(), start, goal, o);
  EXPECT_EQ(b.cells, a.cells);
  EXPECT_EQ(b.prm_points, a.prm_points);
  EXPECT_EQ(b.prm_edges, a.prm_edges);
  EXPECT_EQ(b.local_planner_calls, a.local_planner_calls);
  EXPECT_EQ(b.expansions, a.expansions);
  EXPECT_EQ(b.cells_materialised, a.cells_materialised);
  EXPECT_TRUE(a.feet_planned);
  EXPECT_EQ(b.foot_plan.status, a.foot_plan.status);
  EXPECT_EQ(b.foot_plan.nodes, a.foot_plan.nodes);
  EXPECT_EQ(b.foot_plan.steps.size(), a.foot_plan.steps.size());
  ASSERT_EQ(b.path.size(), a.path.size());
  for (std::size_t k = 0; k < a.path.size(); ++k) {
    EXPECT_EQ(b.path[k].x, a.path[k].x);
    EXPECT_EQ(b.path[k].y, a.path[k].y);
    EXPECT_EQ(b.path[k].theta, a.path[k].theta);
  }
  o.seed = 8;
  const EldershawYimResult c = plan_eldershaw_yim(t, spider(), start, goal, o);
  EXPECT_NE(c.prm_points, a.prm_points);
}

/// `b` is `a` bit for bit: the CG route and path, the roadmap, every counter and the foot plan.
void expect_same_plan(const EldershawYimResult& b, const EldershawYimResult& a,
                      const std::string& label) {
  EXPECT_EQ(b.cells, a.cells) << label;
  EXPECT_EQ(b.prm_points, a.prm_points) << label;
  EXPECT_EQ(b.prm_edges, a.prm_edges) << label;
  EXPECT_EQ(b.prm_trees, a.prm_trees) << label;
  EXPECT_EQ(b.local_planner_calls, a.local_planner_calls) << label;
  EXPECT_EQ(b.local_planner_successes, a.local_planner_successes) << label;
  EXPECT_EQ(b.recreate_calls, a.recreate_calls) << label;
  EXPECT_EQ(b.expansions, a.expansions) << label;
  EXPECT_EQ(b.cells_materialised, a.cells_materialised) << label;
  EXPECT_EQ(b.blocks_materialised, a.blocks_materialised) << label;
  EXPECT_EQ(b.samples_drawn, a.samples_drawn) << label;
  EXPECT_EQ(b.feedback_cells, a.feedback_cells) << label;
  EXPECT_EQ(b.foot_plan.nodes, a.foot_plan.nodes) << label;
  EXPECT_EQ(b.foot_plan.steps.size(), a.foot_plan.steps.size()) << label;
  EXPECT_EQ(b.length_m, a.length_m) << label;
  ASSERT_EQ(b.path.size(), a.path.size()) << label;
  for (std::size_t k = 0; k < a.path.size(); ++k) {
    EXPECT_EQ(b.path[k].x, a.path[k].x) << label;
    EXPECT_EQ(b.path[k].y, a.path[k].y) << label;
    EXPECT_EQ(b.path[k].theta, a.path[k].theta) << label;
  }
}

/// A tree-PRM on mesa() with enough points for batches of several local-planner calls.
EldershawYimPlannerOptions mesa_prm_options() {
  EldershawYimPlannerOptions o;
  o.theta_slices = 8;
  o.prm_points = 300;
  o.connect_radius = 5.0;
  o.seed = 7;
  o.feet.budget = 2000;
  return o;
}

TEST(EldershawYimPlanner, TwoAndFourWorkersGiveTheSerialPlanBitForBit) {
  const RuledTerrain t = mesa();
  const SE2Pose start{4, 8, 0}, goal{12, 8, 0};
  EldershawYimPlannerOptions o = mesa_prm_options();
  const EldershawYimResult a = plan_eldershaw_yim(t, spider(), start, goal, o);
  ASSERT_TRUE(a.found()) << a.brief_report();
  ASSERT_GE(a.prm_points.size(), 4u);  // enough trees for batches of several calls
  for (int workers : {2, 4}) {
    o.workers = workers;
    const EldershawYimResult b = plan_eldershaw_yim(t, spider(), start, goal, o);
    expect_same_plan(b, a, "workers " + std::to_string(workers));
  }
  // A budget spent part-way through the roadmap stops at the same place for any worker count.
  o.budget = a.cells_materialised / 2;
  o.workers = 1;
  const EldershawYimResult s = plan_eldershaw_yim(t, spider(), start, goal, o);
  EXPECT_EQ(s.status, EldershawYimStatus::kBudgetExceeded) << s.brief_report();
  o.workers = 3;
  const EldershawYimResult m = plan_eldershaw_yim(t, spider(), start, goal, o);
  EXPECT_EQ(m.status, s.status);
  EXPECT_EQ(m.prm_points, s.prm_points);
  EXPECT_EQ(m.local_planner_calls, s.local_planner_calls);
  EXPECT_EQ(m.expansions, s.expansions);
  EXPECT_EQ(m.cells_materialised, s.cells_materialised);
  o.workers = 0;
  EXPECT_THROW(plan_eldershaw_yim(t, spider(), start, goal, o), InputError);
}

/// Ranks simulated by threads of this process (the CLI's MPI test runs real ranks).
class ThreadRanks final : public CgRankGroup {
 public:
  struct Board {
    explicit Board(int size) : size(size), sync(size) {}
    int size;
    std::mutex lock;
    std::vector<double> max;
    int arrived = 0;
    std::barrier<> sync;
  };
  ThreadRanks(Board& board, int rank) : board_(board), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return board_.size; }
  void max_all(std::vector<double>& values) const override {
    {
      const std::lock_guard<std::mutex> hold(board_.lock);
      if (board_.arrived++ == 0) board_.max = values;
      for (std::size_t k = 0; k < values.size(); ++k)
        board_.max[k] = std::max(board_.max[k], values[k]);
    }
    board_.sync.arrive_and_wait();
    values = board_.max;
    board_.sync.arrive_and_wait();
    if (rank_ == 0) board_.arrived = 0;
    board_.sync.arrive_and_wait();
  }

 private:
  Board& board_;
  int rank_;
};

TEST(EldershawYimPlanner, RanksSharingTheCallsAllGetTheSerialPlan) {
  const RuledTerrain t = mesa();
  const SE2Pose start{4, 8, 0}, goal{12, 8, 0};
  EldershawYimPlannerOptions o = mesa_prm_options();
  const EldershawYimResult a = plan_eldershaw_yim(t, spider(), start, goal, o);
  ASSERT_TRUE(a.found()) << a.brief_report();
  for (int size : {2, 3}) {
    ThreadRanks::Board board(size);
    std::vector<EldershawYimResult> got(static_cast<std::size_t>(size));
    std::vector<std::thread> ranks;
    for (int k = 0; k < size; ++k)
      ranks.emplace_back([&, k] {
        const ThreadRanks me(board, k);
        EldershawYimPlannerOptions mine = o;
        mine.ranks = &me;
        mine.workers = 2;
        got[static_cast<std::size_t>(k)] = plan_eldershaw_yim(t, spider(), start, goal, mine);
      });
    for (auto& r : ranks) r.join();
    for (const EldershawYimResult& b : got) {
      expect_same_plan(b, a, "ranks " + std::to_string(size));
    }
  }
}

TEST(EldershawYimPlanner, TooFewPointsIsNoPathAndBadOptionsThrow) {
  const RuledTerrain t = mesa();
  EldershawYimPlannerOptions o;
  o.theta_slices = 8;
  o.prm_points = 0;
  const EldershawYimResult r = plan_eldershaw_yim(t, spider(), {4, 8, 0}, {12, 8, 0}, o);
  EXPECT_EQ(r.status, EldershawYimStatus::kNoPath) << r.brief_report();
  EXPECT_TRUE(r.cells.empty() && r.path.empty());
  EXPECT_EQ(r.prm_trees, 2u);
  o.theta_slices = 4;
  EXPECT_THROW(plan_eldershaw_yim(t, spider(), {4, 8, 0}, {12, 8, 0}, o), InputError);
  o.theta_slices = 8;
  o.connect_attempts = 0;
  EXPECT_THROW(plan_eldershaw_yim(t, spider(), {4, 8, 0}, {12, 8, 0}, o), InputError);
  o.connect_attempts = 1;
  EXPECT_THROW(plan_eldershaw_yim(t, spider(), {4, 80, 0}, {12, 8, 0}, o), InputError);
}

TEST(EldershawYimPlanner, AFailedFootPlanMarksItsCellInvalidAndReplans) {
  // One leg per quadrant: every CG cell can be stood on, but under the quadrant rule no foot
  // can ever be lifted, so the feet cannot follow any CG path: feedback fires every round.
  const RuledTerrain flat(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 8, 8, 0.125));
  const LeggedRobot stiff = box_robot(0.5, 0.3, 0.6);
  EldershawYimPlannerOptions o;
  o.direct = true;
  o.theta_slices = 8;
  o.feet.budget = 500;
  o.feedback_rounds = 3;
  const EldershawYimResult r = plan_eldershaw_yim(flat, stiff, {2, 4, 0}, {6, 4, 0}, o);
  ASSERT_TRUE(r.found()) << r.brief_report();
  EXPECT_TRUE(r.feet_planned);
  EXPECT_FALSE(r.foot_plan.found());
  EXPECT_EQ(r.feedback_events, 3u);
  ASSERT_EQ(r.feedback_cells.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t m = 0; m < k; ++m) EXPECT_NE(r.feedback_cells[k], r.feedback_cells[m]);
    EXPECT_EQ(std::count(r.cells.begin(), r.cells.end(), r.feedback_cells[k]), 0) << k;
  }
  // Resuming at the shared start cell got no further than a fresh plan (whose first stance
  // suits the new direction), so the fresh one was kept.
  EXPECT_EQ(r.foot_steps_reused, 0u);
  EXPECT_GT(r.length_m, 4.0);            // the marked cells lay on the straight route
  EXPECT_EQ(r.local_planner_calls, 4u);  // one direct A* per round
  o.feedback_rounds = 0;
  const EldershawYimResult q = plan_eldershaw_yim(flat, stiff, {2, 4, 0}, {6, 4, 0}, o);
  EXPECT_EQ(q.feedback_events, 0u);
  EXPECT_DOUBLE_EQ(q.length_m, 4.0);
}

TEST(EldershawYimFootPlanner, ResumesFromAPrefixAndKeepsIt) {
  const RuledTerrain flat(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 10, 10, 0.125));
  EldershawYimPlannerOptions o;
  o.direct = true;
  o.theta_slices = 8;
  const EldershawYimResult r = plan_eldershaw_yim(flat, spider(), {2, 5, 0}, {8, 5, 0}, o);
  ASSERT_TRUE(r.found() && r.foot_plan.found()) << r.brief_report();
  const Footmap footmap(flat, spider());
  const CgLattice lattice(flat.grid(), spider().foot_print, o.theta_slices);
  const FootPlan fresh = plan_footsteps(footmap, spider(), lattice, r.cells, o.feet);
  ASSERT_TRUE(fresh.found());
  // The steps up to the last one on the middle cell, as feedback would hand them over.
  const std::size_t middle = r.cells.size() / 2;
  std::vector<FootStep> prefix;
  for (const FootStep& step : fresh.steps)
    if (step.path_index <= middle) prefix.push_back(step);
  ASSERT_GT(prefix.size(), 1u);
  const FootPlan resumed = plan_footsteps(footmap, spider(), lattice, r.cells, o.feet, prefix);
  ASSERT_TRUE(resumed.found()) << resumed.message;
  ASSERT_GE(resumed.steps.size(), prefix.size());
  for (std::size_t k = 0; k < prefix.size(); ++k) {
    EXPECT_EQ(resumed.steps[k].move, prefix[k].move) << k;
    EXPECT_EQ(resumed.steps[k].path_index, prefix[k].path_index) << k;
    EXPECT_EQ(resumed.steps[k].leg, prefix[k].leg) << k;
  }
  EXPECT_EQ(resumed.steps.back().path_index, r.cells.size() - 1);
  EXPECT_LT(resumed.nodes, fresh.nodes);  // the prefix was not searched again
  // A prefix whose last stance has every foot in the air cannot be resumed from.
  std::vector<FootStep> airborne = prefix;
  for (FootState& foot : airborne.back().feet) foot.contact = false;
  EXPECT_THROW(plan_footsteps(footmap, spider(), lattice, r.cells, o.feet, airborne), InputError);
}

}  // namespace
}  // namespace talus
