// The global search's turn limit (GlobalSearchOptions::turn_limit): routes over
// (node, arrival direction) states whose turns fit the vehicle's steering limit.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "global_search_test_support.hpp"
#include "talus/optimal/global_search.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

using global_search_test::recomputed_cost;

/// A steep wall along y = 15 from the west edge to x ≈ 25 on a 40 m x 30 m
/// grid of 1 m cells: from (24, 13) to (24, 17) a route must go round its end.
BPatch wall() {
  return BPatch::interpolate(terrain_test::grid_from_function(
      [](double x, double y) {
        const double taper = 1.0 / (1.0 + std::exp(3.0 * (x - 25.0)));
        return 6.0 * std::exp(-0.5 * (y - 15.0) * (y - 15.0)) * taper;
      },
      0, 0, 40, 30, 1.0));
}

/// The rover with a steering limit of curvature `kappa` [1/m] (wheelbase 2 m).
Vehicle steered_rover(double kappa) {
  Vehicle v = vehicle_test::point_mass_rover();
  v.half_wheelbase = 1.0;
  v.max_steering = std::atan(2.0 * v.half_wheelbase * kappa);
  return v;
}

/// The sharpest turn of a polyline against the rule: max over its corners of
/// tan(|Δθ|/2) / (κ min(L₁, L₂) / 2); <= 1 where every turn fits.
double worst_turn(const CandidatePath& c, double kappa) {
  double worst = 0.0;
  for (std::size_t k = 1; k + 1 < c.vertices.size(); ++k) {
    const Vec2 a = c.vertices[k] - c.vertices[k - 1], b = c.vertices[k + 1] - c.vertices[k];
    const double turn = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    worst = std::max(worst,
                     std::tan(0.5 * std::abs(turn)) / (0.5 * kappa * std::min(a.norm(), b.norm())));
  }
  return worst;
}

TEST(GlobalSearchTurnLimit, RoutesRoundAWallTurnWithinTheSteeringLimit) {
  const BPatch terrain = wall();
  const double kappa = 0.6;  // turns of at most 33.4 deg between unit edges
  const Vehicle v = steered_rover(kappa);
  GlobalSearchOptions options;
  options.turn_limit = false;
  const GlobalSearchResult free = global_search(terrain, v, {24, 13}, {24, 17}, options);
  options.turn_limit = true;
  const GlobalSearchResult steered = global_search(terrain, v, {24, 13}, {24, 17}, options);
  ASSERT_EQ(free.status, GlobalSearchStatus::kOk) << free.message;
  ASSERT_EQ(steered.status, GlobalSearchStatus::kOk) << steered.message;
  // Round the wall's end the position-only route turns more sharply than the vehicle can.
  EXPECT_GT(worst_turn(free.candidates[0], kappa), 1.0);
  ASSERT_GE(steered.candidates.size(), 1u);
  EXPECT_FALSE(steered.turn_limit_relaxed);
  for (const CandidatePath& c : steered.candidates) {
    EXPECT_LE(worst_turn(c, kappa), 1.0 + 1e-9);
    // Each candidate (start tree + goal tree of the state graph) costs its own edges.
    EXPECT_NEAR(recomputed_cost(terrain, v, c, 1.0), c.cost_seconds, 1e-9 * c.cost_seconds);
    EXPECT_EQ(c.vertices.front(), steered.start_node);
    EXPECT_EQ(c.vertices.back(), steered.goal_node);
  }
  // A restriction, and here a costly one: the hairpin round the wall's end swings wide
  // (1.87 s against 1.11 s when measured).
  EXPECT_GT(steered.candidates[0].cost_seconds, 1.2 * free.candidates[0].cost_seconds);
  // The node fields are each node's best state: both give the best cost at the other end.
  const std::size_t s = 13 * steered.nx + 24, g = 17 * steered.nx + 24;
  EXPECT_NEAR(steered.cost_from_start[g], steered.candidates[0].cost_seconds, 1e-12);
  EXPECT_NEAR(steered.cost_to_goal[s], steered.candidates[0].cost_seconds, 1e-12);
  EXPECT_EQ(steered.cost_from_start[s], 0.0);
  EXPECT_EQ(steered.cost_to_goal[g], 0.0);
  // A* over the states finds the same best cost.
  options.cost_fields = false;
  options.candidates = 1;
  const GlobalSearchResult astar = global_search(terrain, v, {24, 13}, {24, 17}, options);
  ASSERT_EQ(astar.status, GlobalSearchStatus::kOk) << astar.message;
  EXPECT_NEAR(astar.candidates[0].cost_seconds, steered.candidates[0].cost_seconds, 1e-9);
  EXPECT_LE(worst_turn(astar.candidates[0], kappa), 1.0 + 1e-9);
}

