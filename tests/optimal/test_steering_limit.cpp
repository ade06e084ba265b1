// The steering limit (Vehicle::max_steering, issue #35 item 4): the vehicle file's key and its
// checks, the admissible set's `steering` binding at exactly tan(δ_max) / (2 l), a path that
// needs more steering than the vehicle has is refused by evaluate_trajectory (and one within it
// is not), the local stage keeps it as smooth constraints in both formulations (exact rows and
// derivatives; a U-turn ends at the limit and no tighter), and the simulation's tracker steers
// within the vehicle's own limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/trajectory_tracking.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "talus/optimal/path_time_objective.hpp"
#include "talus/optimal/trajectory.hpp"

namespace talus {
namespace {

/// The Iagnemma UGV with a 0.6 rad steering limit (2.53 1/m at its 0.27 m wheelbase).
Vehicle ugv() {
  Vehicle v = load_vehicle(std::string(TALUS_DATA_DIR) + "/vehicles/iagnemma_ugv.yaml");
  v.max_steering = 0.6;
  return v;
}

TEST(SteeringLimit, TheVehicleFileGivesItAndItsCurvature) {
  const Vehicle v = ugv();
  EXPECT_NEAR(v.max_curvature(), std::tan(0.6) / 0.27, 1e-12);  // 2.53 1/m
  const std::string base = "model: point_mass\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\n";
  EXPECT_TRUE(std::isinf(parse_vehicle(base, "t").max_curvature()));  // none: as before
  EXPECT_EQ(parse_vehicle(base + "half_wheelbase: 1.2\nmax_steering: 0.5\n", "s").max_steering,
            0.5);
  const Vehicle steered =
      parse_vehicle(base + "half_wheelbase: 1.2\nmax_steering: 0.5\n", "steered");
  EXPECT_NEAR(steered.max_curvature(), std::tan(0.5) / 2.4, 1e-12);
  // A point mass with a steering limit needs its wheelbase.
  try {
    parse_vehicle(base + "max_steering: 0.5\n", "nowheelbase.yaml");
    FAIL() << "accepted max_steering without half_wheelbase";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("half_wheelbase"), std::string::npos) << e.what();
  }
  // Another missing key is not blamed on a steering limit the file does not have.
  try {
    parse_vehicle("model: point_mass\ncg_height: 0.5\nhalf_track: 0.6\n", "nofriction.yaml");
    FAIL() << "accepted a file without friction";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("max_steering"), std::string::npos) << e.what();
  }
  for (const char* bad : {"0", "-0.3", "1.5708", "2", ".nan"})
    EXPECT_THROW(parse_vehicle(base + "half_wheelbase: 1\nmax_steering: " + bad + "\n", "bad"),
                 InputError)
        << bad;
}

TEST(SteeringLimit, AStationTurningTighterIsUntraversableNamedSteering) {
  const Vehicle v = ugv();
  const double k = v.max_curvature();
  // Flat ground, slow enough for friction: just inside the limit the turn has a speed limit,
  // just beyond it none, whichever way it turns.
  const SpeedLimits inside = speed_limits(v, {0.0, 0.999 * k, 0.0, 0.0, 1.0, 0.999 * k});
  EXPECT_TRUE(inside.traversable);
  EXPECT_NEAR(inside.v_max, std::sqrt(v.friction * v.gravity / (0.999 * k)), 1e-9);
  for (const double sign : {1.0, -1.0}) {
    const StationGeometry turn{0.0, sign * 1.001 * k, 0.0, 0.0, 1.0, sign * 1.001 * k};
    const SpeedLimits beyond = speed_limits(v, turn);
    EXPECT_FALSE(beyond.traversable);
    EXPECT_EQ(beyond.upper_binding, Constraint::kSteering);
    EXPECT_EQ(beyond.v_max, 0.0);
    EXPECT_TRUE(admissible_squared_speeds(v, turn).empty());
    // The measure is the curvature in plan: the same geodesic curvature from a straight line
    // in plan over a bump with a cross slope is not steering.
    EXPECT_TRUE(speed_limits(v, {0.0, sign * 1.001 * k, 0.0, 0.0, 1.0, 0.0}).traversable);
  }
  EXPECT_EQ(to_string(Constraint::kSteering), "steering");
  Vehicle free = v;
  free.max_steering = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(speed_limits(free, {0.0, 0.1, 0.0, 0.0, 1.0, 10.0 * k}).traversable);
}

