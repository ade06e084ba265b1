// talus/dynamics/limit_summary.hpp: per-constraint limits along a path,
// common-speed acceleration bounds and the path summary, on paths whose
// limits are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/dynamics/limit_summary.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

constexpr double kG = 9.81;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// z = 0 over [-40, 40]^2, 1 m cells.
const BPatch& flat_ground() {
  static const BPatch patch = BPatch::interpolate(
      terrain_test::grid_around_origin([](double, double) { return 0.0; }, 40.0, 1.0));
  return patch;
}

/// A closed circle of radius r about the origin, 256 interpolation points.
Curve2 circle(double r) {
  std::vector<Vec2> points;
  for (int k = 0; k <= 256; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 256;
    points.emplace_back(r * std::cos(t), r * std::sin(t));
  }
  return Curve2::interpolate(points);
}

Curve2 straight_line() {
  return Curve2::interpolate({Vec2(-30, -5), Vec2(0, 0), Vec2(30, 5)});
}

TEST(LimitSummary, ConstraintSpeedsOfAnInterval) {
  EXPECT_EQ(upper_speed({4.0, 9.0}), 3.0);
  EXPECT_EQ(lower_speed({4.0, 9.0}), 2.0);
  EXPECT_EQ(upper_speed({0.0, kInf}), kInf);
  EXPECT_EQ(upper_speed({9.0, 4.0}), 0.0);  // empty: no speed satisfies it
  EXPECT_EQ(lower_speed({9.0, 4.0}), 0.0);
}

TEST(LimitSummary, FlatCircleIsSlidingLimitedEverywhere) {
  const double r = 20.0, mu = 0.7;
  Vehicle v = vehicle_test::point_mass_rover(mu);  // b/h = 1.2 > mu: sliding before tip-over
  v.max_speed = 100.0;
  const SurfacePath path(flat_ground(), circle(r));
  const LimitProfile profile = limit_profile(v, path, 200);
  ASSERT_EQ(profile.stations.size(), 200u);
  for (const LimitStation& st : profile.stations) {
    EXPECT_EQ(st.limits.upper_binding, Constraint::kSliding);
    EXPECT_NEAR(st.v_sliding, std::sqrt(mu * kG * r), 5e-3 * std::sqrt(mu * kG * r));
    EXPECT_NEAR(st.v_tipover, std::sqrt(1.2 * kG * r), 5e-3 * std::sqrt(1.2 * kG * r));
    EXPECT_EQ(st.v_contact, kInf);  // flat ground: the normal force is g at any speed
    EXPECT_EQ(st.v_sliding, st.limits.v_max);
    EXPECT_EQ(st.v_sliding_min, 0.0);
    EXPECT_EQ(st.accel.feasible, false);  // not evaluated yet
  }
  const LimitSummary sum = summarise_limits(profile.stations);
  EXPECT_EQ(sum.stations, 200u);
  EXPECT_EQ(sum.upper_count(Constraint::kSliding), 200u);
  EXPECT_EQ(sum.upper_share(Constraint::kSliding), 1.0);
  EXPECT_EQ(sum.upper_share(Constraint::kMaxSpeed), 0.0);
  EXPECT_EQ(sum.upper_share(Constraint::kContact), 0.0);
  EXPECT_EQ(sum.upper_share(Constraint::kTipover), 0.0);
  EXPECT_EQ(sum.untraversable, 0u);
  EXPECT_EQ(sum.lower_bound_stations, 0u);
  EXPECT_EQ(sum.max_v_min, 0.0);
  EXPECT_EQ(sum.sliding_on_crest, 0u);  // κ_n = 0 on flat ground
  EXPECT_EQ(sum.min_v_contact, kInf);
  EXPECT_EQ(sum.min_v_sliding, sum.min_v_max);
  EXPECT_EQ(sum.min_v_max, profile.stations[sum.min_index].limits.v_max);
  EXPECT_NEAR(sum.median_v_max, std::sqrt(mu * kG * r), 5e-3 * std::sqrt(mu * kG * r));
  // No acceleration bounds evaluated: every station counts as infeasible.
  EXPECT_EQ(sum.accel_infeasible, 200u);
  EXPECT_TRUE(std::isnan(sum.median_a_max));
}

TEST(LimitSummary, TightTrackTipsOverInsteadOfSliding) {
  Vehicle v = vehicle_test::point_mass_rover(0.9);
  v.cg_height = 1.0;
  v.half_track = 0.5;  // b/h = 0.5 < mu
  v.max_speed = 100.0;
  const SurfacePath path(flat_ground(), circle(15.0));
  const LimitSummary sum = summarise_limits(limit_profile(v, path, 100).stations);
  EXPECT_EQ(sum.upper_share(Constraint::kTipover), 1.0);
  EXPECT_NEAR(sum.min_v_tipover, std::sqrt(0.5 * kG * 15.0), 5e-3 * std::sqrt(0.5 * kG * 15.0));
  EXPECT_EQ(sum.min_v_tipover, sum.min_v_max);
}

