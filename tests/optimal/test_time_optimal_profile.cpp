#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <numbers>
#include <random>

#include "talus/core/error.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/dynamics/admissible_set.hpp"
#include "talus/optimal/time_optimal_profile.hpp"
#include "talus/optimal/trajectory.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_from_function;

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;

Vehicle vehicle(double mu, double max_accel = INFINITY, double max_decel = INFINITY,
                double max_speed = INFINITY) {
  Vehicle v;
  v.friction = mu;
  v.cg_height = 0.3;
  v.half_track = 1.0;  // b/h > mu: tip-over never binds in these tests
  v.max_accel = max_accel;
  v.max_decel = max_decel;
  v.max_speed = max_speed;
  return v;
}

/// The library's default spacing (the issue: analytic times within 0.5 % at the default spacing).
std::size_t stations_for(double length) {
  return station_count(length);
}

TimeOptimalProfile solve_straight(const BPatch& patch, const Vec2& a, const Vec2& b,
                                  const Vehicle& v, double v0 = 0.0, double v1 = 0.0) {
  const SurfacePath path(patch, Curve2::interpolate({a, b}));
  const VelocityLimits limits(v, path, stations_for(path.length()));
  TimeOptimalProfileSolver solver;
  return solver.solve(limits, {v0, v1});
}

/// On straight lines over planes the discrete profile is exact except in the one step that
/// straddles a switch, whose error is second order in the spacing (1e-8 relative at the default
/// 0.1 m; DiscreteErrorIsSecondOrderInTheSpacing checks the order): 1e-7 relative. A 1e-3 error
/// in g or mu moves these times by 5e-4.
void expect_exact_up_to_the_switch_step(double actual, double expected) {
  EXPECT_NEAR(actual, expected, 1e-7 * expected);
}

/// Along an interpolated spline circle the limit itself carries the curvature's O(h^2) error
/// (3.5e-4 relative with 200 points at r = 20 m): 1e-3 relative.
void expect_on_spline_circle(double actual, double expected) {
  EXPECT_NEAR(actual, expected, 1e-3 * expected);
}

TEST(TimeOptimalProfile, FlatStraightLineRestToRest) {
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, -5, 210, 5, 1.0));
  const double L = 200.0, mu = 0.7;
  const TimeOptimalProfile p = solve_straight(flat, {5, 0}, {5 + L, 0}, vehicle(mu));
  ASSERT_EQ(p.status, ProfileStatus::kOk) << p.message;
  expect_exact_up_to_the_switch_step(p.travel_time, 2.0 * std::sqrt(L / (mu * kG)));
  EXPECT_EQ(p.v.front(), 0.0);
  EXPECT_NEAR(p.v.back(), 0.0, 1e-9);
  // Accelerate, then decelerate from the middle (the one step that straddles
  // the middle takes an intermediate control).
  ASSERT_GE(p.switching_points.size(), 1u);
  ASSERT_LE(p.switching_points.size(), 2u);
  EXPECT_EQ(p.switching_points.front().from, ControlKind::kAccelerate);
  EXPECT_EQ(p.switching_points.back().to, ControlKind::kDecelerate);
  for (const SwitchingPoint& sp : p.switching_points) EXPECT_NEAR(sp.s, L / 2, 1.0);
}

TEST(TimeOptimalProfile, DriveBrakeAndSpeedLimitsGiveATrapezoid) {
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, -5, 210, 5, 1.0));
  const double L = 200.0, A = 2.0, D = 4.0, V = 10.0;
  const TimeOptimalProfile p = solve_straight(flat, {5, 0}, {5 + L, 0}, vehicle(0.9, A, D, V));
  ASSERT_EQ(p.status, ProfileStatus::kOk) << p.message;
  const double expected = V / A + V / D + (L - V * V / (2 * A) - V * V / (2 * D)) / V;  // 23.75 s
  expect_exact_up_to_the_switch_step(p.travel_time, expected);
  EXPECT_GE(p.switching_points.size(), 2u);  // accelerate -> cruise at the limit -> decelerate
  // Without the speed limit: a triangle with different slopes.
  const TimeOptimalProfile tri = solve_straight(flat, {5, 0}, {5 + L, 0}, vehicle(0.9, A, D));
  const double peak = std::sqrt(2.0 * L * A * D / (A + D));
  expect_exact_up_to_the_switch_step(tri.travel_time, peak / A + peak / D);
}

