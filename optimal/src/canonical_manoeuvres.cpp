#include "talus/optimal/canonical_manoeuvres.hpp"

#include "talus/dynamics/admissible_set.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/terrain_generators.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kCellSize = 0.25;  // [m]: fine enough for the UGV's 0.27 m wheelbase
constexpr double kCircleRadius = 2.0;
constexpr double kBankSlope = 0.2;  // tan θ of the banked circle
constexpr double kHillHeight = 0.4, kHillWidth = 1.0;
constexpr double kSlalomHalfAmplitude = 0.4;   // B [m]: the path swings 0 .. 2 B sideways
constexpr double kSlalomCurvatureShare = 0.9;  // apex curvature / the steering limit
constexpr int kSlalomPeriods = 2;

GridShape grid(double width, double height) {
  GridShape g;
  g.cellsize = kCellSize;
  g.ncols = static_cast<std::size_t>(std::lround(width / kCellSize)) + 1;
  g.nrows = static_cast<std::size_t>(std::lround(height / kCellSize)) + 1;
  return g;
}

/// Points every ~0.5 m from a to b, a included, b excluded.
void append_straight(std::vector<Curve2::Point>& points, const Vec2& a, const Vec2& b) {
  const auto n = std::max<long>(1, std::lround((b - a).norm() / 0.5));
  for (long i = 0; i < n; ++i) points.push_back(a + (b - a) * (static_cast<double>(i) / n));
}

/// Lead-in along y = 12 − R from x = 3 to 12, 1.5 laps anticlockwise round (12, 12), run-out
/// along y = 12 + R back to x = 4: 9 m + 6 π R + 8 m.
Curve2 circle_path(double& key_from, double& key_to) {
  const Vec2 centre(12.0, 12.0);
  const double r = kCircleRadius;
  std::vector<Curve2::Point> points;
  append_straight(points, Vec2(3.0, 12.0 - r), Vec2(12.0, 12.0 - r));
  const int per_lap = 32;
  for (int i = 0; i < 3 * per_lap / 2; ++i) {
    const double a = -0.5 * kPi + 2.0 * kPi * i / per_lap;
    points.push_back(centre + r * Vec2(std::cos(a), std::sin(a)));
  }
  append_straight(points, Vec2(12.0, 12.0 + r), Vec2(4.0, 12.0 + r));
  points.push_back(Vec2(4.0, 12.0 + r));
  // The middle lap, clear of the entry and exit transients.
  key_from = 9.0 + 0.25 * 2.0 * kPi * r;
  key_to = 9.0 + 1.25 * 2.0 * kPi * r;
  return Curve2::interpolate(points);
}

/// A straight path along y = y0 from x0 to x1 (collinear points: the interpolant is exact).
Curve2 straight_path(double x0, double x1, double y0) {
  std::vector<Curve2::Point> points;
  append_straight(points, Vec2(x0, y0), Vec2(x1, y0));
  points.push_back(Vec2(x1, y0));
  return Curve2::interpolate(points);
}

/// Lead-in along y = 4 from x = 2 to 5, `kSlalomPeriods` periods of
/// y = 4 + B (1 − cos k (x − 5)), run-out to 4 m beyond. The key section is the
/// middle apex (u = 2π/k, curving like the entry), ±0.05 m of planar arc length.
Curve2 slalom_path(double k, double& key_from, double& key_to, double& width) {
  const double x0 = 5.0, wavelength = 2.0 * kPi / k;
  const double x1 = x0 + kSlalomPeriods * wavelength;
  std::vector<Curve2::Point> points;
  append_straight(points, Vec2(2.0, 4.0), Vec2(x0, 4.0));
  const auto y = [&](double x) {
    return 4.0 + kSlalomHalfAmplitude * (1.0 - std::cos(k * (x - x0)));
  };
  const int per_period = 24;
  for (int i = 0; i < kSlalomPeriods * per_period; ++i) {
    const double x = x0 + wavelength * i / per_period;
    points.push_back(Vec2(x, y(x)));
  }
  append_straight(points, Vec2(x1, 4.0), Vec2(x1 + 4.0, 4.0));
  points.push_back(Vec2(x1 + 4.0, 4.0));
  // Planar arc length to the middle apex, from the analytic curve (the
  // interpolant matches it to well under the window).
  double apex = x0 - 2.0;
  const int steps = 4000;
  const double x_apex = x0 + wavelength;
  for (int i = 0; i < steps; ++i) {
    const double a = x0 + (x_apex - x0) * i / steps, b = x0 + (x_apex - x0) * (i + 1) / steps;
    apex += std::hypot(b - a, y(b) - y(a));
  }
  key_from = apex - 0.05;
  key_to = apex + 0.05;
  width = x1 + 6.0;
  return Curve2::interpolate(points);
}

