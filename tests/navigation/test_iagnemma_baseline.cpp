// The Iagnemma–Shimoda–Shiller baseline (navigation/) beyond the
// conformance suite: its goal tolerance, its options, the high-level route
// (clearance, waypoints, an enclosed goal), the standard field without the
// lookahead, and a failure of the simulated vehicle as no_path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/navigation/hazard_detection.hpp"
#include "talus/navigation/hazard_route.hpp"
#include "talus/navigation/iagnemma_baseline.hpp"
#include "talus/planners/planner_registry.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

std::string ugv_file() {
  return TALUS_DATA_DIR "/vehicles/iagnemma_ugv.yaml";
}

/// 12 m x 12 m at 0.25 m with 2 m Gaussian hills (sigma 0.35 m) at `hills`.
ElevationGrid hills_grid(const std::vector<Vec2>& hills) {
  ElevationGrid g(49, 49, 0.25, 0.0, 0.0, 0.0);
  for (std::size_t j = 0; j < g.nrows(); ++j)
    for (std::size_t i = 0; i < g.ncols(); ++i) {
      const Vec2 p = g.node_position(i, j);
      for (const Vec2& c : hills) g.at(i, j) += 2.0 * std::exp(-(p - c).squaredNorm() / 0.245);
    }
  return g;
}

std::unique_ptr<BaselinePlanner> make(BaselineOptions extra = {}) {
  BaselineOptions o{{"robot", ugv_file()}};
  for (const auto& [key, value] : extra) o[key] = value;
  return planner_registry().make("iagnemma", o);
}

TEST(IagnemmaBaseline, GoalToleranceIsTheWaypointRadiusWithTheHeadingFree) {
  const auto planner = make({{"waypoint-radius", "0.15"}});
  EXPECT_DOUBLE_EQ(planner->goal_tolerance().position, 0.15);
  EXPECT_DOUBLE_EQ(planner->goal_tolerance().heading, kPi);
  // The interface's default, which the other baselines keep.
  const GoalTolerance d;
  EXPECT_DOUBLE_EQ(d.position, 0.25);
  EXPECT_DOUBLE_EQ(d.heading, 2 * kPi / 32);
}

TEST(IagnemmaBaseline, OptionsNeedAVehicleWithABody) {
  EXPECT_THROW(planner_registry().make("iagnemma", {}), BaselineOptionError);
  EXPECT_THROW(
      planner_registry().make("iagnemma", {{"robot", TALUS_DATA_DIR "/vehicles/rover.yaml"}}),
      InputError);
  EXPECT_THROW(make({{"lookahead", "maybe"}}), BaselineOptionError);
  EXPECT_THROW(make({{"waypoint-radius", "0"}}), BaselineOptionError);
  EXPECT_THROW(make({{"coarse-factor", "0"}}), BaselineOptionError);
  const auto planner = make({{"lookahead", "false"}, {"speed", "0"}});
  const auto& settings = planner->settings();
  const auto setting = [&](const std::string& key) {
    return std::find_if(settings.begin(), settings.end(),
                        [&](const BaselineSetting& s) { return s.key == key; });
  };
  ASSERT_NE(setting("lookahead"), settings.end());
  EXPECT_EQ(std::get<bool>(setting("lookahead")->value), false);
  EXPECT_DOUBLE_EQ(std::get<double>(setting("speed")->value), 6.0);  // the UGV's max_speed
}

