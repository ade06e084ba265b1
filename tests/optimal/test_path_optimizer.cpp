#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "talus/optimal/path_time_objective.hpp"
#include "talus/optimal/trajectory.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

using vehicle_test::point_mass_rover;

class EverySolver : public ::testing::TestWithParam<PathSolver> {};

TEST_P(EverySolver, StraightensABentPathOnAPlane) {
  const BPatch flat = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 60, 40, 1.0));
  PathOptimizerOptions options;
  options.solver = GetParam();
  options.control_points = 6;
  options.relative_tolerance = 1e-9;  // near the optimum T is flat: 0.15 m of bend cost 2.5e-5
  const std::vector<Vec2> bent = {{5, 20}, {20, 30}, {40, 30}, {55, 20}};
  const OptimizedPath best = optimize_path(flat, point_mass_rover(0.5), bent, options);
  // Rest to rest over L = 50 m with a_max = mu g, capped at 10 m/s: the
  // straight line is optimal (accelerate 10.2 m, cruise, brake 10.2 m).
  const double L = 50.0, a = 0.5 * 9.81, v = 10.0;
  const double straight = 2 * v / a + (L - v * v / a) / v;
  EXPECT_LE(best.travel_time, best.initial_time);
  // Every solver ends within 2e-7 of the straight-line time (measured). The bound is the switch
  // steps' discretisation error at the search spacing, (0.5 m / L)^2 = 1e-4: a 1e-3 error in g
  // or mu moves the time by 5e-4.
  const double search_step = search_station_spacing(options, flat, point_mass_rover(0.5)) / L;
  EXPECT_NEAR(best.travel_time, straight, search_step * search_step * straight);
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
  // Started on the straight line, it keeps it, at the analytic time.
  PathOptimizerOptions defaults;
  defaults.solver = GetParam();
  const OptimizedPath kept =
      optimize_path(flat, point_mass_rover(0.5), {{5, 20}, {55, 20}}, defaults);
  for (const Vec2& c : kept.curve.control_points()) EXPECT_NEAR(c.y(), 20.0, 1e-6);
  // On the straight line only the two switch steps differ from the analytic time, by at most
  // (spacing / length)^2 = 1e-4 at the search's default 0.5 m (measured 2e-5).
  const double h = search_station_spacing(defaults, flat, point_mass_rover(0.5)) / L;
  EXPECT_NEAR(kept.travel_time, straight, h * h * straight);
  EXPECT_LE(kept.travel_time, kept.initial_time);
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
  const Vehicle v = point_mass_rover(0.4);
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
  PathTimeObjective objective(terrain, v, {5, 30}, {75, 30}, best.control_points, best.stations,
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

// The planner's output, checked against limits recomputed from scratch: on a
// rough fractal terrain the optimised path's profile at the plan's 0.1 m
// stations respects every speed limit and every acceleration bound at both
// ends of every step, with the geometry re-derived at each station's curve
// parameter by a fresh SurfacePath (not the optimiser's objective).
TEST(PathOptimizer, OptimisedTrajectoryOnFractalTerrainSatisfiesEveryConstraint) {
  FractalTerrainOptions fractal;
  fractal.shape = {97, 97, 1.0, 0.0, 0.0};
  fractal.height_scale = 12.0;
  fractal.seed = 7;
  const BPatch terrain = BPatch::fit_smoothing(generate_fractal_terrain(fractal), 1.0);
  Vehicle v = point_mass_rover(0.6);
  v.max_accel = 2.0;
  v.max_decel = 3.0;
  const Vec2 start(5, 5), goal(90, 88);
  GlobalSearchOptions search;
  search.candidates = 1;
  const GlobalSearchResult global = global_search(terrain, v, start, goal, search);
  ASSERT_EQ(global.status, GlobalSearchStatus::kOk);
  std::vector<Vec2> polyline = global.candidates[0].vertices;
  polyline.front() = start;
  polyline.back() = goal;
  const OptimizedPath best = optimize_path(terrain, v, polyline, PathOptimizerOptions{});
  ASSERT_TRUE(std::isfinite(best.travel_time));
  EXPECT_LE(best.travel_time, best.initial_time);

  const SurfacePath path(terrain, best.curve);
  const auto stations = station_count(path.length());
  const VelocityLimits limits(v, path, stations);
  TimeOptimalProfileSolver solver;
  const TimeOptimalProfile profile = solver.solve(limits, {});
  ASSERT_EQ(profile.status, ProfileStatus::kOk) << profile.message;

  const SurfacePath fresh(terrain, best.curve);
  std::size_t checked = 0;
  for (std::size_t k = 0; k < stations; ++k) {
    const PathFrame f = fresh.frame_at_parameter(limits.frame(k).parameter);
    const StationGeometry g = StationGeometry::from(f);
    const SpeedLimits l = speed_limits(v, g);
    ASSERT_TRUE(l.traversable) << "station " << k;
    EXPECT_LE(profile.v[k], l.v_max * (1 + 1e-7) + 1e-9) << "station " << k;
    EXPECT_GE(profile.v[k], l.v_min * (1 - 1e-7) - 1e-9) << "station " << k;
    if (k + 1 == stations) break;
    const double ds = limits.frame(k + 1).s - limits.frame(k).s;
    const double u = (profile.v[k + 1] * profile.v[k + 1] - profile.v[k] * profile.v[k]) / (2 * ds);
    for (const std::size_t end : {k, k + 1}) {
      const StationGeometry ge =
          end == k ? g
                   : StationGeometry::from(fresh.frame_at_parameter(limits.frame(end).parameter));
      const AccelerationBounds a = acceleration_bounds(v, ge, profile.v[end]);
      ASSERT_TRUE(a.feasible) << "station " << end << ": " << to_string(a.violated);
      EXPECT_LE(u, a.a_max + 1e-6) << "step " << k << " at station " << end;
      EXPECT_GE(u, a.a_min - 1e-6) << "step " << k << " at station " << end;
    }
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
}

/// The hill of ImprovesOnTheGlobalCandidateAroundAHill and its best lattice candidate.
struct HillCase {
  BPatch terrain = BPatch::interpolate(terrain_test::grid_from_function(
      [](double x, double y) {
        return 8.0 * std::exp(-((x - 40) * (x - 40) + (y - 30) * (y - 30)) / (2 * 7.0 * 7.0));
      },
      0, 0, 80, 60, 1.0));
  Vehicle vehicle = point_mass_rover(0.4);
  std::vector<Vec2> candidate = [this] {
    GlobalSearchOptions search;
    search.candidates = 1;
    return global_search(terrain, vehicle, {5, 30}, {75, 30}, search).candidates.at(0).vertices;
  }();
};

// An evaluation budget too small to converge: the restarts resume from the
// best point, then perturb it; the result is the best over every attempt,
// each attempt's time is its own best point's, and reruns are identical.
TEST(PathOptimizerRestarts, ResumeThenPerturbAndKeepTheBestOfEveryAttempt) {
  const HillCase hill;
  PathOptimizerOptions options;
  options.max_evaluations = 10;
  options.more_control_points.clear();  // one fit
  options.restarts = 0;                 // one solve
  ASSERT_FALSE(options.polish);         // the restarts alone (the default)
  const OptimizedPath single = optimize_path(hill.terrain, hill.vehicle, hill.candidate, options);
  ASSERT_EQ(single.attempts.size(), 1u);
  EXPECT_EQ(single.attempts[0].start, "fit");
  ASSERT_FALSE(single.converged) << single.solver_status;
  EXPECT_DOUBLE_EQ(single.attempts[0].travel_time, single.travel_time);

  options.restarts = 3;
  const OptimizedPath multi = optimize_path(hill.terrain, hill.vehicle, hill.candidate, options);
  ASSERT_GE(multi.attempts.size(), 2u);
  EXPECT_EQ(multi.attempts[0].start, "fit");
  EXPECT_EQ(multi.attempts[1].start, "resume");
  for (std::size_t k = 2; k < multi.attempts.size(); ++k)
    EXPECT_EQ(multi.attempts[k].start, "perturbed");
  // The first attempt is the single run's; the rest can only improve on it.
  EXPECT_DOUBLE_EQ(multi.attempts[0].travel_time, single.travel_time);
  EXPECT_LT(multi.travel_time, single.travel_time);
  double best = multi.initial_time;
  for (const LocalAttempt& a : multi.attempts) best = std::min(best, a.travel_time);
  EXPECT_DOUBLE_EQ(multi.travel_time, best);
  EXPECT_DOUBLE_EQ(multi.attempts.at(multi.best_attempt).travel_time, multi.travel_time);
  EXPECT_EQ(multi.solver_status, multi.attempts[multi.best_attempt].solver_status);
  // Restarting stops at the first attempt that converges.
  for (std::size_t k = 0; k + 1 < multi.attempts.size(); ++k)
    EXPECT_FALSE(multi.attempts[k].converged) << k;
  // Independently: the returned curve's profile takes the reported time.
  PathTimeObjective objective(hill.terrain, hill.vehicle, {5, 30}, {75, 30}, multi.control_points,
                              multi.stations, {});
  EXPECT_NEAR(objective.evaluate(objective.variables(multi.curve.control_points())),
              multi.travel_time, 1e-9 * multi.travel_time);

  const OptimizedPath again = optimize_path(hill.terrain, hill.vehicle, hill.candidate, options);
  EXPECT_EQ(again.travel_time, multi.travel_time);
  EXPECT_EQ(again.attempts.size(), multi.attempts.size());
}

// The nested solver stops on its evaluation cap (its objective kinks where a
// switching point crosses a station); the polish NLP from its point converges
// by Ipopt's own status, its point is returned, and that point's exact
// profile takes the reported time, no slower than the fit.
TEST(PathOptimizerPolish, ConvergesFromTheNestedPointOnTheSmoothHill) {
  const HillCase hill;
  PathOptimizerOptions options;
  options.more_control_points.clear();  // one fit
  options.restarts = 0;                 // one nested solve, then the polish
  options.polish = false;
  const OptimizedPath nested = optimize_path(hill.terrain, hill.vehicle, hill.candidate, options);
  ASSERT_FALSE(nested.converged) << nested.solver_status;
  options.polish = true;
  const OptimizedPath polished = optimize_path(hill.terrain, hill.vehicle, hill.candidate, options);
  ASSERT_EQ(polished.attempts.size(), 2u);
  EXPECT_EQ(polished.attempts[1].start, "polish");
  EXPECT_TRUE(polished.attempts[1].converged) << polished.attempts[1].solver_status;
  EXPECT_EQ(polished.best_attempt, 1u);
  EXPECT_TRUE(polished.converged) << polished.solver_status;
  EXPECT_EQ(polished.solver_status, "success");
  EXPECT_DOUBLE_EQ(polished.attempts[0].travel_time, nested.travel_time);
  EXPECT_LE(polished.travel_time, polished.initial_time);
  EXPECT_LE(polished.travel_time, nested.travel_time * (1.0 + options.polish_tolerance));
  EXPECT_TRUE(std::isfinite(polished.nlp_travel_time));
  PathTimeObjective objective(hill.terrain, hill.vehicle, {5, 30}, {75, 30},
                              polished.control_points, polished.stations, {});
  EXPECT_NEAR(objective.evaluate(objective.variables(polished.curve.control_points())),
              polished.travel_time, 1e-9 * polished.travel_time);
  std::printf("nested %.5f s (%s), polished %.5f s (NLP %.5f s, %zu iterations), fit %.5f s\n",
              nested.travel_time, nested.solver_status.c_str(), polished.travel_time,
              polished.nlp_travel_time, polished.attempts[1].iterations, polished.initial_time);
}

// A further start from a 12-point fit: the result is the faster of the two
// whole local stages, every solve is listed with the M of its fit, and the
// first fit stays the start the result is compared with.
TEST(PathOptimizerMoreControlPoints, KeepsTheFasterOfTheStartsAndListsEverySolve) {
  const HillCase hill;
  PathOptimizerOptions options;
  options.more_control_points.clear();
  options.control_points = 8;
  const OptimizedPath eight = optimize_path(hill.terrain, hill.vehicle, hill.candidate, options);
  options.control_points = 12;
  const OptimizedPath twelve = optimize_path(hill.terrain, hill.vehicle, hill.candidate, options);
  options.control_points = 8;
  options.more_control_points = {12};
  const OptimizedPath both = optimize_path(hill.terrain, hill.vehicle, hill.candidate, options);
  EXPECT_DOUBLE_EQ(both.travel_time, std::min(eight.travel_time, twelve.travel_time));
  EXPECT_EQ(both.control_points, eight.travel_time <= twelve.travel_time ? 8u : 12u);
  ASSERT_EQ(both.attempts.size(), eight.attempts.size() + twelve.attempts.size());
  EXPECT_EQ(both.attempts.front().control_points, 8u);
  EXPECT_EQ(both.attempts.back().control_points, 12u);
  EXPECT_EQ(both.attempts.at(both.best_attempt).control_points, both.control_points);
  EXPECT_DOUBLE_EQ(both.attempts.at(both.best_attempt).travel_time, both.travel_time);
  EXPECT_DOUBLE_EQ(both.initial_time, eight.initial_time);
  EXPECT_EQ(both.curve.control_points().size(), both.control_points);
  options.more_control_points = {3};
  EXPECT_THROW(options.validate(), InputError);
  std::printf("M 8: %.5f s, M 12: %.5f s, both: %.5f s (M %zu)\n", eight.travel_time,
              twelve.travel_time, both.travel_time, both.control_points);
}

TEST(PathOptimizerPolish, BadPolishOptionsAreInputErrors) {
  PathOptimizerOptions options;
  options.polish_station_factor = 0;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.polish_max_iterations = 0;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.polish_tolerance = -0.1;
  EXPECT_THROW(options.validate(), InputError);
}

TEST(PathOptimizerRestarts, TheSimultaneousFormulationRestartsToo) {
  const HillCase hill;
  PathOptimizerOptions options;
  options.formulation = PathFormulation::kSimultaneous;
  options.simultaneous_lateral_iterations = 3;
  options.simultaneous_max_iterations = 3;
  options.restarts = 2;
  const OptimizedPath result = optimize_path(hill.terrain, hill.vehicle, hill.candidate, options);
  ASSERT_GE(result.attempts.size(), 2u) << result.solver_status;
  EXPECT_EQ(result.attempts[1].start, "resume");
  double best = result.initial_time;
  for (const LocalAttempt& a : result.attempts) best = std::min(best, a.travel_time);
  EXPECT_DOUBLE_EQ(result.travel_time, best);
  EXPECT_LE(result.travel_time, result.attempts[0].travel_time);
}

TEST(PathOptimizerRestarts, ANegativePerturbationIsAnInputError) {
  PathOptimizerOptions options;
  options.restart_perturbation = -1.0;
  EXPECT_THROW(options.validate(), InputError);
  options.restart_perturbation = std::nan("");
  EXPECT_THROW(options.validate(), InputError);
}

// A candidate within half a cell of the map's edge (the box's margin): the
// solvers start from the fit itself, never from a copy clamped into the box
// (on battery seed 1 with the rigid-body UGV the clamp took away the
// admissible profile of two of three candidates running along the edge).
TEST(PathOptimizer, StartsFromTheFitOfACandidateAlongTheMapsEdge) {
  const BPatch flat = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 20, 10, 1.0));
  ASSERT_NEAR(flat.y_min(), 0.0, 1e-12);
  const std::vector<Vec2> along_edge = {{2, 0.2}, {10, 0.2}, {18, 0.2}};
  for (const PathFormulation formulation :
       {PathFormulation::kNested, PathFormulation::kSimultaneous}) {
    PathOptimizerOptions options;
    options.formulation = formulation;
    options.control_points = 6;
    options.restarts = 0;
    const InitialPath fit = fit_initial_path(flat, point_mass_rover(0.5), along_edge, options);
    ASSERT_TRUE(fit.curve && fit.admissible());
    const OptimizedPath best = optimize_path(flat, point_mass_rover(0.5), along_edge, options);
    const auto& fitted = fit.curve->control_points();
    const auto& started = best.initial_curve.control_points();
    ASSERT_EQ(started.size(), fitted.size());
    for (std::size_t i = 0; i < fitted.size(); ++i) {
      EXPECT_NEAR(started[i].x(), fitted[i].x(), 1e-12) << i;
      EXPECT_NEAR(started[i].y(), 0.2, 1e-9) << i;  // not the margin's 0.5
    }
    // The straight line along the edge is already optimal: the box lets it
    // stay there and never beyond it.
    EXPECT_LE(best.travel_time, best.initial_time);
    for (const Vec2& c : best.curve.control_points()) EXPECT_GE(c.y(), 0.2 - 1e-9);
  }
}

TEST(PathOptimizer, BadInputIsAnInputError) {
  const BPatch flat = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 20, 20, 1.0));
  PathOptimizerOptions options;
  EXPECT_THROW(optimize_path(flat, point_mass_rover(0.5), {{1, 1}, {25, 5}}, options), InputError);
  options.control_points = 3;
  EXPECT_THROW(optimize_path(flat, point_mass_rover(0.5), {{1, 1}, {15, 5}}, options), InputError);
  EXPECT_THROW(parse_path_solver("snopt"), InputError);
  EXPECT_EQ(parse_path_solver("nlopt-lbfgs"), PathSolver::kNloptLbfgs);
}

}  // namespace
}  // namespace talus
