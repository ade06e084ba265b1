// The planner's feedback from the local stage to the global one
// (PlannerOptions::feedback_rounds) on real ground: an 80 x 80-cell window of
// the bundled Big Tujunga DEM (SRTM, 30 m cells) where the lattice's three
// best corridors climb switchbacks that no continuous profile of the rover
// drives (the hairpins are sharp turns on steep side slopes; the lattice
// judges each straight edge alone and cannot see them). Without feedback the
// plan is infeasible; with it the failing stretches are excluded and the
// plan ends feasible, which verify_profile and a fresh evaluation at other
// stations confirm independently. A built chute steeper than atan μ: the
// lattice's braking rule refuses it itself; without that rule the lattice
// takes it and the feedback loop removes it. And the agreement of the local
// stage's stations with the final ones (planner.hpp, step 3): an optimum
// that has no profile at the final stations gives way to the fastest of the
// optimiser's other points there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/grid_window.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/trajectory.hpp"
#include "talus/optimal/verify_profile.hpp"
#include "talus/scenarios/fractal_battery.hpp"

namespace talus {
namespace {

/// A bundled data file, `relative` to the data folder.
std::string data_file(const std::string& relative) {
  return std::string(TALUS_DATA_DIR) + "/" + relative;
}

/// The window round the switchbacks, columns 211–290 and rows 233–312 (from
/// the south) of the 512 x 512 grid.
BPatch switchback_surface() {
  const ElevationGrid dem = read_esri_ascii(data_file("terrain/bigtujunga_srtm30m.asc"));
  return BPatch::interpolate(crop_grid(dem, GridWindow{211, 233, 80, 80}));
}

PlanningProblem switchback_problem(const BPatch& surface) {
  return PlanningProblem(surface, load_vehicle(data_file("vehicles/rover.yaml")),
                         {388538.655454, 3797372.827628}, {389438.655454, 3798452.827628});
}

/// 8-point fits, one solve each: fits that cut the switchbacks' corners,
/// whose failures the feedback loop is about (a 16-point fit follows more
/// of them).
PlannerOptions quick_options(std::size_t feedback_rounds) {
  PlannerOptions options;
  options.feedback_rounds = feedback_rounds;
  options.local.control_points = 8;
  options.local.restarts = 0;
  options.local.max_evaluations = 20;
  return options;
}

TEST(PlannerFeedback, WithoutItNoCandidateOfTheSwitchbackCanBeDriven) {
  const BPatch surface = switchback_surface();
  const PlannerResult result = plan(switchback_problem(surface), quick_options(0));
  EXPECT_EQ(result.status, PlannerStatus::kInfeasible) << result.brief_report();
  EXPECT_EQ(result.feedback_rounds, 0u);
  EXPECT_TRUE(result.excluded.empty());
  ASSERT_FALSE(result.candidates.empty());
  for (const CandidateOutcome& c : result.candidates) {
    EXPECT_FALSE(c.followable);
    EXPECT_FALSE(c.feasible());
  }
}

TEST(PlannerFeedback, ExcludingTheFailingStretchesGivesADrivableTrajectory) {
  const BPatch surface = switchback_surface();
  const PlanningProblem problem = switchback_problem(surface);
  const PlannerResult result = plan(problem, quick_options(8));
  ASSERT_EQ(result.status, PlannerStatus::kOk) << result.brief_report();
  EXPECT_GE(result.feedback_rounds, 1u);
  ASSERT_FALSE(result.excluded.empty());
  const CandidateOutcome& best = result.candidates.at(*result.best_candidate);
  EXPECT_TRUE(best.followable);

  // The kept candidates avoid every excluded region (their ends excepted).
  for (const CandidatePath& candidate : result.global.candidates) {
    for (std::size_t v = 1; v + 1 < candidate.vertices.size(); ++v) {
      for (const ExcludedRegion& region : result.excluded) {
        EXPECT_GT((candidate.vertices[v] - region.centre).norm(), region.radius);
      }
    }
  }

  // Independently: every step of the best profile is admissible, and the
  // same curve evaluated afresh at half the stations' spacing drives in
  // nearly the same time.
  const Trajectory& trajectory = *result.best();
  const ProfileVerification check = verify_profile(*trajectory.limits, trajectory.profile);
  EXPECT_TRUE(check.passed()) << check.message;
  TrajectoryOptions finer;
  finer.station_spacing = 0.5 * default_station_spacing(surface, problem.vehicle);
  const Trajectory fresh =
      evaluate_trajectory(surface, problem.vehicle, trajectory.path->curve(), finer);
  ASSERT_TRUE(fresh.feasible()) << fresh.message;
  EXPECT_NEAR(fresh.travel_time(), trajectory.travel_time(), 0.01 * trajectory.travel_time());
}

/// A plateau 8 m above a plain, the drop a tanh step whose length grows from
/// 3 m on the line y = 0 to 12 m far from it, with a 0.5 m channel along
/// y = 0: a chute at 53° (steeper than atan 0.7 = 35°) on the direct route,
/// concave below its steepest point, and gentler ramps to either side.
/// 97 x 113 nodes at 0.25 m, x in [0, 24], y in [-14, 14].
BPatch chute_surface() {
  ElevationGrid grid(97, 113, 0.25, 0.0, -14.0);
  for (std::size_t j = 0; j < grid.nrows(); ++j) {
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const Vec2 p = grid.node_position(i, j);
      const double length = 3.0 + 9.0 * (1.0 - std::exp(-p.y() * p.y() / 32.0));
      const double channel = 0.5 * std::exp(-p.y() * p.y() / (2.0 * 1.5 * 1.5));
      grid.at(i, j) = 4.0 * (1.0 - std::tanh((p.x() - 12.0) / length)) - channel;
    }
  }
  return BPatch::interpolate(grid);
}

const Vec2 kChuteStart{2.0, 0.0}, kChuteGoal{18.0, 0.0};

/// Whether the best plan avoids the chute: every candidate vertex on ground
/// gentler than atan μ.
void expect_candidates_off_the_chute(const BPatch& surface, const PlannerResult& result,
                                     double friction) {
  for (const CandidatePath& candidate : result.global.candidates) {
    for (const Vec2& vertex : candidate.vertices) {
      EXPECT_LT(surface.evaluate(vertex).gradient.norm(), friction)
          << "a candidate vertex at (" << vertex.x() << ", " << vertex.y() << ") is on the chute";
    }
  }
}

TEST(PlannerFeedback, TheChuteIsSteeperThanAtanMuConcaveBelowAndCannotBeDrivenStraight) {
  const BPatch surface = chute_surface();
  const Vehicle ugv = scenarios::battery_point_mass_ugv();                       // issue #12's UGV
  EXPECT_GT(surface.evaluate({12.0, 0.0}).gradient.norm(), 1.2 * ugv.friction);  // 53° vs 35°
  EXPECT_GT(surface.evaluate({14.0, 0.0}).hessian(0, 0), 0.0);  // concave below the steepest point
  const Trajectory direct = evaluate_trajectory(
      surface, ugv, Curve2::interpolate({kChuteStart, {10.0, 0.0}, kChuteGoal}), {});
  EXPECT_FALSE(direct.feasible()) << "the straight descent of the chute should not be drivable";
}

/// The lattice's own braking rule refuses the chute: down a straight edge
/// the slope is steepest where the edge's normal curvature is zero (the
/// chute's inflection), and there no speed lets the vehicle brake
/// (global_search.hpp, rule (c)). So the first search already routes round
/// it and the feedback loop has nothing to do.
TEST(PlannerFeedback, TheLatticeBrakingRuleRefusesTheChuteItself) {
  const BPatch surface = chute_surface();
  const Vehicle ugv = scenarios::battery_point_mass_ugv();  // issue #12's UGV
  PlannerOptions options;
  options.local.max_evaluations = 20;
  options.local.more_control_points.clear();
  const PlannerResult result =
      plan(PlanningProblem(surface, ugv, kChuteStart, kChuteGoal), options);
  ASSERT_EQ(result.status, PlannerStatus::kOk) << result.brief_report();
  EXPECT_EQ(result.feedback_rounds, 0u);
  EXPECT_TRUE(result.excluded.empty());
  expect_candidates_off_the_chute(surface, result, ugv.friction);
  EXPECT_TRUE(result.candidates.at(*result.best_candidate).followable);
  const ProfileVerification check = verify_profile(*result.best()->limits, result.best()->profile);
  EXPECT_TRUE(check.passed()) << check.message;
}

/// Without the braking rule the lattice's best corridor goes straight down
/// the chute, which no profile drives: the feedback loop finds that from the
/// candidate's initial fit, excludes the stretch and searches again until
/// the corridors keep off the chute, and the plan ends feasible and verified.
TEST(PlannerFeedback, WithoutTheBrakingRuleTheFeedbackLoopRemovesTheChute) {
  const BPatch surface = chute_surface();
  const Vehicle ugv = scenarios::battery_point_mass_ugv();  // issue #12's UGV
  const PlanningProblem problem(surface, ugv, kChuteStart, kChuteGoal);
  PlannerOptions options;
  options.global.braking_rule = false;
  options.local.max_evaluations = 20;
  options.local.more_control_points.clear();

  PlannerOptions first_search = options;
  first_search.feedback_rounds = 0;
  first_search.global.candidates = 1;
  const PlannerResult blind = plan(problem, first_search);
  ASSERT_FALSE(blind.global.candidates.empty());
  double steepest = 0.0;
  for (const Vec2& vertex : blind.global.candidates.front().vertices)
    steepest = std::max(steepest, surface.evaluate(vertex).gradient.norm());
  EXPECT_GT(steepest, ugv.friction) << "the best corridor should take the chute";
  EXPECT_FALSE(blind.candidates.front().followable);

  const PlannerResult result = plan(problem, options);
  ASSERT_EQ(result.status, PlannerStatus::kOk) << result.brief_report();
  EXPECT_GE(result.feedback_rounds, 1u);
  ASSERT_FALSE(result.excluded.empty());
  const CandidateOutcome& best = result.candidates.at(*result.best_candidate);
  EXPECT_TRUE(best.followable);
  const Trajectory& trajectory = *result.best();
  const ProfileVerification check = verify_profile(*trajectory.limits, trajectory.profile);
  EXPECT_TRUE(check.passed()) << check.message;
  TrajectoryOptions finer;
  finer.station_spacing = 0.5 * default_station_spacing(surface, ugv);
  const Trajectory fresh = evaluate_trajectory(surface, ugv, trajectory.path->curve(), finer);
  ASSERT_TRUE(fresh.feasible()) << fresh.message;
  EXPECT_NEAR(fresh.travel_time(), trajectory.travel_time(), 0.01 * trajectory.travel_time());
}

// Fractal battery seed 4, the lattice's best corridor, searched at a coarse spacing (0.6 m
// against the final 0.1 m): the optimiser's best point (8.93 s at its search stations) has no
// admissible profile at the final stations, a profile on the edge of admissibility that the
// coarse stations step over. The planner reports another attempt's point instead, the fastest
// at the final stations, rather than the initial fit. (Until the rigid body's wheels changed
// the floating-point path of the adjoint, the default search on seed 14 with 8 and 16 control
// points met the same case; on the battery it is rare at the default spacing: none of 75
// plans in the scan of that change.)
TEST(PlannerStations, AnOptimumWithoutAProfileAtTheFinalStationsGivesWayToTheFastestAttempt) {
  const BPatch surface =
      BPatch::interpolate(generate_fractal_terrain(scenarios::battery_terrain(4)));
  const Vehicle ugv = scenarios::battery_point_mass_ugv();
  const PlanningProblem problem(surface, ugv, scenarios::kBatteryStart, scenarios::kBatteryGoal);
  PlannerOptions options;
  options.global.candidates = 1;
  options.local.station_spacing = 0.6;
  options.certify = false;  // the rule itself: a certificate may then improve the reported point
  const PlannerResult result = plan(problem, options);
  ASSERT_EQ(result.status, PlannerStatus::kOk) << result.brief_report();
  const CandidateOutcome& outcome = result.candidates.front();
  ASSERT_TRUE(outcome.optimization.has_value());
  const OptimizedPath& optimization = *outcome.optimization;
  const TrajectoryOptions final_stations;  // the planner's default spacing

  // The case exercises the rule: the optimiser's own best disagrees.
  const Trajectory own = evaluate_trajectory(surface, ugv, optimization.curve, final_stations);
  EXPECT_FALSE(own.travel_time() <= optimization.travel_time * (1.0 + kStageDisagreement))
      << "the best point's final time " << own.travel_time() << " s agrees with its search time "
      << optimization.travel_time << " s";

  // The reported point is the fastest attempt at the final stations by a fresh evaluation,
  // and faster than the initial fit: another attempt's when the best point has no profile
  // there (as where this was written). On a machine whose floating-point path differs
  // (OpenBLAS picks its kernels by CPU; on an AVX-512 machine the best point keeps a profile
  // there, 17.5 s against 8.96 s at the search stations, and the other attempts' are slower)
  // the best point may still be the fastest, and is then rightly the one reported.
  ASSERT_TRUE(outcome.reported_attempt.has_value());
  if (!own.feasible()) {
    EXPECT_NE(*outcome.reported_attempt, optimization.best_attempt);
  }
  EXPECT_FALSE(outcome.kept_initial);
  double fastest = std::numeric_limits<double>::infinity();
  for (const LocalAttempt& attempt : optimization.attempts) {
    if (!attempt.curve) continue;
    fastest = std::min(
        fastest, evaluate_trajectory(surface, ugv, *attempt.curve, final_stations).travel_time());
  }
  ASSERT_TRUE(outcome.feasible()) << outcome.trajectory.message;
  EXPECT_NEAR(outcome.trajectory.travel_time(), fastest, 1e-9 * fastest);
  EXPECT_LT(outcome.trajectory.travel_time(), outcome.initial.travel_time());
  const ProfileVerification check =
      verify_profile(*outcome.trajectory.limits, outcome.trajectory.profile);
  EXPECT_TRUE(check.passed()) << check.message;
}

TEST(PlannerFeedback, ANegativeRadiusIsAnInputError) {
  PlannerOptions options;
  options.feedback_radius = -1.0;
  EXPECT_THROW(options.validate(), InputError);
}

}  // namespace
}  // namespace talus