TEST(HazardRoute, KeepsItsClearanceWhereItCanAndFindsNoWayIntoARing) {
  const Vehicle ugv = load_vehicle(ugv_file());
  const ElevationGrid wall = hills_grid({{6, 5.3}, {6, 6}, {6, 6.7}});
  const std::vector<unsigned char> hazard = hazard_node_mask(BPatch::interpolate(wall), ugv);
  const auto clearance_of = [&](const Vec2& p) {
    double d = 1e9;
    for (std::size_t n = 0; n < hazard.size(); ++n)
      if (hazard[n]) d = std::min(d, (wall.node_position(n % 49, n / 49) - p).norm());
    return d;
  };
  for (const double clearance : {0.0, 1.5}) {
    const HazardRoute r = plan_hazard_route(wall, ugv, {2, 6}, {10, 6}, 1, clearance);
    ASSERT_TRUE(r.found);
    EXPECT_EQ(r.points.front(), Vec2(2, 6));
    EXPECT_EQ(r.points.back(), Vec2(10, 6));
    double nearest = 1e9;
    for (const Vec2& p : r.points) nearest = std::min(nearest, clearance_of(p));
    EXPECT_GT(nearest, 0.0);
    // With a clearance the route passes the wall's ends at about it.
    if (clearance > 0.0) {
      EXPECT_GE(nearest, clearance - 0.25) << nearest;
    }
  }
  std::vector<Vec2> ring;
  for (int k = 0; k < 20; ++k)
    ring.emplace_back(6 + 3.5 * std::cos(2 * kPi * k / 20), 6 + 3.5 * std::sin(2 * kPi * k / 20));
  EXPECT_FALSE(plan_hazard_route(hills_grid(ring), ugv, {1.5, 1.5}, {6, 6}, 1, 1.5).found);
  // Coarse data: every other node.
  const HazardRoute coarse = plan_hazard_route(wall, ugv, {2, 6}, {10, 6}, 2, 1.5);
  ASSERT_TRUE(coarse.found);
  EXPECT_DOUBLE_EQ(coarse.cellsize, 0.5);
  EXPECT_EQ(coarse.searched_nodes, 25u * 25u);
  EXPECT_THROW(plan_hazard_route(wall, ugv, {2, 6}, {10, 6}, 0, 1.5), InputError);
  EXPECT_THROW(plan_hazard_route(wall, ugv, {2, 6}, {10, 6}, 100, 1.5), InputError);
  // A caller's own mask of the grid gives the route the grid's own gives.
  const HazardRoute own = plan_hazard_route(wall, ugv, {2, 6}, {10, 6}, 1, 1.5);
  const HazardRoute given = plan_hazard_route(wall, hazard, {2, 6}, {10, 6}, 1.5);
  EXPECT_EQ(given.points, own.points);
  EXPECT_EQ(given.expansions, own.expansions);
  EXPECT_EQ(given.hazard_nodes, own.hazard_nodes);
  EXPECT_THROW(plan_hazard_route(wall, std::vector<unsigned char>(10, 0), {2, 6}, {10, 6}, 1.5),
               InputError);
  EXPECT_EQ(nearest_grid_node(wall, {2.05, 6.02}), (std::pair<std::size_t, std::size_t>{8, 24}));
  EXPECT_EQ(nearest_grid_node(wall, {-5, 99}), (std::pair<std::size_t, std::size_t>{0, 48}));
}

TEST(HazardRoute, WaypointsEverySpacingAndTheGoalLast) {
  const ReferenceTrajectory w = route_waypoints({{0, 0}, {2.5, 0}, {2.5, 1}}, 1.0, 2.0);
  ASSERT_EQ(w.points.size(), 4u);  // at 1, 2, 3 m of length and the end (3.5 m)
  EXPECT_EQ(w.points[0], Vec2(1, 0));
  EXPECT_EQ(w.points[1], Vec2(2, 0));
  EXPECT_NEAR((w.points[2] - Vec2(2.5, 0.5)).norm(), 0.0, 1e-12);
  EXPECT_EQ(w.points[3], Vec2(2.5, 1));
  for (const double v : w.speed) EXPECT_EQ(v, 2.0);
  EXPECT_EQ(route_waypoints({{0, 0}, {2, 0}}, 1.0, 1.0).points.size(), 2u);  // 1 m and the end
  EXPECT_THROW(route_waypoints({{0, 0}}, 1.0, 1.0), InputError);
  EXPECT_THROW(route_waypoints({{0, 0}, {1, 0}}, 0.0, 1.0), InputError);
}

