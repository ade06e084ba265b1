#pragma once
/// @file
/// Vehicle: the immutable model of a ground vehicle that the velocity limits
/// are derived from, loaded from YAML (or JSON) with strict validation.
#include <array>
#include <limits>
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

  /// Throws InputError naming the field, its value and what is expected.
  void validate() const;
};

/// Reads a vehicle from a YAML (or JSON) file: unknown keys, missing required
/// keys, wrong types and invalid values are InputErrors naming the file and key.
Vehicle load_vehicle(const std::string& path);
/// The same from YAML text; `source_name` appears in error messages.
Vehicle parse_vehicle(const std::string& yaml_text, const std::string& source_name);

}  // namespace talus
