#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>

#include "global_search_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/optimal/global_search.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

using global_search_test::bumps;
using global_search_test::hill;
using global_search_test::recomputed_cost;
using terrain_test::grid_from_function;

using vehicle_test::point_mass_rover;

TEST(GlobalSearch, FlatTerrainGivesTheStraightLineAtMaxSpeed) {
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 1.0; }, 0, 0, 60, 40, 1.0));
  GlobalSearchOptions options;
  options.candidates = 1;
  const GlobalSearchResult r = global_search(flat, point_mass_rover(), {5, 20}, {55, 20}, options);
  ASSERT_EQ(r.status, GlobalSearchStatus::kOk) << r.message;
  ASSERT_EQ(r.candidates.size(), 1u);
  EXPECT_NEAR(r.candidates[0].cost_seconds, 50.0 / 10.0, 1e-9);
  EXPECT_NEAR(r.candidates[0].length_m, 50.0, 1e-9);
  for (const Vec2& p : r.candidates[0].vertices) EXPECT_NEAR(p.y(), 20.0, 1e-9);
}

TEST(GlobalSearch, AStarFindsTheSameCostAsTheFullFields) {
  const BPatch terrain = BPatch::interpolate(grid_from_function(
      [](double x, double y) {
        return 3.0 * std::sin(0.15 * x) * std::cos(0.11 * y) + 0.002 * x * y;
      },
      0, 0, 80, 60, 1.0));
  GlobalSearchOptions options;
  options.candidates = 1;
  const GlobalSearchResult full =
      global_search(terrain, point_mass_rover(0.6), {5, 5}, {75, 55}, options);
  options.cost_fields = false;
  const GlobalSearchResult astar =
      global_search(terrain, point_mass_rover(0.6), {5, 5}, {75, 55}, options);
  ASSERT_EQ(full.status, GlobalSearchStatus::kOk);
  ASSERT_EQ(astar.status, GlobalSearchStatus::kOk);
  EXPECT_NEAR(astar.candidates[0].cost_seconds, full.candidates[0].cost_seconds, 1e-9);
  EXPECT_LT(astar.edges_evaluated, full.edges_evaluated);
}

TEST(GlobalSearch, DiagonalOnFlatTerrainUsesKnightMovesWith16Neighbours) {
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 60, 40, 1.0));
  GlobalSearchOptions options;
  options.candidates = 1;
  options.connectivity = 16;
  const GlobalSearchResult r =
      global_search(flat, point_mass_rover(), {5, 5}, {45, 25}, options);  // slope 1/2
  ASSERT_EQ(r.status, GlobalSearchStatus::kOk);
  EXPECT_NEAR(r.candidates[0].cost_seconds, std::hypot(40.0, 20.0) / 10.0, 1e-9);
  options.connectivity = 8;
  const GlobalSearchResult r8 = global_search(flat, point_mass_rover(), {5, 5}, {45, 25}, options);
  EXPECT_GT(r8.candidates[0].cost_seconds, r.candidates[0].cost_seconds * 1.01);
}

TEST(GlobalSearch, HighFrictionCrossesTheHillLowFrictionGoesAround) {
  const BPatch terrain = hill(6.0, 6.0);  // max slope ~ 0.6
  GlobalSearchOptions options;
  options.candidates = 1;
  const auto max_height_on = [&](const CandidatePath& c) {
    double z = 0;
    for (const Vec2& p : c.vertices) z = std::max(z, terrain.elevation(p));
    return z;
  };
  const GlobalSearchResult grippy =
      global_search(terrain, point_mass_rover(1.5), {5, 30}, {75, 30}, options);
  ASSERT_EQ(grippy.status, GlobalSearchStatus::kOk) << grippy.message;
  EXPECT_GT(max_height_on(grippy.candidates[0]), 3.0);  // over the top
  const GlobalSearchResult slippery =
      global_search(terrain, point_mass_rover(0.25), {5, 30}, {75, 30}, options);
  ASSERT_EQ(slippery.status, GlobalSearchStatus::kOk) << slippery.message;
  EXPECT_LT(max_height_on(slippery.candidates[0]), 1.0);  // around it
  for (const GlobalSearchResult* r : {&grippy, &slippery}) {
    EXPECT_NEAR(
        recomputed_cost(terrain, r == &grippy ? point_mass_rover(1.5) : point_mass_rover(0.25),
                        r->candidates[0], 1.0),
        r->candidates[0].cost_seconds, 1e-9 * r->candidates[0].cost_seconds);
  }
}

