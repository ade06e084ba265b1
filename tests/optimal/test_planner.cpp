// The two-stage planner through the library (talus::plan): the analytic
// rest-to-rest time on a flat plane, the "never slower than its own initial
// fit" and best-of-candidates rules around a hill, an independent
// re-evaluation of the best trajectory, the unreachable and infeasible
// statuses, the stop request, reproducibility, invalid input; and the one
// station-count rule.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/trajectory.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

using vehicle_test::point_mass_rover;

/// 61 x 41 nodes at 1 m, (0, 0) the south-west node, holding f.
BPatch surface_of(const terrain_test::HeightFunction& f) {
  return BPatch::interpolate(terrain_test::grid_of_nodes(f, 61, 41, 1.0, 0.0, 0.0));
}

/// A Gaussian hill of height 8 m, sigma 5 m at (30, 20): slopes up to 0.97.
double hill(double x, double y) {
  return 8.0 * std::exp(-((x - 30.0) * (x - 30.0) + (y - 20.0) * (y - 20.0)) / (2.0 * 25.0));
}

PlannerOptions quick_options(std::size_t candidates) {
  PlannerOptions options;
  options.global.candidates = candidates;
  options.local.control_points = 6;
  options.local.solver = PathSolver::kNloptBobyqa;
  return options;
}

TEST(Planner, StationCountIsCeilPlusOneAndAtLeastTwo) {
  EXPECT_EQ(station_count(0.0, 0.1), 2u);
  EXPECT_EQ(station_count(0.05, 0.1), 2u);
  EXPECT_EQ(station_count(1.0, 0.25), 5u);
  EXPECT_EQ(station_count(1.01, 0.25), 6u);
  EXPECT_EQ(station_count(100.0), 1001u);  // the default 0.1 m spacing
  EXPECT_THROW(station_count(-1.0, 0.1), InputError);
  EXPECT_THROW(station_count(std::nan(""), 0.1), InputError);
  EXPECT_THROW(station_count(1.0, 0.0), InputError);
  EXPECT_THROW(station_count(1e300, 1e-300), InputError);
}

TEST(Planner, FlatPlaneStraightRunMatchesTheAnalyticRestToRestTime) {
  // 50 m on flat ground, rest to rest: the friction circle bounds |s̈| by
  // mu g and v by 10 m/s; accelerate at mu g, cruise, brake at mu g.
  const BPatch surface = surface_of([](double, double) { return 0.0; });
  const Vehicle v = point_mass_rover(0.7);
  const PlannerResult result =
      plan(PlanningProblem(surface, v, {5, 20}, {55, 20}), quick_options(1));
  ASSERT_EQ(result.status, PlannerStatus::kOk) << result.brief_report();
  const double a = 0.7 * v.gravity, ramp = v.max_speed * v.max_speed / a;
  const double analytic = 2.0 * v.max_speed / a + (50.0 - ramp) / v.max_speed;
  EXPECT_NEAR(result.travel_time(), analytic, 2e-3 * analytic) << result.brief_report();
  EXPECT_NEAR(result.best()->length(), 50.0, 1e-6);
  EXPECT_EQ(result.best_candidate, 0u);
  EXPECT_TRUE(result.message.empty());
}

// The problem shares (or copies) its surface, the result holds it, and a trajectory copied
// out of the result keeps it alive through its path: nothing dangles once the caller's
// surface, the problem and the result are gone (the sanitizer build checks the reads).
TEST(Planner, ATrajectoryOutlivesTheCallersSurfaceTheProblemAndTheResult) {
  Trajectory kept;
  double planned = 0.0;
  {
    const BPatch surface = surface_of(hill);
    const PlannerResult result =
        plan(PlanningProblem(surface, point_mass_rover(0.7), {5, 20}, {55, 20}), quick_options(1));
    ASSERT_NE(result.best(), nullptr) << result.brief_report();
    ASSERT_NE(result.surface, nullptr);
    EXPECT_NE(result.surface.get(), &surface);  // the problem's own copy
    EXPECT_EQ(result.best()->path->surface().identity(), result.surface->identity());
    kept = *result.best();
    planned = kept.travel_time();
  }
  ASSERT_TRUE(kept.path);
  const PathFrame middle = kept.path->frame_at_parameter(0.5);  // evaluates the surface
  EXPECT_NEAR(middle.point.z(), kept.path->surface().elevation(middle.point.head<2>()), 1e-9);
  EXPECT_GT(planned, 0.0);
  // A shared surface is not copied.
  const auto shared = std::make_shared<const BPatch>(surface_of(hill));
  const PlanningProblem problem(shared, point_mass_rover(0.7), {5, 20}, {55, 20});
  EXPECT_EQ(problem.surface.get(), shared.get());
}