TEST(LimitSummary, StraightFlatLineIsLimitedByTheMaxSpeedAlone) {
  const SurfacePath path(flat_ground(), straight_line());
  const Vehicle v = vehicle_test::point_mass_rover();  // max speed 10 m/s
  const LimitSummary sum = summarise_limits(limit_profile(v, path, 50).stations);
  EXPECT_EQ(sum.upper_share(Constraint::kMaxSpeed), 1.0);
  EXPECT_EQ(sum.min_v_max, 10.0);
  EXPECT_EQ(sum.median_v_max, 10.0);
  EXPECT_EQ(sum.min_index, 0u);
  EXPECT_EQ(sum.dips, 0u);

  Vehicle unlimited = v;
  unlimited.max_speed = kInf;
  const LimitSummary free = summarise_limits(limit_profile(unlimited, path, 50).stations);
  EXPECT_EQ(free.upper_share(Constraint::kNone), 1.0);
  EXPECT_EQ(free.min_v_max, kInf);
}

/// Stations with the given v_max and binding, nothing else.
std::vector<LimitStation> stations_of(const std::vector<double>& v_max,
                                      const std::vector<Constraint>& binding) {
  std::vector<LimitStation> out(v_max.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k].s = static_cast<double>(k);
    out[k].limits.v_max = v_max[k];
    out[k].limits.upper_binding = binding[k];
  }
  return out;
}

TEST(LimitSummary, MinimumMedianDipsAndCountsOfHandMadeStations) {
  const auto S = Constraint::kSliding, M = Constraint::kMaxSpeed, C = Constraint::kContact;
  std::vector<LimitStation> st =
      stations_of({5.0, 3.0, 4.0, 2.0, 6.0, 6.0, 2.0}, {M, S, S, C, M, M, S});
  st[3].limits.v_min = 1.5;
  st[3].geometry.kappa_n = -0.1;  // a crest, but bound by contact
  st[1].geometry.kappa_n = -0.2;  // sliding on a crest
  st[6].limits.traversable = false;
  const LimitSummary sum = summarise_limits(st);
  EXPECT_EQ(sum.min_v_max, 2.0);
  EXPECT_EQ(sum.min_index, 3u);      // the first of the two smallest
  EXPECT_EQ(sum.median_v_max, 4.0);  // sorted 2 2 3 4 5 6 6
  EXPECT_EQ(sum.dips, 2u);           // stations 1 and 3; not the ends
  EXPECT_EQ(sum.upper_count(S), 3u);
  EXPECT_EQ(sum.upper_count(M), 3u);
  EXPECT_EQ(sum.upper_count(C), 1u);
  EXPECT_EQ(sum.upper_share(M), 3.0 / 7.0);
  EXPECT_EQ(sum.untraversable, 1u);
  EXPECT_EQ(sum.lower_bound_stations, 1u);
  EXPECT_EQ(sum.max_v_min, 1.5);
  EXPECT_EQ(sum.sliding_on_crest, 1u);

  // Even count: the upper of the two middle values.
  EXPECT_EQ(summarise_limits(stations_of({1.0, 4.0, 2.0, 3.0}, {S, S, S, S})).median_v_max, 3.0);
  // No stations.
  const LimitSummary none = summarise_limits({});
  EXPECT_EQ(none.stations, 0u);
  EXPECT_EQ(none.min_v_max, kInf);
  EXPECT_TRUE(std::isnan(none.median_v_max));
  EXPECT_EQ(none.upper_share(S), 0.0);
}

