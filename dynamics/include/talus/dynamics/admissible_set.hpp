#pragma once
/// @file
/// AdmissibleSet: the one place that answers, for a vehicle at one station of
/// a path, which speeds and which tangential accelerations are admissible.
///
/// The station's geometry (StationGeometry) maps a state x = ṡ² [m²/s²] and a
/// tangential acceleration u = s̈ [m/s²] affinely to the contact force per unit
/// mass the ground must supply (dynamics/DERIVATION.md):
///     f_t = u + g k_t,   f_q = g k_q + κ_g x,   R = g k_r + κ_n x   [m/s²].
/// The vehicle fixes which forces are admissible, independently of the
/// station (apart from contact at the wheels, which reads the station's
/// kappa_wheels): the friction cone f_t² + f_q² <= μ² R², a short list of linear
/// ForceConditions (contact, the vehicle model's tip-over conditions, drive
/// and brake limits), and x <= max_speed². The admissible (x, u) set of a
/// station is the preimage of that force set: convex (one second-order cone
/// and half-planes), which is what keeps every query below closed form.
///
/// Contract on the conditions (checked when the set is built): a condition
/// with t = 0 is a *speed condition* (it constrains x alone); a condition
/// with t != 0 is a *traction condition* and must hold at f_t = 0 whenever
/// R >= 0 and |f_q| <= μ R (c >= 0, r >= μ |q|), so that it bounds s̈ but
/// removes no speed: some s̈ exists at x iff the speed conditions and
/// |f_q| <= μ R hold.
///
/// Build it once per vehicle (AdmissibleSet(vehicle) asks the vehicle's
/// model, vehicle_physics.hpp); every query is O(number of conditions), never
/// allocates and makes no virtual call, so it is meant for inner loops.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>

#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"
#include "talus/dynamics/wheel_contact.hpp"

namespace talus {

/// One linear condition on the contact force per unit mass F = (f_t, f_q, R):
///     t f_t + q f_q + r R + c >= 0.
struct ForceCondition {
  /// What it models, reported as a binding; conditions with the same name
  /// form one constraint. Not kNone, kSliding or kMaxSpeed (the friction
  /// cone's and the speed limit's own).
  Constraint constraint = Constraint::kNone;
  double t = 0.0, q = 0.0, r = 0.0;  ///< dimensionless coefficients
  double c = 0.0;                    ///< [m/s²]
};

/// The linear conditions of a vehicle, fixed capacity (no allocation).
class ForceConditions {
 public:
  static constexpr std::size_t kCapacity = 12;
  /// Appends a condition; throws std::length_error beyond kCapacity (a model
  /// implementation error, not bad input).
  void add(const ForceCondition& condition);
  /// Appends |f_q| <= ratio R as its two linear halves (ratio R − f_q >= 0 first).
  void add_lateral_ratio(Constraint constraint, double ratio);
  /// Appends |f_t| <= ratio R as its two linear halves (ratio R − f_t >= 0 first).
  void add_tangential_ratio(Constraint constraint, double ratio);
  std::size_t size() const { return size_; }
  const ForceCondition& operator[](std::size_t k) const { return items_[k]; }
  std::span<const ForceCondition> all() const { return {items_.data(), size_}; }

 private:
  std::array<ForceCondition, kCapacity> items_{};
  std::size_t size_ = 0;
};

/// An interval of tangential acceleration u = s̈ [m/s²]; empty when lower > upper.
struct AccelerationInterval {
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

/// Range of the tangential force per unit mass f_t [m/s²] that the traction
/// conditions and the friction cone leave at one state, ignoring the speed
/// conditions (see AdmissibleSet::tangential_forces).
struct TangentialForceRange {
  double lower = 0.0, upper = 0.0;
  Constraint lower_binding = Constraint::kSliding, upper_binding = Constraint::kSliding;
};

/// The admissible (ṡ², s̈) set of one vehicle at any station. Immutable value
/// type of fixed size (about 4 kB, no heap); build it once per vehicle.
class AdmissibleSet {
 public:
  /// Relative slack of the step queries (accelerations_at, accelerations_along)
  /// for floating-point rounding: states computed on the boundary of the set
  /// (a braking curve, the limit curve) come out 1e-12 .. 1e-11 outside it and
  /// must stay admissible.
  static constexpr double kRounding = 1e-10;
  /// Slack of acceleration_bounds(), relative to the station's force scale
  /// g + |κ_n x| + |κ_g x|: a speed on the limit curve computed in floating
  /// point may sit a few ulps outside it.
  static constexpr double kOnLimit = 1e-10;

