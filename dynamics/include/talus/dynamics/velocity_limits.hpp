#pragma once
/// @file
/// Speed limits [v_min, v_max] and tangential-acceleration bounds
/// [a_min, a_max] of a vehicle at one station of a path on the terrain.
///
/// Derivation (point mass; Shiller & Gwo 1991, Iagnemma–Shimoda–Shiller 2008
/// eq. (1)–(5); full text in dynamics/DERIVATION.md). In the path frame
/// (t, q, r) of surface_path.hpp, with x = ṡ² and s̈ the tangential
/// acceleration, the contact force per unit mass is
///     f_t = g k_t + s̈,   f_q = g k_q + κ_g x,   R = g k_r + κ_n x.
/// Constraints:
///   contact   R >= 0; rigid body: also every wheel's load, g k_r + κ_w x >= 0
///             (wheel_contact.hpp; there κ_n is the chassis' mean over the wheels)
///   sliding   f_t² + f_q² <= μ² R²
///   tip-over  |f_q| <= (b/h) R                     (lateral, both models)
///   pitch     |f_t| <= (l/h) R                     (rigid body only)
///   drive     -max_decel <= f_t <= max_accel       (traction/brake force per unit mass)
///   speed     x <= max_speed²
/// Some s̈ exists at speed ṡ iff |f_q| <= μ R (then f_t = 0 is admissible),
/// i.e. iff both  (μ κ_n − κ_g) x + g (μ k_r − k_q) >= 0  and
///                (μ κ_n + κ_g) x + g (μ k_r + k_q) >= 0.
/// These are the two real factors of the paper's quartic a x² + 2 b x + c >= 0
/// restricted to R >= 0. Tip-over is the same pair with μ replaced by b/h,
/// contact is κ_n x + g k_r >= 0. Each condition α x + β >= 0 on x >= 0 is an
/// interval: [0, ∞) (α >= 0, β >= 0), [−β/α, ∞) (α > 0, β < 0: a *lower*
/// speed bound, e.g. a banked curve that must be taken fast enough not to
/// slide inwards), [0, β/−α] (α < 0, β >= 0), or empty (α <= 0, β < 0:
/// not traversable at any speed). The limits are the intersection.
///
/// Curvature combinations |α| below 1e-12 1/m (radius > 10^12 m) are treated
/// as exactly zero, so that a numerically straight path on a side slope
/// steeper than atan(μ) reads "not traversable" rather than "traversable
/// above 10^8 m/s".
#include <cstdint>
#include <limits>
#include <string_view>

#include "talus/bspline/surface_path.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus {

/// The constraint that sets a limit.
enum class Constraint : std::uint8_t {
  kNone,       ///< nothing limits (v_max = ∞, or v_min = 0)
  kSliding,    ///< friction: f_t² + f_q² <= μ² R²
  kTipover,    ///< lateral tip-over: |f_q| <= (b/h) R
  kContact,    ///< loss of contact: R >= 0
  kMaxSpeed,   ///< the vehicle's max_speed
  kPitchover,  ///< longitudinal tip-over (rigid body): |f_t| <= (l/h) R
  kDrive,      ///< drive limit max_accel
  kBrake,      ///< brake limit max_decel
  kSteering,   ///< the path turns tighter than the steering limit: |κ_planar| >
               ///< Vehicle::max_curvature()
};
/// Lower-case name as used in CSV files: none, sliding, tipover, contact,
/// max_speed, pitchover, drive, brake, steering.
std::string_view to_string(Constraint constraint);

/// The path geometry one station's limits depend on (see surface_path.hpp).
struct StationGeometry {
  double kappa_n = 0.0, kappa_g = 0.0;     ///< [1/m]
  double k_t = 0.0, k_q = 0.0, k_r = 1.0;  ///< vertical unit vector in (t, q, r)
  /// Curvature of the path's horizontal projection [1/m]: the steering limit's measure
  /// (PathFrame::kappa_planar).
  double kappa_planar = 0.0;
  /// Load curvature of the least-loaded wheel [1/m]: a rigid body keeps every wheel on the
  /// ground while g k_r + kappa_wheels ṡ² >= 0 (wheel_contact.hpp). For a rigid body
  /// station_geometry() (wheel_contact.hpp) also sets kappa_n to the chassis' curvature,
  /// the mean over the wheels; from() puts the wheels at the c.g.: kappa_wheels = kappa_n.
  double kappa_wheels = 0.0;
  /// The c.g. point's geometry, every wheel at the c.g. (the point mass's view).
  static StationGeometry from(const PathFrame& frame) {
    return {frame.kappa_n, frame.kappa_g,      frame.k_t,    frame.k_q,
            frame.k_r,     frame.kappa_planar, frame.kappa_n};
  }
};

/// Admissible interval of x = ṡ² [m²/s²] for one constraint.
struct SquaredSpeedInterval {
  double lower = 0.0;
  double upper = std::numeric_limits<double>::infinity();
  bool empty() const { return !(lower <= upper); }
};

/// Speed limits at one station.
struct SpeedLimits {
  double v_min = 0.0;  ///< [m/s]; > 0 only where the vehicle must keep speed up
  double v_max = std::numeric_limits<double>::infinity();  ///< [m/s]; 0 = not traversable
  Constraint lower_binding = Constraint::kNone;            ///< what sets v_min
  Constraint upper_binding = Constraint::kNone;            ///< what sets v_max (or makes it 0)
  bool traversable = true;  ///< false: no speed satisfies every constraint (v_min = v_max = 0)
  /// Each constraint's own interval, for plots and diagnostics.
  SquaredSpeedInterval sliding, tipover, contact;
};

// The three queries below are one-off conveniences: each builds the vehicle's
// AdmissibleSet (admissible_set.hpp, which holds the physics of every vehicle
// model) and validates the vehicle; loops should build that set once.

/// Speed limits of `vehicle` at a station with geometry `g`. O(1).
SpeedLimits speed_limits(const Vehicle& vehicle, const StationGeometry& g);

/// The admissible interval of ṡ² alone, without the per-constraint breakdown
/// and bindings of speed_limits() (same interval, about half the cost).
/// Empty when not traversable.
SquaredSpeedInterval admissible_squared_speeds(const Vehicle& vehicle, const StationGeometry& g);

/// Admissible tangential accelerations s̈ at one station and speed.
struct AccelerationBounds {
  double a_min = 0.0;     ///< [m/s²]
  double a_max = 0.0;     ///< [m/s²]
  bool feasible = false;  ///< false: no s̈ is admissible at this speed (a_min/a_max meaningless)
  Constraint lower_binding = Constraint::kNone;  ///< sliding, pitchover or brake
  Constraint upper_binding = Constraint::kNone;  ///< sliding, pitchover or drive
  Constraint violated = Constraint::kNone;       ///< when infeasible: which constraint fails
};

/// [a_min, a_max] of `vehicle` at a station with geometry `g` moving at
/// `speed` >= 0: the friction ellipse ∩ pitch-over (rigid body) ∩ drive and
/// brake limits, all bounds on f_t = s̈ + g k_t. O(1), no allocation.
AccelerationBounds acceleration_bounds(const Vehicle& vehicle, const StationGeometry& g,
                                       double speed);

}  // namespace talus
