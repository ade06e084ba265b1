// profile_convergence: the station-count study on a trapezoid profile whose
// travel time and discretisation error are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/optimal/profile_convergence.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_from_function;

// A point mass on flat, straight ground with drive = brake = A and top speed
// V over L = 4.5 m: accelerate to s1 = V²/(2A) = L/3, cruise, brake from
// s2 = 2L/3. Exact time T = 2 V/A + (L − V²/A)/V = 2.5 s.
constexpr double kA = 3.0, kV = 3.0, kL = 4.5;
constexpr double kExactTime = 2.0 * kV / kA + (kL - kV * kV / kA) / kV;

// With N − 1 = 4^k steps the switches sit at the same fraction θ of their
// step at every level (4^k / 3 has fractional part 1/3). Every step is exact
// (x = ṡ² is linear in s at constant s̈) except the two that straddle a
// switch; each loses A θ (1 − θ) h² / (2 V³) + O(h³), so the error is second
// order: T_N − T = C h² with C = A θ (1 − θ) / V³, θ = 1/3.
constexpr double kTheta = 1.0 / 3.0;
constexpr double kC = kA * kTheta * (1.0 - kTheta) / (kV * kV * kV);

BPatch flat_ground() {
  return BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, -5, 12, 5, 1.0));
}

Vehicle trapezoid_vehicle() {
  Vehicle v;
  v.friction = 0.9;  // μ g = 8.8 m/s² > A: friction never binds
  v.cg_height = 0.3;
  v.half_track = 1.0;
  v.max_accel = kA;
  v.max_decel = kA;
  v.max_speed = kV;
  return v;
}

ProfileConvergenceOptions quadrupling(double richardson_order) {
  ProfileConvergenceOptions options;
  options.station_counts = {5, 17, 65, 257, 1025, 4097};  // N − 1 = 4^k
  options.richardson_order = richardson_order;
  return options;
}

