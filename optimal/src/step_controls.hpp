#pragma once
// The closed-form heart of the time-optimal profile: the admissible constant
// tangential accelerations u of one step when one end's state is known.
//
// Along the step the state x = ṡ² is affine in u: at the known end it is
// fixed, at the other end it is y0 + beta u (beta = ±2 Δs). The admissible
// set of (x, u) at a station is convex (friction ellipse = second-order cone,
// the rest linear; see dynamics/DERIVATION.md), so its intersection with that
// line is one interval of u, found from one quadratic and a few linear
// inequalities. No iteration, no polygonal approximation.
#include <cmath>
#include <limits>

#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"

namespace talus::detail {

inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();
/// Relative slack granted to every bound for floating-point rounding: states
/// computed on the boundary of the admissible set (a braking curve, the limit
/// curve) come out 1e-12 .. 1e-11 outside it, and must stay admissible.
inline constexpr double kRounding = 1e-10;

/// An interval of u; empty when lower > upper.
struct ControlInterval {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool empty() const { return !(lower <= upper); }
  /// Keeps {u : c0 + c1 u >= 0}.
  void require_nonnegative(double c0, double c1) {
    if (c1 > 0.0) {
      lower = std::max(lower, -c0 / c1);
    } else if (c1 < 0.0) {
      upper = std::min(upper, c0 / -c1);
    } else if (c0 < 0.0) {
      lower = std::numeric_limits<double>::infinity();
    }
  }
  void intersect(double lo, double hi) {
    lower = std::max(lower, lo);
    upper = std::min(upper, hi);
  }
};

/// Vehicle constants the step solver needs, precomputed once.
struct VehicleConstants {
  double g, mu, tip;
  double lateral;  // min(mu, b/h): |f_q| <= lateral R covers sliding's lateral part and tip-over
  double pitch, drive, brake;  // pitch = l/h (inf for a point mass)
  explicit VehicleConstants(const Vehicle& v)
      : g(v.gravity),
        mu(v.friction),
        tip(v.half_track / v.cg_height),
        lateral(std::min(v.friction, v.half_track / v.cg_height)),
        pitch(v.model == VehicleModel::kRigidBody ? v.half_wheelbase / v.cg_height
                                                  : std::numeric_limits<double>::infinity()),
        drive(v.max_accel),
        brake(v.max_decel) {}
};

/// The u such that the station with geometry `s`, at state x = y0 + beta u,
/// has (x, u) admissible and x in [x_lower, x_upper]. Tolerances: the
/// quadratic's roots are widened by `slack` (relative) so that a state exactly
/// on the limit curve, computed in floating point, stays admissible.
inline ControlInterval admissible_controls(const VehicleConstants& c, const StationGeometry& s,
                                           double y0, double beta, double x_lower, double x_upper) {
  ControlInterval out;
  // State bounds on y0 + beta u, widened by rounding: a state pinned to one
  // value (the end speed, a boundary of the controllable set) must not come
  // out as an empty interval one ulp wide.
  out.require_nonnegative(y0 - x_lower, beta);
  if (std::isfinite(x_upper)) out.require_nonnegative(x_upper - y0, -beta);
  if (beta != 0.0) {
    const double widen = kRounding * (1.0 + std::abs(out.lower == -kUnbounded ? 0.0 : out.lower) +
                                      std::abs(out.upper == kUnbounded ? 0.0 : out.upper));
    out.lower -= widen;
    out.upper += widen;
  }
  // Affine forces: R = R0 + R1 u, f_q = Q0 + Q1 u, f_t = u + T0.
  const double R0 = c.g * s.k_r + s.kappa_n * y0, R1 = s.kappa_n * beta;
  const double Q0 = c.g * s.k_q + s.kappa_g * y0, Q1 = s.kappa_g * beta;
  const double T0 = c.g * s.k_t;
  // |f_q| <= min(mu, b/h) R: tip-over and the lateral part of sliding at
  // once; together they also imply contact (R >= 0).
  out.require_nonnegative(c.lateral * R0 - Q0, c.lateral * R1 - Q1);
  out.require_nonnegative(c.lateral * R0 + Q0, c.lateral * R1 + Q1);
  if (std::isfinite(c.pitch)) {  // |f_t| <= (l/h) R
    out.require_nonnegative(c.pitch * R0 - T0, c.pitch * R1 - 1.0);
    out.require_nonnegative(c.pitch * R0 + T0, c.pitch * R1 + 1.0);
  }
  out.intersect(-c.brake - T0, c.drive - T0);  // traction force limits
  if (out.empty()) return out;
  // Friction ellipse: (u + T0)^2 + (Q0 + Q1 u)^2 - mu^2 (R0 + R1 u)^2 <= 0.
  const double m2 = c.mu * c.mu;
  const double a = 1.0 + Q1 * Q1 - m2 * R1 * R1;
  const double b = 2.0 * (T0 + Q0 * Q1 - m2 * R0 * R1);
  const double k = T0 * T0 + Q0 * Q0 - m2 * R0 * R0;
  const double scale = std::max({std::abs(T0), std::abs(Q0), c.mu * std::abs(R0), 1e-300});
  const double disc = b * b - 4.0 * a * k;
  if (a > 0.0) {
    if (disc < -kRounding * scale * scale * std::max(a, 1.0)) {
      out.lower = std::numeric_limits<double>::infinity();
      return out;
    }
    // Stable roots: q = -(b + sign(b) sqrt(disc)) / 2, roots q/a and k/q.
    const double root = std::sqrt(std::max(disc, 0.0));
    const double q = -0.5 * (b + std::copysign(root, b));
    double r1 = q / a, r2 = (q != 0.0) ? k / q : r1;
    if (r1 > r2) std::swap(r1, r2);
    const double widen = kRounding * (1.0 + std::abs(r1) + std::abs(r2));
    out.intersect(r1 - widen, r2 + widen);
  } else if (a == 0.0) {
    out.require_nonnegative(-k, -b);
  } else {
    // a < 0: the line crosses both nappes of the cone; the contact and
    // lateral conditions above already keep u on the R >= 0 nappe, where the
    // solution set is the outer piece (-inf, r1] or [r2, inf) that they touch.
    if (disc > 0.0) {
      const double root = std::sqrt(disc);
      const double q = -0.5 * (b + std::copysign(root, b));
      double r1 = q / a, r2 = (q != 0.0) ? k / q : r1;
      if (r1 > r2) std::swap(r1, r2);
      const double widen = kRounding * (1.0 + std::abs(r1) + std::abs(r2));
      if (out.upper <= r1 + widen) {
        // already inside the lower piece
      } else if (out.lower >= r2 - widen) {
        // already inside the upper piece
      } else if (out.lower <= r1 + widen) {
        out.upper = std::min(out.upper, r1 + widen);
      } else {
        out.lower = std::max(out.lower, r2 - widen);
      }
    }
  }
  return out;
}

/// The u admissible at a station whose state x is known: the beta = 0 case
/// of admissible_controls, without the line algebra (half the cost).
inline ControlInterval known_state_controls(const VehicleConstants& c, const StationGeometry& s,
                                            double x) {
  ControlInterval out;
  const double R = c.g * s.k_r + s.kappa_n * x, Q = c.g * s.k_q + s.kappa_g * x;
  const double T0 = c.g * s.k_t;
  const double scale = c.g + std::abs(s.kappa_n * x) + std::abs(s.kappa_g * x);
  if (std::abs(Q) > c.lateral * R + kRounding * scale) {  // tip-over, lateral sliding, contact
    out.lower = kUnbounded;
    return out;
  }
  const double friction = c.mu * std::max(R, 0.0);
  const double half_width = std::sqrt(std::max(friction * friction - Q * Q, 0.0));
  double upper = std::min(half_width, c.drive), lower = std::max(-half_width, -c.brake);
  if (std::isfinite(c.pitch)) {
    const double pitch = c.pitch * std::max(R, 0.0);
    upper = std::min(upper, pitch);
    lower = std::max(lower, -pitch);
  }
  const double widen = kRounding * (1.0 + std::abs(T0) + half_width);
  out.lower = lower - T0 - widen;
  out.upper = upper - T0 + widen;
  return out;
}

}  // namespace talus::detail
