// check_closed_loop (closed_loop_check.hpp): a planned trajectory driven by
// the rigid-body simulation at several multiples of its profile speed.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/closed_loop_check.hpp"
#include "talus/optimal/trajectory.hpp"

namespace talus {
namespace {

Vehicle ugv() {
  return load_vehicle(std::string(TALUS_DATA_DIR) + "/vehicles/iagnemma_ugv.yaml");
}

/// A gentle S-curve over 10 m of flat ground, rest to rest.
Trajectory s_curve(const BPatch& ground, const Vehicle& vehicle) {
  std::vector<Curve2::Point> points;
  for (int i = 0; i <= 10; ++i) points.emplace_back(1.0 + i, 6.0 + 1.0 * std::sin(0.6 * i));
  return evaluate_trajectory(ground, vehicle, Curve2::interpolate(points), TrajectoryOptions{});
}

TEST(ClosedLoopCheck, TheReferenceIsTheTrajectorysStationsAndSpeeds) {
  const BPatch ground = BPatch::interpolate(ElevationGrid(13, 13, 1.0, 0.0, 0.0));
  const Trajectory t = s_curve(ground, ugv());
  ASSERT_TRUE(t.feasible()) << t.message;
  const ReferenceTrajectory r = reference_trajectory(t);
  ASSERT_EQ(r.points.size(), t.limits->size());  // no two stations share a point here
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    EXPECT_EQ(r.points[k].x(), t.limits->frame(k).point.x());
    EXPECT_EQ(r.points[k].y(), t.limits->frame(k).point.y());
    EXPECT_EQ(r.speed[k], t.profile.v[k]);
  }
  EXPECT_NO_THROW(r.validate());
}

TEST(ClosedLoopCheck, DrivesEveryScaleAndSlowerIsNoLessSafe) {
  const BPatch ground = BPatch::interpolate(ElevationGrid(13, 13, 1.0, 0.0, 0.0));
  const Vehicle vehicle = ugv();
  const Trajectory t = s_curve(ground, vehicle);
  ASSERT_TRUE(t.feasible()) << t.message;
  ClosedLoopOptions options;
  options.speed_scales = {0.5, 1.0};
  const ClosedLoopResult r = check_closed_loop(ground, vehicle, t, options);
  std::cout << r.brief_report() << "\n";
  ASSERT_EQ(r.drives.size(), 2u);
  EXPECT_EQ(r.drives[0].speed_scale, 0.5);
  EXPECT_EQ(r.drives[1].speed_scale, 1.0);
  // Half the profile speed on flat ground: far inside every limit, the goal is reached.
  EXPECT_TRUE(r.drives[0].reached()) << r.drives[0].result.message;
  // The planned time at half speed is at most twice that at full speed (same polyline; the
  // tracker's min_speed floor near rest shortens the slower one) and longer than it.
  const double slow = r.drives[0].result.planned_time, fast = r.drives[1].result.planned_time;
  EXPECT_GT(slow, 1.5 * fast);
  EXPECT_LE(slow, 2.0 * fast * (1.0 + 1e-12));
  // Driving slower loads the outer wheels less.
  EXPECT_LE(r.drives[0].result.simulation.diagnostics.peak_lateral_load_ratio,
            r.drives[1].result.simulation.diagnostics.peak_lateral_load_ratio);
  EXPECT_EQ(r.reached(), static_cast<std::size_t>(r.drives[0].reached() + r.drives[1].reached()));
}

TEST(ClosedLoopCheck, BadInputIsAnInputError) {
  const BPatch ground = BPatch::interpolate(ElevationGrid(13, 13, 1.0, 0.0, 0.0));
  const Vehicle vehicle = ugv();
  const Trajectory t = s_curve(ground, vehicle);
  ClosedLoopOptions none;
  none.speed_scales.clear();
  EXPECT_THROW(check_closed_loop(ground, vehicle, t, none), InputError);
  ClosedLoopOptions negative;
  negative.speed_scales = {1.0, -0.5};
  EXPECT_THROW(check_closed_loop(ground, vehicle, t, negative), InputError);
  EXPECT_THROW(reference_trajectory(Trajectory{}), InputError);  // no profile
  Vehicle bodiless = vehicle;
  bodiless.body.reset();
  EXPECT_THROW(check_closed_loop(ground, bodiless, t), InputError);
}

}  // namespace
}  // namespace talus