  /// The set of `vehicle` (validated), from its model's physics:
  /// vehicle_physics(vehicle.model).admissible_set(vehicle).
  explicit AdmissibleSet(const Vehicle& vehicle);

  double gravity() const { return gravity_; }  ///< g [m/s²]
  /// μ of the friction cone: (1 − Vehicle::friction_reserve) μ.
  double friction() const { return friction_; }
  double max_speed() const { return max_speed_; }  ///< [m/s]; ∞ = unlimited
  /// beta [-] in [0, 1]: 0 for the friction cone at the c.g. (the point mass), else the
  /// coupling of the lighter axle's friction (the rigid body, VehiclePhysics::
  /// axle_load_transfer). The tangential force f_t pitches the chassis and moves
  /// tau |f_t| (tau = h / l) of the normal load R from one axle to the other; with f_t shared
  /// by the wheels in proportion to their loads (the simulation's drive and brake) and f_q
  /// equally by the axles (no yaw acceleration, the c.g. midway), the lighter axle, loaded
  /// (R − tau |f_t|) / 2, holds iff f_q² <= (R − tau |f_t|)² (μ² − f_t²/R²). The set keeps
  /// the convex inner bound
  ///     f_t² + 2 beta |f_t f_q| + f_q² <= μ² R²
  /// (two elliptic cones, one per sign of f_t f_q) in place of the friction cone, which it
  /// implies: equal to the axle's condition at f_t = 0 (so every speed limit is the cone's)
  /// and at f_q = 0 (braking and driving straight keep μ R), inside it in between with beta
  /// the smallest such coupling (from tau μ up; 0.315 for the UGV, 0.356 for the rover).
  /// dynamics/DERIVATION.md, "Friction at the lighter axle".
  double friction_coupling() const { return friction_coupling_; }
  /// The wheels where contact is also judged, g k_r + κ_w ṡ² >= 0 with
  /// κ_w = StationGeometry::kappa_wheels (the rigid body; wheel_contact.hpp),
  /// or null (the point mass). Stations for this set are built with
  /// station_geometry(frame, surface, set.wheels()).
  const WheelLayout* wheels() const { return wheels_ ? &*wheels_ : nullptr; }
  /// r g [m/s²]: the normal load per unit mass the contact conditions keep
  /// (Vehicle::contact_reserve), at the c.g. and at every wheel.
  double contact_reserve() const { return contact_reserve_; }
  /// λ: the speed conditions of the form m R ± f_q >= 0 (and contact) are
  /// implied by |f_q| <= λ R, λ = min(μ, every such m): the lateral envelope
  /// the fast queries use instead of the individual conditions.
  double lateral_ratio() const { return lateral_ratio_; }
  /// Every linear condition, in order: the shared ones (contact first), the
  /// model's, then drive and brake (only finite ones).
  std::span<const ForceCondition> conditions() const { return conditions_.all(); }
  /// The speed conditions that the lateral envelope does not imply (none for
  /// the point mass and the rigid body).
  std::span<const ForceCondition> extra_speed_conditions() const { return extra_speed_.all(); }
  /// The conditions with t != 0: they bound f_t (pitch-over, drive, brake).
  std::span<const ForceCondition> traction_conditions() const { return traction_.all(); }

  /// Speed limits with each constraint's interval and the bindings. O(1).
  SpeedLimits speed_limits(const StationGeometry& g) const;
  /// The admissible interval of ṡ² alone (same interval as speed_limits(),
  /// about half the cost). Empty when not traversable.
  SquaredSpeedInterval squared_speeds(const StationGeometry& g) const;
  /// [a_min, a_max] at `speed` [m/s] >= 0 with bindings, or infeasible with
  /// the violated constraint; states within kOnLimit of the boundary count
  /// as admissible.
  AccelerationBounds acceleration_bounds(const StationGeometry& g, double speed) const;
  /// f_t range at state x from the friction cone and the traction conditions
  /// (R clamped at 0), ignoring the speed conditions: the traction and
  /// braking force available there.
  TangentialForceRange tangential_forces(const StationGeometry& g, double x) const;

