// The contract every planner in planner_registry() must meet (the kinematic
// baselines and Talus's own two-stage planner, "talus"), instantiated over the
// registry's names (after OMPL's
// tests/base/PlannerTest.h): a straight route on flat ground is found; an
// enclosed goal is "no path"; an invalid start or goal is its status; reruns
// are bit-identical; the path's ends match the query; every pose of a path
// passes the planner's own validity check; a tiny budget is "budget
// exceeded"; bad options and malformed queries throw InputError. The path's
// end is held to the planner's own goal_tolerance() (a navigator that reaches
// a goal position says it does not control the heading).
#include <gtest/gtest.h>

#include <chrono>

#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/planners/planner_registry.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;
/// How far a path's first pose may be from the start: a quarter-metre cell
/// and one of 32 heading cells, the coarsest resolution a registered baseline
/// uses (every baseline starts its path at the start's heading). The last
/// pose is held to the planner's own goal_tolerance() instead.
constexpr double kStartPositionTolerance = 0.25 + 1e-9;         // [m]
constexpr double kStartHeadingTolerance = 2 * kPi / 32 + 1e-9;  // [rad]

/// What each baseline needs beyond its defaults to plan on the rover-scale
/// terrains below (a robot, ...). A new baseline adds its line here.
BaselineOptions conformance_options(const std::string& name) {
  const std::map<std::string, BaselineOptions> options{
      {"hait", {{"robot", TALUS_DATA_DIR "/robots/rover4_sprung.yaml"}}},
      {"dacre-wright", {{"robot", TALUS_DATA_DIR "/robots/dacre_wright_six_wheel.yaml"}}},
      {"eldershaw-yim", {{"robot", TALUS_DATA_DIR "/robots/eldershaw_spider.yaml"}}},
      {"iagnemma", {{"robot", TALUS_DATA_DIR "/vehicles/iagnemma_ugv.yaml"}}},
      {"talus", {{"robot", TALUS_DATA_DIR "/vehicles/iagnemma_ugv.yaml"}}},
  };
  const auto it = options.find(name);
  return it == options.end() ? BaselineOptions{} : it->second;
}

/// 12 m x 12 m at 0.25 m: z = sum of steep Gaussian hills (height 2 m, sigma
/// 0.35 m) at `hills`, flat elsewhere.
RuledTerrain hills_terrain(const std::vector<Vec2>& hills) {
  ElevationGrid g(49, 49, 0.25, 0.0, 0.0, 0.0);
  for (std::size_t j = 0; j < g.nrows(); ++j) {
    for (std::size_t i = 0; i < g.ncols(); ++i) {
      const Vec2 p = g.node_position(i, j);
      for (const Vec2& c : hills) g.at(i, j) += 2.0 * std::exp(-(p - c).squaredNorm() / 0.245);
    }
  }
  return RuledTerrain(g);
}

const RuledTerrain& flat() {
  static const RuledTerrain t = hills_terrain({});
  return t;
}

/// A closed ring of 20 hills of radius 3.5 m around (6, 6).
const RuledTerrain& ring() {
  static const RuledTerrain t = [] {
    std::vector<Vec2> hills;
    for (int k = 0; k < 20; ++k) {
      const double a = 2 * kPi * k / 20;
      hills.emplace_back(6 + 3.5 * std::cos(a), 6 + 3.5 * std::sin(a));
    }
    return hills_terrain(hills);
  }();
  return t;
}

/// Three hills across the straight line y = 6 at x = 6: a detour is needed.
const RuledTerrain& wall() {
  static const RuledTerrain t = hills_terrain({{6, 5.3}, {6, 6}, {6, 6.7}});
  return t;
}

double heading_error(double a, double b) {
  return std::abs(std::remainder(a - b, 2 * kPi));
}

class BaselineConformance : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<BaselinePlanner> make(BaselineOptions extra = {}) const {
    BaselineOptions o = conformance_options(GetParam());
    for (const auto& [key, value] : extra) o[key] = value;
    return planner_registry().make(GetParam(), o);
  }

  /// A found path that starts and ends at the query, has one motion label per
  /// pose (or none), a length no shorter than its polyline, and whose every
  /// pose is valid for the planner.
  void expect_sound_path(const BaselinePlanner& planner, const RuledTerrain& terrain,
                         const SE2Pose& start, const SE2Pose& goal, const BaselineResult& r) {
    ASSERT_EQ(r.status, BaselineStatus::kFound) << r.brief_report();
    ASSERT_GE(r.path.size(), 2u);
    EXPECT_LE((r.path.front().position() - start.position()).norm(), kStartPositionTolerance);
    EXPECT_LE(heading_error(r.path.front().theta, start.theta), kStartHeadingTolerance);
    const GoalTolerance tolerance = planner.goal_tolerance();
    EXPECT_LE((r.path.back().position() - goal.position()).norm(), tolerance.position + 1e-9);
    EXPECT_LE(heading_error(r.path.back().theta, goal.theta), tolerance.heading + 1e-9);
    EXPECT_TRUE(r.motions.empty() || r.motions.size() == r.path.size()) << r.motions.size();
    double polyline = 0.0;
    for (std::size_t k = 1; k < r.path.size(); ++k) {
      polyline += (r.path[k].position() - r.path[k - 1].position()).norm();
    }
    EXPECT_GE(r.length_m, polyline - 1e-9);
    const ValidityFunction valid = planner.validity(terrain);
    std::size_t invalid = 0;
    for (const SE2Pose& q : r.path) invalid += valid(q).valid ? 0 : 1;
    EXPECT_EQ(invalid, 0u) << "of " << r.path.size() << " poses";
  }
};