TEST(GlobalSearch, SymmetricTerrainGivesTwoMirrorCandidatesOfEqualCost) {
  const BPatch terrain = hill(20.0, 6.0);  // far too steep to cross
  GlobalSearchOptions options;
  options.candidates = 2;
  const GlobalSearchResult r =
      global_search(terrain, point_mass_rover(0.5), {5, 30}, {75, 30}, options);
  ASSERT_EQ(r.status, GlobalSearchStatus::kOk) << r.message;
  ASSERT_EQ(r.candidates.size(), 2u);
  EXPECT_NEAR(r.candidates[0].cost_seconds, r.candidates[1].cost_seconds,
              1e-6 * r.candidates[0].cost_seconds);
  // One passes north of the hill, the other south.
  double north = 0, south = 0;
  for (const CandidatePath& c : r.candidates) {
    double mean_y = 0;
    for (const Vec2& p : c.vertices) mean_y += p.y() / static_cast<double>(c.vertices.size());
    (mean_y > 30 ? north : south) += 1;
  }
  EXPECT_EQ(north, 1);
  EXPECT_EQ(south, 1);
}

TEST(GlobalSearch, RidgeWithOneGapIsCrossedThroughTheGap) {
  // A steep ridge along x = 40 except for a gap at 45 < y < 52.
  const BPatch terrain = BPatch::interpolate(grid_from_function(
      [](double x, double y) {
        const double ridge = 8.0 * std::exp(-(x - 40) * (x - 40) / 8.0);
        const double gap =
            (y > 45 && y < 52) ? 1.0 - std::exp(-std::pow(std::min(y - 45, 52 - y), 2) / 2.0) : 0.0;
        return ridge * (1.0 - 0.97 * gap);
      },
      0, 0, 80, 60, 1.0));
  GlobalSearchOptions options;
  options.candidates = 1;
  const GlobalSearchResult r =
      global_search(terrain, point_mass_rover(0.6), {10, 15}, {70, 15}, options);
  ASSERT_EQ(r.status, GlobalSearchStatus::kOk) << r.message;
  bool through_gap = false;
  for (const Vec2& p : r.candidates[0].vertices)
    through_gap = through_gap || (std::abs(p.x() - 40) < 1.5 && p.y() > 44 && p.y() < 53);
  EXPECT_TRUE(through_gap);
}

TEST(GlobalSearch, UnreachableGoalIsAStatusWithTheReachableRegion) {
  // A wall all the way across.
  const BPatch terrain = BPatch::interpolate(grid_from_function(
      [](double x, double) { return 10.0 * std::exp(-(x - 40) * (x - 40) / 4.0); }, 0, 0, 80, 40,
      1.0));
  GlobalSearchOptions options;
  const GlobalSearchResult r =
      global_search(terrain, point_mass_rover(0.5), {10, 20}, {70, 20}, options);
  EXPECT_EQ(r.status, GlobalSearchStatus::kUnreachable);
  EXPECT_NE(r.message.find("unreachable"), std::string::npos) << r.message;
  EXPECT_GT(r.reachable_nodes, 0u);
  EXPECT_LT(r.reachable_nodes, r.nodes / 2 + 100);
  EXPECT_TRUE(r.candidates.empty());
}

TEST(GlobalSearch, BadInputIsAnInputError) {
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 40, 40, 1.0));
  GlobalSearchOptions options;
  EXPECT_THROW(global_search(flat, point_mass_rover(), {-1, 5}, {20, 20}, options), InputError);
  EXPECT_THROW(global_search(flat, point_mass_rover(), {5, 5}, {20, 41}, options), InputError);
  Vehicle unlimited = point_mass_rover();
  unlimited.max_speed = INFINITY;
  EXPECT_THROW(global_search(flat, unlimited, {5, 5}, {20, 20}, options), InputError);
  options.connectivity = 12;
  EXPECT_THROW(global_search(flat, point_mass_rover(), {5, 5}, {20, 20}, options), InputError);
}