TEST(TimeOptimalProfile, StraightUpAndDownAnInclinedPlane) {
  const double alpha = 0.15, mu = 0.8, L = 150.0;
  const BPatch plane = BPatch::interpolate(grid_from_function(
      [&](double x, double) { return std::tan(alpha) * x; }, 0, -5, 160, 5, 1.0));
  const double run = L * std::cos(alpha);
  for (const bool up : {true, false}) {
    const Vec2 a = up ? Vec2(5, 0) : Vec2(5 + run, 0), b = up ? Vec2(5 + run, 0) : Vec2(5, 0);
    const TimeOptimalProfile p = solve_straight(plane, a, b, vehicle(mu));
    ASSERT_EQ(p.status, ProfileStatus::kOk)
        << p.message << " up=" << up << " n=" << p.s.size() << " L=" << p.s.back();
    const double s = up ? 1.0 : -1.0;
    const double acc = kG * (mu * std::cos(alpha) - s * std::sin(alpha));
    const double dec = kG * (mu * std::cos(alpha) + s * std::sin(alpha));
    const double peak = std::sqrt(2.0 * L * acc * dec / (acc + dec));
    expect_exact_up_to_the_switch_step(p.travel_time, peak / acc + peak / dec);
  }
}

TEST(TimeOptimalProfile, DiscreteErrorIsSecondOrderInTheSpacing) {
  // Rest to rest on flat ground with different drive and brake limits: the switch falls inside a
  // step, whose error shrinks about fourfold each time the spacing halves.
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, -5, 210, 5, 1.0));
  const double L = 200.0, A = 2.0, D = 4.0;
  const double peak = std::sqrt(2.0 * L * A * D / (A + D)), exact = peak / A + peak / D;
  const SurfacePath path(flat, Curve2::interpolate({Vec2(5, 0), Vec2(5 + L, 0)}));
  TimeOptimalProfileSolver solver;
  std::vector<double> errors;
  // Station counts chosen so that the switch at 2L/3 never lands on a station.
  for (std::size_t n : {101u, 201u, 401u, 801u}) {
    const TimeOptimalProfile p = solver.solve(VelocityLimits(vehicle(0.9, A, D), path, n), {0, 0});
    ASSERT_EQ(p.status, ProfileStatus::kOk) << p.message;
    errors.push_back(std::abs(p.travel_time - exact));
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double order = std::log2(errors[k - 1] / errors[k]);
    EXPECT_GT(order, 1.8) << "errors " << errors[k - 1] << " -> " << errors[k];
    EXPECT_LT(order, 2.5) << "errors " << errors[k - 1] << " -> " << errors[k];
  }
}

TEST(TimeOptimalProfile, RigidBodyPitchOverBindsBothWaysOnAStraightLine) {
  // l/h = 0.4 < mu = 0.9: the rigid body tips forward under braking and backward under drive at
  // 0.4 g, so rest to rest over L takes 2 sqrt(L / (0.4 g)) where the point mass takes
  // 2 sqrt(L / (0.9 g)).
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, -5, 210, 5, 1.0));
  const double L = 200.0;
  Vehicle rb = vehicle(0.9);
  rb.cg_height = 1.0;
  rb.half_track = 1.2;
  rb.model = VehicleModel::kRigidBody;
  rb.half_wheelbase = 0.4;
  const TimeOptimalProfile p = solve_straight(flat, {5, 0}, {5 + L, 0}, rb);
  ASSERT_EQ(p.status, ProfileStatus::kOk) << p.message;
  expect_exact_up_to_the_switch_step(p.travel_time, 2.0 * std::sqrt(L / (0.4 * kG)));
  EXPECT_NEAR(p.a.front(), 0.4 * kG, 1e-9);
  const TimeOptimalProfile pm = solve_straight(flat, {5, 0}, {5 + L, 0}, vehicle(0.9));
  expect_exact_up_to_the_switch_step(pm.travel_time, 2.0 * std::sqrt(L / (0.9 * kG)));
}

