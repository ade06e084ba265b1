// The multi-resolution (coarse-to-fine) global search against the full one,
// and the global search's stop check.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "global_search_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/optimal/global_search.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

using global_search_test::bumps;
using global_search_test::hill;
using terrain_test::grid_from_function;
using vehicle_test::point_mass_rover;

/// One case of test_global_search.cpp: terrain, vehicle, start, goal, options.
struct Case {
  std::string name;
  BPatch terrain;
  Vehicle vehicle;
  Vec2 start, goal;
  GlobalSearchOptions options;
};

BPatch flat(double z, double w, double h) {
  return BPatch::interpolate(
      grid_from_function([z](double, double) { return z; }, 0, 0, w, h, 1.0));
}

GlobalSearchOptions with(std::size_t candidates, int connectivity = 16, double lattice = 0.0,
                         bool fields = true) {
  GlobalSearchOptions o;
  o.candidates = candidates;
  o.connectivity = connectivity;
  o.lattice_spacing = lattice;
  o.cost_fields = fields;
  return o;
}

/// The global-search test cases (test_global_search.cpp), same terrains,
/// vehicles, ends and options.
std::vector<Case> existing_cases() {
  std::vector<Case> cases;
  const BPatch sine = BPatch::interpolate(grid_from_function(
      [](double x, double y) {
        return 3.0 * std::sin(0.15 * x) * std::cos(0.11 * y) + 0.002 * x * y;
      },
      0, 0, 80, 60, 1.0));
  const BPatch ridge = BPatch::interpolate(grid_from_function(
      [](double x, double y) {
        const double r = 8.0 * std::exp(-(x - 40) * (x - 40) / 8.0);
        const double gap =
            (y > 45 && y < 52) ? 1.0 - std::exp(-std::pow(std::min(y - 45, 52 - y), 2) / 2.0) : 0.0;
        return r * (1.0 - 0.97 * gap);
      },
      0, 0, 80, 60, 1.0));
  const BPatch plane = BPatch::interpolate(
      grid_from_function([](double x, double y) { return 0.3 * x - 0.2 * y; }, 0, 0, 60, 40, 1.0));
  cases.push_back({"flat line", flat(1.0, 60, 40), point_mass_rover(), {5, 20}, {55, 20}, with(1)});
  cases.push_back({"sine fields", sine, point_mass_rover(0.6), {5, 5}, {75, 55}, with(1)});
  cases.push_back(
      {"sine A*", sine, point_mass_rover(0.6), {5, 5}, {75, 55}, with(1, 16, 0.0, false)});
  cases.push_back({"knight 16", flat(0.0, 60, 40), point_mass_rover(), {5, 5}, {45, 25}, with(1)});
  cases.push_back(
      {"knight 8", flat(0.0, 60, 40), point_mass_rover(), {5, 5}, {45, 25}, with(1, 8)});
  cases.push_back({"hill grippy", hill(6, 6), point_mass_rover(1.5), {5, 30}, {75, 30}, with(1)});
  cases.push_back(
      {"hill slippery", hill(6, 6), point_mass_rover(0.25), {5, 30}, {75, 30}, with(1)});
  cases.push_back({"mirror", hill(20, 6), point_mass_rover(0.5), {5, 30}, {75, 30}, with(2)});
  cases.push_back({"ridge gap", ridge, point_mass_rover(0.6), {10, 15}, {70, 15}, with(1)});
  cases.push_back({"plane", plane, point_mass_rover(), {5, 5}, {45, 25}, with(1)});
  for (const Vec2& d : {Vec2(10, 30), Vec2(20, 30), Vec2(-30, 10), Vec2(30, -20)}) {
    const Vec2 start = d.x() > 0 ? Vec2(3, d.y() > 0 ? 5 : 45) : Vec2(35, 5);
    cases.push_back(
        {"32 neighbours", flat(0.0, 40, 50), point_mass_rover(), start, start + d, with(1, 32)});
  }
  for (double spacing : {2.0, 1.0, 0.5}) {  // 0.25 as well in the full test
    cases.push_back({"finer lattice " + std::to_string(spacing),
                     flat(1.0, 60, 40),
                     point_mass_rover(),
                     {6, 20},
                     {54, 20},
                     with(1, 16, spacing)});
  }
  for (double d : {6.0, 12.0}) {
    GlobalSearchOptions o = with(5);
    o.max_cost_ratio = 3.0;
    o.distinctness = d;
    cases.push_back({"bumps separation " + std::to_string(d),
                     bumps(),
                     point_mass_rover(0.3),
                     {3, 30},
                     {77, 30},
                     o});
  }
  for (double ratio : {3.0, 1.02}) {  // 1.1 and 1.0 as well in the full test
    GlobalSearchOptions o = with(6);
    o.distinctness = 5.0;
    o.max_cost_ratio = ratio;
    cases.push_back({"bumps ratio " + std::to_string(ratio),
                     bumps(),
                     point_mass_rover(0.3),
                     {3, 30},
                     {77, 30},
                     o});
  }
  return cases;
}

