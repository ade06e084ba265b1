// The planner's feedback from the local stage to the global one
// (PlannerOptions::feedback_rounds) on real ground: an 80 x 80-cell window of
// the bundled Big Tujunga DEM (SRTM, 30 m cells) where the lattice's three
// best corridors climb switchbacks that no continuous profile of the rover
// drives (the hairpins are sharp turns on steep side slopes; the lattice
// judges each straight edge alone and cannot see them). Without feedback the
// plan is infeasible; with it the failing stretches are excluded and the
// plan ends feasible, which verify_profile and a fresh evaluation at other
// stations confirm independently.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/grid_window.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/trajectory.hpp"
#include "talus/optimal/verify_profile.hpp"

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

PlannerOptions quick_options(std::size_t feedback_rounds) {
  PlannerOptions options;
  options.feedback_rounds = feedback_rounds;
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

TEST(PlannerFeedback, ANegativeRadiusIsAnInputError) {
  PlannerOptions options;
  options.feedback_radius = -1.0;
  EXPECT_THROW(options.validate(), InputError);
}

}  // namespace
}  // namespace talus