void require_finite_drive(const Vehicle& v, CanonicalManoeuvre m) {
  if (!std::isfinite(v.max_accel) || !std::isfinite(v.max_decel))
    throw InputError(std::string("make_canonical_manoeuvre(") + std::string(to_string(m)) +
                     "): the vehicle needs a finite max_accel and max_decel");
}

}  // namespace

std::string_view to_string(CanonicalManoeuvre manoeuvre) {
  switch (manoeuvre) {
    case CanonicalManoeuvre::kFlatCircle:
      return "flat-circle";
    case CanonicalManoeuvre::kBankedCircle:
      return "banked-circle";
    case CanonicalManoeuvre::kCrest:
      return "crest";
    case CanonicalManoeuvre::kSideSlope:
      return "side-slope";
    case CanonicalManoeuvre::kStraightDriveBrake:
      return "straight-drive-brake";
    case CanonicalManoeuvre::kSlalom:
      return "slalom";
  }
  return "unknown";
}

std::vector<CanonicalManoeuvre> all_canonical_manoeuvres() {
  return {CanonicalManoeuvre::kFlatCircle,
          CanonicalManoeuvre::kBankedCircle,
          CanonicalManoeuvre::kCrest,
          CanonicalManoeuvre::kSideSlope,
          CanonicalManoeuvre::kStraightDriveBrake,
          CanonicalManoeuvre::kSlalom};
}