/// Multi-resolution options with a corridor narrow enough to leave most of
/// these small maps out (so the comparison is not the full search again).
GlobalSearchOptions multi(GlobalSearchOptions o) {
  o.resolution = GlobalSearchResolution::kMulti;
  o.coarse_factor = 2;
  o.corridor_width = 3.0;
  return o;
}

TEST(GlobalSearchMulti, SameBestCandidateAsTheFullSearchOnEveryGlobalSearchTestCase) {
  std::size_t restricted = 0;
  for (const Case& c : existing_cases()) {
    const GlobalSearchResult full = global_search(c.terrain, c.vehicle, c.start, c.goal, c.options);
    const GlobalSearchResult m =
        global_search(c.terrain, c.vehicle, c.start, c.goal, multi(c.options));
    ASSERT_EQ(full.status, GlobalSearchStatus::kOk) << c.name;
    ASSERT_EQ(m.status, GlobalSearchStatus::kOk) << c.name << ": " << m.message;
    EXPECT_EQ(m.resolution, GlobalSearchResolution::kMulti);
    EXPECT_FALSE(m.fell_back_to_full) << c.name;
    // The same cost to the bit, and the same node sequence (hence the same
    // length), except on the 8-neighbour flat plane, where many paths tie
    // exactly: there the corridor's search picks another of the optima.
    EXPECT_EQ(m.candidates[0].cost_seconds, full.candidates[0].cost_seconds) << c.name;
    if (c.name != "knight 8") {
      EXPECT_EQ(m.candidates[0].vertices, full.candidates[0].vertices) << c.name;
      EXPECT_EQ(m.candidates[0].length_m, full.candidates[0].length_m) << c.name;
    }

    EXPECT_EQ(m.start_node, full.start_node);
    EXPECT_EQ(m.goal_node, full.goal_node);
    EXPECT_TRUE(m.cost_from_start.empty());
    // On these cases every candidate agrees too (not promised in general).
    ASSERT_EQ(m.candidates.size(), full.candidates.size()) << c.name;
    for (std::size_t k = 1; k < m.candidates.size(); ++k) {
      EXPECT_EQ(m.candidates[k].vertices, full.candidates[k].vertices) << c.name << " " << k;
    }
    restricted += m.nodes < full.nodes;
  }
  // Most cases searched a corridor smaller than the map.
  EXPECT_GE(restricted, 13u);
}

TEST(GlobalSearchMulti, AWholeMapCorridorIsTheFullSearch) {
  const Case c = existing_cases()[1];
  GlobalSearchOptions o = c.options;
  o.resolution = GlobalSearchResolution::kMulti;
  o.corridor_width = 1e4;
  const GlobalSearchResult full = global_search(c.terrain, c.vehicle, c.start, c.goal, c.options);
  const GlobalSearchResult m = global_search(c.terrain, c.vehicle, c.start, c.goal, o);
  EXPECT_EQ(m.nodes, full.nodes);
  EXPECT_EQ(m.candidates[0].vertices, full.candidates[0].vertices);
  EXPECT_EQ(m.edges_evaluated - full.edges_evaluated, m.edges_evaluated - full.edges_evaluated);
  EXPECT_GT(m.coarse_nodes, 0u);
}

TEST(GlobalSearchMulti, BadOptionsAreInputErrors) {
  const BPatch terrain = flat(0.0, 30, 30);
  GlobalSearchOptions o;
  o.resolution = GlobalSearchResolution::kMulti;
  o.coarse_factor = 1;
  EXPECT_THROW(global_search(terrain, point_mass_rover(), {2, 2}, {20, 20}, o), InputError);
  o.coarse_factor = 4;
  o.corridor_width = -1.0;
  EXPECT_THROW(global_search(terrain, point_mass_rover(), {2, 2}, {20, 20}, o), InputError);
  o.corridor_width = 0.0;
  o.stop_interval = 0;
  EXPECT_THROW(global_search(terrain, point_mass_rover(), {2, 2}, {20, 20}, o), InputError);
  EXPECT_EQ(parse_global_search_resolution("multi"), GlobalSearchResolution::kMulti);
  EXPECT_EQ(to_string(GlobalSearchResolution::kFull), "full");
  EXPECT_THROW(parse_global_search_resolution("coarse"), InputError);
}

