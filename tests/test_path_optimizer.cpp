#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "talus/core/error.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "talus/optimal/path_time_objective.hpp"
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

class EverySolver : public ::testing::TestWithParam<PathSolver> {};

TEST_P(EverySolver, StraightensABentPathOnAPlane) {
  const BPatch flat = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 60, 40, 1.0));
  PathOptimizerOptions options;
  options.solver = GetParam();
  options.control_points = 6;
  const std::vector<Vec2> bent = {{5, 20}, {20, 30}, {40, 30}, {55, 20}};
  const OptimizedPath best = optimize_path(flat, rover(0.5), bent, options);
  // Rest to rest over L = 50 m with a_max = mu g, capped at 10 m/s: the
  // straight line is optimal (accelerate 10.2 m, cruise, brake 10.2 m).
  const double L = 50.0, a = 0.5 * 9.81, v = 10.0;
  const double straight = 2 * v / a + (L - v * v / a) / v;
  EXPECT_LE(best.travel_time, best.initial_time);
  EXPECT_NEAR(best.travel_time, straight, 0.01 * straight);
  EXPECT_GT(best.initial_time, 1.05 * straight);
  EXPECT_FALSE(best.solver_failed) << best.solver_status;
  EXPECT_EQ(best.solver, to_string(GetParam()));
  // The path is straight: every control point on y = 20; there the travel
  // time is smooth and its gradient vanishes.
  const double tolerance = GetParam() == PathSolver::kNloptBobyqa ? 1.0 : 0.1;
  for (const Vec2& c : best.curve.control_points()) EXPECT_NEAR(c.y(), 20.0, tolerance);
  if (GetParam() != PathSolver::kNloptBobyqa) {
    EXPECT_LT(best.optimality, 1e-2);  // s/m; the bent start has O(0.1)
  }
  std::printf("%s: %.6f s (straight %.6f), %zu iterations, %zu evaluations, optimality %.2e\n",
              best.solver.c_str(), best.travel_time, straight, best.iterations, best.evaluations,
              best.optimality);
}

TEST_P(EverySolver, ImprovesOnTheGlobalCandidateAroundAHill) {
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
  options.solver = GetParam();
  const OptimizedPath best = optimize_path(terrain, v, global.candidates[0].vertices, options);
  EXPECT_LT(best.travel_time, 0.99 * best.initial_time);  // the lattice path is not time-optimal
  EXPECT_TRUE(std::isfinite(best.travel_time));
  // Independently: the returned curve's profile takes the reported time.
  PathTimeObjective objective(terrain, v, {5, 30}, {75, 30}, options.control_points, best.stations,
                              {});
  EXPECT_NEAR(objective.evaluate(objective.variables(best.curve.control_points())),
              best.travel_time, 1e-9 * best.travel_time);
  EXPECT_TRUE(std::isfinite(best.optimality));
  std::printf("%s: %.4f s from %.4f s, %zu iterations, %zu evaluations, optimality %.2e, %s\n",
              best.solver.c_str(), best.travel_time, best.initial_time, best.iterations,
              best.evaluations, best.optimality, best.solver_status.c_str());
}

INSTANTIATE_TEST_SUITE_P(PathOptimizer, EverySolver,
                         ::testing::Values(PathSolver::kIpopt, PathSolver::kNloptLbfgs,
                                           PathSolver::kNloptBobyqa),
                         [](const auto& info) {
                           std::string name(to_string(info.param));
                           std::erase(name, '-');
                           return name;
                         });

TEST(PathOptimizer, BadInputIsAnInputError) {
  const BPatch flat = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 20, 20, 1.0));
  PathOptimizerOptions options;
  EXPECT_THROW(optimize_path(flat, rover(0.5), {{1, 1}, {25, 5}}, options), InputError);
  options.control_points = 3;
  EXPECT_THROW(optimize_path(flat, rover(0.5), {{1, 1}, {15, 5}}, options), InputError);
  EXPECT_THROW(parse_path_solver("snopt"), InputError);
  EXPECT_EQ(parse_path_solver("nlopt-lbfgs"), PathSolver::kNloptLbfgs);
}

}  // namespace
}  // namespace talus