  /// The u admissible at a station whose state x is known, widened by
  /// kRounding; empty when x itself is not admissible.
  AccelerationInterval accelerations_at(const StationGeometry& g, double x) const;
  /// The u such that (y0 + beta u, u) is admissible at the station and the
  /// state y0 + beta u lies in [x_lower, x_upper] (x_upper may be ∞): the set
  /// along one step's line (beta = ±2 Δs), one quadratic and a few linear
  /// inequalities; bounds widened by kRounding.
  AccelerationInterval accelerations_along(const StationGeometry& g, double y0, double beta,
                                           double x_lower, double x_upper) const;

 private:
  friend class VehiclePhysics;
  AdmissibleSet(double gravity, double friction, double axle_transfer, double max_speed,
                double max_curvature, const ForceConditions& conditions,
                const std::optional<WheelLayout>& wheels);
  TangentialForceRange traction_range(double normal, double f_q, double half_width) const;

  static constexpr std::size_t kCandidates = ForceConditions::kCapacity + 2;
  /// A traction condition t f_t + q f_q + r R + c >= 0 solved for f_t:
  /// f_t <= (t < 0) or >= (t > 0) factor (r R + q f_q + c), factor = −1/t.
  struct TractionBound {
    double r = 0.0, q = 0.0, c = 0.0, t = 0.0, factor = 0.0;
    Constraint constraint = Constraint::kNone;
  };

  double gravity_ = 9.81, friction_ = 0.0;
  /// beta of friction_coupling(), or 0.
  double friction_coupling_ = 0.0;
  double max_speed_ = 0.0, max_speed_squared_ = 0.0;
  /// Vehicle::max_curvature(): a station turning tighter (|κ_planar| above it) has no admissible
  /// speed (binding kSteering); +inf without a steering limit.
  double max_curvature_ = std::numeric_limits<double>::infinity();
  double lateral_ratio_ = 0.0;
  /// The model judges contact at these wheels too: g k_r + κ_w x >= 0 (StationGeometry::
  /// kappa_wheels), a speed condition named kContact.
  std::optional<WheelLayout> wheels_;
  double contact_reserve_ = 0.0;  ///< r g [m/s²]
  ForceConditions conditions_, speed_, extra_speed_, traction_;
  /// One constraint of speed_limits(), with the shape of its speed
  /// conditions recognised once so that the common shapes take their
  /// closed forms: R >= 0, or |f_q| <= ratio R (both halves), or a list of
  /// conditions grouped_[begin, end).
  struct Candidate {
    enum class Shape : std::uint8_t { kContact, kLateralPair, kConditions, kMaxSpeed };
    /// Which per-constraint interval of SpeedLimits it fills.
    enum class Slot : std::uint8_t { kNone, kContact, kSliding, kTipover };
    Constraint constraint = Constraint::kNone;
    Shape shape = Shape::kConditions;
    double ratio = 0.0;
    std::size_t begin = 0, end = 0;
    Slot slot = Slot::kNone;
  };
  // speed_limits(): the constraints in tie order (contact, sliding, the
  // model's, max speed).
  std::array<Candidate, kCandidates> candidates_{};
  std::size_t candidate_count_ = 0;
  ForceConditions grouped_;
  // The traction conditions as bounds on f_t: the constant ones (drive,
  // brake: r = q = 0) folded into one interval, the others in order.
  double f_t_max_ = std::numeric_limits<double>::infinity();
  double f_t_min_ = -std::numeric_limits<double>::infinity();
  Constraint f_t_max_constraint_ = Constraint::kNone, f_t_min_constraint_ = Constraint::kNone;
  std::array<TractionBound, ForceConditions::kCapacity> upper_bounds_{}, lower_bounds_{};
  std::size_t upper_count_ = 0, lower_count_ = 0;
};

}  // namespace talus
