// The planner's time limit (PlannerOptions::termination), hit deterministically
// through an injected clock: in the global stage before any route (no
// trajectory), just before the first candidate (its initial fit, feasible),
// and inside the first candidate's optimisation (its best point so far); a
// generous limit changes nothing; the optimiser's own limit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "talus/optimal/planner.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

using vehicle_test::point_mass_rover;

/// A Gaussian hill (8 m, sigma 5 m) at (30, 20) on 61 x 41 nodes at 1 m.
BPatch hill_surface() {
  return BPatch::interpolate(terrain_test::grid_of_nodes(
      [](double x, double y) {
        return 8.0 * std::exp(-((x - 30.0) * (x - 30.0) + (y - 20.0) * (y - 20.0)) / 50.0);
      },
      61, 41, 1.0, 0.0, 0.0));
}

PlannerOptions two_candidates(PathSolver solver) {
  PlannerOptions options;
  options.global.candidates = 2;
  options.local.control_points = 6;
  options.local.solver = solver;
  options.local.max_evaluations = 40;  // quick
  return options;
}

PlanningProblem problem_on(const BPatch& surface) {
  return PlanningProblem(surface, point_mass_rover(0.4), {5, 20}, {55, 20});
}

TEST(PlannerTimeLimit, AGenerousLimitGivesBitIdenticalResults) {
  const BPatch surface = hill_surface();
  for (const PathSolver solver : {PathSolver::kIpopt}) {
    const PlannerResult free = plan(problem_on(surface), two_candidates(solver));
    PlannerOptions options = two_candidates(solver);
    options.termination = Termination::time_budget(1e6);
    const PlannerResult limited = plan(problem_on(surface), options);
    ASSERT_EQ(free.status, PlannerStatus::kOk);
    ASSERT_EQ(limited.status, PlannerStatus::kOk) << limited.brief_report();
    EXPECT_TRUE(limited.not_optimised.empty());
    ASSERT_EQ(limited.candidates.size(), free.candidates.size());
    for (std::size_t c = 0; c < free.candidates.size(); ++c) {
      EXPECT_EQ(limited.candidates[c].trajectory.travel_time(),
                free.candidates[c].trajectory.travel_time());
      EXPECT_EQ(limited.candidates[c].optimization->iterations,
                free.candidates[c].optimization->iterations);
      EXPECT_FALSE(limited.candidates[c].time_limited);
    }
    EXPECT_EQ(limited.best()->path->curve().control_points(),
              free.best()->path->curve().control_points());
  }
}

TEST(PlannerTimeLimit, ALimitPassedBeforeTheFirstCandidateReturnsItsInitialFitFeasible) {
  const BPatch surface = hill_surface();
  for (const PathSolver solver : {PathSolver::kIpopt, PathSolver::kNloptBobyqa}) {
    PlannerOptions options = two_candidates(solver);
    double now = 0.0;
    options.termination = Termination::time_budget(10.0, [&now] { return now; });
    // The deadline passes just as the local stage begins.
    options.progress = [&now](const PlannerProgress& p) {
      if (p.stage == PlannerStage::kLocalOptimisation) now = 100.0;
      return true;
    };
    const PlannerResult r = plan(problem_on(surface), options);
    ASSERT_EQ(r.status, PlannerStatus::kTimeLimit) << r.brief_report();
    EXPECT_EQ(to_string(r.status), "time_limit");
    ASSERT_EQ(r.global.candidates.size(), 2u);
    ASSERT_EQ(r.candidates.size(), 1u);
    EXPECT_EQ(r.not_optimised, std::vector<std::size_t>{1});
    ASSERT_NE(r.best(), nullptr);
    EXPECT_EQ(r.best_candidate, 0u);
    const CandidateOutcome& c = r.candidates[0];
    EXPECT_TRUE(c.time_limited);
    ASSERT_TRUE(c.optimization.has_value());
    EXPECT_EQ(c.optimization->solver_status, "time_limit");
    // Stopped before its first step: the result is the initial fit itself.
    EXPECT_TRUE(c.trajectory.feasible());
    EXPECT_EQ(c.optimization->curve.control_points(),
              c.optimization->initial_curve.control_points());
    EXPECT_EQ(c.trajectory.travel_time(), c.initial.travel_time());
    EXPECT_NE(r.message.find("candidate 1 not optimised"), std::string::npos) << r.message;
    EXPECT_NE(r.brief_report().find("time limit: 1 candidate not optimised: 1"), std::string::npos)
        << r.brief_report();
  }
}

TEST(PlannerTimeLimit, ALimitInTheGlobalStageBeforeAnyRouteGivesNoTrajectory) {
  const BPatch surface = hill_surface();
  PlannerOptions options = two_candidates(PathSolver::kIpopt);
  double ticks = 0.0;
  // One tick per look at the clock: passes while the lattice is being sampled.
  options.termination = Termination::time_budget(2.5, [&ticks] { return ticks++; });
  const PlannerResult r = plan(problem_on(surface), options);
  ASSERT_EQ(r.status, PlannerStatus::kTimeLimit) << r.brief_report();
  EXPECT_EQ(r.global.status, GlobalSearchStatus::kStopped);
  EXPECT_TRUE(r.global.candidates.empty());
  EXPECT_TRUE(r.candidates.empty());
  EXPECT_EQ(r.best(), nullptr);
  EXPECT_NE(r.message.find("no trajectory"), std::string::npos) << r.message;
}