// A start (or goal) on a slope steeper than friction is an expected outcome, not bad input:
// unreachable, the message naming the end and why, in both resolutions and both ways.
TEST(GlobalSearch, AnUntraversableStartOrGoalIsUnreachableWithTheReason) {
  const BPatch steep = BPatch::interpolate(grid_from_function(
      [](double x, double y) { return x < 20 ? 2.0 * y : 0.0; }, 0, 0, 40, 40, 1.0));
  for (const GlobalSearchResolution resolution :
       {GlobalSearchResolution::kFull, GlobalSearchResolution::kMulti}) {
    GlobalSearchOptions options;
    options.resolution = resolution;
    const GlobalSearchResult from =
        global_search(steep, point_mass_rover(0.5), {10, 20}, {35, 20}, options);
    EXPECT_EQ(from.status, GlobalSearchStatus::kUnreachable);
    EXPECT_TRUE(from.candidates.empty());
    EXPECT_NE(from.message.find("start node (10, 20) is on untraversable terrain"),
              std::string::npos)
        << from.message;
    const GlobalSearchResult into =
        global_search(steep, point_mass_rover(0.5), {35, 20}, {10, 20}, options);
    EXPECT_EQ(into.status, GlobalSearchStatus::kUnreachable);
    EXPECT_NE(into.message.find("goal node (10, 20) is on untraversable terrain"),
              std::string::npos)
        << into.message;
  }
}

// ---- Edge costs against closed forms -------------------------------------
// On a plane z = p . (x, y) a straight edge is a straight 3-D segment of
// length l sqrt(1 + (p . d)^2) (l its planar length, d its unit direction),
// with no curvature, so the speed limits are speed-independent: v_max is the
// max_speed cap wherever the point mass can stand at all, and
// J = l sqrt(1 + (p . d)^2) / v_cap. Simpson's rule is exact on a constant
// integrand, and not-a-knot interpolation reproduces a plane exactly, so
// only round-off separates the two: 1e-12 relative.

TEST(GlobalSearchEdgeCost, InclinedPlaneCostsItsSurfaceLengthAtTopSpeed) {
  const double px = 0.3, py = -0.2;  // steepest slope 0.36 < mu = 0.7 < b/h = 1.2
  const BPatch plane = BPatch::interpolate(grid_from_function(
      [&](double x, double y) { return 2.0 + px * x + py * y; }, 0, 0, 30, 30, 1.0));
  const Vehicle rover = point_mass_rover(0.7);
  const Vec2 a(12.0, 14.0);
  for (const Vec2& offset : {Vec2(1, 0), Vec2(0, 1), Vec2(1, 1), Vec2(-1, 2), Vec2(3, -1),
                             Vec2(-2.5, -4.0), Vec2(7.3, 1.9)}) {
    const Vec2 b = a + offset;
    const double l = offset.norm(), slope = (px * offset.x() + py * offset.y()) / l;
    const double length = l * std::sqrt(1.0 + slope * slope);
    for (int stations : {3, 5, 9}) {
      const EdgeCost c = edge_cost(plane, rover, a, b, stations);
      EXPECT_NEAR(c.length, length, 1e-12 * length);
      EXPECT_NEAR(c.forward, length / rover.max_speed, 1e-12 * length / rover.max_speed);
      EXPECT_NEAR(c.backward, length / rover.max_speed, 1e-12 * length / rover.max_speed);
    }
  }
}