TEST(TimeOptimalProfile, FlatCircleAtItsSteadySpeedStaysThere) {
  const double r = 20.0, mu = 0.6;
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, -25, -25, 25, 25, 1.0));
  std::vector<Vec2> pts;
  for (int k = 0; k <= 200; ++k)
    pts.emplace_back(r * std::cos(2 * kPi * k / 200), r * std::sin(2 * kPi * k / 200));
  const SurfacePath path(flat, Curve2::interpolate(pts));
  const VelocityLimits limits(vehicle(mu), path, stations_for(path.length()));
  // The limit along the fitted circle wobbles by ~1e-5 relative: enter at the smallest one.
  double v_lim = INFINITY;
  for (const SpeedLimits& l : limits.all_limits()) v_lim = std::min(v_lim, l.v_max);
  expect_on_spline_circle(v_lim, std::sqrt(mu * kG * r));
  TimeOptimalProfileSolver solver;
  const TimeOptimalProfile p = solver.solve(limits, {v_lim, v_lim});
  ASSERT_EQ(p.status, ProfileStatus::kOk) << p.message;
  expect_on_spline_circle(p.travel_time, 2 * kPi * r / std::sqrt(mu * kG * r));
  for (double v : p.v) EXPECT_NEAR(v, v_lim, 2e-3 * v_lim);
}

TEST(TimeOptimalProfile, CrestForcesSlowingToTheContactLimit) {
  // Flat run-up, then a crest of radius R (z = sqrt(R^2 - (x-30)^2) - R for
  // |x - 30| < 12), then flat again: with high friction the vehicle would go
  // much faster than sqrt(g R cos(alpha)) and must slow down for the crest.
  const double R = 20.0, half = 12.0;
  const auto z = [&](double x, double) {
    const double d = std::clamp(x - 30.0, -half, half),
                 slope = half / std::sqrt(R * R - half * half);
    const double cap = std::sqrt(R * R - d * d) - R;
    return cap - slope * (std::abs(x - 30.0) - std::abs(d));  // continues with the edge slope
  };
  const BPatch terrain = BPatch::interpolate(grid_from_function(z, 0, -3, 60, 3, 0.25));
  const SurfacePath path(terrain, Curve2::interpolate({Vec2(1, 0), Vec2(59, 0)}));
  const VelocityLimits limits(vehicle(2.0), path, 1200);
  TimeOptimalProfileSolver solver;
  const TimeOptimalProfile p = solver.solve(limits, {});
  ASSERT_EQ(p.status, ProfileStatus::kOk) << p.message;
  std::size_t touching = 0, top = 0;
  for (std::size_t k = 0; k < p.v.size(); ++k) {
    EXPECT_LE(p.v[k], p.v_max[k] * (1 + 1e-9));
    if (limits.limits(k).upper_binding == Constraint::kContact && p.v[k] >= 0.99 * p.v_max[k])
      ++touching;
    if (std::abs(limits.frame(k).point.x() - 30.0) < std::abs(limits.frame(top).point.x() - 30.0))
      top = k;
  }
  EXPECT_GT(touching, 0u) << "the profile never reaches the contact limit";
  // The crest is a bicubic interpolation of 0.25 m samples: its curvature at the top is within
  // 1e-4 of 1/R (the limit measured 9e-6 relative).
  EXPECT_NEAR(limits.limits(top).v_max, std::sqrt(kG * R), 1e-4 * std::sqrt(kG * R));
  EXPECT_LE(p.v[top], std::sqrt(kG * R) * 1.005);
  // On the crest the vehicle is slower than the flat-ground profile would allow there.
  const double flat_peak =
      std::sqrt(2.0 * 2.0 * kG * 29.0);  // accelerate at 2 g over half the path
  EXPECT_LT(p.v[top], 0.5 * flat_peak);
}

TEST(TimeOptimalProfile, StartOrEndAboveTheLimitIsAnInputError) {
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, -5, 60, 5, 1.0));
  const SurfacePath path(flat, Curve2::interpolate({Vec2(5, 0), Vec2(55, 0)}));
  const VelocityLimits limits(vehicle(0.7, INFINITY, INFINITY, 10.0), path, 51);
  TimeOptimalProfileSolver solver;
  EXPECT_THROW(solver.solve(limits, {12.0, 0.0}), InputError);
  EXPECT_THROW(solver.solve(limits, {0.0, 10.5}), InputError);
  EXPECT_THROW(solver.solve(limits, {-1.0, 0.0}), InputError);
  // Too fast to stop within 50 m: infeasible status, not an exception.
  const TimeOptimalProfile p = solver.solve(limits, {10.0, 0.0});
  EXPECT_EQ(p.status, ProfileStatus::kOk);  // 10 m/s stops in 7.3 m at 0.7 g
  const VelocityLimits short_path(vehicle(0.1, INFINITY, INFINITY, 10.0), path, 51);
  const TimeOptimalProfile q = solver.solve(short_path, {10.0, 0.0});  // needs 51 m at 0.1 g
  EXPECT_EQ(q.status, ProfileStatus::kInfeasible);
  EXPECT_FALSE(q.message.empty());
}