TEST(LimitSummary, CommonSpeedAccelerationsOnAStraightFlatLine) {
  // Straight and flat: no lateral force, R = g, so |s̈| <= mu g, at any speed.
  const SurfacePath path(flat_ground(), straight_line());
  Vehicle slow = vehicle_test::point_mass_rover(0.5);
  slow.max_speed = 8.0;
  Vehicle rigid = vehicle_test::point_mass_rover(0.7);
  rigid.model = VehicleModel::kRigidBody;
  rigid.half_wheelbase = 0.3;  // l/h = 0.6 < mu: pitch-over caps s̈ at (l/h) g
  LimitProfile a = limit_profile(slow, path, 40), b = limit_profile(rigid, path, 40);
  evaluate_common_accelerations({&a, &b}, 0.8);
  for (std::size_t k = 0; k < 40; ++k) {
    EXPECT_EQ(a.stations[k].accel_speed, 0.8 * 8.0);  // 0.8 x the smaller v_max
    EXPECT_EQ(b.stations[k].accel_speed, 0.8 * 8.0);
    ASSERT_TRUE(a.stations[k].accel.feasible);
    EXPECT_NEAR(a.stations[k].accel.a_max, 0.5 * kG, 1e-12);
    EXPECT_NEAR(a.stations[k].accel.a_min, -0.5 * kG, 1e-12);
    EXPECT_NEAR(b.stations[k].accel.a_max, 0.6 * kG, 1e-12);
    EXPECT_EQ(b.stations[k].accel.upper_binding, Constraint::kPitchover);
  }
  const LimitSummary sa = summarise_limits(a.stations), sb = summarise_limits(b.stations);
  EXPECT_EQ(sa.accel_infeasible, 0u);
  EXPECT_EQ(sa.accel_bound_stations(Constraint::kSliding), 40u);
  EXPECT_EQ(sa.accel_bound_stations(Constraint::kPitchover), 0u);
  EXPECT_EQ(sb.accel_bound_stations(Constraint::kPitchover), 40u);
  EXPECT_NEAR(sa.median_a_max, 0.5 * kG, 1e-12);
  EXPECT_NEAR(sb.median_a_min, -0.6 * kG, 1e-12);

  EXPECT_FALSE(same_acceleration_bounds(a, b));
  EXPECT_FALSE(same_speed_limits(a, b));  // max speeds 8 and 10
  EXPECT_TRUE(same_acceleration_bounds(a, a));
}

TEST(LimitSummary, RigidBodyWithLongWheelbaseHasThePointMassLimits) {
  const SurfacePath path(flat_ground(), circle(20.0));
  const Vehicle point = vehicle_test::point_mass_rover(0.7);
  Vehicle rigid = point;
  rigid.model = VehicleModel::kRigidBody;
  rigid.half_wheelbase = 1.0;  // l/h = 2 > mu
  LimitProfile a = limit_profile(point, path, 60), b = limit_profile(rigid, path, 60);
  EXPECT_TRUE(same_speed_limits(a, b));
  evaluate_common_accelerations({&a, &b}, 0.8);
  EXPECT_TRUE(same_acceleration_bounds(a, b));
  EXPECT_FALSE(same_speed_limits(a, limit_profile(point, path, 61)));
}

TEST(LimitSummary, SummaryOfVelocityLimitsMatchesTheProfileSummary) {
  // Hills and a winding path: every binding and dips occur somewhere.
  static const BPatch hills = BPatch::interpolate(terrain_test::grid_around_origin(
      [](double x, double y) { return 3.0 * std::sin(x / 6.0) * std::cos(y / 7.0); }, 40.0, 1.0));
  const SurfacePath path(
      hills, Curve2::interpolate({Vec2(-35, -30), Vec2(-10, 5), Vec2(12, -8), Vec2(33, 30)}));
  Vehicle v = vehicle_test::point_mass_rover(0.6);
  v.max_speed = 8.0;
  const VelocityLimits limits(v, path, 400);
  const LimitSummary direct = summarise_limits(limits);
  const LimitSummary copied = summarise_limits(limit_profile(limits).stations);
  EXPECT_EQ(direct.stations, 400u);
  EXPECT_EQ(direct.upper_counts, copied.upper_counts);
  EXPECT_EQ(direct.min_v_max, copied.min_v_max);
  EXPECT_EQ(direct.min_index, copied.min_index);
  EXPECT_EQ(direct.median_v_max, copied.median_v_max);
  EXPECT_EQ(direct.dips, copied.dips);
  EXPECT_EQ(direct.sliding_on_crest, copied.sliding_on_crest);
  EXPECT_EQ(direct.min_v_sliding, copied.min_v_sliding);
  EXPECT_EQ(direct.min_v_contact, copied.min_v_contact);
  EXPECT_EQ(direct.accel_infeasible, 400u);
  EXPECT_GT(direct.dips, 0u);
  EXPECT_GT(direct.upper_count(Constraint::kSliding), 0u);
  EXPECT_GT(direct.upper_count(Constraint::kMaxSpeed), 0u);
  // Independent re-evaluation of the minimum.
  double lowest = kInf;
  for (std::size_t k = 0; k < limits.size(); ++k) lowest = std::min(lowest, limits.limits(k).v_max);
  EXPECT_EQ(direct.min_v_max, lowest);
}

TEST(LimitSummary, CommonAccelerationsRejectBadInput) {
  const SurfacePath path(flat_ground(), straight_line());
  const Vehicle v = vehicle_test::point_mass_rover();
  LimitProfile a = limit_profile(v, path, 10), b = limit_profile(v, path, 11);
  EXPECT_THROW(evaluate_common_accelerations({&a}, 1.5), InputError);
  EXPECT_THROW(evaluate_common_accelerations({&a}, std::nan("")), InputError);
  EXPECT_THROW(evaluate_common_accelerations({&a, &b}, 0.8), InputError);
  EXPECT_NO_THROW(evaluate_common_accelerations({}, 0.8));
}

}  // namespace
}  // namespace talus