TEST(Planner, AroundAHillTheBestIsTheFastestCandidateAndNoneIsSlowerThanItsFit) {
  const BPatch surface = surface_of(hill);
  const PlannerResult result =
      plan(PlanningProblem(surface, point_mass_rover(0.4), {5, 20}, {55, 20}), quick_options(2));
  ASSERT_EQ(result.status, PlannerStatus::kOk) << result.brief_report();
  ASSERT_EQ(result.candidates.size(), result.global.candidates.size());
  ASSERT_EQ(result.candidates.size(), 2u);
  double fastest = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < result.candidates.size(); ++c) {
    const CandidateOutcome& o = result.candidates[c];
    EXPECT_EQ(o.candidate, c);
    ASSERT_TRUE(o.initial.feasible()) << o.initial.message;
    EXPECT_LE(o.trajectory.travel_time(), o.initial.travel_time());
    EXPECT_EQ(o.kept_initial, o.trajectory.path == o.initial.path);
    ASSERT_TRUE(o.optimization.has_value());
    fastest = std::min(fastest, o.trajectory.travel_time());
  }
  EXPECT_EQ(result.travel_time(), fastest);
  EXPECT_EQ(result.best()->travel_time(),
            result.candidates[*result.best_candidate].trajectory.travel_time());
  EXPECT_LE(result.travel_time(), result.global_travel_time());
  EXPECT_NEAR(
      result.improvement_percent(),
      100.0 * (result.global_travel_time() - result.travel_time()) / result.global_travel_time(),
      1e-12);
  // Slower than the straight run: the hill is out of reach at mu = 0.4.
  EXPECT_GT(result.travel_time(), 50.0 / 10.0);

  // Independent re-evaluation: rebuild the best curve from its control points.
  const Trajectory& best = *result.best();
  const Curve2 rebuilt = best.path->curve();
  const Trajectory again =
      evaluate_trajectory(surface, point_mass_rover(0.4), rebuilt, TrajectoryOptions{});
  EXPECT_NEAR(again.travel_time(), result.travel_time(), 1e-9 * result.travel_time());
  EXPECT_LT((best.limits->frame(0).point.head<2>() - Vec2(5, 20)).norm(), 1e-9);
  EXPECT_LT((best.limits->frame(best.limits->size() - 1).point.head<2>() - Vec2(55, 20)).norm(),
            1e-9);
  const std::string report = result.brief_report();
  EXPECT_NE(report.find("ok"), std::string::npos);
  EXPECT_NE(report.find("candidate 1"), std::string::npos);
}

TEST(Planner, RerunsAreBitIdentical) {
  const BPatch surface = surface_of(hill);
  const PlanningProblem problem(surface, point_mass_rover(0.4), {5, 20}, {55, 20});
  const PlannerResult a = plan(problem, quick_options(2)), b = plan(problem, quick_options(2));
  ASSERT_EQ(a.candidates.size(), b.candidates.size());
  for (std::size_t c = 0; c < a.candidates.size(); ++c) {
    EXPECT_EQ(a.candidates[c].trajectory.travel_time(), b.candidates[c].trajectory.travel_time());
    EXPECT_EQ(a.candidates[c].trajectory.path->curve().control_points(),
              b.candidates[c].trajectory.path->curve().control_points());
  }
}