TEST_P(BaselineConformance, NamesItselfAsRegistered) {
  EXPECT_EQ(make()->name(), GetParam());
}

TEST_P(BaselineConformance, FindsTheStraightRouteOnFlatGround) {
  const auto planner = make();
  const SE2Pose start{2, 6, 0}, goal{10, 6, 0};
  const auto before = std::chrono::steady_clock::now();
  const BaselineResult r = planner->plan(flat(), start, goal);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
  expect_sound_path(*planner, flat(), start, goal, r);
  EXPECT_LE(r.length_m, 8.0 * 1.05) << r.brief_report();
  // The stage timings are parts of the call: together no longer than the call itself.
  EXPECT_LE(r.preprocessing_seconds + r.search_seconds, wall) << r.brief_report();
}

TEST_P(BaselineConformance, DetourIsSoundAndRerunsAreBitIdentical) {
  const auto planner = make();
  const SE2Pose start{2, 6, 0}, goal{10, 6, 0};
  const BaselineResult a = planner->plan(wall(), start, goal);
  expect_sound_path(*planner, wall(), start, goal, a);
  EXPECT_GT(a.length_m, 8.2) << "the wall must be avoided: " << a.brief_report();
  const BaselineResult b = make()->plan(wall(), start, goal);  // a fresh planner, too
  const BaselineResult c = planner->plan(wall(), start, goal);
  for (const BaselineResult* rerun : {&b, &c}) {
    EXPECT_EQ(rerun->status, a.status);
    EXPECT_EQ(rerun->message, a.message);
    EXPECT_EQ(rerun->motions, a.motions);
    EXPECT_EQ(rerun->counters, a.counters);
    EXPECT_EQ(rerun->length_m, a.length_m);
    ASSERT_EQ(rerun->path.size(), a.path.size());
    for (std::size_t k = 0; k < a.path.size(); ++k) {
      EXPECT_EQ(rerun->path[k].x, a.path[k].x) << k;
      EXPECT_EQ(rerun->path[k].y, a.path[k].y) << k;
      EXPECT_EQ(rerun->path[k].theta, a.path[k].theta) << k;
    }
  }
}

TEST_P(BaselineConformance, EnclosedGoalIsNoPath) {
  const BaselineResult r = make()->plan(ring(), {1.5, 1.5, 0}, {6, 6, 0});
  EXPECT_EQ(r.status, BaselineStatus::kNoPath) << r.brief_report();
  EXPECT_TRUE(r.path.empty());
  EXPECT_FALSE(r.message.empty());
}

TEST_P(BaselineConformance, InvalidStartOrGoalIsItsStatus) {
  const auto planner = make();
  // On a hill's flank, across the slope.
  const SE2Pose flank{9.2, 6, kPi / 2}, open{1.5, 1.5, 0};
  ASSERT_FALSE(planner->validity(ring())(flank).valid);
  const BaselineResult s = planner->plan(ring(), flank, open);
  EXPECT_EQ(s.status, BaselineStatus::kStartInvalid) << s.brief_report();
  EXPECT_TRUE(s.path.empty());
  const BaselineResult g = planner->plan(ring(), open, flank);
  EXPECT_EQ(g.status, BaselineStatus::kGoalInvalid) << g.brief_report();
  EXPECT_TRUE(g.path.empty());
}

TEST_P(BaselineConformance, TinyBudgetIsBudgetExceeded) {
  const BaselineResult r = make({{"budget", "1"}})->plan(flat(), {2, 6, 0}, {10, 6, 0});
  EXPECT_EQ(r.status, BaselineStatus::kBudgetExceeded) << r.brief_report();
  EXPECT_TRUE(r.path.empty());
}

TEST_P(BaselineConformance, BadOptionsAndQueriesThrowInputError) {
  EXPECT_THROW(make({{"no-such-option", "1"}}), BaselineOptionError);
  EXPECT_THROW(make({{"budget", "0"}}), BaselineOptionError);
  EXPECT_THROW(make({{"budget", "many"}}), BaselineOptionError);
  const auto planner = make();
  EXPECT_THROW(planner->plan(flat(), {-1, 6, 0}, {10, 6, 0}), InputError);
  EXPECT_THROW(planner->plan(flat(), {2, 6, 0}, {10, 60, 0}), InputError);
  EXPECT_THROW(planner->plan(flat(), {2, 6, std::nan("")}, {10, 6, 0}), InputError);
}

INSTANTIATE_TEST_SUITE_P(Registered, BaselineConformance,
                         ::testing::ValuesIn(planner_registry().names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name) c = std::isalnum(c) ? c : '_';
                           return name;
                         });

}  // namespace
}  // namespace talus