/// Half a circle of radius r on flat ground between two straights.
Curve2 u_turn(double r) {
  std::vector<Curve2::Point> points;
  for (int i = 0; i <= 4; ++i) points.emplace_back(1.0 + 0.5 * i, 4.0);
  for (int i = 1; i < 16; ++i) {
    const double a = -M_PI / 2 + M_PI * i / 16.0;
    points.emplace_back(3.0 + r * std::cos(a), 4.0 + r + r * std::sin(a));
  }
  for (int i = 0; i <= 4; ++i) points.emplace_back(3.0 - 0.5 * i, 4.0 + 2.0 * r);
  return Curve2::interpolate(points);
}

TEST(SteeringLimit, APathNeedingMoreSteeringIsRefused) {
  const BPatch flat = BPatch::interpolate(ElevationGrid(9, 9, 1.0, 0.0, 0.0));
  const Vehicle v = ugv();  // minimum turning radius 0.395 m
  const Trajectory wide = evaluate_trajectory(flat, v, u_turn(0.6), TrajectoryOptions{});
  EXPECT_TRUE(wide.feasible()) << wide.message;
  const Trajectory tight = evaluate_trajectory(flat, v, u_turn(0.3), TrajectoryOptions{});
  ASSERT_FALSE(tight.feasible());
  EXPECT_EQ(tight.profile.infeasible_binding, Constraint::kSteering);
  EXPECT_NE(tight.message.find("steering"), std::string::npos) << tight.message;
  Vehicle free = v;  // without a steering limit the same turn is driven slowly
  free.max_steering = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(evaluate_trajectory(flat, free, u_turn(0.3), TrajectoryOptions{}).feasible());
}

// A lattice-like corridor that leaves the start with a right-angle kink: the 16-point fit
// follows the kink tighter than the UGV steers; the fit then gets fewer control points (not
// more, as for a winding corridor) until it turns within the limit.
TEST(SteeringLimit, AFitTurningTooTightlyGetsFewerControlPoints) {
  const BPatch flat = BPatch::interpolate(ElevationGrid(13, 13, 1.0, 0.0, 0.0));
  std::vector<Vec2> corridor = {Vec2(1.0, 1.0), Vec2(1.24, 1.0)};
  for (int i = 1; i <= 10; ++i) corridor.emplace_back(1.24, 1.0 + 0.24 * i);
  PathOptimizerOptions options;
  Vehicle free = ugv();
  free.max_steering = std::numeric_limits<double>::infinity();
  const InitialPath loose = fit_initial_path(flat, free, corridor, options);
  ASSERT_TRUE(loose.admissible()) << loose.failure;
  EXPECT_EQ(loose.control_points, options.control_points);
  const InitialPath steered = fit_initial_path(flat, ugv(), corridor, options);
  EXPECT_TRUE(steered.admissible()) << steered.failure;
  EXPECT_LT(steered.control_points, options.control_points);
  // The 16-point fit itself needed more steering than the UGV has.
  options.adaptive_control_points = false;
  const InitialPath fixed = fit_initial_path(flat, ugv(), corridor, options);
  EXPECT_FALSE(fixed.admissible());
  EXPECT_NE(fixed.failure.find("steering"), std::string::npos) << fixed.failure;
}