TEST(GlobalSearchEdgeCost, SideSlopeIsFreeBelowTheSlidingAndTipOverLimitsAndClosedAbove) {
  // An edge along x across the side slope z = s y: level along the edge, a
  // lateral slope angle atan s. The point mass stands still (a = 0) iff
  // friction holds the lateral gravity component, s <= mu, and the normal
  // force stays inside the track, s <= b/h (= 0.6 / 0.5 = 1.2). Below both,
  // J = l / v_cap; above either, the edge is closed both ways.
  struct Case {
    double s, mu;
    bool open;
  };
  for (const Case k : {Case{0.69, 0.7, true}, Case{0.71, 0.7, false},     // sliding binds at 0.7
                       Case{1.19, 1.5, true}, Case{1.21, 1.5, false}}) {  // tip-over binds at 1.2
    const BPatch slope = BPatch::interpolate(
        grid_from_function([&](double, double y) { return k.s * y; }, 0, 0, 20, 20, 1.0));
    const EdgeCost c = edge_cost(slope, point_mass_rover(k.mu), {5, 10}, {9, 10}, 5);
    if (k.open) {
      EXPECT_NEAR(c.length, 4.0, 1e-12 * 4.0) << k.s;
      EXPECT_NEAR(c.forward, 0.4, 1e-12 * 0.4) << k.s << " " << k.mu;
      EXPECT_NEAR(c.backward, 0.4, 1e-12 * 0.4) << k.s << " " << k.mu;
    } else {
      EXPECT_EQ(c.forward, INFINITY) << k.s << " " << k.mu;
      EXPECT_EQ(c.backward, INFINITY) << k.s << " " << k.mu;
    }
  }
}

TEST(GlobalSearch, InclinedPlaneSearchCostIsTheStraightSurfaceLengthAtTopSpeed) {
  // The 3-D length on a plane is a strictly convex norm of the planar
  // displacement, so the straight lattice line is the unique best path when
  // the lattice has its direction: here (2, 1), a knight move.
  const double px = 0.3, py = -0.2;
  const BPatch plane = BPatch::interpolate(
      grid_from_function([&](double x, double y) { return px * x + py * y; }, 0, 0, 60, 40, 1.0));
  GlobalSearchOptions options;
  options.candidates = 1;
  const Vec2 start(5, 5), goal(45, 25);
  const GlobalSearchResult r = global_search(plane, point_mass_rover(), start, goal, options);
  ASSERT_EQ(r.status, GlobalSearchStatus::kOk) << r.message;
  const Vec2 d = goal - start;
  const double slope = (px * d.x() + py * d.y()) / d.norm();
  const double length = d.norm() * std::sqrt(1.0 + slope * slope);
  EXPECT_NEAR(r.candidates[0].cost_seconds, length / 10.0, 1e-12 * length / 10.0);
  EXPECT_NEAR(r.candidates[0].length_m, length, 1e-12 * length);
}

// ---- Options --------------------------------------------------------------

TEST(GlobalSearch, ThirtyTwoNeighboursTakeTheOneThreeAndTwoThreeDirectionsStraight) {
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, 0, 40, 50, 1.0));
  GlobalSearchOptions options;
  options.candidates = 1;
  for (const Vec2& d : {Vec2(10, 30), Vec2(20, 30), Vec2(-30, 10), Vec2(30, -20)}) {
    const Vec2 start = d.x() > 0 ? Vec2(3, d.y() > 0 ? 5 : 45) : Vec2(35, 5);
    const Vec2 goal = start + d;
    options.connectivity = 32;
    const GlobalSearchResult r32 = global_search(flat, point_mass_rover(), start, goal, options);
    ASSERT_EQ(r32.status, GlobalSearchStatus::kOk) << r32.message;
    // Straight at 10 m/s: exact up to round-off.
    EXPECT_NEAR(r32.candidates[0].cost_seconds, d.norm() / 10.0, 1e-12 * d.norm() / 10.0);
    for (const Vec2& p : r32.candidates[0].vertices) {
      const Vec2 q = p - start;  // every vertex on the line start -> goal
      EXPECT_NEAR(q.x() * d.y() - q.y() * d.x(), 0.0, 1e-9);
    }
    // 16 neighbours have no (1, 3) or (2, 3) move: the best path bends, and the
    // best lattice approximation of these directions costs >= 1 % more.
    options.connectivity = 16;
    const GlobalSearchResult r16 = global_search(flat, point_mass_rover(), start, goal, options);
    EXPECT_GT(r16.candidates[0].cost_seconds, 1.01 * r32.candidates[0].cost_seconds);
  }
}

