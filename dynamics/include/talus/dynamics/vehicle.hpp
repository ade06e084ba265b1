#pragma once
/// @file
/// Vehicle: the immutable model of a ground vehicle that the velocity limits
/// are derived from, loaded from YAML (or JSON) with strict validation.
#include <array>
#include <limits>
#include <optional>
#include <string>

namespace talus {

/// Which dynamic model the limits use.
enum class VehicleModel {
  kPointMass,  ///< Shiller–Gwo point mass: sliding, lateral tip-over, contact
  kRigidBody,  ///< Mann–Shiller rigid body on four wheels: adds longitudinal tip-over
};
/// Every model, for tests and tools that must cover them all; the physics of
/// each is in vehicle_physics.hpp.
inline constexpr std::array<VehicleModel, 2> kVehicleModels = {VehicleModel::kPointMass,
                                                               VehicleModel::kRigidBody};

/// Largest VehicleBody::cornering_stiffness accepted [1/rad] (tyres have about 5-30).
inline constexpr double kMaxCorneringStiffness = 100.0;
/// Largest ride frequency sqrt(k / (m/4)) / 2π accepted [Hz] (vehicles ride at 1-5 Hz).
inline constexpr double kMaxRideFrequency = 50.0;

/// The mass, inertia, suspension and tyres of a vehicle: what the rigid-body
/// simulation (vehicle_simulation.hpp) needs beyond the speed-limit models.
/// Optional in a vehicle file: present when the file has `mass`; the other
/// keys then default as documented (data/vehicles/README.md).
struct VehicleBody {
  double mass = 1.0;  ///< [mass] m [kg] (> 0)
  /// [inertia_roll], [inertia_pitch], [inertia_yaw] principal moments about the
  /// body axes through the centre of mass [kg m^2] (> 0); default: a uniform
  /// box of 2 half_wheelbase × 2 half_track × 2 cg_height, I_xx = m (w² + H²)/12 etc.
  double inertia_roll = 1.0;
  double inertia_pitch = 1.0;
  double inertia_yaw = 1.0;
  /// [wheel_radius] r [m] (> 0); default 0.5 cg_height. Sets where the
  /// wheel centres sit (r above the contact points at static load).
  double wheel_radius = 0.25;
  /// [suspension_stiffness] k per wheel [N/m] (> 0); default (m/4)(2π·3 Hz)²,
  /// a 3 Hz ride frequency; at most a ride frequency of kMaxRideFrequency. It
  /// lumps spring and tyre radial compliance.
  double suspension_stiffness = 1.0;
  /// [suspension_damping] c per wheel [N s/m] (>= 0); default 2·0.4·sqrt(k m/4),
  /// a damping ratio of 0.4.
  double suspension_damping = 0.0;
  /// [cornering_stiffness] C_α / N, the tyre's cornering stiffness per unit
  /// normal load [1/rad] (> 0); default 8 (Dugoff's model: F_y = C_α tan α
  /// in the linear range); at most kMaxCorneringStiffness.
  double cornering_stiffness = 8.0;
  /// Throws InputError naming the field.
  void validate() const;
  bool operator==(const VehicleBody&) const = default;
};

/// The defaults above for a vehicle of this mass and geometry.
VehicleBody default_vehicle_body(double mass, double half_wheelbase, double half_track,
                                 double cg_height);

/// A ground vehicle, SI units. Every field has its YAML key in brackets.
struct Vehicle {
  VehicleModel model = VehicleModel::kPointMass;  ///< [model] point_mass | rigid_body
  double gravity = 9.81;                          ///< [gravity] g [m/s^2] (> 0)
  double friction = 0.7;  ///< [friction] tyre–terrain coefficient mu (> 0); required
  double cg_height =
      0.5;  ///< [cg_height] h, centre of mass above the ground plane [m] (> 0); required
  double half_track = 0.6;  ///< [half_track] b, centre of mass to the wheel contact line, lateral
                            ///< [m] (> 0); required
  double half_wheelbase = 1.0;  ///< [half_wheelbase] l, centre of mass to the axles [m] (> 0);
                                ///< rigid_body only, required there
  double max_speed =
      std::numeric_limits<double>::infinity();  ///< [max_speed] [m/s] (> 0); omitted = unlimited
  /// [max_accel] drive limit [m/s^2] (> 0); omitted = unlimited. It bounds the
  /// tangential traction force per unit mass, f_t = s̈ + g k_t <= max_accel, so
  /// it equals the largest s̈ on level ground and shrinks by g sin(α) uphill.
  double max_accel = std::numeric_limits<double>::infinity();
  /// [max_decel] brake limit [m/s^2] (> 0, a positive number); omitted =
  /// unlimited. Bounds f_t >= -max_decel, the braking force per unit mass.
  double max_decel = std::numeric_limits<double>::infinity();
  /// [max_steering] front-wheel steering limit δ_max [rad] (in (0, π/2)); omitted =
  /// unlimited. A kinematic bicycle of wheelbase 2 l turns no tighter than
  /// max_curvature() = tan δ_max / (2 l): the planner's paths keep the curvature of
  /// their horizontal projection within it (a station beyond it is untraversable, binding
  /// `steering`), and the simulation's tracker, which steers in plan, at most δ_max.
  /// In plan, not on the surface (the geodesic curvature): a straight line in plan
  /// lifted over wheel-scale bumps with a cross slope has a geodesic curvature beyond
  /// the UGV's 2.53 1/m on the fractal battery, which the chassis, spanning the bumps,
  /// does not steer. A point_mass vehicle with max_steering needs half_wheelbase.
  double max_steering = std::numeric_limits<double>::infinity();
  /// [contact_reserve] r [-] in [0, 1), default 0: the planner keeps the normal load per
  /// unit mass at least r g, R >= r g (and every wheel's, for the rigid body): a margin
  /// against losing contact over crests it sees only through the fitted surface.
  double contact_reserve = 0.0;
  /// [friction_reserve] ε [-] in [0, 1), default 0: the planner uses (1 − ε) μ for its
  /// friction cone, a control margin for the tracker; the simulation keeps μ.
  double friction_reserve = 0.0;
  /// [drive_reserve] ε_d [-] in [0, 1), default 0: the planner's drive and brake limits are
  /// (1 − ε_d) max_accel and (1 − ε_d) max_decel, a control margin for the tracker's speed
  /// loop: a climb planned at full drive leaves a tracker that has fallen behind no force
  /// to catch up with, and it stalls on the slope. The simulation keeps the full limits.
  double drive_reserve = 0.0;
  /// [axle_friction] rigid_body only, default false: the planner judges friction at the
  /// lighter axle (AdmissibleSet::friction_coupling) instead of on the total contact force.
  /// The tangential force pitches the chassis and unloads one axle by (h / l) |f_t| (the rear
  /// under braking and on a descent held by the brakes); with the drive and brake shared by
  /// the wheels in proportion to their loads, as in the simulation, and the lateral force
  /// equally by the axles, that axle slides first. Off: the friction cone f_t² + f_q² <= μ²R²
  /// (Mann & Shiller 2006).
  bool axle_friction = false;
  /// Mass, inertia, suspension and tyres (the keys of VehicleBody); empty when
  /// the file has no `mass`. Only the simulation needs it; the speed limits
  /// ignore it.
  std::optional<VehicleBody> body;

  /// tan(max_steering) / (2 half_wheelbase) [1/m]; +inf without a steering limit.
  double max_curvature() const;
  /// The planner's drive and brake limits [m/s²]: (1 − drive_reserve) max_accel and
  /// (1 − drive_reserve) max_decel (+inf where unlimited).
  double planned_max_accel() const { return (1.0 - drive_reserve) * max_accel; }
  double planned_max_decel() const { return (1.0 - drive_reserve) * max_decel; }
  /// Throws InputError naming the field, its value and what is expected.
  void validate() const;
  /// Field by field (NaN fields compare unequal).
  bool operator==(const Vehicle&) const = default;
};

/// Reads a vehicle from a YAML (or JSON) file: unknown keys, missing required
/// keys, wrong types and invalid values are InputErrors naming the file and key.
Vehicle load_vehicle(const std::string& path);
/// The same from YAML text; `source_name` appears in error messages.
Vehicle parse_vehicle(const std::string& yaml_text, const std::string& source_name);

}  // namespace talus