TEST(SteeringLimit, TheTrackerSteersWithinTheVehiclesLimit) {
  Vehicle v = ugv();
  TrackingOptions o;
  EXPECT_EQ(tracking_steering_limit(o, v), 0.6);
  v.max_steering = 0.35;
  EXPECT_EQ(tracking_steering_limit(o, v), 0.35);
  v.max_steering = std::numeric_limits<double>::infinity();
  EXPECT_EQ(tracking_steering_limit(o, v), kDefaultTrackingSteering);
  o.max_steering = 0.2;  // an explicit option wins
  EXPECT_EQ(tracking_steering_limit(o, v), 0.2);
  // Driven round a turn too tight for a 0.35 rad limit, the tracker never commands more.
  const BPatch flat = BPatch::interpolate(ElevationGrid(9, 9, 1.0, 0.0, 0.0));
  v.max_steering = 0.35;
  ReferenceTrajectory r;
  for (int i = 0; i <= 40; ++i) {
    const double a = -M_PI / 2 + M_PI * i / 40.0;
    r.points.emplace_back(3.0 + 0.5 * std::cos(a), 4.5 + 0.5 * std::sin(a));
    r.speed.push_back(0.5);
  }
  TrackingOptions drive;
  drive.simulation.output_interval = 0.01;
  const TrackingResult result = track_trajectory(flat, v, r, drive);
  double peak = 0.0;
  for (const VehicleSample& s : result.simulation.trace)
    peak = std::max(peak, std::abs(s.controls.steering));
  EXPECT_GT(peak, 0.3) << result.brief_report();  // the turn needed the whole lock
  EXPECT_LE(peak, 0.35 + 1e-12);
}

// The steering rows of the nested formulation: κ at every station against the curve's own
// curvature, and their derivatives against central differences.
TEST(SteeringLimit, TheCurvatureRowsAndTheirDerivativesAreExact) {
  const BPatch flat = BPatch::interpolate(ElevationGrid(13, 13, 1.0, 0.0, 0.0));
  const std::vector<Vec2> control = {Vec2(1, 1), Vec2(3, 1.5), Vec2(5, 4),  Vec2(4, 7),
                                     Vec2(7, 8), Vec2(9, 6),   Vec2(10, 10)};
  PathTimeObjective objective(flat, ugv(), control.front(), control.back(), control.size(), 41,
                              ProfileOptions{});
  const Eigen::VectorXd z = objective.variables(control);
  const std::size_t n = objective.curvature_samples();
  EXPECT_EQ(n, PathTimeObjective::kCurvatureSamplesPerSpan * (control.size() - 3) + 1);
  const auto& pattern = objective.curvature_pattern();
  std::vector<double> kappa(n), jacobian(pattern.size());
  ASSERT_TRUE(objective.curvatures(z, kappa.data(), jacobian.data()));
  const Curve2 curve = objective.curve(z);
  for (std::size_t k = 0; k < n; ++k) {
    const double u = curve.parameter_begin() + (curve.parameter_end() - curve.parameter_begin()) *
                                                   static_cast<double>(k) / (n - 1);
    Curve2::Derivatives d;
    curve.derivatives(u, 2, d);
    const Vec2 d1 = d.col(1), d2 = d.col(2);
    EXPECT_NEAR(kappa[k], (d1.x() * d2.y() - d1.y() * d2.x()) / std::pow(d1.norm(), 3), 1e-9);
  }
  std::vector<double> plus(n), minus(n);
  for (std::size_t e = 0; e < pattern.size(); ++e) {
    Eigen::VectorXd probe = z;
    const double h = 1e-6;
    probe[pattern[e].second] += h;
    objective.curvatures(probe, plus.data(), nullptr);
    probe[pattern[e].second] -= 2 * h;
    objective.curvatures(probe, minus.data(), nullptr);
    const std::size_t row = static_cast<std::size_t>(pattern[e].first);
    EXPECT_NEAR(jacobian[e], (plus[row] - minus[row]) / (2 * h), 1e-5) << e;
  }
  // Every variable a station's curvature depends on is in the pattern: moving any other
  // leaves the row unchanged.
  for (long c = 0; c < z.size(); ++c) {
    Eigen::VectorXd probe = z;
    probe[c] += 0.1;
    objective.curvatures(probe, plus.data(), nullptr);
    for (std::size_t k = 0; k < n; ++k) {
      const bool listed = std::any_of(pattern.begin(), pattern.end(), [&](const auto& p) {
        return p.first == static_cast<long>(k) && p.second == c;
      });
      if (!listed) {
        EXPECT_EQ(plus[k], kappa[k]) << k << " " << c;
      }
    }
  }
}

