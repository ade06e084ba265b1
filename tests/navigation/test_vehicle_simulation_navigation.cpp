// navigate_potential_field (potential_field_navigation.hpp): the standard
// potential-field navigation of Iagnemma et al. 2008 (§III) with the paper's
// gains drives the simulated UGV to a goal on flat ground, and around a
// hazard on the direct line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/navigation/hazard_detection.hpp"
#include "talus/navigation/navigation_lookahead.hpp"
#include "talus/navigation/potential_field_navigation.hpp"

namespace talus {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vehicle ugv() {
  return load_vehicle(std::string(TALUS_DATA_DIR) + "/vehicles/iagnemma_ugv.yaml");
}

/// Level ground 24 m x 16 m. Wide enough for the field's swerve round a hazard
/// on the direct line, which reaches 5.9 m to the side: on a 12 m wide map the
/// outer wheels passed within a centimetre of its edge, and a small change of
/// the tyre model (Dugoff to brush) took them over it.
BPatch flat() {
  return BPatch::interpolate(ElevationGrid(25, 17, 1.0, -2.0, -8.0));
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

// A goal inside the turning circle: 0.4 m to the left and 0.1 m ahead of the UGV at rest,
// near the centre of its tightest circle (radius 1 / 2.53 = 0.395 m); the arc through it
// (curvature 4.7 1/m) is tighter than its steering allows. Turning at full lock the UGV
// circled it about 0.4 m away, outside the 0.3 m goal radius, until the time limit; it now
// drives on until the goal is outside the circle and takes the arc.
TEST(PotentialFieldNavigation, AGoalInsideTheTurningCircleIsCaptured) {
  const BPatch ground = flat();
  const Vehicle vehicle = ugv();
  const Vec2 target(0.1, 0.4);
  ASSERT_GT(2.0 * target.y() / target.squaredNorm(), vehicle.max_curvature());
  PotentialFieldNavigationOptions options;
  options.max_steering = vehicle.max_steering;
  options.time_limit = 20.0;
  const PotentialFieldNavigationResult r = navigate_potential_field(
      ground, vehicle, Vec2(0, 0), 0.0, goal(target.x(), target.y(), 1.0), {}, options);
  std::cout << r.brief_report() << "\n";
  ASSERT_EQ(r.status, TrackingStatus::kReachedGoal) << r.message;
  EXPECT_LT(r.navigation_time, 10.0);
}

/// A Gaussian crest across the x axis: 0.25 m high, σ 0.7 m, at x = 9 m, so
/// its top curves at κ = 0.25 / 0.7² = 0.51 1/m and the UGV loses contact
/// above about √(g / κ) = 4.4 m/s there.
BPatch crest() {
  ElevationGrid grid(131, 41, 0.2, -2.0, -4.0);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const double x = grid.node_position(i, j).x();
      grid.at(i, j) = 0.25 * std::exp(-(x - 9.0) * (x - 9.0) / (2.0 * 0.7 * 0.7));
    }
  return BPatch::interpolate(grid);
}

// §IV's purpose: the standard field drives over the crest at the waypoint's
// 5.5 m/s and fails; with the lookahead the predicted path meets the crest's
// contact limit within the horizon, the speed is capped before the crest and
// the run reaches the goal.
TEST(PotentialFieldNavigation, TheLookaheadSlowsForACrestTheStandardFieldTakesTooFast) {
  const BPatch ground = crest();
  PotentialFieldNavigationOptions standard;
  const PotentialFieldNavigationResult fast =
      navigate_potential_field(ground, ugv(), Vec2(0, 0), 0.0, goal(20.0, 0.0, 5.5), {}, standard);
  std::cout << "standard: " << fast.brief_report() << "\n";
  EXPECT_NE(fast.status, TrackingStatus::kReachedGoal);
  EXPECT_EQ(fast.lookahead_caps_applied, 0u);
  // Without the lookahead there is no safe speed to record.
  ASSERT_EQ(fast.lookahead_safe_speeds.size(), fast.commands.size());
  for (const double v : fast.lookahead_safe_speeds) EXPECT_TRUE(std::isnan(v));

  PotentialFieldNavigationOptions near_optimal;
  near_optimal.lookahead.enabled = true;
  const PotentialFieldNavigationResult safe = navigate_potential_field(
      ground, ugv(), Vec2(0, 0), 0.0, goal(20.0, 0.0, 5.5), {}, near_optimal);
  std::cout << "lookahead: " << safe.brief_report() << "\n";
  ASSERT_EQ(safe.status, TrackingStatus::kReachedGoal) << safe.message;
  EXPECT_GT(safe.lookahead_caps_applied, 0u);
  ASSERT_EQ(safe.lookahead_caps.size(), safe.commands.size());
  ASSERT_EQ(safe.lookahead_safe_speeds.size(), safe.commands.size());
  // Every command sent is within its tick's cap, and a safe speed was recorded at every tick
  // the UGV moved; it drops below the top speed before the crest (figure 8's limit curve).
  double lowest_safe = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < safe.commands.size(); ++k) {
    EXPECT_LE(safe.commands[k].speed, safe.lookahead_caps[k]) << k;
    if (safe.command_times[k] > 0.5) {
      EXPECT_TRUE(std::isfinite(safe.lookahead_safe_speeds[k])) << k;
      lowest_safe = std::min(lowest_safe, safe.lookahead_safe_speeds[k]);
    }
  }
  EXPECT_LT(lowest_safe, 6.0);  // the UGV's top speed
  // Over the crest's top the UGV was below the contact limit √(g / κ).
  const double limit = std::sqrt(9.81 / (0.25 / (0.7 * 0.7)));
  for (const VehicleSample& k : safe.simulation.trace)
    if (std::abs(k.state.position.x() - 9.0) < 0.2) {
      EXPECT_LT(k.state.velocity.x(), limit);
    }
}

