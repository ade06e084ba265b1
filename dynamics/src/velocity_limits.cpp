#include "talus/dynamics/velocity_limits.hpp"

#include <cmath>

namespace talus {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kCurvatureEpsilon = 1e-12;  // [1/m]: see the header

/// {x >= 0 : alpha x + beta >= 0}.
SquaredSpeedInterval linear_condition(double alpha, double beta) {
  if (std::abs(alpha) < kCurvatureEpsilon) alpha = 0.0;
  SquaredSpeedInterval out;
  if (alpha > 0.0) {
    out.lower = beta >= 0.0 ? 0.0 : -beta / alpha;
  } else if (alpha < 0.0) {
    out.upper = beta / -alpha;  // negative (empty) when beta < 0
    if (out.upper < 0.0) out.lower = kInfinity;
  } else if (beta < 0.0) {
    out.lower = kInfinity;  // empty
    out.upper = 0.0;
  }
  return out;
}

SquaredSpeedInterval intersect(const SquaredSpeedInterval& a, const SquaredSpeedInterval& b) {
  return {std::max(a.lower, b.lower), std::min(a.upper, b.upper)};
}

/// |f_q| <= m R as the intersection of its two linear conditions.
SquaredSpeedInterval lateral_ratio_condition(double m, double g, const StationGeometry& s) {
  return intersect(linear_condition(m * s.kappa_n - s.kappa_g, g * (m * s.k_r - s.k_q)),
                   linear_condition(m * s.kappa_n + s.kappa_g, g * (m * s.k_r + s.k_q)));
}

}  // namespace

std::string_view to_string(Constraint constraint) {
  switch (constraint) {
    case Constraint::kNone:
      return "none";
    case Constraint::kSliding:
      return "sliding";
    case Constraint::kTipover:
      return "tipover";
    case Constraint::kContact:
      return "contact";
    case Constraint::kMaxSpeed:
      return "max_speed";
    case Constraint::kPitchover:
      return "pitchover";
    case Constraint::kDrive:
      return "drive";
    case Constraint::kBrake:
      return "brake";
  }
  return "unknown";
}

SpeedLimits speed_limits(const Vehicle& vehicle, const StationGeometry& g) {
  const double gravity = vehicle.gravity;
  SpeedLimits out;
  out.sliding = lateral_ratio_condition(vehicle.friction, gravity, g);
  out.tipover = lateral_ratio_condition(vehicle.half_track / vehicle.cg_height, gravity, g);
  out.contact = linear_condition(g.kappa_n, gravity * g.k_r);
  const SquaredSpeedInterval speed{0.0, vehicle.max_speed * vehicle.max_speed};

  struct Candidate {
    Constraint constraint;
    const SquaredSpeedInterval* interval;
  };
  // Contact comes first: the sliding and tip-over intervals always lie inside
  // the contact interval, so they only tie with it where the lateral force
  // vanishes, and there the vehicle is really leaving the ground.
  const Candidate candidates[] = {{Constraint::kContact, &out.contact},
                                  {Constraint::kSliding, &out.sliding},
                                  {Constraint::kTipover, &out.tipover},
                                  {Constraint::kMaxSpeed, &speed}};
  double lower = 0.0, upper = kInfinity;
  // A later constraint takes over only if it is tighter by more than rounding,
  // so ties (equal up to 1e-12 relative) go to the first in the list.
  constexpr double kTie = 1e-12;
  for (const Candidate& c : candidates) {
    if (c.interval->lower > lower * (1.0 + kTie)) {
      lower = c.interval->lower;
      out.lower_binding = c.constraint;
    }
    if (c.interval->upper < upper * (1.0 - kTie)) {
      upper = c.interval->upper;
      out.upper_binding = c.constraint;
    }
  }
  for (const Candidate& c : candidates) {
    if (c.interval->empty()) {  // a constraint that no speed satisfies names the failure
      out.upper_binding = c.constraint;
      out.lower_binding = c.constraint;
      lower = kInfinity;
      break;
    }
  }
  if (!(lower <= upper)) {
    out.traversable = false;
    out.v_min = out.v_max = 0.0;
    return out;
  }
  out.v_min = std::sqrt(lower);
  out.v_max = std::sqrt(upper);
  return out;
}

SquaredSpeedInterval admissible_squared_speeds(const Vehicle& vehicle, const StationGeometry& g) {
  // With R >= 0 (which both conditions of a pair imply), |f_q| <= mu R and
  // |f_q| <= (b/h) R together are |f_q| <= min(mu, b/h) R; contact follows.
  const double ratio = std::min(vehicle.friction, vehicle.half_track / vehicle.cg_height);
  SquaredSpeedInterval out = lateral_ratio_condition(ratio, vehicle.gravity, g);
  out.upper = std::min(out.upper, vehicle.max_speed * vehicle.max_speed);
  return out;
}

AccelerationBounds acceleration_bounds(const Vehicle& vehicle, const StationGeometry& g,
                                       double speed) {
  const double x = speed * speed;
  const double f_q = vehicle.gravity * g.k_q + g.kappa_g * x;
  const double normal = vehicle.gravity * g.k_r + g.kappa_n * x;
  AccelerationBounds out;
  // A speed exactly on the limit curve, computed in floating point, may sit a
  // few ulps outside it; kOnLimit keeps such states admissible.
  constexpr double kOnLimit = 1e-10;
  const double scale = vehicle.gravity + std::abs(g.kappa_n * x) + std::abs(g.kappa_g * x);
  if (!(normal >= -kOnLimit * scale)) {
    out.violated = Constraint::kContact;
    return out;
  }
  if (std::abs(f_q) > vehicle.half_track / vehicle.cg_height * normal + kOnLimit * scale) {
    out.violated = Constraint::kTipover;
    return out;
  }
  const double friction_force = vehicle.friction * std::max(normal, 0.0);
  double slack = friction_force * friction_force - f_q * f_q;
  if (!(slack >= -kOnLimit * scale * scale)) {
    out.violated = Constraint::kSliding;
    return out;
  }
  slack = std::max(slack, 0.0);
  if (speed > vehicle.max_speed * (1.0 + 1e-12)) {
    out.violated = Constraint::kMaxSpeed;
    return out;
  }
  // Bounds on f_t, then s̈ = f_t − g k_t.
  double upper = std::sqrt(slack), lower = -upper;
  out.upper_binding = out.lower_binding = Constraint::kSliding;
  if (vehicle.model == VehicleModel::kRigidBody) {
    const double pitch = vehicle.half_wheelbase / vehicle.cg_height * std::max(normal, 0.0);
    if (pitch < upper) {
      upper = pitch;
      lower = -pitch;
      out.upper_binding = out.lower_binding = Constraint::kPitchover;
    }
  }
  if (vehicle.max_accel < upper) {
    upper = vehicle.max_accel;
    out.upper_binding = Constraint::kDrive;
  }
  if (-vehicle.max_decel > lower) {
    lower = -vehicle.max_decel;
    out.lower_binding = Constraint::kBrake;
  }
  const double weight = vehicle.gravity * g.k_t;
  out.a_min = lower - weight;
  out.a_max = upper - weight;
  out.feasible = true;
  return out;
}

}  // namespace talus
