// The trajectory-space potential field (trajectory_space_field.hpp, Iagnemma
// et al. 2008 §III): each term against its equation, the curvature limits
// against the closed forms on level ground and a side slope, and the descent
// step reaching the desired manoeuvre when it is safe, stopping at the slip
// boundary when it is not, and turning away from a hazard.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "talus/core/error.hpp"
#include "talus/navigation/trajectory_space_field.hpp"

namespace talus {
namespace {

TrajectorySpaceInputs level() {
  TrajectorySpaceInputs in;  // the UGV: d 0.124 m, h 0.06 m, mu 0.7
  in.max_curvature = 2.0;
  in.max_speed = 8.0;
  return in;
}

TEST(TrajectorySpaceField, LimitsAreTheClosedForms) {
  TrajectorySpaceInputs in = level();
  const double v = 3.0, g = 9.81;
  const auto [r_minus, r_plus] = rollover_limits(in, v);
  EXPECT_NEAR(r_plus, in.half_track * g / (in.cg_height * v * v), 1e-12);
  EXPECT_NEAR(r_minus, -r_plus, 1e-12);
  const auto [s_minus, s_plus] = slip_limits(in, v);
  EXPECT_NEAR(s_plus, in.friction * g / (v * v), 1e-12);
  EXPECT_NEAR(s_minus, -s_plus, 1e-12);
  // A side slope whose gravity pulls left (g_y > 0) allows tighter left turns.
  in.gravity_lateral = 2.0;
  in.gravity_normal = std::sqrt(g * g - 4.0);
  EXPECT_GT(slip_limits(in, v).second, s_plus);
  EXPECT_GT(slip_limits(in, v).first, s_minus);
  EXPECT_NEAR(slip_limits(in, v).second + slip_limits(in, v).first, 2.0 * 2.0 / (v * v), 1e-12);
}

TEST(TrajectorySpaceField, TermsFollowTheirEquations) {
  TrajectorySpaceInputs in = level();
  in.desired_curvature = 0.3;
  in.desired_speed = 2.0;
  const double v = 4.0;
  const double ks = slip_limits(in, v).second;  // 0.429 /m < rollover's 2.13 /m
  // (10): zero inside the limit, K_s at kappa_max, the parabola between.
  EXPECT_EQ(trajectory_space_field(in, {v, 0.9 * ks}).side_slip, 0.0);
  EXPECT_NEAR(trajectory_space_field(in, {v, ks}).side_slip, 0.0, 1e-12);
  EXPECT_NEAR(trajectory_space_field(in, {v, in.max_curvature}).side_slip, 800.0, 1e-9);
  const double k = 0.5 * (ks + in.max_curvature);
  const double r = (k - in.max_curvature) / (ks - in.max_curvature);
  EXPECT_NEAR(trajectory_space_field(in, {v, k}).side_slip, 800.0 * (1.0 - r * r), 1e-9);
  EXPECT_NEAR(trajectory_space_field(in, {v, -k}).side_slip, 800.0 * (1.0 - r * r), 1e-9);
  // (11), (12) in cm/s.
  const TrajectorySpaceTerms t = trajectory_space_field(in, {3.0, 0.1});
  EXPECT_NEAR(t.waypoint, 0.3 * 0.04, 1e-15);
  EXPECT_NEAR(t.velocity, 0.5e-5 * std::pow(100.0, 4), 1e-9);
  // (13): at the hazard's centre curvature.
  in.hazards.push_back({0.2, -0.2, 3.0, 0.5});
  const double expected = 1500.0 * (0.07 * 300.0 + 1.0) / ((0.05 * 3.0 + 1.0) * (10.0 * 0.5 + 1.0));
  EXPECT_NEAR(trajectory_space_field(in, {3.0, 0.0}).hazards, expected, 1e-9);
  EXPECT_NEAR(trajectory_space_field(in, {3.0, 0.1}).hazards,
              expected * std::exp(-0.01 / (2.0 * 0.2)), 1e-9);
  EXPECT_THROW(
      [] {
        TrajectorySpaceInputs bad = level();
        bad.hazards.push_back({-0.1, 0.1, 1.0, 0.0});
        bad.validate();
      }(),
      InputError);
}

TrajectoryPoint run_descent(const TrajectorySpaceInputs& in, TrajectoryPoint p, int steps,
                            std::uint64_t seed = 7) {
  std::mt19937_64 rng(seed);
  for (int k = 0; k < steps; ++k) p = descend(in, p, rng);
  return p;
}

TEST(TrajectorySpaceField, DescentReachesASafeDesiredManoeuvre) {
  TrajectorySpaceInputs in = level();
  in.desired_speed = 3.0;
  in.desired_curvature = 0.4;  // a_y = 3.6 m/s^2 < mu g
  const TrajectoryPoint p = run_descent(in, {1.0, 0.0}, 400);
  std::cout << "safe: (" << p.speed << " m/s, " << p.curvature << " /m)\n";
  EXPECT_NEAR(p.speed, 3.0, 0.1);
  EXPECT_NEAR(p.curvature, 0.4, 0.05);
}

TEST(TrajectorySpaceField, DescentStopsAtTheSlipBoundaryOfAnUnsafeOne) {
  TrajectorySpaceInputs in = level();
  in.desired_speed = 4.0;
  in.desired_curvature = 1.0;  // v^2 kappa = 16 m/s^2 > mu g = 6.9
  const TrajectoryPoint p = run_descent(in, {1.0, 0.0}, 600);
  const double lateral = p.speed * p.speed * p.curvature;
  std::cout << "unsafe: (" << p.speed << " m/s, " << p.curvature << " /m), v^2 kappa = " << lateral
            << " m/s^2, mu g = " << in.friction * 9.81 << "\n";
  EXPECT_LT(lateral, 1.15 * in.friction * 9.81) << p.speed << " " << p.curvature;
  EXPECT_GT(lateral, 0.5 * in.friction * 9.81);
}

TEST(TrajectorySpaceField, DescentTurnsAwayFromAHazardAhead) {
  TrajectorySpaceInputs in = level();
  in.desired_speed = 2.0;
  in.desired_curvature = 0.0;
  in.hazards.push_back({0.15, -0.05, 2.0, 0.0});  // ahead, a little to the left
  const TrajectoryPoint p = run_descent(in, {2.0, 0.0}, 400);
  std::cout << "hazard: (" << p.speed << " m/s, " << p.curvature << " /m)\n";
  EXPECT_TRUE(p.curvature < -0.05 || p.curvature > 0.15) << p.curvature;
  EXPECT_LT(p.curvature, 0.0);                                         // the nearer way round
  EXPECT_EQ(run_descent(in, {2.0, 0.0}, 400).curvature, p.curvature);  // seeded
}

}  // namespace
}  // namespace talus
