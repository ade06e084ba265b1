#include <gtest/gtest.h>

#include <cmath>

#include "talus/core/error.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

Vehicle rover(double mu) {
  Vehicle v;
  v.friction = mu;
  v.cg_height = 0.5;
  v.half_track = 0.6;
  v.max_speed = 10.0;
  return v;
}

TEST(PathOptimizer, StraightensABentPathOnAPlane) {
  const BPatch flat = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 60, 40, 1.0));
  PathOptimizerOptions options;
  options.control_points = 6;
  const std::vector<Vec2> bent = {{5, 20}, {20, 30}, {40, 30}, {55, 20}};
  const OptimizedPath best = optimize_path_bobyqa(flat, rover(0.5), bent, options);
  // Rest to rest over L = 50 m with a_max = mu g, capped at 10 m/s: the
  // straight line is optimal (accelerate 10.2 m, cruise, brake 10.2 m).
  const double L = 50.0, a = 0.5 * 9.81, v = 10.0;
  const double straight = 2 * v / a + (L - v * v / a) / v;
  EXPECT_LE(best.travel_time, best.initial_time);
  EXPECT_NEAR(best.travel_time, straight, 0.01 * straight);
  EXPECT_GT(best.initial_time, 1.05 * straight);
  EXPECT_GT(best.evaluations, 10u);
  EXPECT_FALSE(best.solver_status.empty());
}

TEST(PathOptimizer, ImprovesOnTheGlobalCandidateAroundAHill) {
  const BPatch terrain = BPatch::interpolate(terrain_test::grid_from_function(
      [](double x, double y) {
        return 8.0 * std::exp(-((x - 40) * (x - 40) + (y - 30) * (y - 30)) / (2 * 7.0 * 7.0));
      },
      0, 0, 80, 60, 1.0));
  const Vehicle v = rover(0.4);
  GlobalSearchOptions search;
  search.candidates = 1;
  const GlobalSearchResult global = global_search(terrain, v, {5, 30}, {75, 30}, search);
  ASSERT_EQ(global.status, GlobalSearchStatus::kOk);
  PathOptimizerOptions options;
  options.control_points = 8;
  const OptimizedPath best =
      optimize_path_bobyqa(terrain, v, global.candidates[0].vertices, options);
  EXPECT_LT(best.travel_time, best.initial_time);  // the lattice path is not time-optimal
  EXPECT_TRUE(std::isfinite(best.travel_time));
  // Independently: the returned curve's time equals the reported one.
  EXPECT_NEAR(
      path_travel_time(terrain, v, best.curve.control_points(), options.station_spacing, {}),
      best.travel_time, 1e-9 * best.travel_time);
}

TEST(PathOptimizer, InitialPathOffTheMapIsAnInputError) {
  const BPatch flat = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 20, 20, 1.0));
  PathOptimizerOptions options;
  EXPECT_THROW(optimize_path_bobyqa(flat, rover(0.5), {{1, 1}, {25, 5}}, options), InputError);
  options.control_points = 3;
  EXPECT_THROW(optimize_path_bobyqa(flat, rover(0.5), {{1, 1}, {15, 5}}, options), InputError);
}

}  // namespace
}  // namespace talus