TEST(GlobalSearchTurnLimit, WhereNoRouteTurnsWithinTheLimitThePositionOnlyRoutesAreReturned) {
  // At 0.3 1/m on 1 m edges no turn between a unit edge and its neighbours fits, and the
  // diagonal directions turn among themselves by at most 37 deg: no route rounds the wall.
  const BPatch terrain = wall();
  const Vehicle v = steered_rover(0.3);
  GlobalSearchOptions options;
  const GlobalSearchResult limited = global_search(terrain, v, {24, 13}, {24, 17}, options);
  options.turn_limit = false;
  const GlobalSearchResult free = global_search(terrain, v, {24, 13}, {24, 17}, options);
  ASSERT_EQ(limited.status, GlobalSearchStatus::kOk) << limited.message;
  EXPECT_TRUE(limited.turn_limit_relaxed);
  EXPECT_FALSE(free.turn_limit_relaxed);
  EXPECT_NE(limited.message.find("steering limit"), std::string::npos) << limited.message;
  ASSERT_EQ(limited.candidates.size(), free.candidates.size());
  for (std::size_t k = 0; k < free.candidates.size(); ++k) {
    EXPECT_EQ(limited.candidates[k].vertices, free.candidates[k].vertices);
    EXPECT_EQ(limited.candidates[k].cost_seconds, free.candidates[k].cost_seconds);
  }
  EXPECT_GT(limited.expanded, free.expanded);  // both searches counted
}

TEST(GlobalSearchTurnLimit, WithoutASteeringLimitTheSearchIsPositionOnly) {
  const BPatch terrain = wall();
  const Vehicle v = vehicle_test::point_mass_rover();
  GlobalSearchOptions options;
  const GlobalSearchResult limited = global_search(terrain, v, {24, 13}, {24, 17}, options);
  options.turn_limit = false;
  const GlobalSearchResult free = global_search(terrain, v, {24, 13}, {24, 17}, options);
  ASSERT_EQ(limited.candidates.size(), free.candidates.size());
  for (std::size_t k = 0; k < free.candidates.size(); ++k) {
    EXPECT_EQ(limited.candidates[k].vertices, free.candidates[k].vertices);
    EXPECT_EQ(limited.candidates[k].cost_seconds, free.candidates[k].cost_seconds);
  }
  EXPECT_EQ(limited.expanded, free.expanded);
  EXPECT_EQ(limited.cost_from_start, free.cost_from_start);
}

TEST(GlobalSearchTurnLimit, ALooseLimitKeepsThePositionOnlyOptimum) {
  // tan(0.75) / 0.02 = 47 1/m: every turn but the U-turn fits, and no best route has one.
  const BPatch terrain = wall();
  Vehicle v = vehicle_test::point_mass_rover();
  v.half_wheelbase = 0.01;
  v.max_steering = 0.75;
  GlobalSearchOptions options;
  const GlobalSearchResult limited = global_search(terrain, v, {24, 13}, {24, 17}, options);
  options.turn_limit = false;
  const GlobalSearchResult free = global_search(terrain, v, {24, 13}, {24, 17}, options);
  ASSERT_EQ(limited.status, GlobalSearchStatus::kOk) << limited.message;
  EXPECT_NEAR(limited.candidates[0].cost_seconds, free.candidates[0].cost_seconds, 1e-12);
  EXPECT_EQ(limited.reachable_nodes, free.reachable_nodes);
  const auto same = [](double a, double b) { return a == b || std::abs(a - b) <= 1e-9; };
  for (std::size_t n = 0; n < free.cost_from_start.size(); ++n) {
    ASSERT_TRUE(same(limited.cost_from_start[n], free.cost_from_start[n])) << n;
    ASSERT_TRUE(same(limited.cost_to_goal[n], free.cost_to_goal[n])) << n;
  }
}

}  // namespace
}  // namespace talus