namespace {

/// A flat circle of radius 2 m.
ManoeuvreCase flat_circle_case(CanonicalManoeuvre manoeuvre, const Vehicle& vehicle) {
  const double g = vehicle.gravity, mu = vehicle.friction;
  PlaneOptions plane;
  plane.shape = grid(24.0, 24.0);
  double from = 0.0, to = 0.0;
  Curve2 path = circle_path(from, to);
  ManoeuvreCase c(manoeuvre, BPatch::interpolate(generate_plane(plane)), std::move(path));
  c.key_from = from;
  c.key_to = to;
  c.analytic_limit = std::sqrt(mu * g * kCircleRadius);
  c.description = "flat ground, a circle of radius 2 m: v = sqrt(mu g R)";
  return c;
}

/// A banked circle round the apex of a cone.
ManoeuvreCase banked_circle_case(CanonicalManoeuvre manoeuvre, const Vehicle& vehicle) {
  const double g = vehicle.gravity, mu = vehicle.friction;
  // A cone z = tan θ ρ round (12, 12): every horizontal circle is banked at θ, and the
  // lead-in and run-out climb no more steeply than θ (a bowl's walls steepen beyond
  // what the drive limit climbs from rest).
  ElevationGrid cone(grid(24.0, 24.0).ncols, grid(24.0, 24.0).nrows, kCellSize, 0.0, 0.0);
  for (std::size_t j = 0; j < cone.nrows(); ++j)
    for (std::size_t i = 0; i < cone.ncols(); ++i)
      cone.set(i, j, kBankSlope * (cone.node_position(i, j) - Vec2(12.0, 12.0)).norm());
  double from = 0.0, to = 0.0;
  Curve2 path = circle_path(from, to);
  ManoeuvreCase c(manoeuvre, BPatch::interpolate(cone), std::move(path));
  c.key_from = from;
  c.key_to = to;
  const double theta = std::atan(kBankSlope);
  const double denominator = std::cos(theta) - mu * std::sin(theta);
  if (!(denominator > 0.0))
    throw InputError("make_canonical_manoeuvre(banked-circle): mu tan(theta) >= 1, no limit");
  c.analytic_limit =
      std::sqrt(g * kCircleRadius * (std::sin(theta) + mu * std::cos(theta)) / denominator);
  c.description =
      "a horizontal circle of radius 2 m round the apex of the cone z = 0.2 rho (bank "
      "tan theta = 0.2): v^2 = g R (sin theta + mu cos theta) / (cos theta - mu sin theta)";
  return c;
}

/// Straight over the top of a Gaussian hill.
ManoeuvreCase crest_case(CanonicalManoeuvre manoeuvre, const Vehicle& vehicle) {
  const double g = vehicle.gravity;
  GaussianHillsOptions hills;
  hills.shape = grid(24.0, 12.0);
  hills.hills = {GaussianHill{Vec2(12.0, 6.0), kHillHeight, kHillWidth}};
  ManoeuvreCase c(manoeuvre, BPatch::interpolate(generate_gaussian_hills(hills)),
                  straight_path(2.0, 22.0, 6.0));
  // A rigid body over the top stands on its axles at x = ±l, where the section has
  // z'' = (H / σ²)(l² / σ² − 1) e^(−l²/2σ²) and slope z' = −(H l / σ²) e^(−l²/2σ²): its
  // chassis curvature is z'' / sqrt(1 + z'²) (wheel_contact.hpp; l = 0: the point mass).
  const double l = vehicle.model == VehicleModel::kRigidBody ? vehicle.half_wheelbase : 0.0;
  const double w2 = kHillWidth * kHillWidth, decay = std::exp(-l * l / (2.0 * w2));
  const double curvature = kHillHeight / w2 * (l * l / w2 - 1.0) * decay;
  const double slope = kHillHeight * l / w2 * decay;
  c.analytic_limit = std::sqrt(g * std::sqrt(1.0 + slope * slope) / -curvature);
  c.key_from = 9.9;  // the hill's top, x = 12
  c.key_to = 10.1;
  c.description =
      "straight over the top of a Gaussian hill 0.4 m high, sigma 1 m (crest radius "
      "sigma^2 / H = 2.5 m): v = sqrt(g sigma^2 / H) for a point mass; a rigid body's "
      "axles stand at x = +-l: v^2 = g sqrt(1 + z'(l)^2) / -z''(l)";
  return c;
}

/// Straight along the contour of a side slope at tan θ = 0.9 μ.
ManoeuvreCase side_slope_case(CanonicalManoeuvre manoeuvre, const Vehicle& vehicle) {
  const double g = vehicle.gravity, mu = vehicle.friction;
  if (!(mu > 0.0)) throw InputError("make_canonical_manoeuvre(side-slope): needs mu > 0");
  PlaneOptions plane;
  plane.shape = grid(20.0, 12.0);
  plane.slope = std::atan(0.9 * mu);
  plane.aspect = 0.5 * kPi;  // rises to the north: the path along x is on the contour
  ManoeuvreCase c(manoeuvre, BPatch::interpolate(generate_plane(plane)),
                  straight_path(3.0, 17.0, 6.0));
  const double theta = plane.slope;
  // Normal load R = g cos θ, lateral force Q = g sin θ per unit mass; |f_t| <= w on the friction
  // cone, w = sqrt(μ²R² − Q²); the rigid body judges friction at its lighter axle,
  // f_t² + 2 β |f_t| Q + Q² <= μ² R² (β = AdmissibleSet::friction_coupling, fitted inside the
  // axle's condition), whose root is w = (μ²R² − Q²) / (β Q + sqrt(μ²R² − (1 − β²) Q²)).
  const double R = g * std::cos(theta), Q = g * std::sin(theta);
  const double beta = AdmissibleSet(vehicle).friction_coupling();
  const double slack = mu * mu * R * R - Q * Q;
  const double bound = slack / (beta * Q + std::sqrt(slack + beta * beta * Q * Q));
  c.limit_kind = AnalyticLimitKind::kAcceleration;
  c.analytic_limit = std::min(bound, vehicle.planned_max_accel());
  c.analytic_brake_limit = std::min(bound, vehicle.planned_max_decel());
  c.key_from = 0.0;
  c.key_to = 14.0;
  c.description =
      "straight along the contour of a plane with tan theta = 0.9 mu: the tangential "
      "acceleration is bounded by g cos theta sqrt(mu^2 - tan^2 theta) both ways (a point mass; "
      "a rigid body at its lighter axle, f_t^2 + 2 beta |f_t| g sin theta + (g sin theta)^2 <= "
      "(mu g cos theta)^2)";
  return c;
}

/// Straight on flat ground, rest to rest.
ManoeuvreCase straight_drive_brake_case(CanonicalManoeuvre manoeuvre, const Vehicle& vehicle) {
  const double g = vehicle.gravity, mu = vehicle.friction;
  require_finite_drive(vehicle, manoeuvre);
  PlaneOptions plane;
  plane.shape = grid(20.0, 8.0);
  ManoeuvreCase c(manoeuvre, BPatch::interpolate(generate_plane(plane)),
                  straight_path(3.0, 17.0, 4.0));
  c.limit_kind = AnalyticLimitKind::kAcceleration;
  c.analytic_limit = std::min(vehicle.planned_max_accel(), mu * g);
  c.analytic_brake_limit = std::min(vehicle.planned_max_decel(), mu * g);
  c.key_from = 0.0;
  c.key_to = 14.0;
  c.description =
      "straight on flat ground, rest to rest: min((1 - drive_reserve) max_accel, mu g) and "
      "min((1 - drive_reserve) max_decel, mu g)";
  return c;
}

/// A slalom at 0.9 of the steering limit.
ManoeuvreCase slalom_case(CanonicalManoeuvre manoeuvre, const Vehicle& vehicle) {
  const double g = vehicle.gravity, mu = vehicle.friction;
  const double kappa_max = vehicle.max_curvature();
  if (!(kappa_max >= 0.05))
    throw InputError(
        "make_canonical_manoeuvre(slalom): the vehicle needs a steering limit (max_steering) "
        "of at least 0.05 1/m; it has " +
        std::to_string(kappa_max) + " 1/m");
  const double apex_curvature = kSlalomCurvatureShare * kappa_max;
  const double k = std::sqrt(apex_curvature / kSlalomHalfAmplitude);
  double from = 0.0, to = 0.0, width = 0.0;
  Curve2 path = slalom_path(k, from, to, width);
  PlaneOptions plane;
  plane.shape = grid(width, 8.0);
  ManoeuvreCase c(manoeuvre, BPatch::interpolate(generate_plane(plane)), std::move(path));
  c.key_from = from;
  c.key_to = to;
  c.analytic_limit = std::sqrt(mu * g / apex_curvature);
  c.description =
      "flat ground, a slalom y = B (1 - cos k u) with B = 0.4 m and apex curvature B k^2 = 0.9 "
      "of the steering limit: v = sqrt(mu g / (B k^2)) at each apex";
  return c;
}

}  // namespace