// The paper's high level: Talus's time-optimal plan on the coarse map, its waypoints carrying
// the profile's speeds capped at `speed`; no plan into a closed ring of hills.
TEST(IagnemmaBaseline, TheTimeOptimalPlanAsTheHighLevel) {
  EXPECT_THROW(make({{"high-level", "astar"}}), BaselineOptionError);
  const auto planner = make({{"high-level", "plan"}});
  const auto& settings = planner->settings();
  const auto it = std::find_if(settings.begin(), settings.end(),
                               [](const BaselineSetting& s) { return s.key == "high_level"; });
  ASSERT_NE(it, settings.end());
  EXPECT_EQ(std::get<std::string>(it->value), "plan");
  const RuledTerrain flat(hills_grid({}));
  const BaselineResult r = planner->plan(flat, {2, 6, 0}, {10, 6, 0});
  ASSERT_TRUE(r.found()) << r.brief_report();
  EXPECT_GE(r.counters.at("plan_candidates"), 1u);
  EXPECT_EQ(r.counters.at("waypoints_reached"), r.counters.at("waypoints"));
  EXPECT_LE((r.path.back().position() - Vec2(10, 6)).norm(), 0.2);
  std::vector<Vec2> ring;
  for (int k = 0; k < 20; ++k)
    ring.emplace_back(6 + 3.5 * std::cos(2 * kPi * k / 20), 6 + 3.5 * std::sin(2 * kPi * k / 20));
  const BaselineResult none =
      planner->plan(RuledTerrain(hills_grid(ring)), {1.5, 1.5, 0}, {6, 6, 0});
  EXPECT_EQ(none.status, BaselineStatus::kNoPath) << none.brief_report();
  EXPECT_NE(none.message.find("time-optimal"), std::string::npos) << none.message;
}

TEST(IagnemmaBaseline, TheStandardFieldAlsoDrivesToTheGoalOnFlatGround) {
  const RuledTerrain flat(hills_grid({}));
  const BaselineResult r = make({{"lookahead", "false"}})->plan(flat, {2, 6, 0}, {10, 6, 0});
  ASSERT_TRUE(r.found()) << r.brief_report();
  EXPECT_FALSE(r.flags.at("lookahead"));
  EXPECT_EQ(r.counters.at("lookahead_caps_applied"), 0u);
  EXPECT_EQ(r.counters.at("waypoints_reached"), r.counters.at("waypoints"));
  EXPECT_EQ(r.path.front().x, 2.0);
  EXPECT_EQ(r.path.front().y, 6.0);
  EXPECT_LE((r.path.back().position() - Vec2(10, 6)).norm(), 0.2);
  // Poses one control period (0.01 s) apart at about 1 m/s.
  for (std::size_t k = 1; k < r.path.size(); ++k)
    EXPECT_LE((r.path[k].position() - r.path[k - 1].position()).norm(), 0.03) << k;
}

TEST(IagnemmaBaseline, AVehicleFailureIsNoPathAndNamed) {
  // Starting 0.3 m from the west edge facing it: the UGV cannot turn round
  // (0.4 m turning radius) before a wheel leaves the map. The standard
  // field: with the lookahead, whose prediction off the map has no safe
  // speed, the UGV would not move at all (and the time limit would end it).
  const RuledTerrain flat(hills_grid({}));
  const BaselineResult r = make({{"lookahead", "false"}})->plan(flat, {0.3, 6, kPi}, {10, 6, 0});
  EXPECT_EQ(r.status, BaselineStatus::kNoPath) << r.brief_report();
  EXPECT_TRUE(r.flags.at("vehicle_failed"));
  EXPECT_TRUE(r.flags.at("route_found"));
  EXPECT_NE(r.message.find("left_terrain"), std::string::npos) << r.message;
  EXPECT_TRUE(r.path.empty());
  EXPECT_EQ(r.length_m, 0.0);
}

TEST(IagnemmaBaseline, TheTimeLimitIsBudgetExceeded) {
  const RuledTerrain flat(hills_grid({}));
  const BaselineResult r = make({{"time-limit", "2"}})->plan(flat, {2, 6, 0}, {10, 6, 0});
  EXPECT_EQ(r.status, BaselineStatus::kBudgetExceeded) << r.brief_report();
  EXPECT_NE(r.message.find("time limit"), std::string::npos) << r.message;
  EXPECT_TRUE(r.path.empty());
}

}  // namespace
}  // namespace talus
