// analyze_profile, classify_steps, switching_points, limiting_lengths and
// describe_infeasibility on profiles with closed-form switching positions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/optimal/profile_analysis.hpp"
#include "talus/optimal/time_optimal_profile.hpp"
#include "talus/optimal/verify_profile.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_from_function;

constexpr double kG = 9.81;

/// Flat ground z = 0 over [0, 30] x [-5, 5].
BPatch flat_ground() {
  return BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, -5, 30, 5, 1.0));
}

/// A point mass on flat, straight ground: drive `accel`, brake `decel` and
/// top speed `top`, all well inside friction (μ g = 8.83 m/s²), so the
/// profile from rest to rest is a trapezoid.
Vehicle trapezoid_vehicle(double accel, double decel, double top) {
  Vehicle v;
  v.friction = 0.9;
  v.cg_height = 0.3;
  v.half_track = 1.0;  // b/h > μ: tip-over never binds
  v.max_accel = accel;
  v.max_decel = decel;
  v.max_speed = top;
  return v;
}

struct Solved {
  std::unique_ptr<SurfacePath> path;
  std::unique_ptr<VelocityLimits> limits;
  TimeOptimalProfile profile;
};

Solved solve_straight(const BPatch& ground, const Vehicle& vehicle, double length,
                      std::size_t stations) {
  Solved r;
  r.path = std::make_unique<SurfacePath>(ground, Curve2::interpolate({{5, 0}, {5 + length, 0}}));
  r.limits = std::make_unique<VelocityLimits>(vehicle, *r.path, stations);
  TimeOptimalProfileSolver solver;
  r.profile = solver.solve(*r.limits, ProfileOptions{});
  return r;
}

