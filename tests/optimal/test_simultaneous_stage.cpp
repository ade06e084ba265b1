// The simultaneous (direct-transcription) local stage: its own convergence
// status, agreement with the nested formulation, a start from an initial fit
// without an admissible profile, and the straight-line closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <utility>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/hessian_probes.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "talus/optimal/path_time_objective.hpp"
#include "talus/optimal/trajectory.hpp"
#include "talus/optimal/verify_profile.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

using vehicle_test::point_mass_rover;

/// A smooth Gaussian hill, 8 m high with a 7 m standard deviation, centred
/// at (40, 30) on an 80 × 60 m map at 1 m cells; its steepest slope is
/// 8 / 7 e^(-1/2) = 0.69.
BPatch gaussian_hill() {
  return BPatch::interpolate(terrain_test::grid_from_function(
      [](double x, double y) {
        return 8.0 * std::exp(-((x - 40) * (x - 40) + (y - 30) * (y - 30)) / (2 * 7.0 * 7.0));
      },
      0, 0, 80, 60, 1.0));
}

PathOptimizerOptions simultaneous_options() {
  PathOptimizerOptions options;
  options.formulation = PathFormulation::kSimultaneous;
  options.more_control_points.clear();  // one fit: the tests are about the NLP itself
  return options;
}

bool converged_by_ipopt(const OptimizedPath& o) {
  return o.solver_status == "success" || o.solver_status == "stop_at_acceptable_point";
}

TEST(SimultaneousStage, StraightLineOnAPlaneAtTheAnalyticTime) {
  const BPatch flat = BPatch::interpolate(
      terrain_test::grid_from_function([](double, double) { return 0.0; }, 0, 0, 60, 40, 1.0));
  PathOptimizerOptions options = simultaneous_options();
  options.control_points = 6;
  const std::vector<Vec2> bent = {{5, 20}, {20, 30}, {40, 30}, {55, 20}};
  const OptimizedPath best = optimize_path(flat, point_mass_rover(0.5), bent, options);
  // Rest to rest over L = 50 m with a_max = mu g, capped at 10 m/s.
  const double L = 50.0, a = 0.5 * 9.81, v = 10.0;
  const double straight = 2 * v / a + (L - v * v / a) / v;
  EXPECT_TRUE(converged_by_ipopt(best)) << best.solver_status;
  EXPECT_TRUE(best.converged);
  EXPECT_EQ(best.formulation, "simultaneous");
  EXPECT_GT(best.initial_time, 1.05 * straight);
  // The exact profile of the result at the search stations: only the two
  // switch steps differ from the closed form, by at most (spacing / L)^2.
  const double h = search_station_spacing(options, flat, point_mass_rover(0.5)) / L;
  EXPECT_NEAR(best.travel_time, straight, h * h * straight);
  // Straight to within 1 cm (a bend that small costs nothing measurable).
  for (const Vec2& c : best.curve.control_points()) EXPECT_NEAR(c.y(), 20.0, 1e-2);
  // The NLP's own time is that of the same discrete model, up to its
  // 1 cm/s speed floor at the two ends (2 Δs / ṡ with ṡ >= 1 cm/s).
  EXPECT_NEAR(best.nlp_travel_time, best.travel_time, 1e-3 * straight);
  std::printf("flat: %.6f s (straight %.6f, NLP %.6f), %zu iterations, %s\n", best.travel_time,
              straight, best.nlp_travel_time, best.iterations, best.solver_status.c_str());
}

TEST(SimultaneousStage, ConvergesByIpoptsOwnStatusAroundASmoothHill) {
  const BPatch terrain = gaussian_hill();
  const Vehicle v = point_mass_rover(0.4);
  GlobalSearchOptions search;
  search.candidates = 1;
  const GlobalSearchResult global = global_search(terrain, v, {5, 30}, {75, 30}, search);
  ASSERT_EQ(global.status, GlobalSearchStatus::kOk);
  const OptimizedPath best =
      optimize_path(terrain, v, global.candidates[0].vertices, simultaneous_options());
  EXPECT_TRUE(converged_by_ipopt(best)) << best.solver_status;
  EXPECT_TRUE(best.converged);
  EXPECT_FALSE(best.solver_failed);
  EXPECT_LT(best.travel_time, 0.99 * best.initial_time);
  // Independently: the returned curve's exact profile takes the reported time.
  PathTimeObjective objective(terrain, v, {5, 30}, {75, 30}, best.control_points, best.stations,
                              {});
  EXPECT_NEAR(objective.evaluate(objective.variables(best.curve.control_points())),
              best.travel_time, 1e-9 * best.travel_time);
  std::printf("hill: %.4f s from %.4f s (NLP %.4f), %zu iterations, %s, %.3f s\n", best.travel_time,
              best.initial_time, best.nlp_travel_time, best.iterations, best.solver_status.c_str(),
              best.seconds);
}

TEST(SimultaneousStage, AgreesWithTheNestedOptimumOnASmoothCase) {
  const BPatch terrain = gaussian_hill();
  const Vehicle v = point_mass_rover(0.4);
  GlobalSearchOptions search;
  search.candidates = 1;
  const GlobalSearchResult global = global_search(terrain, v, {5, 30}, {75, 30}, search);
  ASSERT_EQ(global.status, GlobalSearchStatus::kOk);
  PathOptimizerOptions nested;
  nested.more_control_points.clear();  // both at the same M
  nested.max_iterations = 400;
  nested.max_evaluations = 2000;
  nested.relative_tolerance = 1e-10;
  const OptimizedPath a = optimize_path(terrain, v, global.candidates[0].vertices, nested);
  const OptimizedPath b =
      optimize_path(terrain, v, global.candidates[0].vertices, simultaneous_options());
  ASSERT_EQ(a.control_points, b.control_points);
  ASSERT_EQ(a.stations, b.stations);
  EXPECT_NEAR(b.travel_time, a.travel_time, 0.005 * a.travel_time);
  std::printf("nested %.5f s (%s, %zu evaluations), simultaneous %.5f s (%s, %zu iterations)\n",
              a.travel_time, a.solver_status.c_str(), a.evaluations, b.travel_time,
              b.solver_status.c_str(), b.iterations);
}