TEST(NavigationLookahead, SafeSpeedsBrakeAheadOfTheCrestsContactLimit) {
  const BPatch ground = crest();
  std::vector<Vec2> points;
  for (double x = 0.0; x <= 14.0; x += 0.5) points.emplace_back(x, 0.0);
  const std::vector<double> safe = safe_speed_profile(ground, ugv(), points);
  ASSERT_EQ(safe.size(), points.size());
  const double limit = std::sqrt(9.81 / (0.25 / (0.7 * 0.7)));
  // At the top: near the contact limit (the rigid body's own, within 15 %).
  EXPECT_NEAR(safe[18], limit, 0.15 * limit);
  // Braking ahead of it: the safe speed rises no faster than braking allows,
  // the brake's 5 m/s² plus gravity on the crest's steepest slope
  // (0.25 / 0.7 e^(-1/2) = 0.22), over steps of at most 0.5 m × 1.03 of 3-D length.
  const double decel = 5.0 + 9.81 * 0.22;
  for (std::size_t k = 1; k <= 18; ++k) {
    EXPECT_LE(safe[k - 1] * safe[k - 1], safe[k] * safe[k] + 2.0 * decel * 0.5 * 1.03 + 1e-9) << k;
  }
  // Off the map: nothing is safe.
  EXPECT_EQ(safe_speed_profile(ground, ugv(), {Vec2(0, 0), Vec2(100, 0)}).front(), 0.0);
  EXPECT_THROW(safe_speed_profile(ground, ugv(), {Vec2(0, 0)}), InputError);
}