// Drive 2 m/s², brake 4 m/s², top speed 4 m/s over 20 m: accelerate to
// s1 = v²/(2A) = 4 m, cruise on the limit to s2 = L − v²/(2D) = 18 m, brake.
// The stations are 0.15 m apart, so each switch falls strictly inside a step.
TEST(ProfileAnalysis, TrapezoidSwitchesAtTheAnalyticPositions) {
  const double A = 2.0, D = 4.0, V = 4.0, L = 20.0;
  const double s1 = V * V / (2 * A), s2 = L - V * V / (2 * D);
  const std::size_t n = 134;  // h = 20 / 133 = 0.150 m
  const BPatch ground = flat_ground();
  const Solved solved = solve_straight(ground, trapezoid_vehicle(A, D, V), L, n);
  ASSERT_EQ(solved.profile.status, ProfileStatus::kOk) << solved.profile.message;
  const TimeOptimalProfile& p = solved.profile;
  const ProfileAnalysis a = analyze_profile(*solved.limits, p);
  const double h = L / static_cast<double>(n - 1);
  ASSERT_NEAR(p.s.back(), L, 1e-9);

  ASSERT_EQ(a.bounds.size(), n);
  ASSERT_EQ(a.steps.size(), n - 1);
  // The analytic switching steps: the steps that contain s1 and s2.
  const auto k1 = static_cast<std::size_t>(std::floor(s1 / h));
  const auto k2 = static_cast<std::size_t>(std::floor(s2 / h));
  ASSERT_LT(p.s[k1], s1);
  ASSERT_GT(p.s[k1 + 1], s1);
  ASSERT_LT(p.s[k2], s2);
  ASSERT_GT(p.s[k2 + 1], s2);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const StepClass& step = a.steps[k];
    if (k < k1) {
      EXPECT_EQ(step.kind, ControlKind::kAccelerate) << "step " << k;
      EXPECT_EQ(step.binding, Constraint::kDrive) << "step " << k;
    } else if (k == k1 || k == k2) {
      // The switch within the step: s̈ strictly between the bounds.
      EXPECT_EQ(step.kind, ControlKind::kLimit) << "step " << k;
      EXPECT_TRUE(step.inside) << "step " << k;
      EXPECT_EQ(step.binding, Constraint::kNone) << "step " << k;
    } else if (k < k2) {
      EXPECT_EQ(step.kind, ControlKind::kLimit) << "step " << k;
      EXPECT_FALSE(step.inside) << "step " << k;
      EXPECT_EQ(step.binding, Constraint::kMaxSpeed) << "step " << k;
    } else {
      EXPECT_EQ(step.kind, ControlKind::kDecelerate) << "step " << k;
      EXPECT_EQ(step.binding, Constraint::kBrake) << "step " << k;
    }
  }
  // Two switches: accelerate -> limit at the first station of its switching
  // step; the braking switching step has kind kLimit and so belongs to the
  // limit arc before it, and the switch is at the first braking step.
  ASSERT_EQ(a.switches.size(), 2u);
  EXPECT_EQ(a.switches[0].station, k1);
  EXPECT_EQ(a.switches[0].from, ControlKind::kAccelerate);
  EXPECT_EQ(a.switches[0].to, ControlKind::kLimit);
  EXPECT_EQ(a.switches[0].s, p.s[k1]);
  EXPECT_EQ(a.switches[1].station, k2 + 1);
  EXPECT_EQ(a.switches[1].from, ControlKind::kLimit);
  EXPECT_EQ(a.switches[1].to, ControlKind::kDecelerate);
  EXPECT_EQ(a.switches[1].s, p.s[k2 + 1]);

  // Limiting lengths: the accelerating and braking steps, and everything
  // else on the limit curve; they add up to the path length.
  const LimitingLengths& l = a.lengths;
  EXPECT_NEAR(l.accelerate_drive, p.s[k1], 1e-12);
  EXPECT_NEAR(l.decelerate_brake, L - p.s[k2 + 1], 1e-9);
  EXPECT_NEAR(l.limit, p.s[k2 + 1] - p.s[k1], 1e-9);
  EXPECT_EQ(l.accelerate_sliding + l.accelerate_pitch + l.decelerate_sliding + l.decelerate_pitch +
                l.other,
            0.0);
  EXPECT_NEAR(l.accelerating() + l.decelerating() + l.limit, L, 1e-9);

  // On the limit curve from the end of the accelerating switch step to the
  // start of the braking one: one stretch.
  EXPECT_EQ(a.touch_segments, 1u);
  EXPECT_EQ(a.touching, k2 - k1);
  EXPECT_NEAR(a.touch_length, p.s[k2] - p.s[k1 + 1], 1e-9);
  EXPECT_EQ(a.max_speed, V);
  // Constant v_max: no dips; the first station holds the smallest.
  EXPECT_EQ(a.dips, 0u);
  EXPECT_EQ(a.slowest_station, 0u);
  EXPECT_EQ(a.slowest_v_max, V);
  EXPECT_EQ(a.slowest_v, 0.0);
  // The bounds are the vehicle's drive and brake at every station.
  for (const AccelerationBounds& b : a.bounds) {
    ASSERT_TRUE(b.feasible);
    EXPECT_NEAR(b.a_max, A, 1e-12);
    EXPECT_NEAR(b.a_min, -D, 1e-12);
  }
  // The solver itself agrees on where the switches are.
  EXPECT_TRUE(verify_profile(*solved.limits, p).passed());
}