TEST(TimeOptimalProfile, UntraversableStationIsReportedWithItsConstraint) {
  // A side slope steeper than friction across the middle of the path.
  const BPatch ridge = BPatch::interpolate(grid_from_function(
      [](double x, double y) { return (x > 20 && x < 40) ? 0.9 * y : 0.0; }, 0, -5, 60, 5, 0.5));
  const SurfacePath path(ridge, Curve2::interpolate({Vec2(5, 0), Vec2(55, 0)}));
  const VelocityLimits limits(vehicle(0.6), path, 201);
  TimeOptimalProfileSolver solver;
  const TimeOptimalProfile p = solver.solve(limits, {});
  ASSERT_EQ(p.status, ProfileStatus::kInfeasible);
  EXPECT_EQ(p.infeasible_binding, Constraint::kSliding);
  EXPECT_GT(p.s[p.infeasible_station], 14.0);
  EXPECT_NE(p.message.find("not traversable"), std::string::npos) << p.message;
}

TEST(TimeOptimalProfile, NearlyCoincidentStationsAreMerged) {
  const BPatch flat = BPatch::interpolate(
      grid_from_function([](double, double) { return 0.0; }, 0, -5, 60, 5, 1.0));
  const SurfacePath path(flat, Curve2::interpolate({Vec2(5, 0), Vec2(55, 0)}));
  // 5e7 stations would be 1e-9 m apart; use a huge count on a tiny path instead.
  const SurfacePath tiny(flat, Curve2::interpolate({Vec2(5, 0), Vec2(5 + 2e-8, 0)}));
  const VelocityLimits limits(vehicle(0.7), tiny, 101);
  TimeOptimalProfileSolver solver;
  const TimeOptimalProfile p = solver.solve(limits, {});
  EXPECT_EQ(p.status, ProfileStatus::kOk) << p.message;
  EXPECT_GT(p.merged_stations, 0u);
  EXPECT_TRUE(std::isfinite(p.travel_time));
}