/// A wall one node wide (1.5 m high) along x = 58, open only for 70 < y < 78.
BPatch thin_wall() {
  return BPatch::interpolate(grid_from_function(
      [](double x, double y) {
        return (std::abs(x - 58) < 0.5 && !(y > 70 && y < 78)) ? 1.5 : 0.0;
      },
      0, 0, 120, 90, 1.0));
}

TEST(GlobalSearchMulti, TheCorridorWidensWhenItHasNoRoute) {
  const BPatch terrain = thin_wall();
  GlobalSearchOptions o = with(1);
  const GlobalSearchResult full =
      global_search(terrain, point_mass_rover(0.6), {20, 15}, {100, 15}, o);
  o.resolution = GlobalSearchResolution::kMulti;
  o.coarse_factor = 8;
  o.corridor_width = 4.0;
  const GlobalSearchResult m =
      global_search(terrain, point_mass_rover(0.6), {20, 15}, {100, 15}, o);
  ASSERT_EQ(full.status, GlobalSearchStatus::kOk);
  ASSERT_EQ(m.status, GlobalSearchStatus::kOk) << m.message;
  // The coarse lattice's edges step over the wall: its route is straight.
  o.resolution = GlobalSearchResolution::kFull;
  o.lattice_spacing = 8.0;
  const GlobalSearchResult coarse =
      global_search(terrain, point_mass_rover(0.6), {20, 15}, {100, 15}, o);
  ASSERT_EQ(coarse.status, GlobalSearchStatus::kOk);
  for (const Vec2& p : coarse.candidates[0].vertices) EXPECT_LT(p.y(), 30.0);
  // So the first corridor (y < ~20) has no route; it widened to the gap.
  EXPECT_GE(m.corridor_widenings, 1u);
  EXPECT_GT(m.corridor_width, 4.0);
  EXPECT_EQ(m.candidates[0].vertices, full.candidates[0].vertices);
  EXPECT_EQ(m.candidates[0].cost_seconds, full.candidates[0].cost_seconds);
  bool through_gap = false;
  for (const Vec2& p : m.candidates[0].vertices) {
    through_gap = through_gap || (std::abs(p.x() - 58) < 0.5 && p.y() > 70 && p.y() < 78);
  }
  EXPECT_TRUE(through_gap);
}

// ---- The stop check --------------------------------------------------------

TEST(GlobalSearchStop, ExpandsAtMostOneBatchAfterTheStopIsDue) {
  const Case c = existing_cases()[1];  // 81 x 61 = 4941 nodes, both fields
  struct Due {
    std::size_t polls, interval;
    const char* phase;  // where the stop falls
  };
  // Sampling polls every interval nodes (4941 / 16 -> 309, / 100 -> 50
  // polls), then each search every interval expansions.
  for (const Due due :
       {Due{0, 16, "before the search"}, Due{3, 100, "sampling"}, Due{400, 16, "from the start"},
        Due{70, 100, "from the start"}, Due{110, 100, "to the goal"}}) {
    GlobalSearchOptions o = c.options;
    o.stop_interval = due.interval;
    std::size_t polls = 0;
    // "The deadline passes" after `due.polls` polls said no.
    o.termination = Termination::when([&polls, due] { return polls++ >= due.polls; });
    const GlobalSearchResult r = global_search(c.terrain, c.vehicle, c.start, c.goal, o);
    ASSERT_EQ(r.status, GlobalSearchStatus::kStopped) << due.polls;
    EXPECT_EQ(polls, due.polls + 1);  // it stopped at the first yes
    EXPECT_NE(r.message.find(due.phase), std::string::npos) << r.message;
    // Every poll but the first follows a batch of at most `interval` nodes
    // sampled or expanded: at most one batch after the last "no".
    EXPECT_LE(r.expanded, due.polls * due.interval) << r.message;
  }
}

TEST(GlobalSearchStop, AStopAfterTheGoalWasReachedKeepsARealPath) {
  const Case c = existing_cases()[1];
  const GlobalSearchResult full = global_search(c.terrain, c.vehicle, c.start, c.goal, c.options);
  // The whole search's polls, then stop at the last one (while computing the
  // field to the goal, or ordering the seeds).
  std::size_t total = 0;
  GlobalSearchOptions o = c.options;
  o.stop_interval = 64;
  o.termination = Termination::when([&total] {
    ++total;
    return false;
  });
  global_search(c.terrain, c.vehicle, c.start, c.goal, o);
  std::size_t polls = 0;
  o.termination = Termination::when([&polls, total] { return ++polls >= total; });
  const GlobalSearchResult r = global_search(c.terrain, c.vehicle, c.start, c.goal, o);
  ASSERT_EQ(r.status, GlobalSearchStatus::kStopped) << r.message;
  ASSERT_EQ(r.candidates.size(), 1u) << r.message;
  // The start tree was complete: its path is the optimum.
  EXPECT_EQ(r.candidates[0].vertices, full.candidates[0].vertices);
  EXPECT_EQ(r.candidates[0].cost_seconds, full.candidates[0].cost_seconds);
}