TEST(GlobalSearch, FinerLatticeKeepsTheStraightLineCost) {
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 1.0; }, 0, 0, 60, 40, 1.0));
  GlobalSearchOptions options;
  options.candidates = 1;
  std::size_t previous_nodes = 0;
  for (double spacing : {2.0, 1.0, 0.5, 0.25}) {
    options.lattice_spacing = spacing;
    const GlobalSearchResult r =
        global_search(flat, point_mass_rover(), {6, 20}, {54, 20}, options);
    ASSERT_EQ(r.status, GlobalSearchStatus::kOk) << r.message;
    EXPECT_EQ(r.spacing, spacing);
    EXPECT_NEAR(r.candidates[0].cost_seconds, 48.0 / 10.0, 1e-12 * 4.8) << spacing;
    // One vertex per lattice step along the line.
    EXPECT_EQ(r.candidates[0].vertices.size(), static_cast<std::size_t>(48.0 / spacing) + 1);
    if (previous_nodes > 0) {
      EXPECT_GT(r.nodes, 3 * previous_nodes);  // about 4x per halving
    }
    previous_nodes = r.nodes;
  }
  // A (2, 1) diagonal on the half-spacing lattice is a knight move there too.
  options.lattice_spacing = 0.5;
  const GlobalSearchResult r = global_search(flat, point_mass_rover(), {6, 5}, {46, 25}, options);
  EXPECT_NEAR(r.candidates[0].cost_seconds, std::hypot(40.0, 20.0) / 10.0,
              1e-12 * std::hypot(40.0, 20.0) / 10.0);
}

/// Euclidean distance from p to the nearest vertex of c.
double to_vertices(const Vec2& p, const CandidatePath& c) {
  double d = INFINITY;
  for (const Vec2& q : c.vertices) d = std::min(d, (p - q).norm());
  return d;
}

TEST(GlobalSearch, CandidatesAreAtLeastTheSeparationApart) {
  // The rule (options header): a candidate has a vertex >= d from every
  // accepted one, and at most half its vertices within d / 2 of it, in
  // chamfer distance. Chamfer (steps h, h sqrt 2) overestimates the Euclidean
  // distance by at most sqrt(4 - 2 sqrt 2) = 1.0824 and never under-
  // estimates it, so in Euclidean terms: farthest >= d / 1.0824, and at most
  // half the vertices within d / (2 * 1.0824).
  const BPatch terrain = bumps();
  const Vehicle rover = point_mass_rover(0.3);
  const double chamfer = std::sqrt(4.0 - 2.0 * std::sqrt(2.0));
  GlobalSearchOptions options;
  options.candidates = 5;
  options.max_cost_ratio = 3.0;
  for (double d : {6.0, 12.0}) {
    options.distinctness = d;
    const GlobalSearchResult r = global_search(terrain, rover, {3, 30}, {77, 30}, options);
    ASSERT_EQ(r.status, GlobalSearchStatus::kOk) << r.message;
    ASSERT_GE(r.candidates.size(), 3u) << d;  // the rule is exercised
    for (std::size_t j = 1; j < r.candidates.size(); ++j) {
      EXPECT_GE(r.candidates[j].cost_seconds, r.candidates[j - 1].cost_seconds);  // best first
      EXPECT_NEAR(recomputed_cost(terrain, rover, r.candidates[j], 1.0),
                  r.candidates[j].cost_seconds, 1e-9 * r.candidates[j].cost_seconds);
      for (std::size_t i = 0; i < j; ++i) {
        double farthest = 0.0;
        std::size_t near = 0;
        for (const Vec2& p : r.candidates[j].vertices) {
          const double e = to_vertices(p, r.candidates[i]);
          farthest = std::max(farthest, e);
          near += e < d / (2.0 * chamfer);
        }
        EXPECT_GE(farthest, d / chamfer - 1e-6) << d << ": " << j << " vs " << i;
        EXPECT_LE(2 * near, r.candidates[j].vertices.size()) << d << ": " << j << " vs " << i;
      }
    }
  }
}

