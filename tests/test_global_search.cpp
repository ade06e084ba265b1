#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "talus/core/error.hpp"
#include "talus/optimal/global_search.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_from_function;

using vehicle_test::point_mass_rover;

/// J recomputed independently along a candidate's vertices.
double recomputed_cost(const BPatch& terrain, const Vehicle& v, const CandidatePath& c,
                       double spacing) {
  double total = 0.0;
  for (std::size_t k = 0; k + 1 < c.vertices.size(); ++k) {
    const Vec2 a = c.vertices[k], b = c.vertices[k + 1];
    const int stations = edge_stations((b - a).norm(), spacing);
    total += edge_cost(terrain, v, a, b, stations).forward;
  }
  return total;
}

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
  const GlobalSearchResult full = global_search(terrain, point_mass_rover(0.6), {5, 5}, {75, 55}, options);
  options.cost_fields = false;
  const GlobalSearchResult astar = global_search(terrain, point_mass_rover(0.6), {5, 5}, {75, 55}, options);
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

/// A Gaussian hill between start and goal.
BPatch hill(double height, double sigma) {
  return BPatch::interpolate(grid_from_function(
      [&](double x, double y) {
        return height *
               std::exp(-((x - 40) * (x - 40) + (y - 30) * (y - 30)) / (2 * sigma * sigma));
      },
      0, 0, 80, 60, 1.0));
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
  const GlobalSearchResult grippy = global_search(terrain, point_mass_rover(1.5), {5, 30}, {75, 30}, options);
  ASSERT_EQ(grippy.status, GlobalSearchStatus::kOk) << grippy.message;
  EXPECT_GT(max_height_on(grippy.candidates[0]), 3.0);  // over the top
  const GlobalSearchResult slippery =
      global_search(terrain, point_mass_rover(0.25), {5, 30}, {75, 30}, options);
  ASSERT_EQ(slippery.status, GlobalSearchStatus::kOk) << slippery.message;
  EXPECT_LT(max_height_on(slippery.candidates[0]), 1.0);  // around it
  for (const GlobalSearchResult* r : {&grippy, &slippery}) {
    EXPECT_NEAR(
        recomputed_cost(terrain, r == &grippy ? point_mass_rover(1.5) : point_mass_rover(0.25), r->candidates[0], 1.0),
        r->candidates[0].cost_seconds, 1e-9 * r->candidates[0].cost_seconds);
  }
}

TEST(GlobalSearch, SymmetricTerrainGivesTwoMirrorCandidatesOfEqualCost) {
  const BPatch terrain = hill(20.0, 6.0);  // far too steep to cross
  GlobalSearchOptions options;
  options.candidates = 2;
  const GlobalSearchResult r = global_search(terrain, point_mass_rover(0.5), {5, 30}, {75, 30}, options);
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
  const GlobalSearchResult r = global_search(terrain, point_mass_rover(0.6), {10, 15}, {70, 15}, options);
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
  const GlobalSearchResult r = global_search(terrain, point_mass_rover(0.5), {10, 20}, {70, 20}, options);
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
  // Start on a slope steeper than friction.
  const BPatch steep = BPatch::interpolate(grid_from_function(
      [](double x, double y) { return x < 20 ? 2.0 * y : 0.0; }, 0, 0, 40, 40, 1.0));
  GlobalSearchOptions ok;
  EXPECT_THROW(global_search(steep, point_mass_rover(0.5), {10, 20}, {35, 20}, ok), InputError);
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

}  // namespace
}  // namespace talus
