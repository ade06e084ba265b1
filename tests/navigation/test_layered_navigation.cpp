// navigate_layered (layered_navigation.hpp): the high-level plan on the
// decimated map, its waypoints, and the potential-field navigation of the
// simulated UGV on the fine terrain.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/navigation/layered_navigation.hpp"

namespace talus {
namespace {

Vehicle ugv() {
  return load_vehicle(std::string(TALUS_DATA_DIR) + "/vehicles/iagnemma_ugv.yaml");
}

/// 24 m x 9.6 m at 0.24 m cells (two wheel diameters), a gentle 0.3 m swell.
ElevationGrid ground() {
  ElevationGrid grid(101, 41, 0.24, 0.0, 0.0);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const Vec2 p = grid.node_position(i, j);
      grid.at(i, j) = 0.3 * std::sin(p.x() / 4.0) * std::cos(p.y() / 5.0);
    }
  return grid;
}

TEST(LayeredNavigation, PlansOnTheCoarseMapAndDrivesThroughItsWaypointsToTheGoal) {
  const ElevationGrid fine = ground();
  const Vec2 start(1.0, 4.8), goal(21.0, 4.8);
  // The UGV as its file describes it (brush tyres, steering limit, rigid body). Before the
  // navigator captured the goal it needed Dugoff tyres, no steering limit on the plan and the
  // point mass here: with any of those three the UGV passed the goal 0.85 m to the side and
  // orbited it for 20 s or until the time limit.
  const LayeredNavigationOptions options;
  const Vehicle vehicle = ugv();
  const LayeredNavigationResult r = navigate_layered(fine, vehicle, start, goal, options);
  std::cout << r.brief_report();
  ASSERT_EQ(r.status, LayeredNavigationStatus::kReachedGoal) << r.message;
  EXPECT_EQ(r.plan_status, PlannerStatus::kOk);
  ASSERT_TRUE(r.navigation.has_value());
  // Waypoints about four coarse cells (3.84 m) apart, the last the goal.
  ASSERT_GE(r.waypoints.points.size(), 4u);
  EXPECT_LT((r.waypoints.points.back() - goal).norm(), 1e-9);
  EXPECT_GT(r.waypoints.speed.back(), 0.0);
  // The optimal time is at least the straight line at the top speed, and the
  // navigation (which passes the goal at speed) is within a factor of it.
  EXPECT_GT(r.optimal_time, 20.0 / ugv().max_speed);
  EXPECT_GT(r.time_increase(), -0.3);
  EXPECT_LT(r.time_increase(), 1.0);
  const Vec3 end = r.navigation->simulation.final.state.position;
  EXPECT_LT((Vec2(end.x(), end.y()) - goal).norm(), 0.5);
}

TEST(LayeredNavigation, BadInputIsAnInputError) {
  const ElevationGrid fine = ground();
  Vehicle no_body = ugv();
  no_body.body.reset();
  EXPECT_THROW(navigate_layered(fine, no_body, {1, 4.8}, {21, 4.8}), InputError);
  LayeredNavigationOptions options;
  options.coarse_factor = 0;
  EXPECT_THROW(navigate_layered(fine, ugv(), {1, 4.8}, {21, 4.8}, options), InputError);
  options.coarse_factor = 50;  // 41 rows: one node left
  EXPECT_THROW(navigate_layered(fine, ugv(), {1, 4.8}, {21, 4.8}, options), InputError);
  EXPECT_EQ(to_string(LayeredNavigationStatus::kNoPlan), "no_plan");
}

}  // namespace
}  // namespace talus