TEST(GlobalSearch, NoCandidateCostsMoreThanTheRatioTimesTheBest) {
  const BPatch terrain = bumps();
  const Vehicle rover = point_mass_rover(0.3);
  GlobalSearchOptions options;
  options.candidates = 6;
  options.distinctness = 5.0;
  options.max_cost_ratio = 3.0;
  const GlobalSearchResult loose = global_search(terrain, rover, {3, 30}, {77, 30}, options);
  ASSERT_EQ(loose.status, GlobalSearchStatus::kOk) << loose.message;
  const double best = loose.candidates[0].cost_seconds;
  // Non-vacuous: without a tight ratio some candidate costs over 1.02 x best.
  ASSERT_GT(loose.candidates.back().cost_seconds, 1.02 * best);
  for (double ratio : {1.02, 1.1}) {
    options.max_cost_ratio = ratio;
    const GlobalSearchResult r = global_search(terrain, rover, {3, 30}, {77, 30}, options);
    ASSERT_EQ(r.status, GlobalSearchStatus::kOk);
    ASSERT_FALSE(r.candidates.empty());
    EXPECT_EQ(r.candidates[0].cost_seconds, best);  // the best does not depend on the ratio
    for (const CandidatePath& c : r.candidates)
      EXPECT_LE(c.cost_seconds, ratio * best * (1 + 1e-12)) << ratio;
  }
  // Ratio 1: only paths as good as the best.
  options.max_cost_ratio = 1.0;
  const GlobalSearchResult tight = global_search(terrain, rover, {3, 30}, {77, 30}, options);
  for (const CandidatePath& c : tight.candidates) EXPECT_LE(c.cost_seconds, best * (1 + 1e-12));
}

TEST(GlobalSearch, SlopeSteeperThanFrictionCanBeNeitherClimbedNorDescended) {
  // A plane of slope 0.5 with mu = 0.4: sliding limits do not bind on the fall
  // line, but the vehicle can neither climb it nor stop descending it.
  const BPatch plane = BPatch::interpolate(
      grid_from_function([](double x, double) { return 0.5 * x; }, 0, 0, 20, 20, 1.0));
  const EdgeCost c = edge_cost(plane, point_mass_rover(0.4), {5, 10}, {6, 10}, 5);
  EXPECT_EQ(c.forward, INFINITY);
  EXPECT_EQ(c.backward, INFINITY);
  const EdgeCost gentle = edge_cost(plane, point_mass_rover(0.7), {5, 10}, {6, 10}, 5);
  EXPECT_LT(gentle.forward, INFINITY);
  EXPECT_LT(gentle.backward, INFINITY);
}

// GlobalSearchOptions::threads: every edge computed up front on several threads gives the
// serial search's candidates, costs and both cost fields bit for bit.
TEST(GlobalSearchThreads, AnyThreadCountGivesTheSerialCandidatesAndFields) {
  const BPatch terrain = bumps();
  GlobalSearchOptions options;
  options.candidates = 3;
  const Vehicle v = point_mass_rover(0.3);
  const GlobalSearchResult serial = global_search(terrain, v, {3, 30}, {77, 30}, options);
  ASSERT_EQ(serial.status, GlobalSearchStatus::kOk) << serial.message;
  ASSERT_GE(serial.candidates.size(), 2u);
  for (const std::size_t threads : {2u, 3u}) {
    options.threads = threads;
    const GlobalSearchResult r = global_search(terrain, v, {3, 30}, {77, 30}, options);
    ASSERT_EQ(r.status, GlobalSearchStatus::kOk) << r.message;
    ASSERT_EQ(r.candidates.size(), serial.candidates.size()) << threads;
    for (std::size_t c = 0; c < r.candidates.size(); ++c) {
      EXPECT_EQ(r.candidates[c].cost_seconds, serial.candidates[c].cost_seconds);
      EXPECT_EQ(r.candidates[c].length_m, serial.candidates[c].length_m);
      EXPECT_EQ(r.candidates[c].vertices, serial.candidates[c].vertices);
    }
    EXPECT_EQ(r.cost_from_start, serial.cost_from_start);
    EXPECT_EQ(r.cost_to_goal, serial.cost_to_goal);
    // Up front it also computes the edges at nodes no search reaches.
    EXPECT_GE(r.edges_evaluated, serial.edges_evaluated);
  }
  options.threads = 2000;
  EXPECT_THROW(global_search(terrain, v, {3, 30}, {77, 30}, options), InputError);
}