// The reduced model's speed on a plane rising 20° to the east (tan 20° = 0.364): gravity
// along the ground is g sin 20° = 3.36 m/s² heading east, none heading north, the opposite
// heading west; the drive and brake clip before it is added, so at full drive (3 m/s²) the
// UGV loses speed up that slope, as the simulated one does (it climbs no steeper than
// asin(3 / g) = 17.8° at constant speed).
TEST(NavigationLookahead, TheReducedModelFeelsGravityAlongTheGround) {
  PlaneOptions plane;
  plane.shape = GridShape{41, 41, 0.5, 0.0, 0.0};
  plane.slope = 20.0 * kPi / 180.0;
  plane.aspect = 0.0;
  const BPatch ground = BPatch::interpolate(generate_plane(plane));
  const Vehicle vehicle = ugv();
  const double along = vehicle.gravity * std::sin(plane.slope), dt = 0.05, gain = 4.0;
  const Vec2 gradient = ground.evaluate(Vec2(10.0, 10.0)).gradient;
  const auto step = [&](double heading, double speed, double commanded) {
    return reduced_model_speed(vehicle, slope_sine_along(gradient, heading), speed, commanded, gain,
                               dt);
  };
  // Holding speed (no speed error): only gravity.
  EXPECT_NEAR(step(0.0, 2.0, 2.0), 2.0 - along * dt, 1e-9);
  EXPECT_NEAR(step(0.5 * kPi, 2.0, 2.0), 2.0, 1e-9);
  EXPECT_NEAR(step(kPi, 2.0, 2.0), 2.0 + along * dt, 1e-9);
  // Asking for far more: the drive limit, then gravity.
  const double climb = step(0.0, 2.0, 6.0);
  EXPECT_NEAR(climb, 2.0 + (vehicle.max_accel - along) * dt, 1e-9);
  EXPECT_LT(climb, 2.0);
  // Never backwards; level ground (off the surface the navigator passes 0), no gravity.
  EXPECT_EQ(step(0.0, 0.0, 0.0), 0.0);
  EXPECT_EQ(slope_sine_along(Vec2::Zero(), 1.0), 0.0);
  EXPECT_NEAR(reduced_model_speed(vehicle, 0.0, 2.0, 2.0, gain, dt), 2.0, 1e-12);
}

// A prediction turning at the UGV's steering limit (the bicycle saturated): the cubic through
// its points overshoots that curvature a little; the safe speed is the sliding limit
// sqrt(mu g / kappa) = 1.65 m/s everywhere, not 0 where the overshoot is (it was, at the
// first point, before the steering check was left out of the prediction's limits).
TEST(NavigationLookahead, APredictionAtTheSteeringLimitIsNotUntraversable) {
  const Vehicle vehicle = ugv();
  ASSERT_TRUE(std::isfinite(vehicle.max_steering));
  const double kappa = vehicle.max_curvature();
  std::vector<Vec2> points;
  Vec2 p(2.0, 0.0);
  double heading = 0.0;
  for (int k = 0; k < 20; ++k) {
    points.push_back(p);
    heading += 0.15 * kappa;
    p += 0.15 * Vec2(std::cos(heading), std::sin(heading));
  }
  const std::vector<double> safe = safe_speed_profile(flat(), vehicle, points);
  const double sliding = std::sqrt(vehicle.friction * vehicle.gravity / kappa);
  for (std::size_t k = 0; k < safe.size(); ++k) EXPECT_NEAR(safe[k], sliding, 0.05 * sliding) << k;
}

/// Flat ground at 0.2 m cells, 26 m x 24 m (past a hazard the waypoint
/// field steers along the arc through the goal, metres wide), with a 1 m x 1 m block 0.3 m high
/// centred on (6, 0): a step five times the UGV's wheel radius.
BPatch block() {
  ElevationGrid grid(131, 121, 0.2, -2.0, -12.0);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const Vec2 p = grid.node_position(i, j);
      grid.at(i, j) = std::abs(p.x() - 6.0) <= 0.5 && std::abs(p.y()) <= 0.5 ? 0.3 : 0.0;
    }
  return BPatch::interpolate(grid);
}

