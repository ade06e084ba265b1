#include "talus/dynamics/admissible_set.hpp"

#include <cmath>
#include <stdexcept>

#include "talus/core/error.hpp"
#include "talus/dynamics/vehicle_physics.hpp"

namespace talus {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kCurvatureEpsilon = 1e-12;  // [1/m]: see velocity_limits.hpp

/// {x >= 0 : alpha x + beta >= 0}.
[[gnu::always_inline]] inline SquaredSpeedInterval linear_condition(double alpha, double beta) {
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

/// |f_q| <= m R as the intersection of its two linear conditions in x.
[[gnu::always_inline]] inline SquaredSpeedInterval lateral_pair(double m, double g,
                                                                const StationGeometry& s) {
  return intersect(linear_condition(m * s.kappa_n - s.kappa_g, g * (m * s.k_r - s.k_q)),
                   linear_condition(m * s.kappa_n + s.kappa_g, g * (m * s.k_r + s.k_q)));
}

/// A speed condition (t = 0) as alpha x + beta >= 0.
SquaredSpeedInterval speed_condition(const ForceCondition& c, double g, const StationGeometry& s) {
  double beta = g * (c.r * s.k_r + c.q * s.k_q);
  if (c.c != 0.0) beta += c.c;
  return linear_condition(c.r * s.kappa_n + c.q * s.kappa_g, beta);
}

/// Contact at the wheels: g k_r − reserve + κ_w x >= 0.
[[gnu::always_inline]] inline SquaredSpeedInterval wheel_contact(const StationGeometry& s, double g,
                                                                 double reserve) {
  return linear_condition(s.kappa_wheels, g * s.k_r - reserve);
}

/// Whether c is implied by |f_q| <= lambda R (which implies R >= 0).
bool implied_by_lateral(const ForceCondition& c, double lambda) {
  return c.t == 0.0 && c.c == 0.0 && c.r >= lambda * std::abs(c.q);
}

/// Half-width w of the tangential force interval |f_t| <= w at normal load R and lateral force
/// Q [m/s²] (0 where none is admissible, |Q| > μ R): the friction cone f_t² + Q² <= μ² R²
/// (beta = 0), or the lighter axle's f_t² + 2 beta |f_t Q| + Q² <= μ² R² (see
/// AdmissibleSet::friction_coupling), written without cancellation:
/// w = (μ²R² − Q²) / (beta |Q| + sqrt(μ²R² − (1 − beta²) Q²)).
[[gnu::always_inline]] inline double friction_half_width(double mu, double beta, double R,
                                                         double Q) {
  const double mR = mu * std::max(R, 0.0);
  const double slack = mR * mR - Q * Q;
  if (!(slack > 0.0)) return 0.0;
  if (beta == 0.0) return std::sqrt(slack);
  return slack / (beta * std::abs(Q) + std::sqrt(slack + beta * beta * Q * Q));
}

/// The smallest coupling beta (AdmissibleSet::friction_coupling) whose set
/// f_t² + 2 beta |f_t f_q| + f_q² <= μ² R² lies inside the lighter axle's condition
/// f_q² <= (R − tau |f_t|)² (μ² − f_t² / R²): by bisection on the section R = 1, checked at
/// 4,096 points a = |f_t| in (0, μ), plus 0.1 %. Both boundaries start at |f_q| = μ with
/// slopes −beta and −tau μ, and both end at |f_t| = μ, so beta >= tau μ. NaN when not even
/// beta = 1 (the square |f_t| + |f_q| <= μ R) fits: a vehicle with tau μ near 1 or above, whose
/// lighter axle unloads completely before the total force reaches μ R. About a millisecond:
/// lighter_axle_coupling() remembers it.
double fit_lighter_axle_coupling(double mu, double tau) {
  const auto inside = [&](double beta) {
    constexpr int kPoints = 4096;
    for (int i = 1; i < kPoints; ++i) {
      const double t = static_cast<double>(i) / kPoints;
      const double a = mu * (1.0 - t * t);
      const double q = std::sqrt(std::max(mu * mu - (1.0 - beta * beta) * a * a, 0.0)) - beta * a;
      const double axle = std::max(1.0 - tau * a, 0.0) * std::sqrt(std::max(mu * mu - a * a, 0.0));
      if (q > axle) return false;
    }
    return true;
  };
  double lo = tau * mu, hi = 1.0;
  if (!inside(hi)) return std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (inside(mid) ? hi : lo) = mid;
  }
  return std::min(1.0, hi * 1.001);
}

/// fit_lighter_axle_coupling(mu, tau), remembered per thread for the last few vehicles: an
/// AdmissibleSet is built per objective evaluation (the adjoint) and per one-off query, where
/// a millisecond's fit would dominate (a set is a microsecond without it).
double lighter_axle_coupling(double mu, double tau) {
  if (!(tau > 0.0)) return 0.0;
  struct Fit {
    double mu = std::numeric_limits<double>::quiet_NaN(), tau = 0.0, beta = 0.0;
  };
  thread_local std::array<Fit, 4> fits{};
  thread_local std::size_t next = 0;
  for (const Fit& f : fits)
    if (f.mu == mu && f.tau == tau) return f.beta;
  const double beta = fit_lighter_axle_coupling(mu, tau);
  fits[next] = {mu, tau, beta};
  next = (next + 1) % fits.size();
  return beta;
}

/// Keeps the u with f_t² + 2 c f_t f_q + f_q² <= μ² R² (f_t = u + T0, f_q = Q0 + Q1 u,
/// R = R0 + R1 u; c = 0 the friction cone, |c| < 1) on the nappe R >= 0, which the caller's
/// conditions already select (they keep |f_q| <= μ R).
void intersect_friction_cone(AccelerationInterval& out, double T0, double Q0, double Q1, double R0,
                             double R1, double mu, double c) {
  const double m2 = mu * mu;
  const double a = 1.0 + 2.0 * c * Q1 + Q1 * Q1 - m2 * R1 * R1;
  const double b = 2.0 * (T0 + c * (Q0 + Q1 * T0) + Q0 * Q1 - m2 * R0 * R1);
  const double k = T0 * T0 + 2.0 * c * Q0 * T0 + Q0 * Q0 - m2 * R0 * R0;
  const double scale = std::max({std::abs(T0), std::abs(Q0), mu * std::abs(R0), 1e-300});
  const double disc = b * b - 4.0 * a * k;
  // The roots r1 <= r2 of a u² + b u + k, stably: q = -(b + sign(b) sqrt(disc)) / 2, roots
  // q/a and k/q; and the rounding slack round them.
  const auto roots = [&](double& r1, double& r2, double& widen) {
    const double root = std::sqrt(std::max(disc, 0.0));
    const double q = -0.5 * (b + std::copysign(root, b));
    r1 = q / a;
    r2 = (q != 0.0) ? k / q : r1;
    if (r1 > r2) std::swap(r1, r2);
    widen = AdmissibleSet::kRounding * (1.0 + std::abs(r1) + std::abs(r2));
  };
  double r1 = 0.0, r2 = 0.0, widen = 0.0;
  if (a > 0.0) {
    if (disc < -AdmissibleSet::kRounding * scale * scale * std::max(a, 1.0)) {
      out.lower = kInfinity;
      return;
    }
    roots(r1, r2, widen);
    out.intersect(r1 - widen, r2 + widen);
  } else if (a == 0.0) {
    out.require_nonnegative(-k, -b);
  } else if (disc > 0.0) {
    // a < 0: the line crosses both nappes of the cone; the caller's conditions
    // keep u on the R >= 0 nappe, where the solution set is the outer piece
    // (-inf, r1] or [r2, inf) that they touch.
    roots(r1, r2, widen);
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

}  // namespace

void ForceConditions::add(const ForceCondition& condition) {
  if (size_ == kCapacity)
    throw std::length_error("ForceConditions: more than " + std::to_string(kCapacity) +
                            " conditions");
  items_[size_++] = condition;
}

void ForceConditions::add_lateral_ratio(Constraint constraint, double ratio) {
  add({constraint, 0.0, -1.0, ratio, 0.0});
  add({constraint, 0.0, 1.0, ratio, 0.0});
}

void ForceConditions::add_tangential_ratio(Constraint constraint, double ratio) {
  add({constraint, -1.0, 0.0, ratio, 0.0});
  add({constraint, 1.0, 0.0, ratio, 0.0});
}

AdmissibleSet::AdmissibleSet(const Vehicle& vehicle)
    : AdmissibleSet(vehicle_physics(vehicle.model).admissible_set(vehicle)) {}

AdmissibleSet::AdmissibleSet(double gravity, double friction, double axle_transfer,
                             double max_speed, double max_curvature,
                             const ForceConditions& conditions,
                             const std::optional<WheelLayout>& wheels)
    : gravity_(gravity),
      friction_(friction),
      friction_coupling_(lighter_axle_coupling(friction, axle_transfer)),
      max_speed_(max_speed),
      max_speed_squared_(max_speed * max_speed),
      max_curvature_(max_curvature),
      wheels_(wheels),
      conditions_(conditions) {
  if (std::isnan(friction_coupling_)) {
    throw InputError(
        "Vehicle.axle_friction: no friction cone fits inside the lighter axle's "
        "friction at mu h / l = " +
        std::to_string(friction * axle_transfer) +
        " (its axle unloads before the tyres slide; the pitch-over limit binds "
        "first): leave axle_friction off for this vehicle");
  }
  for (const ForceCondition& c : conditions.all()) {
    if (c.constraint == Constraint::kContact && c.t == 0.0 && c.q == 0.0 && c.r == 1.0)
      contact_reserve_ = std::max(contact_reserve_, -c.c);
  }
  // The lateral envelope: every symmetric pair m R ± f_q >= 0 tightens lambda.
  lateral_ratio_ = friction;
  for (const ForceCondition& a : conditions.all()) {
    if (a.t != 0.0 || a.c != 0.0 || a.q != -1.0 || !(a.r > 0.0)) continue;
    for (const ForceCondition& b : conditions.all()) {
      if (b.t == 0.0 && b.c == 0.0 && b.q == 1.0 && b.r == a.r)
        lateral_ratio_ = std::min(lateral_ratio_, a.r);
    }
  }
  for (const ForceCondition& c : conditions.all()) {
    if (c.t != 0.0) {
      traction_.add(c);
      const TractionBound bound{c.r, c.q, c.c, c.t, -1.0 / c.t, c.constraint};
      const bool constant = c.r == 0.0 && c.q == 0.0;
      if (constant && c.t < 0.0) {
        if (bound.factor * c.c < f_t_max_) {
          f_t_max_ = bound.factor * c.c;
          f_t_max_constraint_ = c.constraint;
        }
      } else if (constant) {
        if (bound.factor * c.c > f_t_min_) {
          f_t_min_ = bound.factor * c.c;
          f_t_min_constraint_ = c.constraint;
        }
      } else if (c.t < 0.0) {
        upper_bounds_[upper_count_++] = bound;
      } else {
        lower_bounds_[lower_count_++] = bound;
      }
      continue;
    }
    speed_.add(c);
    if (!implied_by_lateral(c, lateral_ratio_)) extra_speed_.add(c);
  }
  // Candidates of speed_limits() in tie order: contact (the first
  // condition), sliding, the model's speed conditions grouped by constraint
  // in order of first appearance, max speed.
  using Shape = Candidate::Shape;
  const auto add_group = [this](Constraint constraint) {
    Candidate c{constraint, Shape::kConditions, 0.0, grouped_.size(), 0};
    for (const ForceCondition& row : speed_.all()) {
      if (row.constraint == constraint) grouped_.add(row);
    }
    c.end = grouped_.size();
    const ForceCondition* rows = c.end > c.begin ? &grouped_[c.begin] : nullptr;
    if (c.end - c.begin == 1 && rows[0].r == 1.0 && rows[0].q == 0.0 && rows[0].c == 0.0) {
      c.shape = Shape::kContact;
    } else if (c.end - c.begin == 2 && rows[0].q == -1.0 && rows[1].q == 1.0 &&
               rows[0].r == rows[1].r && rows[0].c == 0.0 && rows[1].c == 0.0) {
      c.shape = Shape::kLateralPair;
      c.ratio = rows[0].r;
    }
    candidates_[candidate_count_++] = c;
  };
  const bool contact_first = speed_.size() > 0 && speed_[0].constraint == Constraint::kContact;
  if (contact_first) add_group(Constraint::kContact);
  candidates_[candidate_count_++] = {Constraint::kSliding, Shape::kLateralPair, friction, 0, 0};
  for (std::size_t k = contact_first ? 1 : 0; k < speed_.size(); ++k) {
    const Constraint c = speed_[k].constraint;
    bool seen = false;
    for (std::size_t j = 0; j < candidate_count_; ++j)
      seen = seen || candidates_[j].constraint == c;
    if (!seen) add_group(c);
  }
  candidates_[candidate_count_++] = {Constraint::kMaxSpeed, Shape::kMaxSpeed, 0.0, 0, 0};
  for (std::size_t j = 0; j < candidate_count_; ++j) {
    Candidate& c = candidates_[j];
    c.slot = c.constraint == Constraint::kContact   ? Candidate::Slot::kContact
             : c.constraint == Constraint::kSliding ? Candidate::Slot::kSliding
             : c.constraint == Constraint::kTipover ? Candidate::Slot::kTipover
                                                    : Candidate::Slot::kNone;
  }
}

SpeedLimits AdmissibleSet::speed_limits(const StationGeometry& s) const {
  using Shape = Candidate::Shape;
  SpeedLimits out;
  // One pass over the candidates in tie order. Contact comes first: the
  // sliding and tip-over intervals always lie inside the contact interval,
  // so they only tie with it where the lateral force vanishes, and there the
  // vehicle is really leaving the ground. A later constraint takes over only
  // if it is tighter by more than rounding, so ties (equal up to 1e-12
  // relative) go to the first in the list; the first constraint no speed
  // satisfies names the failure.
  SquaredSpeedInterval* const slots[] = {nullptr, &out.contact, &out.sliding, &out.tipover};
  double lower = 0.0, upper = kInfinity;
  constexpr double kTie = 1e-12;
  Constraint empty = Constraint::kNone;
  bool any_empty = false;
  for (std::size_t j = 0; j < candidate_count_; ++j) {
    const Candidate& c = candidates_[j];
    SquaredSpeedInterval interval;
    switch (c.shape) {
      case Shape::kContact:
        interval = linear_condition(s.kappa_n, gravity_ * s.k_r);
        break;
      case Shape::kLateralPair:
        interval = lateral_pair(c.ratio, gravity_, s);
        break;
      case Shape::kConditions:
        for (std::size_t k = c.begin; k < c.end; ++k)
          interval = intersect(interval, speed_condition(grouped_[k], gravity_, s));
        break;
      case Shape::kMaxSpeed:
        interval.upper = max_speed_squared_;
        break;
    }
    if (wheels_ && c.constraint == Constraint::kContact)
      interval = intersect(interval, wheel_contact(s, gravity_, contact_reserve_));
    if (c.slot != Candidate::Slot::kNone) *slots[static_cast<std::size_t>(c.slot)] = interval;
    if (interval.lower > lower * (1.0 + kTie)) {
      lower = interval.lower;
      out.lower_binding = c.constraint;
    }
    if (interval.upper < upper * (1.0 - kTie)) {
      upper = interval.upper;
      out.upper_binding = c.constraint;
    }
    if (!any_empty && interval.empty()) {
      any_empty = true;
      empty = c.constraint;
    }
  }
  // Steering is geometry, not a speed: a turn tighter than the vehicle can steer has no
  // admissible speed, named so unless a force condition already failed there.
  if (!any_empty && std::abs(s.kappa_planar) > max_curvature_) {
    any_empty = true;
    empty = Constraint::kSteering;
  }
  if (any_empty) {
    out.upper_binding = out.lower_binding = empty;
    lower = kInfinity;
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

SquaredSpeedInterval AdmissibleSet::squared_speeds(const StationGeometry& s) const {
  if (std::abs(s.kappa_planar) > max_curvature_) return {kInfinity, 0.0};  // steering: empty
  SquaredSpeedInterval out = lateral_pair(lateral_ratio_, gravity_, s);
  for (const ForceCondition& c : extra_speed_.all())
    out = intersect(out, speed_condition(c, gravity_, s));
  if (wheels_) out = intersect(out, wheel_contact(s, gravity_, contact_reserve_));
  out.upper = std::min(out.upper, max_speed_squared_);
  return out;
}

[[gnu::always_inline]] inline TangentialForceRange AdmissibleSet::traction_range(
    double normal, double f_q, double half_width) const {
  TangentialForceRange out;
  out.upper = half_width;
  out.lower = -half_width;
  for (std::size_t k = 0; k < upper_count_; ++k) {
    const TractionBound& b = upper_bounds_[k];
    const double bound = b.factor * (b.r * normal + b.q * f_q + b.c);
    if (bound < out.upper) {
      out.upper = bound;
      out.upper_binding = b.constraint;
    }
  }
  for (std::size_t k = 0; k < lower_count_; ++k) {
    const TractionBound& b = lower_bounds_[k];
    const double bound = b.factor * (b.r * normal + b.q * f_q + b.c);
    if (bound > out.lower) {
      out.lower = bound;
      out.lower_binding = b.constraint;
    }
  }
  if (f_t_max_ < out.upper) {
    out.upper = f_t_max_;
    out.upper_binding = f_t_max_constraint_;
  }
  if (f_t_min_ > out.lower) {
    out.lower = f_t_min_;
    out.lower_binding = f_t_min_constraint_;
  }
  return out;
}

AccelerationBounds AdmissibleSet::acceleration_bounds(const StationGeometry& s,
                                                      double speed) const {
  const double x = speed * speed;
  const double f_q = gravity_ * s.k_q + s.kappa_g * x;
  const double normal = gravity_ * s.k_r + s.kappa_n * x;
  AccelerationBounds out;
  const double scale = gravity_ + std::abs(s.kappa_n * x) + std::abs(s.kappa_g * x);
  for (const ForceCondition& c : speed_.all()) {  // contact, then the model's
    if (!(c.r * normal + c.q * f_q + c.c >= -kOnLimit * scale)) {
      out.violated = c.constraint;
      return out;
    }
  }
  if (wheels_ && !(gravity_ * s.k_r - contact_reserve_ + s.kappa_wheels * x >=
                   -kOnLimit * (scale + std::abs(s.kappa_wheels * x)))) {
    out.violated = Constraint::kContact;
    return out;
  }
  const double friction_force = friction_ * std::max(normal, 0.0);
  const double slack = friction_force * friction_force - f_q * f_q;
  if (!(slack >= -kOnLimit * scale * scale)) {
    out.violated = Constraint::kSliding;
    return out;
  }
  if (speed > max_speed_ * (1.0 + 1e-12)) {
    out.violated = Constraint::kMaxSpeed;
    return out;
  }
  // Bounds on f_t, then s̈ = f_t − g k_t.
  const TangentialForceRange f = traction_range(
      std::max(normal, 0.0), f_q, friction_half_width(friction_, friction_coupling_, normal, f_q));
  const double weight = gravity_ * s.k_t;
  out.a_min = f.lower - weight;
  out.a_max = f.upper - weight;
  out.lower_binding = f.lower_binding;
  out.upper_binding = f.upper_binding;
  out.feasible = true;
  return out;
}

TangentialForceRange AdmissibleSet::tangential_forces(const StationGeometry& s, double x) const {
  const double normal = std::max(gravity_ * s.k_r + s.kappa_n * x, 0.0);
  const double f_q = gravity_ * s.k_q + s.kappa_g * x;
  return traction_range(normal, f_q,
                        friction_half_width(friction_, friction_coupling_, normal, f_q));
}

AccelerationInterval AdmissibleSet::accelerations_at(const StationGeometry& s, double x) const {
  AccelerationInterval out;
  const double R = gravity_ * s.k_r + s.kappa_n * x, Q = gravity_ * s.k_q + s.kappa_g * x;
  const double T0 = gravity_ * s.k_t;
  const double scale = gravity_ + std::abs(s.kappa_n * x) + std::abs(s.kappa_g * x);
  // The lateral envelope: tip-over, lateral sliding and contact at once.
  if (std::abs(Q) > lateral_ratio_ * R + kRounding * scale) {
    out.lower = kInfinity;
    return out;
  }
  for (const ForceCondition& c : extra_speed_.all()) {
    if (c.r * R + c.q * Q + c.c < -kRounding * scale) {
      out.lower = kInfinity;
      return out;
    }
  }
  if (wheels_ && gravity_ * s.k_r - contact_reserve_ + s.kappa_wheels * x <
                     -kRounding * (scale + std::abs(s.kappa_wheels * x))) {
    out.lower = kInfinity;
    return out;
  }
  const double half_width = friction_half_width(friction_, friction_coupling_, R, Q);
  const double normal = std::max(R, 0.0);
  double upper = std::min(half_width, f_t_max_), lower = std::max(-half_width, f_t_min_);
  for (std::size_t k = 0; k < upper_count_; ++k) {
    const TractionBound& b = upper_bounds_[k];
    upper = std::min(upper, b.factor * (b.r * normal + b.q * Q + b.c));
  }
  for (std::size_t k = 0; k < lower_count_; ++k) {
    const TractionBound& b = lower_bounds_[k];
    lower = std::max(lower, b.factor * (b.r * normal + b.q * Q + b.c));
  }
  const double widen = kRounding * (1.0 + std::abs(T0) + half_width);
  out.lower = lower - T0 - widen;
  out.upper = upper - T0 + widen;
  return out;
}

AccelerationInterval AdmissibleSet::accelerations_along(const StationGeometry& s, double y0,
                                                        double beta, double x_lower,
                                                        double x_upper) const {
  AccelerationInterval out;
  // State bounds on y0 + beta u, widened by rounding: a state pinned to one
  // value (the end speed, a boundary of the controllable set) must not come
  // out as an empty interval one ulp wide.
  out.require_nonnegative(y0 - x_lower, beta);
  if (std::isfinite(x_upper)) out.require_nonnegative(x_upper - y0, -beta);
  if (beta != 0.0) {
    const double widen = kRounding * (1.0 + std::abs(out.lower == -kInfinity ? 0.0 : out.lower) +
                                      std::abs(out.upper == kInfinity ? 0.0 : out.upper));
    out.lower -= widen;
    out.upper += widen;
  }
  // Affine forces: R = R0 + R1 u, f_q = Q0 + Q1 u, f_t = u + T0.
  const double g = gravity_;
  const double R0 = g * s.k_r + s.kappa_n * y0, R1 = s.kappa_n * beta;
  const double Q0 = g * s.k_q + s.kappa_g * y0, Q1 = s.kappa_g * beta;
  const double T0 = g * s.k_t;
  // |f_q| <= lambda R: tip-over and the lateral part of sliding at once;
  // together they also imply contact (R >= 0).
  const double lambda = lateral_ratio_;
  out.require_nonnegative(lambda * R0 - Q0, lambda * R1 - Q1);
  out.require_nonnegative(lambda * R0 + Q0, lambda * R1 + Q1);
  for (const ForceCondition& c : extra_speed_.all())
    out.require_nonnegative(c.r * R0 + c.q * Q0 + c.c, c.r * R1 + c.q * Q1);
  if (wheels_)
    out.require_nonnegative(g * s.k_r - contact_reserve_ + s.kappa_wheels * y0,
                            s.kappa_wheels * beta);
  for (std::size_t k = 0; k < upper_count_ + lower_count_; ++k) {  // pitch-over
    const TractionBound& c = k < upper_count_ ? upper_bounds_[k] : lower_bounds_[k - upper_count_];
    out.require_nonnegative(c.r * R0 + c.q * Q0 + c.t * T0 + c.c, c.r * R1 + c.q * Q1 + c.t);
  }
  out.intersect(f_t_min_ - T0, f_t_max_ - T0);  // the constant traction force limits
  if (out.empty()) return out;
  // Friction: (u + T0)^2 + (Q0 + Q1 u)^2 - mu^2 (R0 + R1 u)^2 <= 0, or the lighter axle's
  // two coupled cones, with + 2 (± beta) (u + T0) (Q0 + Q1 u). The lateral conditions above
  // keep u on the R >= 0 nappe of each.
  if (friction_coupling_ == 0.0) {
    intersect_friction_cone(out, T0, Q0, Q1, R0, R1, friction_, 0.0);
    return out;
  }
  for (const double coupling : {friction_coupling_, -friction_coupling_}) {
    intersect_friction_cone(out, T0, Q0, Q1, R0, R1, friction_, coupling);
    if (out.empty()) return out;
  }
  return out;
}

}  // namespace talus