TEST(Planner, AWallOfHillsIsUnreachableAsAStatus) {
  const BPatch surface = surface_of([](double x, double y) {
    double z = 0.0;
    for (int c = -10; c <= 70; c += 5) {
      z += 30.0 * std::exp(-((x - c) * (x - c) + (y - 20.0) * (y - 20.0)) / 18.0);
    }
    return z;
  });
  const PlannerResult result =
      plan(PlanningProblem(surface, point_mass_rover(0.7), {30, 5}, {30, 35}), quick_options(1));
  EXPECT_EQ(result.status, PlannerStatus::kUnreachable);
  EXPECT_FALSE(result.message.empty());
  EXPECT_EQ(result.best(), nullptr);
  EXPECT_TRUE(result.candidates.empty());
  EXPECT_TRUE(std::isinf(result.travel_time()));
  EXPECT_TRUE(std::isnan(result.improvement_percent()));
}

TEST(Planner, NoAdmissibleProfileOnAnyCandidateIsInfeasible) {
  // At 10 m/s with 1 m/s² of brakes the vehicle needs 50 m to stop; the goal
  // is 20 m away.
  const BPatch surface = surface_of([](double, double) { return 0.0; });
  Vehicle v = point_mass_rover(0.7);
  v.max_decel = 1.0;
  PlanningProblem problem(surface, v, {10, 20}, {30, 20});
  problem.start_speed = 10.0;
  const PlannerResult result = plan(problem, quick_options(2));
  EXPECT_EQ(result.status, PlannerStatus::kInfeasible) << result.brief_report();
  EXPECT_FALSE(result.message.empty());
  ASSERT_FALSE(result.candidates.empty());
  for (const CandidateOutcome& c : result.candidates) {
    EXPECT_FALSE(c.feasible());
    EXPECT_FALSE(c.trajectory.message.empty());
  }
  EXPECT_EQ(result.best(), nullptr);
  // The message names why and where the best corridor cannot be driven, also after the feedback
  // rounds have bent the corridors (whose fits then fail on the start speed before any profile).
  for (const std::size_t rounds : {std::size_t{0}, std::size_t{8}}) {
    PlannerOptions options = quick_options(2);
    options.feedback_rounds = rounds;
    const PlannerResult r = plan(problem, options);
    ASSERT_EQ(r.status, PlannerStatus::kInfeasible) << r.brief_report();
    EXPECT_NE(r.message.find("candidate 0: "), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("start speed 10 m/s"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("near (10.00, 20.00)"), std::string::npos) << r.message;
  }
}

TEST(Planner, TheProgressCallbackSeesEveryStageAndCanStop) {
  const BPatch surface = surface_of(hill);
  const PlanningProblem problem(surface, point_mass_rover(0.4), {5, 20}, {55, 20});
  PlannerOptions options = quick_options(2);
  std::vector<PlannerProgress> seen;
  options.progress = [&](const PlannerProgress& p) {
    seen.push_back(p);
    return !(p.stage == PlannerStage::kLocalOptimisation && p.candidate == 1);
  };
  const PlannerResult stopped = plan(problem, options);
  EXPECT_EQ(stopped.status, PlannerStatus::kStopped);
  EXPECT_EQ(stopped.candidates.size(), 1u);  // candidate 0 done, 1 never started
  ASSERT_EQ(seen.size(), 4u);
  EXPECT_EQ(seen[0].stage, PlannerStage::kGlobalSearch);
  EXPECT_EQ(seen[1].stage, PlannerStage::kLocalOptimisation);
  EXPECT_EQ(seen[1].candidate, 0u);
  EXPECT_EQ(seen[1].candidates, 2u);
  EXPECT_EQ(seen[3].stage, PlannerStage::kDone);
  EXPECT_LE(seen[1].seconds, seen[3].seconds);

  options.progress = [](const PlannerProgress&) { return false; };
  const PlannerResult at_once = plan(problem, options);
  EXPECT_EQ(at_once.status, PlannerStatus::kStopped);
  EXPECT_EQ(at_once.global.candidates.size(), 0u);
}

TEST(Planner, GlobalStageOnlyReturnsCandidatesWithoutTrajectories) {
  const BPatch surface = surface_of(hill);
  PlannerOptions options = quick_options(2);
  options.optimize = false;
  const PlannerResult result =
      plan(PlanningProblem(surface, point_mass_rover(0.4), {5, 20}, {55, 20}), options);
  EXPECT_EQ(result.status, PlannerStatus::kOk);
  EXPECT_EQ(result.global.candidates.size(), 2u);
  EXPECT_TRUE(result.candidates.empty());
  EXPECT_EQ(result.best(), nullptr);
}

/// The direction of travel [rad] of `curve` at parameter t (0 or 1).
double heading_at(const Curve2& curve, double t) {
  Curve2::Derivatives d;
  curve.derivatives(t, 1, d);
  return std::atan2(d(1, 1), d(0, 1));
}

TEST(Planner, AHeadingGivenAtTheStartOrTheGoalIsKept) {
  // On flat ground the free plan is the straight line east (heading 0 at
  // both ends); with headings of 0.6 rad (leaving north-east) and -0.9 rad
  // (arriving south-east) the path bends, with its end tangents exactly
  // along them, with every solver family.
  const BPatch surface = surface_of([](double, double) { return 0.0; });
  PlanningProblem problem(surface, point_mass_rover(0.7), {5, 20}, {55, 20});
  problem.start_heading = 0.6;
  problem.goal_heading = -0.9;
  // The nested formulation with both solver families; the simultaneous NLP
  // pins the same coordinates through the same bounds but needs minutes on
  // this plane, so it is not run here.
  for (const PathFormulation formulation : {PathFormulation::kNested}) {
    for (const PathSolver solver : {PathSolver::kIpopt, PathSolver::kNloptBobyqa}) {
      PlannerOptions options = quick_options(1);
      options.local.formulation = formulation;
      options.local.solver = solver;
      options.local.restarts = 0;
      const PlannerResult result = plan(problem, options);
      SCOPED_TRACE(std::string(to_string(formulation)) + " " + std::string(to_string(solver)));
      ASSERT_EQ(result.status, PlannerStatus::kOk) << result.brief_report();
      const Curve2& path = result.best()->path->curve();
      EXPECT_NEAR(heading_at(path, 0.0), 0.6, 1e-9);
      EXPECT_NEAR(heading_at(path, 1.0), -0.9, 1e-9);
      // The optimiser moved the rest of the path (it is not the fit).
      const CandidateOutcome& outcome = result.candidates[*result.best_candidate];
      ASSERT_TRUE(outcome.optimization);
      EXPECT_LT(outcome.trajectory.travel_time(), outcome.initial.travel_time());
    }
  }
  // Free headings give the straight line.
  const PlannerResult free =
      plan(PlanningProblem(surface, point_mass_rover(0.7), {5, 20}, {55, 20}), quick_options(1));
  ASSERT_EQ(free.status, PlannerStatus::kOk);
  EXPECT_NEAR(heading_at(free.best()->path->curve(), 0.0), 0.0, 1e-6);
  problem.start_heading = std::nan("");
  EXPECT_THROW(plan(problem, quick_options(1)), InputError);
}

TEST(Planner, InvalidInputThrowsInputError) {
  const BPatch surface = surface_of([](double, double) { return 0.0; });
  const Vehicle v = point_mass_rover(0.7);
  EXPECT_THROW(plan(PlanningProblem(surface, v, {-1, 20}, {55, 20}), {}), InputError);
  EXPECT_THROW(plan(PlanningProblem(surface, v, {5, 20}, {55, 41}), {}), InputError);
  Vehicle unlimited = v;
  unlimited.max_speed = std::numeric_limits<double>::infinity();
  EXPECT_THROW(plan(PlanningProblem(surface, unlimited, {5, 20}, {55, 20}), {}), InputError);
  PlanningProblem too_fast(surface, v, {5, 20}, {55, 20});
  too_fast.end_speed = 11.0;
  EXPECT_THROW(plan(too_fast, {}), InputError);
  PlannerOptions options;
  options.global.candidates = 0;
  EXPECT_THROW(plan(PlanningProblem(surface, v, {5, 20}, {55, 20}), options), InputError);
  options = {};
  options.station_spacing = -0.1;  // (0 means the scale-aware default)
  EXPECT_THROW(plan(PlanningProblem(surface, v, {5, 20}, {55, 20}), options), InputError);
}

}  // namespace
}  // namespace talus