TEST(ProfileConvergence, TrapezoidConvergesAtSecondOrderAsTheoryPredicts) {
  const BPatch ground = flat_ground();
  const SurfacePath path(ground, Curve2::interpolate({{2, 0}, {2 + kL, 0}}));
  ASSERT_NEAR(path.length(), kL, 1e-12);
  const ProfileConvergence study = profile_convergence(trapezoid_vehicle(), path, quadrupling(2));
  ASSERT_EQ(study.status, ConvergenceStatus::kOk);
  ASSERT_EQ(study.levels.size(), 6u);
  const ConvergenceLevel& ref = study.reference();
  EXPECT_EQ(ref.stations, 4097u);
  EXPECT_EQ(ref.error, 0.0);
  for (std::size_t i = 0; i < study.levels.size(); ++i) {
    const ConvergenceLevel& l = study.levels[i];
    SCOPED_TRACE(l.stations);
    ASSERT_TRUE(l.feasible);
    EXPECT_TRUE(l.in_sequence);
    const double h = kL / static_cast<double>(l.stations - 1);
    EXPECT_NEAR(l.mean_spacing, h, 1e-12);
    EXPECT_NEAR(l.max_spacing, h, 1e-9);  // a straight line: equally spaced in s
    // Conservative, and the closed-form leading error term (the O(h³) rest
    // is below 10 % of it from h = 0.07 m on).
    EXPECT_GT(l.travel_time, kExactTime);
    if (h < 0.1) {
      EXPECT_NEAR((l.travel_time - kExactTime) / (kC * h * h), 1.0, 0.1);
    }
    EXPECT_NEAR(l.error, l.travel_time / ref.travel_time - 1.0, 1e-15);
    EXPECT_GE(l.limits_seconds, 0.0);
    EXPECT_GE(l.solve_seconds, 0.0);
  }
  // Observed orders: 2, up to the reference's own error, which raises the
  // order at level i by log4((1 − 16^{i−5}) / (1 − 16^{i−4})) (+0.023 at i = 3).
  for (std::size_t i = 1; i + 2 < study.levels.size(); ++i) {
    const double bias = std::log((1.0 - std::pow(16.0, static_cast<double>(i) - 5.0)) /
                                 (1.0 - std::pow(16.0, static_cast<double>(i) - 4.0))) /
                        std::log(4.0);
    EXPECT_NEAR(study.levels[i].order, 2.0 + bias, 0.05) << "level " << i;
  }
  // No order against the reference.
  EXPECT_TRUE(std::isnan(study.levels[4].order));
  EXPECT_TRUE(std::isnan(study.levels[5].order));
  // The Richardson extrapolate for p = 2 removes the h² term: far closer to
  // the exact time than the finest level itself.
  const double fine_error = ref.travel_time - kExactTime;
  const double extrapolated_error = study.extrapolated_time - kExactTime;
  EXPECT_GT(fine_error, 0.0);
  EXPECT_LT(std::abs(extrapolated_error), 0.05 * fine_error);
  // Its formula, recomputed: T_ref + (T_ref − T_c) / ((h_c / h_ref)² − 1) with h_c / h_ref = 4.
  const ConvergenceLevel& coarse = study.levels[4];
  const double ratio = coarse.mean_spacing / ref.mean_spacing;
  EXPECT_NEAR(ratio, 4.0, 1e-12);
  EXPECT_NEAR(study.extrapolated_time,
              ref.travel_time + (ref.travel_time - coarse.travel_time) / (ratio * ratio - 1.0),
              1e-14);

  // An assumed first order extrapolates less far (T* = T_ref − (T_c − T_ref)/3):
  // it overshoots below the exact time, since the true order is 2.
  const ProfileConvergence first = profile_convergence(trapezoid_vehicle(), path, quadrupling(1));
  EXPECT_LT(first.extrapolated_time, kExactTime);
  EXPECT_NEAR(first.extrapolated_time,
              ref.travel_time - (coarse.travel_time - ref.travel_time) / 3.0, 1e-14);

  // The levels' results do not depend on the timing repeats.
  ProfileConvergenceOptions repeated = quadrupling(2);
  repeated.timing_repeats = 3;
  repeated.timing_budget_seconds = 1e-4;
  const ProfileConvergence again = profile_convergence(trapezoid_vehicle(), path, repeated);
  for (std::size_t i = 0; i < study.levels.size(); ++i)
    EXPECT_EQ(again.levels[i].travel_time, study.levels[i].travel_time);

  // coarsest_within: the coarsest sequence level from which on all finer
  // non-reference levels are within the target.
  EXPECT_EQ(study.coarsest_within(1.0), 0u);
  const double e2 = study.levels[2].error;
  EXPECT_EQ(study.coarsest_within(e2), 2u);
  EXPECT_EQ(study.coarsest_within(0.99 * e2), 3u);
  EXPECT_EQ(study.coarsest_within(0.0), study.levels.size());
}

TEST(ProfileConvergence, ExtraLevelsAreComparedButLeftOutOfOrdersAndRichardson) {
  const BPatch ground = flat_ground();
  const SurfacePath path(ground, Curve2::interpolate({{2, 0}, {2 + kL, 0}}));
  ProfileConvergenceOptions options = quadrupling(2);
  options.extra_station_counts = {101, 1025, 3000};  // 1025 is a sequence level already
  const ProfileConvergence plain = profile_convergence(trapezoid_vehicle(), path, quadrupling(2));
  const ProfileConvergence study = profile_convergence(trapezoid_vehicle(), path, options);
  ASSERT_EQ(study.levels.size(), 8u);
  const std::vector<std::size_t> expected = {5, 17, 65, 101, 257, 1025, 3000, 4097};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(study.levels[i].stations, expected[i]);
    EXPECT_EQ(study.find(expected[i]), i);
  }
  EXPECT_EQ(study.find(6), study.levels.size());
  const ConvergenceLevel& extra = study.levels[study.find(101)];
  EXPECT_FALSE(extra.in_sequence);
  EXPECT_TRUE(std::isnan(extra.order));
  EXPECT_GT(extra.error, 0.0);
  EXPECT_FALSE(study.levels[study.find(3000)].in_sequence);
  EXPECT_TRUE(study.levels[study.find(1025)].in_sequence);
  // Orders and the extrapolate are those without the extra levels.
  EXPECT_EQ(study.extrapolated_time, plain.extrapolated_time);
  for (const std::size_t n : {5u, 17u, 65u, 257u})
    EXPECT_EQ(study.levels[study.find(n)].order, plain.levels[plain.find(n)].order) << n;
  // Extra levels count in coarsest_within (every finer level must be within
  // the target) but are no candidates themselves.
  EXPECT_EQ(study.coarsest_within(1.0), 0u);
  EXPECT_EQ(study.coarsest_within(study.levels[study.find(65)].error), study.find(65));
  EXPECT_EQ(study.coarsest_within(extra.error), study.find(257));
}

