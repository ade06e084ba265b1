// check_closed_loop (closed_loop_check.hpp): a planned trajectory driven by
// the rigid-body simulation at several multiples of its profile speed.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
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

/// A hairpin on flat ground: an 8 m straight, then half a circle of radius 1.5 m (planned at
/// its friction limit, sqrt(mu g r) = 3.2 m/s for the UGV) and back, rest to rest.
Trajectory hairpin(const BPatch& ground, const Vehicle& vehicle) {
  std::vector<Curve2::Point> points;
  for (int i = 0; i <= 8; ++i) points.emplace_back(2.0 + i, 6.0);
  for (int i = 1; i < 12; ++i) {
    const double a = -M_PI / 2 + M_PI * i / 12.0;
    points.emplace_back(10.0 + 1.5 * std::cos(a), 7.5 + 1.5 * std::sin(a));
  }
  for (int i = 0; i <= 4; ++i) points.emplace_back(10.0 - i, 9.0);
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

TEST(ClosedLoopCheck, TheSpeedScaleLimitIsBracketedByAReachingAndAFailingDrive) {
  const BPatch ground = BPatch::interpolate(ElevationGrid(13, 13, 1.0, 0.0, 0.0));
  const Vehicle vehicle = ugv();
  const Trajectory t = hairpin(ground, vehicle);
  ASSERT_TRUE(t.feasible()) << t.message;
  SpeedScaleLimitOptions options;
  options.lowest = 0.5;
  options.highest = 4.0;  // far above the plan's friction limit: the hairpin must fail there
  options.tolerance = 0.05;
  const SpeedScaleLimit limit = find_speed_scale_limit(ground, vehicle, t, options);
  std::cout << limit.brief_report() << "\n";
  ASSERT_EQ(limit.status, SpeedScaleLimitStatus::kBracketed);
  EXPECT_LE(limit.smallest_failing_scale - limit.largest_reaching_scale, options.tolerance);
  EXPECT_GT(limit.smallest_failing_scale, limit.largest_reaching_scale);
  ASSERT_NE(limit.largest_reaching_drive(), nullptr);
  ASSERT_NE(limit.bounding_failure(), nullptr);
  EXPECT_TRUE(limit.largest_reaching_drive()->reached());
  EXPECT_FALSE(limit.bounding_failure()->reached());
  // Bisection from the midpoint: ceil(log2(3.5 / 0.05)) = 7 drives, the ends never driven.
  EXPECT_EQ(limit.drives.size(), 7u);
  EXPECT_EQ(limit.drives.front().speed_scale, 0.5 * (options.lowest + options.highest));
  // Every probe agrees with the bracket: reached at or below s*, failed at or above the failure.
  for (const ClosedLoopDrive& d : limit.drives) {
    if (d.speed_scale <= limit.largest_reaching_scale) {
      EXPECT_TRUE(d.reached()) << d.speed_scale;
    }
    if (d.speed_scale >= limit.smallest_failing_scale) {
      EXPECT_FALSE(d.reached()) << d.speed_scale;
    }
  }
}

/// 20 m straight on flat ground with the UGV's top speed lowered to 2 m/s: the plan cruises at
/// its top speed, so no scale above 1 can be driven faster, and nothing slides or lifts.
TEST(ClosedLoopCheck, AVehicleThatCannotKeepTheScaledScheduleBoundsTheSpeedScale) {
  const BPatch ground = BPatch::interpolate(ElevationGrid(25, 13, 1.0, 0.0, 0.0));
  Vehicle vehicle = ugv();
  vehicle.max_speed = 2.0;
  std::vector<Curve2::Point> points;
  for (int i = 0; i <= 20; ++i) points.emplace_back(2.0 + i, 6.0);
  const Trajectory t =
      evaluate_trajectory(ground, vehicle, Curve2::interpolate(points), TrajectoryOptions{});
  ASSERT_TRUE(t.feasible()) << t.message;

  // Reaching alone: every scale up to 2 reaches the goal, at the top speed, about half as fast
  // as the schedule at 2 asks (the tracker never asks for more than the top speed; without that
  // the UGV's 3 m/s^2 drive would keep the 4 m/s cruise within ~20 %).
  SpeedScaleLimitOptions reaching;
  reaching.highest = 2.0;
  reaching.tolerance = 0.1;
  reaching.schedule_tolerance = std::numeric_limits<double>::infinity();
  const SpeedScaleLimit lenient = find_speed_scale_limit(ground, vehicle, t, reaching);
  ASSERT_EQ(lenient.status, SpeedScaleLimitStatus::kReachesHighest) << lenient.brief_report();
  EXPECT_EQ(lenient.bounding_reason(), "");
  EXPECT_GT(lenient.largest_reaching_drive()->schedule_ratio(), 1.7);

  // On schedule (10 %): the ratio grows like the scale over the cruise, so s* is just above 1
  // and bounded by the schedule, not by a failure event.
  SpeedScaleLimitOptions on_schedule = reaching;
  on_schedule.schedule_tolerance = 0.1;
  on_schedule.tolerance = 0.02;
  const SpeedScaleLimit tight = find_speed_scale_limit(ground, vehicle, t, on_schedule);
  std::cout << tight.brief_report() << "\n";
  ASSERT_EQ(tight.status, SpeedScaleLimitStatus::kBracketed);
  EXPECT_GE(tight.largest_reaching_scale, 1.0);
  EXPECT_LE(tight.smallest_failing_scale, 1.2);
  EXPECT_EQ(tight.bounding_reason(), "behind_schedule");
  ASSERT_NE(tight.bounding_failure(), nullptr);
  EXPECT_TRUE(tight.bounding_failure()->reached());
  EXPECT_FALSE(tight.bounding_failure()->kept_schedule(0.1));
  EXPECT_TRUE(tight.largest_reaching_drive()->kept_schedule(0.1));

  on_schedule.schedule_tolerance = -0.1;
  EXPECT_THROW(find_speed_scale_limit(ground, vehicle, t, on_schedule), InputError);
}

TEST(ClosedLoopCheck, TheSpeedScaleLimitSaysWhenTheBracketIsTooLowOrTooHigh) {
  const BPatch ground = BPatch::interpolate(ElevationGrid(13, 13, 1.0, 0.0, 0.0));
  const Vehicle vehicle = ugv();
  const Trajectory t = hairpin(ground, vehicle);
  ASSERT_TRUE(t.feasible()) << t.message;
  SpeedScaleLimitOptions slow;  // far inside every limit: the highest end is driven and reached
  slow.lowest = 0.3;
  slow.highest = 0.5;
  slow.tolerance = 0.1;
  const SpeedScaleLimit reaches = find_speed_scale_limit(ground, vehicle, t, slow);
  EXPECT_EQ(reaches.status, SpeedScaleLimitStatus::kReachesHighest) << reaches.brief_report();
  EXPECT_EQ(reaches.largest_reaching_scale, 0.5);
  EXPECT_EQ(reaches.bounding_failure(), nullptr);
  ASSERT_NE(reaches.largest_reaching_drive(), nullptr);
  EXPECT_TRUE(reaches.largest_reaching_drive()->reached());

  SpeedScaleLimitOptions
      fast;  // 2.5 times the hairpin's friction limit speed: the lowest end fails
  fast.lowest = 2.5;
  fast.highest = 3.0;
  fast.tolerance = 0.5;
  const SpeedScaleLimit fails = find_speed_scale_limit(ground, vehicle, t, fast);
  EXPECT_EQ(fails.status, SpeedScaleLimitStatus::kFailsLowest) << fails.brief_report();
  EXPECT_TRUE(std::isnan(fails.largest_reaching_scale));
  EXPECT_EQ(fails.smallest_failing_scale, 2.5);
  ASSERT_NE(fails.bounding_failure(), nullptr);
  EXPECT_FALSE(fails.bounding_failure()->reached());
  EXPECT_EQ(fails.largest_reaching_drive(), nullptr);

  SpeedScaleLimitOptions bad;
  bad.lowest = 1.0;
  bad.highest = 1.0;
  EXPECT_THROW(find_speed_scale_limit(ground, vehicle, t, bad), InputError);
  bad.highest = 2.0;
  bad.tolerance = 0.0;
  EXPECT_THROW(find_speed_scale_limit(ground, vehicle, t, bad), InputError);
}

}  // namespace
}  // namespace talus