// The termination is polled between the parallel batches of edge costs (on the calling
// thread only): a stop after the first batch ends the search there.
TEST(GlobalSearchThreads, StopIsPolledBetweenTheBatchesOfEdgeCosts) {
  const BPatch terrain = bumps();
  GlobalSearchOptions options;
  options.threads = 2;
  options.stop_interval = 1;
  const Vehicle v = point_mass_rover(0.3);
  const std::size_t nodes = global_search(terrain, v, {3, 30}, {77, 30}, options).nodes;
  // Sampling the surface polls once per node (interval 1); the edge stage then once per batch.
  std::size_t calls = 0;
  options.termination = Termination::when([&] { return ++calls > nodes + 1; });
  const GlobalSearchResult r = global_search(terrain, v, {3, 30}, {77, 30}, options);
  EXPECT_EQ(r.status, GlobalSearchStatus::kStopped);
  EXPECT_NE(r.message.find("computing the edge costs"), std::string::npos) << r.message;
  EXPECT_EQ(calls, nodes + 2);
  // One batch of stop_interval nodes per thread, plus the start's and goal's own checks.
  EXPECT_LE(r.edges_evaluated, 2u * 8u + 2u * 16u);
}

/// Candidates, costs and cost fields of two searches are identical.
void expect_same_search(const GlobalSearchResult& a, const GlobalSearchResult& b) {
  ASSERT_EQ(a.status, b.status) << a.message << " / " << b.message;
  ASSERT_EQ(a.candidates.size(), b.candidates.size());
  for (std::size_t c = 0; c < a.candidates.size(); ++c) {
    EXPECT_EQ(a.candidates[c].cost_seconds, b.candidates[c].cost_seconds) << c;
    EXPECT_EQ(a.candidates[c].length_m, b.candidates[c].length_m) << c;
    EXPECT_EQ(a.candidates[c].vertices, b.candidates[c].vertices) << c;
  }
  EXPECT_EQ(a.cost_from_start, b.cost_from_start);
  EXPECT_EQ(a.cost_to_goal, b.cost_to_goal);
  EXPECT_EQ(a.expanded, b.expanded);
}

// A workspace keeps the lattice's edge costs between searches on one terrain and vehicle:
// a search with other excluded regions (the planner's feedback rounds) computes no edge
// again, gives exactly the search without a workspace, and a region excluded before is not
// excluded after.
TEST(GlobalSearchWorkspace, ReusesTheEdgeCostsAndGivesTheSearchWithoutIt) {
  const BPatch terrain = bumps();
  const Vehicle v = point_mass_rover(0.3);
  GlobalSearchOptions options;
  options.candidates = 3;
  GlobalSearchWorkspace workspace;
  const GlobalSearchResult first = global_search(terrain, v, {3, 30}, {77, 30}, options, workspace);
  expect_same_search(first, global_search(terrain, v, {3, 30}, {77, 30}, options));
  ASSERT_EQ(first.status, GlobalSearchStatus::kOk);
  EXPECT_GT(first.edges_evaluated, 0u);
  EXPECT_EQ(workspace.lattices(), 1u);

  // Exclude a disc on the best candidate's middle: another route, no edge recomputed.
  const std::vector<Vec2>& best = first.candidates.front().vertices;
  options.excluded = {{best[best.size() / 2], 6.0}};
  const GlobalSearchResult round = global_search(terrain, v, {3, 30}, {77, 30}, options, workspace);
  const GlobalSearchResult fresh = global_search(terrain, v, {3, 30}, {77, 30}, options);
  expect_same_search(round, fresh);
  EXPECT_NE(round.candidates.front().vertices, best);
  EXPECT_EQ(round.edges_evaluated, 0u);
  EXPECT_GT(fresh.edges_evaluated, 0u);

  // Without the disc again: the first search, from the cache.
  options.excluded.clear();
  expect_same_search(global_search(terrain, v, {3, 30}, {77, 30}, options, workspace), first);

  // Another start and goal reuse it too; another vehicle or connectivity starts afresh.
  expect_same_search(global_search(terrain, v, {5, 10}, {70, 50}, options, workspace),
                     global_search(terrain, v, {5, 10}, {70, 50}, options));
  const Vehicle slippery = point_mass_rover(0.2);
  const GlobalSearchResult other =
      global_search(terrain, slippery, {3, 30}, {77, 30}, options, workspace);
  expect_same_search(other, global_search(terrain, slippery, {3, 30}, {77, 30}, options));
  EXPECT_GT(other.edges_evaluated, 0u);
  options.connectivity = 8;
  expect_same_search(global_search(terrain, slippery, {3, 30}, {77, 30}, options, workspace),
                     global_search(terrain, slippery, {3, 30}, {77, 30}, options));
  EXPECT_EQ(workspace.lattices(), 1u);
  workspace.clear();
  EXPECT_EQ(workspace.lattices(), 0u);
}