// Uphill on a 45° slope with μ = 0.9 < tan 45°: the vehicle slides back at
// any speed, so no level has a profile, and standing still is no way out.
TEST(ProfileConvergence, AnInfeasibleReferenceLeavesErrorsUndefined) {
  const BPatch steep = BPatch::interpolate(
      grid_from_function([](double x, double) { return x; }, 0, -5, 12, 5, 1.0));
  const SurfacePath path(steep, Curve2::interpolate({{2, 0}, {2 + kL, 0}}));
  ProfileConvergenceOptions options;
  options.station_counts = {10, 20, 40};
  const ProfileConvergence study = profile_convergence(trapezoid_vehicle(), path, options);
  EXPECT_EQ(study.status, ConvergenceStatus::kReferenceInfeasible);
  ASSERT_EQ(study.levels.size(), 3u);
  for (const ConvergenceLevel& l : study.levels) {
    EXPECT_FALSE(l.feasible);
    EXPECT_TRUE(std::isnan(l.travel_time));
    EXPECT_TRUE(std::isnan(l.error));
    EXPECT_TRUE(std::isnan(l.order));
    EXPECT_FALSE(l.failure.message.empty());
    EXPECT_FALSE(l.failure.rest_admissible);
    EXPECT_LT(l.failure.station, l.stations);
  }
  EXPECT_TRUE(std::isnan(study.extrapolated_time));
  EXPECT_EQ(study.coarsest_within(1.0), study.levels.size());
}

TEST(ProfileConvergence, ValidateRejectsBadOptions) {
  const auto rejects = [](auto&& change) {
    ProfileConvergenceOptions options;
    change(options);
    EXPECT_THROW(options.validate(), InputError);
  };
  EXPECT_NO_THROW(ProfileConvergenceOptions{}.validate());
  rejects([](ProfileConvergenceOptions& o) { o.station_counts = {100}; });
  rejects([](ProfileConvergenceOptions& o) { o.station_counts = {}; });
  rejects([](ProfileConvergenceOptions& o) { o.station_counts = {1, 10}; });
  rejects([](ProfileConvergenceOptions& o) { o.station_counts = {10, 10, 20}; });
  rejects([](ProfileConvergenceOptions& o) { o.station_counts = {20, 10}; });
  rejects([](ProfileConvergenceOptions& o) { o.extra_station_counts = {1}; });
  rejects([](ProfileConvergenceOptions& o) { o.extra_station_counts = {3200}; });  // the reference
  rejects([](ProfileConvergenceOptions& o) { o.extra_station_counts = {5000}; });
  rejects([](ProfileConvergenceOptions& o) { o.richardson_order = 0.0; });
  rejects([](ProfileConvergenceOptions& o) { o.richardson_order = NAN; });
  rejects([](ProfileConvergenceOptions& o) { o.richardson_order = INFINITY; });
  rejects([](ProfileConvergenceOptions& o) { o.timing_repeats = 0; });
  rejects([](ProfileConvergenceOptions& o) { o.timing_budget_seconds = -1.0; });
  rejects([](ProfileConvergenceOptions& o) { o.timing_budget_seconds = INFINITY; });
  rejects([](ProfileConvergenceOptions& o) { o.speeds.start_speed = -1.0; });
  // profile_convergence validates before it solves anything.
  const BPatch ground = flat_ground();
  const SurfacePath path(ground, Curve2::interpolate({{2, 0}, {2 + kL, 0}}));
  ProfileConvergenceOptions bad;
  bad.station_counts = {10};
  EXPECT_THROW(profile_convergence(trapezoid_vehicle(), path, bad), InputError);
}

}  // namespace
}  // namespace talus