// Without drive and brake limits friction bounds s̈ (μ g) and the profile is
// a triangle: accelerate to the middle, then brake, both on friction.
TEST(ProfileAnalysis, FrictionTriangleAcceleratesAndBrakesOnSliding) {
  const double L = 20.0, mu = 0.9;
  const std::size_t n = 134;
  Vehicle v = trapezoid_vehicle(INFINITY, INFINITY, INFINITY);
  v.friction = mu;
  const BPatch ground = flat_ground();
  const Solved solved = solve_straight(ground, v, L, n);
  ASSERT_EQ(solved.profile.status, ProfileStatus::kOk) << solved.profile.message;
  const ProfileAnalysis a = analyze_profile(*solved.limits, solved.profile);
  const TimeOptimalProfile& p = solved.profile;
  const double h = L / static_cast<double>(n - 1);
  const auto km = static_cast<std::size_t>(std::floor(0.5 * L / h));  // step holding L/2
  ASSERT_EQ(a.switches.size(), 1u);
  EXPECT_EQ(a.switches[0].station, km);
  EXPECT_EQ(a.switches[0].from, ControlKind::kAccelerate);
  EXPECT_EQ(a.switches[0].to, ControlKind::kDecelerate);
  EXPECT_NEAR(a.lengths.accelerate_sliding, p.s[km], 1e-12);
  EXPECT_NEAR(a.lengths.decelerate_sliding, L - p.s[km + 1], 1e-9);
  EXPECT_NEAR(a.lengths.limit, h, 1e-9);
  EXPECT_EQ(a.lengths.accelerate_drive + a.lengths.decelerate_brake, 0.0);
  EXPECT_EQ(a.touching, 0u);  // v_max is infinite on flat, straight ground
  EXPECT_NEAR(a.max_speed, std::sqrt(mu * kG * 2 * p.s[km]), 1e-6 * a.max_speed);
}

// The two-step marking rule of switching_points, on hand-made classes.
TEST(ProfileAnalysis, SwitchingPointsMarkInsideStepsBetweenArcs) {
  const auto arc = [](ControlKind kind) { return StepClass{kind, Constraint::kNone, false}; };
  const StepClass inside{ControlKind::kLimit, Constraint::kNone, true};
  const StepClass acc = arc(ControlKind::kAccelerate), dec = arc(ControlKind::kDecelerate);
  const std::vector<double> s = {0, 1, 2, 3, 4, 5, 6, 7};
  // acc acc inside dec dec: one switch acc -> dec at the inside step (station 2).
  std::vector<SwitchingPoint> sw =
      switching_points({acc, acc, inside, dec, dec}, {0, 1, 2, 3, 4, 5});
  ASSERT_EQ(sw.size(), 1u);
  EXPECT_EQ(sw[0].station, 2u);
  EXPECT_EQ(sw[0].s, 2.0);
  EXPECT_EQ(sw[0].from, ControlKind::kAccelerate);
  EXPECT_EQ(sw[0].to, ControlKind::kDecelerate);
  // acc inside acc: no switch at all.
  EXPECT_TRUE(switching_points({acc, acc, inside, acc}, {0, 1, 2, 3, 4}).empty());
  // Two inside steps in a row are an arc of their own (riding a boundary).
  sw = switching_points({acc, inside, inside, dec, dec, dec, acc}, s);
  ASSERT_EQ(sw.size(), 3u);
  EXPECT_EQ(sw[0].station, 1u);
  EXPECT_EQ(sw[0].to, ControlKind::kLimit);
  EXPECT_EQ(sw[1].station, 3u);
  EXPECT_EQ(sw[1].from, ControlKind::kLimit);
  EXPECT_EQ(sw[1].to, ControlKind::kDecelerate);
  EXPECT_EQ(sw[2].station, 6u);
  EXPECT_EQ(sw[2].to, ControlKind::kAccelerate);
  // Sizes must agree.
  EXPECT_THROW(switching_points({acc, dec}, {0, 1}), InputError);
  EXPECT_THROW(limiting_lengths({acc, dec}, {0, 1, 2, 3}), InputError);
  const LimitingLengths l =
      limiting_lengths({StepClass{ControlKind::kAccelerate, Constraint::kPitchover, false},
                        StepClass{ControlKind::kDecelerate, Constraint::kPitchover, false},
                        StepClass{ControlKind::kDecelerate, Constraint::kTipover, false}},
                       {0.0, 0.5, 2.0, 4.5});
  EXPECT_EQ(l.accelerate_pitch, 0.5);
  EXPECT_EQ(l.decelerate_pitch, 1.5);
  EXPECT_EQ(l.other, 2.5);
}

