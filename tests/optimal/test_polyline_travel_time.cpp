// talus/optimal/polyline_travel_time.hpp: rest-to-rest time along a polyline,
// against the closed form on flat ground.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "talus/optimal/polyline_travel_time.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

const BPatch& flat_ground() {
  static const BPatch patch = BPatch::interpolate(
      terrain_test::grid_around_origin([](double, double) { return 0.0; }, 40.0, 1.0));
  return patch;
}

TEST(PolylineTravelTime, StraightFlatLineIsTheBangBangTime) {
  Vehicle v = vehicle_test::point_mass_rover();  // 10 m/s
  v.max_accel = 1.0;
  v.max_decel = 1.0;
  // 40 m: accelerate over 20 m, brake over 20 m (the top speed, sqrt(40) m/s,
  // stays below 10 m/s and friction allows 6.9 m/s²): t = 2 sqrt(L / a).
  const std::vector<Vec2> line{Vec2(-20, 0), Vec2(-5, 0), Vec2(20, 0)};
  TimeOptimalProfileSolver solver;
  const double t = polyline_travel_time(flat_ground(), v, line, {}, &solver);
  EXPECT_NEAR(t, 2.0 * std::sqrt(40.0), 1e-6 * t);
  // Long enough to reach the top speed: L / v + v / a.
  const std::vector<Vec2> long_line{Vec2(-35, -30), Vec2(35, 30)};
  const double length = std::hypot(70.0, 60.0);
  v.max_speed = 4.0;
  EXPECT_NEAR(polyline_travel_time(flat_ground(), v, long_line), length / 4.0 + 4.0, 1e-6 * length);
}

TEST(PolylineTravelTime, DegenerateAndInfeasiblePolylines) {
  const Vehicle v = vehicle_test::point_mass_rover();
  EXPECT_EQ(polyline_travel_time(flat_ground(), v, {Vec2(1, 1)}), 0.0);
  EXPECT_EQ(polyline_travel_time(flat_ground(), v, {Vec2(1, 1), Vec2(1, 1 + 1e-7)}), 0.0);
  // Off the terrain: no profile.
  EXPECT_TRUE(std::isinf(polyline_travel_time(flat_ground(), v, {Vec2(0, 0), Vec2(60, 0)})));
}

}  // namespace
}  // namespace talus
