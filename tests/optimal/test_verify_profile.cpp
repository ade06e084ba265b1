#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/optimal/trajectory.hpp"
#include "talus/optimal/verify_profile.hpp"
#include "talus/scenarios/fractal_battery.hpp"

namespace talus {
namespace {

Vehicle rover(VehicleModel model, bool limited) {
  Vehicle v;
  v.model = model;
  v.friction = 0.8;
  v.cg_height = 0.5;
  v.half_track = 0.35;
  v.half_wheelbase = 0.3;  // l/h = 0.6 < mu: pitch-over binds
  if (limited) {
    v.max_speed = 12.0;
    v.max_accel = 3.0;
    v.max_decel = 6.0;
  }
  return v;
}

/// Random 5-point splines over random fractal terrains (seeded), every
/// vehicle model: the solver's profiles verify; corrupted copies do not.
TEST(VerifyProfile, SolverProfilesVerifyOnRandomTerrainsForEveryModel) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> coordinate(12.0, 52.0);  // splines overshoot their points
  int verified = 0, corrupted = 0;
  for (const unsigned seed : {3u, 8u}) {
    FractalTerrainOptions terrain;
    terrain.shape = {129, 129, 0.5, 0.0, 0.0};
    terrain.height_scale = 5.0 + seed;
    terrain.seed = seed;
    const BPatch patch = BPatch::fit_smoothing(generate_fractal_terrain(terrain), 1.0);
    for (const VehicleModel model : kVehicleModels) {
      for (const bool limited : {false, true}) {
        const Vehicle v = rover(model, limited);
        TimeOptimalProfileSolver solver;
        for (int trial = 0; trial < 4; ++trial) {
          std::vector<Vec2> points;
          for (int k = 0; k < 5; ++k) points.emplace_back(coordinate(rng), coordinate(rng));
          std::unique_ptr<SurfacePath> path;
          try {
            path = std::make_unique<SurfacePath>(patch, Curve2::interpolate(points));
          } catch (const InputError&) {
            continue;  // a random spline may overshoot the map: not this test's subject
          }
          const VelocityLimits limits(v, *path, 300);
          // Rest to rest is an input error where an end station needs a minimum speed (a steep
          // side slope the vehicle tips on at rest): not this test's subject either.
          if (limits.limits(0).v_min > 0.0 || limits.limits(limits.size() - 1).v_min > 0.0)
            continue;
          const TimeOptimalProfile p = solver.solve(limits, {});
          if (p.status != ProfileStatus::kOk) continue;
          const ProfileVerification check = verify_profile(limits, p);
          EXPECT_TRUE(check.passed()) << check.message;
          EXPECT_EQ(check.speed_violations + check.inadmissible_states +
                        check.acceleration_violations + check.inconsistencies,
                    0u);
          ++verified;

          // One speed raised above v_max (at an interior station with a finite limit).
          std::uniform_int_distribution<std::size_t> station(1, p.v.size() - 2);
          std::size_t k = station(rng);
          while (!std::isfinite(p.v_max[k]) && k + 2 < p.v.size()) ++k;
          if (std::isfinite(p.v_max[k])) {
            TimeOptimalProfile fast = p;
            fast.v[k] = 1.01 * limits.limits(k).v_max + 1e-3;
            const ProfileVerification bad = verify_profile(limits, fast);
            EXPECT_EQ(bad.status, VerificationStatus::kSpeedAboveLimit) << bad.message;
            EXPECT_EQ(bad.speed_violations, 1u);
            EXPECT_EQ(bad.worst_speed.station, k);
            ++corrupted;
          }
          // One arrival time shifted by a millisecond.
          TimeOptimalProfile late = p;
          late.t[k] += 1e-3;
          const ProfileVerification shifted = verify_profile(limits, late);
          EXPECT_EQ(shifted.status, VerificationStatus::kInconsistent) << shifted.message;
          EXPECT_EQ(shifted.worst_time.station, k);
          EXPECT_NEAR(shifted.worst_time.amount, 1e-3, 1e-9);
          // One step's acceleration pushed up by 0.5 m/s²: out of bounds
          // wherever the step was already at its upper bound, inconsistent
          // with the speeds everywhere.
          TimeOptimalProfile pushed = p;
          pushed.a[k] += 0.5;
          EXPECT_FALSE(verify_profile(limits, pushed).passed());
        }
      }
    }
  }
  EXPECT_GE(verified, 16);
  EXPECT_GE(corrupted, 16);
}

TEST(VerifyProfile, AStepBeyondTheBrakeLimitIsOutOfBounds) {
  FractalTerrainOptions terrain;
  terrain.shape = {65, 65, 1.0, 0.0, 0.0};
  terrain.height_scale = 0.0;  // flat
  const BPatch flat = BPatch::fit_smoothing(generate_fractal_terrain(terrain), 1.0);
  const SurfacePath path(flat, Curve2::interpolate({Vec2(10, 10), Vec2(40, 12), Vec2(50, 40)}));
  const VelocityLimits limits(rover(VehicleModel::kPointMass, true), path, 200);
  TimeOptimalProfileSolver solver;
  const TimeOptimalProfile p = solver.solve(limits, {});
  ASSERT_EQ(p.status, ProfileStatus::kOk) << p.message;
  ASSERT_TRUE(verify_profile(limits, p).passed());
  // Stop dead at the last station from the speed one station before: the
  // implied deceleration is far beyond the 6 m/s² brake.
  TimeOptimalProfile abrupt = p;
  const std::size_t n = p.v.size();
  abrupt.v[n - 2] = 5.0;
  abrupt.a[n - 3] = (5.0 * 5.0 - p.v[n - 3] * p.v[n - 3]) / (2.0 * (p.s[n - 2] - p.s[n - 3]));
  abrupt.a[n - 2] = -5.0 * 5.0 / (2.0 * (p.s[n - 1] - p.s[n - 2]));
  double t = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    t += 2.0 * (p.s[k + 1] - p.s[k]) / (abrupt.v[k] + abrupt.v[k + 1]);
    abrupt.t[k + 1] = t;
  }
  abrupt.travel_time = t;
  const ProfileVerification check = verify_profile(limits, abrupt);
  EXPECT_EQ(check.status, VerificationStatus::kAccelerationOutOfBounds) << check.message;
  EXPECT_EQ(check.inconsistencies, 0u) << check.message;
  EXPECT_GT(check.worst_acceleration.amount, 1.0);
}