ManoeuvreCase make_canonical_manoeuvre(CanonicalManoeuvre manoeuvre, const Vehicle& vehicle) {
  vehicle.validate();
  switch (manoeuvre) {
    case CanonicalManoeuvre::kFlatCircle:
      return flat_circle_case(manoeuvre, vehicle);
    case CanonicalManoeuvre::kBankedCircle:
      return banked_circle_case(manoeuvre, vehicle);
    case CanonicalManoeuvre::kCrest:
      return crest_case(manoeuvre, vehicle);
    case CanonicalManoeuvre::kSideSlope:
      return side_slope_case(manoeuvre, vehicle);
    case CanonicalManoeuvre::kStraightDriveBrake:
      return straight_drive_brake_case(manoeuvre, vehicle);
    case CanonicalManoeuvre::kSlalom:
      return slalom_case(manoeuvre, vehicle);
  }
  throw InputError("make_canonical_manoeuvre: unknown manoeuvre");
}

ManoeuvreKeySection measure_key_section(const ManoeuvreCase& manoeuvre,
                                        const Trajectory& trajectory) {
  if (!trajectory.feasible() || trajectory.limits == nullptr)
    throw InputError("measure_key_section: the trajectory has no feasible profile");
  const VelocityLimits& limits = *trajectory.limits;
  ManoeuvreKeySection key;
  key.v_min = std::numeric_limits<double>::infinity();
  double planar = 0.0, v_sum = 0.0;
  for (std::size_t k = 0; k < limits.size(); ++k) {
    if (k > 0) {
      const Vec3 a = limits.frame(k - 1).point, b = limits.frame(k).point;
      planar += std::hypot(b.x() - a.x(), b.y() - a.y());
    }
    if (planar < manoeuvre.key_from || planar > manoeuvre.key_to) continue;
    const double v = trajectory.profile.v[k], a = trajectory.profile.a[k];
    ++key.stations;
    v_sum += v;
    key.v_min = std::min(key.v_min, v);
    key.v_max = std::max(key.v_max, v);
    key.accel_max = std::max(key.accel_max, a);
    key.decel_max = std::max(key.decel_max, -a);
  }
  if (key.stations == 0)
    throw InputError("measure_key_section: no station on the key section of " +
                     std::string(to_string(manoeuvre.manoeuvre)));
  key.v_mean = v_sum / static_cast<double>(key.stations);
  return key;
}

}  // namespace talus