/// Invariants on random paths over fractal terrain (rover scale).
TEST(TimeOptimalProfile, InvariantsOnRandomFractalPaths) {
  FractalTerrainOptions terrain;
  terrain.shape = {129, 129, 0.5, 0.0, 0.0};
  terrain.height_scale = 6.0;
  terrain.seed = 4;
  const BPatch patch = BPatch::fit_smoothing(generate_fractal_terrain(terrain), 1.0);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> coordinate(12.0, 52.0);  // splines overshoot their points
  Vehicle v = vehicle(0.8, 3.0, 6.0, 12.0);
  v.half_track = 0.35;
  v.cg_height = 0.5;
  int solved = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<Vec2> pts;
    for (int k = 0; k < 5; ++k) pts.emplace_back(coordinate(rng), coordinate(rng));
    std::unique_ptr<SurfacePath> path;
    try {
      path = std::make_unique<SurfacePath>(patch, Curve2::interpolate(pts));
    } catch (const InputError&) {
      continue;  // a random spline may overshoot the map: not this test's subject
    }
    const VelocityLimits limits(v, *path, 400);
    TimeOptimalProfileSolver solver;
    const TimeOptimalProfile p = solver.solve(limits, {});
    if (p.status != ProfileStatus::kOk) continue;
    ++solved;
    const AdmissibleSet c(v);
    double t = 0.0;
    for (std::size_t k = 0; k < p.v.size(); ++k) {
      EXPECT_LE(p.v[k], p.v_max[k] * (1 + 1e-9) + 1e-9) << "station " << k;
      if (k + 1 == p.v.size()) break;
      const double ds = p.s[k + 1] - p.s[k];
      const double u = (p.v[k + 1] * p.v[k + 1] - p.v[k] * p.v[k]) / (2 * ds);
      EXPECT_NEAR(u, p.a[k], 1e-6 * (1 + std::abs(u)));
      // The step's acceleration is admissible at both of its ends.
      const AccelerationBounds b0 = limits.acceleration_bounds(k, p.v[k]);
      const AccelerationBounds b1 = limits.acceleration_bounds(k + 1, p.v[k + 1]);
      ASSERT_TRUE(b0.feasible && b1.feasible) << k;
      const double tol = 1e-6 * (1 + std::abs(u));
      EXPECT_GE(u, std::max(b0.a_min, b1.a_min) - tol) << k;
      EXPECT_LE(u, std::min(b0.a_max, b1.a_max) + tol) << k;
      t += 2 * ds / (p.v[k] + p.v[k + 1]);
      EXPECT_NEAR(p.t[k + 1], t, 1e-9 * t);
      // Maximality: raising this station's speed breaks a constraint of a neighbouring step.
      if (k > 0) {
        const double x_up = p.v[k] * p.v[k] * (1 + 1e-5) + 1e-6;
        const double ds_prev = p.s[k] - p.s[k - 1];
        const double u_in = (x_up - p.v[k - 1] * p.v[k - 1]) / (2 * ds_prev);
        const double u_out = (p.v[k + 1] * p.v[k + 1] - x_up) / (2 * ds);
        const bool in_ok =
            !c.accelerations_along(limits.geometry(k - 1), p.v[k - 1] * p.v[k - 1], 0, 0, INFINITY)
                 .empty() &&
            [&] {
              auto a = c.accelerations_along(limits.geometry(k - 1), p.v[k - 1] * p.v[k - 1], 0, 0,
                                             INFINITY);
              auto b =
                  c.accelerations_along(limits.geometry(k), x_up, 0, 0, p.v_max[k] * p.v_max[k]);
              return u_in >= std::max(a.lower, b.lower) && u_in <= std::min(a.upper, b.upper);
            }();
        const bool out_ok = [&] {
          auto a = c.accelerations_along(limits.geometry(k), x_up, 0, 0, p.v_max[k] * p.v_max[k]);
          auto b = c.accelerations_along(limits.geometry(k + 1), p.v[k + 1] * p.v[k + 1], 0, 0,
                                         INFINITY);
          return u_out >= std::max(a.lower, b.lower) && u_out <= std::min(a.upper, b.upper);
        }();
        EXPECT_FALSE(in_ok && out_ok)
            << "station " << k << " could go faster: v " << p.v[k - 1] << " " << p.v[k] << " "
            << p.v[k + 1] << " vmax " << p.v_max[k] << " a " << p.a[k - 1] << " " << p.a[k]
            << " ctrl " << to_string(p.control[k - 1]) << " " << to_string(p.control[k]) << " n "
            << p.v.size();
      }
    }
  }
  EXPECT_GE(solved, 6);
}

/// Every field of two results, compared bit for bit.
void expect_identical(const TimeOptimalProfile& a, const TimeOptimalProfile& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(std::memcmp(&a.travel_time, &b.travel_time, sizeof(double)), 0);
  EXPECT_EQ(a.s, b.s);
  EXPECT_EQ(a.v, b.v);
  EXPECT_EQ(a.a, b.a);
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.v_max, b.v_max);
  EXPECT_EQ(a.binding, b.binding);
  EXPECT_EQ(a.control, b.control);
  ASSERT_EQ(a.switching_points.size(), b.switching_points.size());
  for (std::size_t k = 0; k < a.switching_points.size(); ++k) {
    EXPECT_EQ(a.switching_points[k].station, b.switching_points[k].station);
    EXPECT_EQ(a.switching_points[k].s, b.switching_points[k].s);
    EXPECT_EQ(a.switching_points[k].from, b.switching_points[k].from);
    EXPECT_EQ(a.switching_points[k].to, b.switching_points[k].to);
  }
  EXPECT_EQ(a.infeasible_station, b.infeasible_station);
  EXPECT_EQ(a.infeasible_binding, b.infeasible_binding);
  EXPECT_EQ(a.merged_stations, b.merged_stations);
}