/// Regression (issue #12, fractal battery seed 17): the planner's best path
/// there crosses a crest 6e-8 m/s under its sliding limit, with the normal
/// force down to 1.7e-3 m/s² per unit mass, where the s̈ interval is only
/// 4e-5 m/s² wide. The step into it brakes 3.7e-6 m/s² harder than that
/// interval allows, yet the contact force it needs lies 7.5e-8 m/s² (8e-9 g)
/// outside the friction cone: the profile solver's rounding slack, not
/// physics. So the profile verifies, because the check measures force; the
/// s̈ interval alone would have rejected it.
TEST(VerifyProfile, AStepIntoTheTipOfASlidingLimitIsMeasuredInForce) {
  const BPatch surface =
      BPatch::interpolate(generate_fractal_terrain(scenarios::battery_terrain(17)));
  const Vehicle ugv = scenarios::battery_point_mass_ugv();
  std::vector<double> breakpoints;
  for (int i = 0; i <= 13; ++i) breakpoints.push_back(i / 13.0);
  const std::vector<Vec2> control_points{{2, 2},
                                         {3.0023287958242832, 3.5044981524071441},
                                         {4.0568860105771023, 5.8322770173892264},
                                         {4.2166606898568766, 9.8873878275293983},
                                         {3.4454650762701351, 13.194868919906376},
                                         {3.0463473531246503, 15.521727345295393},
                                         {5.6640676739620064, 16.763795159583676},
                                         {8.2745287658824385, 18.080839531279899},
                                         {12.17485027262285, 19.329795549995957},
                                         {14.720330256884802, 21.352043573554472},
                                         {16.660159494320727, 23.009071172684536},
                                         {19.823314453319679, 24.758165567027568},
                                         {22.612507372017397, 26.228434007279599},
                                         {24.681864617558784, 27.485490438474905},
                                         {26.691394061354561, 27.879895533942801},
                                         {28.5, 28.5}};
  const Curve2 curve(KnotVector::clamped(3, breakpoints), control_points);
  TrajectoryOptions options;
  options.station_spacing = 0.024;
  const Trajectory trajectory = evaluate_trajectory(surface, ugv, curve, options);
  const TimeOptimalProfile& p = trajectory.profile;
  ASSERT_EQ(p.status, ProfileStatus::kOk) << p.message;
  const ProfileVerification check = verify_profile(*trajectory.limits, p);
  EXPECT_TRUE(check.passed()) << check.message;
  EXPECT_LT(check.worst_acceleration.amount, 1e-7) << check.message;
  // The tip: some step end's s̈ is outside its interval by more than the
  // tolerance (so this path does exercise the ill-conditioned case).
  const VelocityLimits& limits = *trajectory.limits;
  double worst_interval_distance = 0.0;
  for (std::size_t k = 1; k < limits.size(); ++k) {
    const AccelerationBounds b =
        limits.admissible_set().acceleration_bounds(limits.geometry(k), p.v[k]);
    if (!b.feasible) continue;
    const double a = p.a[k - 1];
    worst_interval_distance = std::max({worst_interval_distance, b.a_min - a, a - b.a_max});
  }
  EXPECT_GT(worst_interval_distance, 1e-6);
}

TEST(VerifyProfile, InvalidInputThrowsAndNoProfileIsAStatus) {
  FractalTerrainOptions terrain;
  terrain.shape = {65, 65, 1.0, 0.0, 0.0};
  terrain.height_scale = 0.0;
  const BPatch flat = BPatch::fit_smoothing(generate_fractal_terrain(terrain), 1.0);
  const SurfacePath path(flat, Curve2::interpolate({Vec2(10, 10), Vec2(40, 12)}));
  const VelocityLimits limits(rover(VehicleModel::kRigidBody, true), path, 50);
  TimeOptimalProfileSolver solver;
  TimeOptimalProfile p = solver.solve(limits, {});
  ASSERT_EQ(p.status, ProfileStatus::kOk);
  ProfileVerificationOptions options;
  options.acceleration_tolerance = -1.0;
  EXPECT_THROW(verify_profile(limits, p, options), InputError);
  TimeOptimalProfile short_profile = p;
  short_profile.v.pop_back();
  EXPECT_THROW(verify_profile(limits, short_profile), InputError);
  p.status = ProfileStatus::kInfeasible;
  const ProfileVerification none = verify_profile(limits, p);
  EXPECT_EQ(none.status, VerificationStatus::kNoProfile);
  EXPECT_FALSE(none.passed());
  EXPECT_EQ(to_string(VerificationStatus::kAccelerationOutOfBounds), "acceleration_out_of_bounds");
  EXPECT_EQ(to_string(VerificationStatus::kPass), "pass");
}

}  // namespace
}  // namespace talus
