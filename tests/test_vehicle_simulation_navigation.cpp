// navigate_potential_field (potential_field_navigation.hpp): the standard
// potential-field navigation of Iagnemma et al. 2008 (§III) with the paper's
// gains drives the simulated UGV to a goal on flat ground, and around a
// hazard on the direct line.
#include <gtest/gtest.h>

#include <iostream>
#include <string>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/potential_field_navigation.hpp"

namespace talus {
namespace {

Vehicle ugv() {
  return load_vehicle(std::string(TALUS_DATA_DIR) + "/vehicles/iagnemma_ugv.yaml");
}

BPatch flat() {
  return BPatch::interpolate(ElevationGrid(25, 13, 1.0, -2.0, -6.0));
}

ReferenceTrajectory goal(double x, double y, double speed) {
  ReferenceTrajectory w;
  w.points = {Vec2(x, y)};
  w.speed = {speed};
  return w;
}

TEST(PotentialFieldNavigation, AStraightRunOnFlatGroundReachesTheGoal) {
  const BPatch ground = flat();
  const PotentialFieldNavigationResult r =
      navigate_potential_field(ground, ugv(), Vec2(0, 0), 0.0, goal(15.0, 0.0, 3.0), {});
  std::cout << r.brief_report() << "\n";
  ASSERT_EQ(r.status, TrackingStatus::kReachedGoal) << r.message;
  // At about 3 m/s after a short acceleration.
  EXPECT_LT(r.navigation_time, 15.0 / 3.0 + 2.0);
  EXPECT_GT(r.navigation_time, 15.0 / 3.0);
  for (const VehicleSample& k : r.simulation.trace) EXPECT_LT(std::abs(k.state.position.y()), 0.05);
}

TEST(PotentialFieldNavigation, AvoidsAHazardOnTheDirectLine) {
  const BPatch ground = flat();
  const std::vector<DiscHazard> hazards = {{Vec2(7.0, 0.05), 0.5}};
  const PotentialFieldNavigationResult r =
      navigate_potential_field(ground, ugv(), Vec2(0, 0), 0.0, goal(15.0, 0.0, 2.0), hazards);
  std::cout << r.brief_report() << "\n";
  ASSERT_EQ(r.status, TrackingStatus::kReachedGoal) << r.message;
  EXPECT_GT(r.min_hazard_clearance, 0.0);
  // Seeded: the same run twice.
  const PotentialFieldNavigationResult again =
      navigate_potential_field(ground, ugv(), Vec2(0, 0), 0.0, goal(15.0, 0.0, 2.0), hazards);
  EXPECT_EQ(again.navigation_time, r.navigation_time);
  EXPECT_EQ(again.simulation.final.state.position, r.simulation.final.state.position);
}

TEST(PotentialFieldNavigation, BadInputIsAnInputError) {
  const BPatch ground = flat();
  ReferenceTrajectory none;
  EXPECT_THROW(navigate_potential_field(ground, ugv(), Vec2(0, 0), 0.0, none, {}), InputError);
  EXPECT_THROW(
      navigate_potential_field(ground, ugv(), Vec2(0, 0), 0.0, goal(5, 0, 1), {{Vec2(3, 0), -1.0}}),
      InputError);
}

}  // namespace
}  // namespace talus