TEST(TimeOptimalProfile, AReusedResultIsBitIdenticalToFreshSolves) {
  // Three different solves into one result object, longest first (the later ones must not
  // inherit tails, switching points or failure fields), against fresh solves with fresh solvers.
  const BPatch hills = BPatch::interpolate(grid_from_function(
      [](double x, double y) { return 1.5 * std::sin(0.2 * x) * std::cos(0.25 * y); }, 0, -10, 80,
      10, 1.0));
  const BPatch ridge = BPatch::interpolate(grid_from_function(
      [](double x, double y) { return (x > 20 && x < 40) ? 0.9 * y : 0.0; }, 0, -5, 60, 5, 0.5));
  const SurfacePath winding(hills, Curve2::interpolate({Vec2(5, 0), Vec2(25, 6), Vec2(45, -6),
                                                        Vec2(60, 4), Vec2(75, 0)}));
  const SurfacePath blocked(ridge, Curve2::interpolate({Vec2(5, 0), Vec2(55, 0)}));
  const SurfacePath short_one(hills, Curve2::interpolate({Vec2(10, -2), Vec2(30, 3)}));
  const Vehicle v = vehicle(0.7, 3.0, 5.0, 12.0);
  const VelocityLimits first(v, winding, 1500), second(vehicle(0.6), blocked, 201),
      third(v, short_one, 90);
  const ProfileOptions rest{}, moving{2.0, 1.0};
  TimeOptimalProfileSolver reused_solver;
  TimeOptimalProfile reused;
  reused_solver.solve(first, rest, reused);
  expect_identical(reused, TimeOptimalProfileSolver().solve(first, rest));
  EXPECT_EQ(reused.status, ProfileStatus::kOk);
  EXPECT_FALSE(reused.switching_points.empty());
  reused_solver.solve(second, rest, reused);
  expect_identical(reused, TimeOptimalProfileSolver().solve(second, rest));
  EXPECT_EQ(reused.status, ProfileStatus::kInfeasible);
  reused_solver.solve(third, moving, reused);
  expect_identical(reused, TimeOptimalProfileSolver().solve(third, moving));
  EXPECT_EQ(reused.status, ProfileStatus::kOk);
  EXPECT_EQ(reused.v.size(), 90u);
}

TEST(TrajectoryDefaults, SameRelativeErrorOnAOneMetreAndAFifteenKilometreGrid) {
  // One grid of heights at 1 m cells and the same grid scaled by 15,000 in x, y and z (the Mars
  // MOLA cell size), one path scaled with it, a vehicle limited by friction and tip-over only
  // (no length or speed scale of its own besides the half-track, which is below both cells).
  // The default spacing's relative error against a 16 times finer spacing must agree within a
  // factor 2 (with an absolute spacing the 15 km copy would be 15,000 times finer and its error
  // near zero).
  const auto heights = [](double x, double y) {
    return 1.2 * std::sin(0.35 * x) * std::cos(0.3 * y) + 0.4 * std::sin(0.9 * y + 0.5 * x);
  };
  Vehicle v = vehicle(0.7);
  v.half_track = 0.6;
  v.cg_height = 0.5;
  std::vector<double> errors;
  for (const double scale : {1.0, 15000.0}) {
    const BPatch surface = BPatch::interpolate(grid_from_function(
        [&](double x, double y) { return scale * heights(x / scale, y / scale); }, 0, 0, 64 * scale,
        64 * scale, scale));
    std::vector<Vec2> points;
    for (const Vec2& p : {Vec2(8, 10), Vec2(25, 30), Vec2(40, 20), Vec2(56, 50)})
      points.push_back(scale * p);
    const Curve2 curve = Curve2::interpolate(points);
    const double spacing = default_station_spacing(surface, v);
    EXPECT_DOUBLE_EQ(spacing, 0.1 * scale);
    TrajectoryOptions fine;
    fine.station_spacing = spacing / 16.0;
    const Trajectory coarse = evaluate_trajectory(surface, v, curve, {});
    const Trajectory reference = evaluate_trajectory(surface, v, curve, fine);
    ASSERT_TRUE(coarse.feasible()) << coarse.message;
    ASSERT_TRUE(reference.feasible()) << reference.message;
    EXPECT_EQ(coarse.limits->size(), station_count(coarse.length(), spacing));
    errors.push_back(coarse.travel_time() / reference.travel_time() - 1.0);
  }
  ASSERT_GT(errors[0], 1e-5);  // the default spacing's error is measurable
  EXPECT_LT(errors[1] / errors[0], 2.0) << errors[0] << " vs " << errors[1];
  EXPECT_GT(errors[1] / errors[0], 0.5) << errors[0] << " vs " << errors[1];
}

}  // namespace
}  // namespace talus