TEST(GlobalSearchStop, ANeverTrueStopChangesNothing) {
  const std::vector<Case> cases = existing_cases();
  for (const std::size_t i : {1u, 2u, 7u, 18u}) {
    const Case& c = cases[i];
    const GlobalSearchResult a = global_search(c.terrain, c.vehicle, c.start, c.goal, c.options);
    GlobalSearchOptions o = c.options;
    o.termination = Termination::when([] { return false; });
    o.stop_interval = 7;
    const GlobalSearchResult b = global_search(c.terrain, c.vehicle, c.start, c.goal, o);
    ASSERT_EQ(a.candidates.size(), b.candidates.size()) << c.name;
    for (std::size_t k = 0; k < a.candidates.size(); ++k) {
      EXPECT_EQ(a.candidates[k].vertices, b.candidates[k].vertices) << c.name;
    }
    EXPECT_EQ(a.expanded, b.expanded);
    EXPECT_EQ(a.cost_to_goal, b.cost_to_goal);
  }
}

// A tile-size search under a time budget: the route level (at most kRouteLevelNodes nodes) runs
// to its end whatever the budget, so a budget spent before the coarse search could finish still
// returns a route, and the same search without a budget is unchanged.
TEST(GlobalSearchRouteLevel, ABudgetSpentEarlyStillReturnsTheRouteLevelsCandidates) {
  // 600 x 600 nodes at 1 m: 360,000 lattice nodes, a route level 5 times coarser (14,400 nodes,
  // coarser than the coarse level's factor 4). A hill in the way: the route bends round it.
  const BPatch terrain = BPatch::interpolate(grid_from_function(
      [](double x, double y) {
        return 60.0 *
               std::exp(-((x - 300) * (x - 300) + (y - 300) * (y - 300)) / (2 * 60.0 * 60.0));
      },
      0, 0, 599, 599, 1.0));
  const Vehicle v = point_mass_rover(0.5);
  GlobalSearchOptions o = with(2, 16, 0.0, false);
  o.resolution = GlobalSearchResolution::kMulti;
  // A clock that runs a second per look: the 1 s budget has passed at the coarse search's first.
  double now = 0.0;
  o.termination = Termination::time_budget(1.0, [&now] { return now += 1.0; });
  const GlobalSearchResult cut = global_search(terrain, v, {20, 20}, {580, 580}, o);
  EXPECT_EQ(cut.status, GlobalSearchStatus::kStopped);
  ASSERT_FALSE(cut.candidates.empty()) << cut.message;
  EXPECT_TRUE(cut.coarse_candidates);
  EXPECT_EQ(cut.spacing, 5.0);
  EXPECT_EQ(cut.route_nodes, 120u * 120u);
  EXPECT_LE(cut.route_nodes, kRouteLevelNodes);
  EXPECT_NE(cut.message.find("the route level's"), std::string::npos) << cut.message;
  // A route from the start's node to the goal's, round the hill (no vertex on its top).
  const std::vector<Vec2>& route = cut.candidates.front().vertices;
  EXPECT_LE((route.front() - Vec2(20, 20)).norm(), 5.0);
  EXPECT_LE((route.back() - Vec2(580, 580)).norm(), 5.0);
  for (const Vec2& p : route) EXPECT_GT((p - Vec2(300, 300)).norm(), 30.0) << p.transpose();

  // No budget: no route level, and the fine search's own best route.
  o.termination = Termination();
  const GlobalSearchResult full = global_search(terrain, v, {20, 20}, {580, 580}, o);
  EXPECT_EQ(full.status, GlobalSearchStatus::kOk) << full.message;
  EXPECT_EQ(full.route_nodes, 0u);
  EXPECT_FALSE(full.coarse_candidates);
  EXPECT_EQ(full.spacing, 1.0);
  // The route level's lattice path is a route, not the optimum: no faster than the fine one.
  EXPECT_GE(cut.candidates.front().cost_seconds, 0.98 * full.candidates.front().cost_seconds);
}

}  // namespace
}  // namespace talus