TEST(ProfileAnalysis, OnLimitAndOptionsValidation) {
  EXPECT_TRUE(on_limit(9.99, 10.0));        // within 0.1 %
  EXPECT_FALSE(on_limit(9.98, 10.0));       // 0.2 % below
  EXPECT_FALSE(on_limit(1e300, INFINITY));  // no limit curve to ride
  EXPECT_TRUE(on_limit(9.98, 10.0, 0.01));
  ProfileAnalysisOptions options;
  EXPECT_NO_THROW(options.validate());
  options.touch_tolerance = 1.0;
  EXPECT_THROW(options.validate(), InputError);
  options.touch_tolerance = -1e-3;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.acceleration_tolerance = NAN;
  EXPECT_THROW(options.validate(), InputError);
  options.acceleration_tolerance = -1.0;
  EXPECT_THROW(options.validate(), InputError);
}

TEST(ProfileAnalysis, RejectsInfeasibleAndMismatchedProfiles) {
  const BPatch ground = flat_ground();
  Solved solved = solve_straight(ground, trapezoid_vehicle(2, 4, 4), 20.0, 50);
  ASSERT_EQ(solved.profile.status, ProfileStatus::kOk);
  EXPECT_THROW(describe_infeasibility(*solved.limits, solved.profile), InputError);
  TimeOptimalProfile shorter = solved.profile;
  shorter.v.pop_back();
  EXPECT_THROW(analyze_profile(*solved.limits, shorter), InputError);
  TimeOptimalProfile none;  // kInfeasible
  EXPECT_THROW(analyze_profile(*solved.limits, none), InputError);
  EXPECT_THROW(classify_steps(solved.profile, {}), InputError);
}

// describe_infeasibility says whether standing still is admissible from the
// failing station to the end: on level ground it is, on a slope steeper than
// friction holds it is not.
TEST(ProfileAnalysis, DescribeInfeasibilityChecksRestFromTheFailingStation) {
  const BPatch ground = flat_ground();
  Vehicle v = trapezoid_vehicle(2, 4, 4);
  Solved solved = solve_straight(ground, v, 20.0, 50);
  // Forge an infeasible result at station 10 on level ground: rest is
  // admissible everywhere from there.
  TimeOptimalProfile failed;
  failed.status = ProfileStatus::kInfeasible;
  failed.message = "forged";
  failed.infeasible_station = 10;
  const InfeasibilityDiagnosis d = describe_infeasibility(*solved.limits, failed);
  EXPECT_EQ(d.message, "forged");
  EXPECT_EQ(d.station, 10u);
  EXPECT_EQ(d.s, solved.limits->frame(10).s);
  EXPECT_TRUE(d.rest_admissible);
  failed.infeasible_station = 50;
  EXPECT_THROW(describe_infeasibility(*solved.limits, failed), InputError);

  // On a slope steeper than friction holds (tan 45° = 1 > μ = 0.9), standing
  // still slides: rest is not admissible.
  const BPatch steep = BPatch::interpolate(
      grid_from_function([](double x, double) { return x; }, 0, -5, 30, 5, 1.0));
  Solved up = solve_straight(steep, v, 20.0, 50);
  failed.infeasible_station = 10;
  EXPECT_FALSE(describe_infeasibility(*up.limits, failed).rest_admissible);
}

// Two profiles along the same stations: where and by how much they differ.
TEST(ProfileAnalysis, ProfileDifferenceFindsTheLargestGap) {
  TimeOptimalProfile a, b;
  a.v = {0.0, 2.0, 3.0, 1.0, 0.0};
  b.v = {0.0, 1.5, 3.5, 0.25, 0.0};
  const ProfileDifference d = profile_difference(a, b);
  EXPECT_EQ(d.largest_gap, 0.75);  // a − b at station 3
  EXPECT_EQ(d.largest_gap_station, 3u);
  EXPECT_EQ(d.largest_difference, 0.75);  // |a − b|: 0.5, 0.5, 0.75
  const ProfileDifference r = profile_difference(b, a);
  EXPECT_EQ(r.largest_gap, 0.5);  // b − a at station 2
  EXPECT_EQ(r.largest_gap_station, 2u);
  EXPECT_EQ(r.largest_difference, 0.75);
  b.v.pop_back();
  EXPECT_THROW(profile_difference(a, b), InputError);
}

}  // namespace
}  // namespace talus