TEST(HazardDetection, TheBlockIsOneDiscAndFlatOrGentleGroundNone) {
  const BPatch ground = block();
  const std::vector<DiscHazard> seen = detect_hazards(ground, ugv(), Vec2(4.0, 0.0));
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_NEAR(seen[0].centre.x(), 6.0, 0.15);
  EXPECT_NEAR(seen[0].centre.y(), 0.0, 0.15);
  // It covers the block's corners (0.71 m from its centre) and not much more.
  EXPECT_GE(seen[0].radius, 0.71);
  EXPECT_LE(seen[0].radius, 1.2);
  // Out of the sensor's 3 m.
  EXPECT_TRUE(detect_hazards(ground, ugv(), Vec2(0.0, 0.0)).empty());
  EXPECT_TRUE(detect_hazards(flat(), ugv(), Vec2(0.0, 0.0)).empty());

  // Planes either side of the UGV's static limit atan(min(mu, b/h)) = atan(0.7) = 35 deg.
  const auto plane = [](double degrees) {
    ElevationGrid grid(31, 31, 0.2, 0.0, 0.0);
    for (std::size_t j = 0; j < grid.nrows(); ++j)
      for (std::size_t i = 0; i < grid.ncols(); ++i)
        grid.at(i, j) = std::tan(degrees * M_PI / 180.0) * grid.node_position(i, j).x();
    return BPatch::interpolate(grid);
  };
  // A plane's 3 x 3 relief is 2 cells of rise: 0.4 tan(30 deg) = 0.23 m; the step test is off.
  HazardDetectionOptions slope_only;
  slope_only.max_step = 10.0;
  EXPECT_TRUE(detect_hazards(plane(30.0), ugv(), Vec2(3, 3), slope_only).empty());
  EXPECT_EQ(detect_hazards(plane(40.0), ugv(), Vec2(3, 3), slope_only).size(), 1u);
  HazardDetectionOptions bad;
  bad.sensor_radius = 0.0;
  EXPECT_THROW(detect_hazards(ground, ugv(), Vec2(0, 0), bad), InputError);
}

// The whole map's node test is the sensor's: every hazard node within the
// sensor radius lies in a disc detect_hazards returns, and the block's nodes
// are hazards while flat ground has none.
TEST(HazardDetection, TheNodeMaskIsTheSensorsTestOverTheWholeMap) {
  const BPatch ground = block();
  const std::vector<unsigned char> mask = hazard_node_mask(ground, ugv());
  ASSERT_EQ(mask.size(), ground.ncols() * ground.nrows());
  const auto node = [&](std::size_t n) {
    return Vec2(ground.x_min() + static_cast<double>(n % ground.ncols()) * ground.cellsize(),
                ground.y_min() + static_cast<double>(n / ground.ncols()) * ground.cellsize());
  };
  std::size_t hazards = 0;
  const Vec2 from(4.0, 0.0);
  const std::vector<DiscHazard> seen = detect_hazards(ground, ugv(), from);
  for (std::size_t n = 0; n < mask.size(); ++n) {
    if (!mask[n]) continue;
    ++hazards;
    const Vec2 p = node(n);
    EXPECT_LE(std::abs(p.x() - 6.0), 0.5 + 0.2 + 1e-9) << p.transpose();  // the block's rim
    EXPECT_LE(std::abs(p.y()), 0.5 + 0.2 + 1e-9) << p.transpose();
    if ((p - from).norm() > 3.0) continue;
    bool covered = false;
    for (const DiscHazard& d : seen) covered = covered || (p - d.centre).norm() <= d.radius;
    EXPECT_TRUE(covered) << p.transpose();
  }
  EXPECT_GT(hazards, 0u);
  const std::vector<unsigned char> none = hazard_node_mask(flat(), ugv());
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);
}

// The block lies on the direct line; no hazard is given, the sensor finds it.
TEST(PotentialFieldNavigation, AvoidsAHazardItDetectsOnTheMap) {
  const BPatch ground = block();
  PotentialFieldNavigationOptions options;
  options.hazards_from_map = true;
  const PotentialFieldNavigationResult r =
      navigate_potential_field(ground, ugv(), Vec2(0, 0), 0.0, goal(14.0, 0.0, 2.0), {}, options);
  std::cout << r.brief_report() << "\n";
  ASSERT_EQ(r.status, TrackingStatus::kReachedGoal) << r.message;
  // The c.g. never crossed the block (its half-diagonal is 0.71 m).
  for (const VehicleSample& k : r.simulation.trace) {
    const Vec2 cg(k.state.position.x(), k.state.position.y());
    EXPECT_FALSE(std::abs(cg.x() - 6.0) <= 0.5 && std::abs(cg.y()) <= 0.5) << cg.transpose();
  }
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