// A workspace recognises its terrain by BPatch::identity(), not by address: a new terrain
// built where a destroyed one stood is another terrain (the workspace used to reuse the old
// lattice's samples and costs there, the reason clear() had to be called), and so is a new
// fit of the same grid; a copy is the same terrain.
TEST(GlobalSearchWorkspace, ANewTerrainAtADestroyedOnesAddressIsAnotherTerrain) {
  const Vehicle v = point_mass_rover(0.3);
  GlobalSearchOptions options;
  GlobalSearchWorkspace workspace;
  std::optional<BPatch> slot;
  slot.emplace(bumps());
  const BPatch* address = &*slot;
  const GlobalSearchResult on_bumps =
      global_search(*slot, v, {3, 30}, {77, 30}, options, workspace);
  ASSERT_EQ(on_bumps.status, GlobalSearchStatus::kOk);
  slot.reset();
  slot.emplace(BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 80, 60, 1.0)));
  ASSERT_EQ(&*slot, address);  // the new terrain stands where the old one did
  const GlobalSearchResult reused = global_search(*slot, v, {3, 30}, {77, 30}, options, workspace);
  expect_same_search(reused, global_search(*slot, v, {3, 30}, {77, 30}, options));
  EXPECT_GT(reused.edges_evaluated, 0u);
  EXPECT_LT(reused.candidates.front().cost_seconds, on_bumps.candidates.front().cost_seconds);
  // The same terrain again keeps the lattice; so does a copy of it (the same immutable
  // coefficients), even once the original is gone: the workspace holds its own copy.
  EXPECT_EQ(global_search(*slot, v, {3, 30}, {77, 30}, options, workspace).edges_evaluated, 0u);
  const BPatch copy = *slot;
  EXPECT_EQ(copy.identity(), slot->identity());
  slot.reset();
  const GlobalSearchResult on_copy = global_search(copy, v, {3, 30}, {77, 30}, options, workspace);
  EXPECT_EQ(on_copy.edges_evaluated, 0u);
  expect_same_search(on_copy, reused);
  // A new fit of the same grid is another terrain.
  const BPatch refit = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 80, 60, 1.0));
  EXPECT_NE(refit.identity(), copy.identity());
  EXPECT_GT(global_search(refit, v, {3, 30}, {77, 30}, options, workspace).edges_evaluated, 0u);
}

// Coarse to fine: the coarse lattice is kept, the corridors are not; same result.
TEST(GlobalSearchWorkspace, MultiResolutionKeepsTheCoarseLattice) {
  const BPatch terrain = bumps();
  const Vehicle v = point_mass_rover(0.3);
  GlobalSearchOptions options;
  options.resolution = GlobalSearchResolution::kMulti;
  GlobalSearchWorkspace workspace;
  for (int round = 0; round < 2; ++round) {
    const GlobalSearchResult r = global_search(terrain, v, {3, 30}, {77, 30}, options, workspace);
    expect_same_search(r, global_search(terrain, v, {3, 30}, {77, 30}, options));
  }
  EXPECT_GE(workspace.lattices(), 1u);
}

}  // namespace
}  // namespace talus