// A U-turn between lanes 6 m apart, both headings pinned, for a vehicle whose tightest turn
// (1.67 m radius) is wider than half the lanes' distance would need: the shortest turn is
// Dubins' left-straight-left at the limit, and the fastest at these speeds turns at the limit
// too. The local stage (Ipopt, the steering rows) ends with the path at the limit within the
// rows' margin, and the path is within it at the evaluation's finer stations; without a
// limit the same corridor turns tighter.
TEST(SteeringLimit, TheLocalStageTurnsAtTheLimitAndNoTighter) {
  const BPatch flat = BPatch::interpolate(ElevationGrid(21, 21, 1.0, 0.0, 0.0));
  Vehicle v = ugv();
  v.max_steering = std::atan(0.6 * 0.27);  // 0.6 1/m
  std::vector<Vec2> corridor;              // a half circle of radius 3 m, from heading east to west
  for (int i = 0; i <= 24; ++i) {
    const double t = -M_PI / 2 + M_PI * i / 24.0;
    corridor.emplace_back(4.0 + 3.0 * std::cos(t), 10.0 + 3.0 * std::sin(t));
  }
  PathOptimizerOptions options;
  options.start_heading = 0.0;
  options.goal_heading = M_PI;
  options.restarts = 0;
  options.max_iterations = 300;
  options.max_evaluations = 3000;
  const auto sharpest = [&](const Vehicle& vehicle, const Curve2& curve) {
    const Trajectory t = evaluate_trajectory(flat, vehicle, curve, TrajectoryOptions{});
    EXPECT_TRUE(t.feasible()) << t.message;
    double k = 0.0;
    for (std::size_t i = 0; t.limits && i < t.limits->size(); ++i)
      k = std::max(k, std::abs(t.limits->geometry(i).kappa_planar));
    return k;
  };
  const OptimizedPath steered = optimize_path(flat, v, corridor, options);
  EXPECT_LT(steered.travel_time, 0.95 * steered.initial_time);
  const double kappa = sharpest(v, steered.curve);
  EXPECT_LE(kappa, v.max_curvature());
  EXPECT_GE(kappa, (1.0 - 2 * PathTimeObjective::kSteeringMargin) * v.max_curvature());
  Vehicle free = v;
  free.max_steering = std::numeric_limits<double>::infinity();
  EXPECT_GT(sharpest(free, optimize_path(flat, free, corridor, options).curve),
            1.5 * v.max_curvature());
  // The simultaneous formulation's steering rows: the same turn at the limit, from a fit with
  // as many control points as the nested formulation's (the 16-point fit turns too tightly
  // where the headings pin it).
  options.formulation = PathFormulation::kSimultaneous;
  options.control_points = steered.control_points;
  const OptimizedPath together = optimize_path(flat, v, corridor, options);
  const double kappa_together = sharpest(v, together.curve);
  EXPECT_LE(kappa_together, v.max_curvature());
  EXPECT_GE(kappa_together, (1.0 - 2 * PathTimeObjective::kSteeringMargin) * v.max_curvature());
  EXPECT_LT(together.travel_time, 1.01 * steered.travel_time);
}

}  // namespace
}  // namespace talus