TEST(PlannerTimeLimit, ALimitDuringTheOptimisationKeepsItsBestPointSoFar) {
  const BPatch surface = hill_surface();
  PlannerOptions options = two_candidates(PathSolver::kIpopt);
  double ticks = 0.0;
  const auto clock = [&ticks] { return ticks++; };
  // First, where the local stage starts on this clock.
  double at_local = -1.0;
  options.termination = Termination::time_budget(1e12, clock);
  options.progress = [&](const PlannerProgress& p) {
    if (p.stage == PlannerStage::kLocalOptimisation && p.candidate == 0) at_local = ticks;
    return true;
  };
  const PlannerResult free = plan(problem_on(surface), options);
  ASSERT_EQ(free.status, PlannerStatus::kOk);
  ASSERT_GT(free.candidates[0].optimization->iterations, 4u);
  // Then a limit 3 ticks (Ipopt iterations) into candidate 0's optimisation.
  ticks = 0.0;
  options.termination = Termination::time_budget(at_local + 3.0, clock);
  options.progress = nullptr;
  const PlannerResult r = plan(problem_on(surface), options);
  ASSERT_EQ(r.status, PlannerStatus::kTimeLimit) << r.brief_report();
  ASSERT_EQ(r.candidates.size(), 1u);
  EXPECT_EQ(r.not_optimised, std::vector<std::size_t>{1});
  const CandidateOutcome& c = r.candidates[0];
  EXPECT_TRUE(c.time_limited);
  EXPECT_EQ(c.optimization->solver_status, "time_limit");
  EXPECT_LT(c.optimization->iterations, free.candidates[0].optimization->iterations);
  ASSERT_NE(r.best(), nullptr);
  EXPECT_TRUE(r.best()->feasible());
  EXPECT_LE(r.travel_time(), c.initial.travel_time());
  EXPECT_NE(r.message.find("candidate 0 cut short"), std::string::npos) << r.message;
}

TEST(PlannerTimeLimit, TheOptimiserStopsAtItsOwnLimitWithTheInitialFit) {
  const BPatch surface = hill_surface();
  const std::vector<Vec2> polyline = {{5, 20}, {20, 8}, {40, 8}, {55, 20}};
  for (const PathSolver solver :
       {PathSolver::kIpopt, PathSolver::kNloptLbfgs, PathSolver::kNloptBobyqa}) {
    PathOptimizerOptions options;
    options.control_points = 6;
    options.solver = solver;
    options.termination = Termination::time_budget(1e-9);  // passed before the solver's first look
    const OptimizedPath p = optimize_path(surface, point_mass_rover(0.4), polyline, options);
    EXPECT_EQ(p.solver_status, "time_limit") << to_string(solver);
    EXPECT_FALSE(p.solver_failed);
    EXPECT_EQ(p.travel_time, p.initial_time) << to_string(solver);
  }
  PathOptimizerOptions simultaneous;
  simultaneous.control_points = 6;
  simultaneous.formulation = PathFormulation::kSimultaneous;
  simultaneous.termination = Termination::when([] { return true; });
  const OptimizedPath s = optimize_path(surface, point_mass_rover(0.4), polyline, simultaneous);
  EXPECT_EQ(s.solver_status, "time_limit");
  EXPECT_EQ(s.phase, 1);  // phase 2 never started
  EXPECT_LE(s.travel_time, s.initial_time);
}

TEST(PlannerTimeLimit, ANonPositiveLimitIsAnInputError) {
  for (const double limit : {0.0, -1.0, std::nan("")}) {
    EXPECT_THROW(Termination::time_budget(limit), InputError) << limit;
  }
}

// A stop request in the same termination: status kStopped, not kTimeLimit, whether it comes
// before the global search or between candidates.
TEST(PlannerTimeLimit, AStopRequestStopsThePlanWithStatusStopped) {
  const BPatch surface = hill_surface();
  PlannerOptions options = two_candidates(PathSolver::kIpopt);
  options.termination = Termination::time_budget(1e6) | Termination::when([] { return true; });
  const PlannerResult early = plan(problem_on(surface), options);
  EXPECT_EQ(early.status, PlannerStatus::kStopped) << early.brief_report();
  EXPECT_EQ(early.global.status, GlobalSearchStatus::kStopped);
  EXPECT_NE(early.global.message.find("stop_requested"), std::string::npos) << early.global.message;
  EXPECT_EQ(early.best(), nullptr);

  bool requested = false;
  options.termination = Termination::when([&requested] { return requested; });
  options.progress = [&requested](const PlannerProgress& p) {
    if (p.stage == PlannerStage::kLocalOptimisation && p.candidate == 1) requested = true;
    return true;
  };
  const PlannerResult late = plan(problem_on(surface), options);
  EXPECT_EQ(late.status, PlannerStatus::kStopped) << late.brief_report();
  EXPECT_EQ(late.global.status, GlobalSearchStatus::kOk);
  // Candidate 1's solver saw the request at its first look (its status says "time_limit", the
  // one status of a solver stopped by its termination); the plan reports the request.
  ASSERT_EQ(late.candidates.size(), 2u);
  EXPECT_EQ(late.candidates[1].optimization->solver_status, "time_limit");
}

}  // namespace
}  // namespace talus