TEST(SimultaneousStage, StartsFromAnInfeasibleFitAndEndsFeasible) {
  const BPatch terrain = gaussian_hill();
  const Vehicle v = point_mass_rover(0.4);
  // 6 m south of the summit the slope is 8 · 6 / 49 · e^(-0.37) = 0.68 > μ:
  // the vehicle slides even at rest, so the fit has no admissible profile.
  const std::vector<Vec2> over = {{5, 30}, {40, 24}, {75, 30}};
  PathOptimizerOptions nested;
  nested.adaptive_control_points = false;
  EXPECT_THROW(optimize_path(terrain, v, over, nested), InputError);
  // Feasibility is the claim here, not convergence (which the smooth hill
  // tests): how many iterations Ipopt needs after restoration differs with
  // the BLAS kernels of the CPU (it converges on some machines and stops at
  // 600 iterations on others), so the budget is capped.
  PathOptimizerOptions options = simultaneous_options();
  options.simultaneous_lateral_iterations = 100;
  options.simultaneous_max_iterations = 100;
  const OptimizedPath best = optimize_path(terrain, v, over, options);
  EXPECT_FALSE(std::isfinite(best.initial_time));
  ASSERT_TRUE(std::isfinite(best.travel_time)) << best.solver_status;
  // Re-evaluated from scratch at the plan's spacing, and checked by
  // verify_profile against its own admissible sets.
  const Trajectory initial = evaluate_trajectory(terrain, v, best.initial_curve, {});
  EXPECT_FALSE(initial.feasible());
  const Trajectory result = evaluate_trajectory(terrain, v, best.curve, {});
  ASSERT_TRUE(result.feasible()) << result.message;
  const ProfileVerification check = verify_profile(*result.limits, result.profile);
  EXPECT_TRUE(check.passed()) << check.message;
  std::printf("infeasible start: %.4f s at 0.1 m (%.4f s at search), %zu iterations, %s\n",
              result.travel_time(), best.travel_time, best.iterations, best.solver_status.c_str());
}

TEST(SimultaneousStage, FormulationNamesAndOptions) {
  EXPECT_EQ(parse_path_formulation("nested"), PathFormulation::kNested);
  EXPECT_EQ(parse_path_formulation("simultaneous"), PathFormulation::kSimultaneous);
  EXPECT_EQ(to_string(PathFormulation::kSimultaneous), "simultaneous");
  EXPECT_THROW(parse_path_formulation("collocation"), InputError);
  PathOptimizerOptions options;
  EXPECT_EQ(options.formulation, PathFormulation::kNested);
  options.simultaneous_max_iterations = 0;
  EXPECT_THROW(options.validate(), InputError);
  options.simultaneous_max_iterations = 10;
  options.simultaneous_tolerance = 0.0;
  EXPECT_THROW(options.validate(), InputError);
}

// The NLP's Hessian pattern: each of `steps` steps couples the controls
// first..first+4 of its two stations (five consecutive, shifting every
// `stations_per_span` steps) and its two speeds, as SimultaneousNlp builds it.
std::vector<std::pair<int, int>> banded_pattern(int controls, int stations, int stations_per_span) {
  std::set<std::pair<int, int>> entries;
  for (int j = 0; j + 1 < stations; ++j) {
    std::vector<int> columns;
    const int first = std::min(j / stations_per_span, controls - 5);
    for (int c = first; c < first + 5; ++c) columns.push_back(c);
    columns.push_back(controls + j);
    columns.push_back(controls + j + 1);
    for (int a : columns)
      for (int b : columns)
        if (a >= b) entries.insert({a, b});
  }
  return {entries.begin(), entries.end()};
}

TEST(SimultaneousHessianProbes, NoRowSeesTwoColumnsOfOneGroup) {
  const int controls = 55, stations = 435;
  const auto pattern = banded_pattern(controls, stations, 8);
  const auto groups = probe_groups(pattern, controls, controls + stations);
  // Every column in exactly one group.
  std::vector<int> seen(controls, 0);
  for (const auto& g : groups)
    for (std::size_t c : g) ++seen[c];
  for (int c = 0; c < controls; ++c) EXPECT_EQ(seen[c], 1) << "column " << c;
  // The invariant that makes a group's probe exact: no row with an entry in
  // two of its columns (the pattern is symmetric: (r, c) stands for (c, r) too).
  std::vector<std::set<int>> rows(controls);
  for (const auto& [r, c] : pattern) {
    if (c < controls) rows[c].insert(r);
    if (r < controls) rows[r].insert(c);
  }
  for (const auto& g : groups) {
    for (std::size_t a = 0; a < g.size(); ++a)
      for (std::size_t b = a + 1; b < g.size(); ++b)
        for (int r : rows[g[a]])
          EXPECT_EQ(rows[g[b]].count(r), 0u)
              << "columns " << g[a] << ", " << g[b] << " share row " << r;
  }
  // Columns up to eight apart share a row (a control both share a step
  // with), nine apart share nothing: nine groups, not 55 probes.
  EXPECT_EQ(groups.size(), 9u);
}

TEST(SimultaneousHessianProbes, RejectsAnEntryOutOfRange) {
  EXPECT_THROW(probe_groups({{7, 0}}, 2, 5), InputError);
}

}  // namespace
}  // namespace talus
