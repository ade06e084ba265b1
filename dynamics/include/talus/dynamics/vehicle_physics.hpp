#pragma once
/// @file
/// VehiclePhysics: the extension point for vehicle models. A model states
/// only its own physics, as linear conditions on the contact force per unit
/// mass F = (f_t, f_q, R) (admissible_set.hpp); the shared work (validation,
/// the friction cone, contact, drive and brake limits, max speed, and every
/// per-station query) stays in the non-virtual admissible_set() and in
/// AdmissibleSet. Adding a model is one source file with a VehiclePhysics
/// subclass, plus its VehicleModel value and a line in vehicle_physics().
///
/// Models: point mass (Shiller & Gwo 1991): lateral tip-over |f_q| <= (b/h) R;
/// rigid body on four wheels (Mann & Shiller 2006): the same plus
/// longitudinal tip-over |f_t| <= (l/h) R, with the normal load and contact
/// judged at the wheels (wheel_contact.hpp). See dynamics/DERIVATION.md.
#include <string_view>

#include "talus/dynamics/admissible_set.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus {

/// The physics of one vehicle model. Stateless; one instance per model.
class VehiclePhysics {
 public:
  virtual ~VehiclePhysics() = default;
  /// The model's YAML name (point_mass, rigid_body).
  virtual std::string_view name() const = 0;

  /// The admissible set of `vehicle`: validates it (InputError), then
  /// conditions = contact R >= 0, the model's conditions, drive
  /// max_accel − f_t >= 0 and brake max_decel + f_t >= 0 (the last two only
  /// when finite), and checks the conditions' contract (admissible_set.hpp).
  AdmissibleSet admissible_set(const Vehicle& vehicle) const;
  /// Whether the model judges contact at the wheels as well as at the c.g.
  /// (StationGeometry::kappa_wheels, wheel_contact.hpp): the rigid body.
  virtual bool contact_at_wheels() const { return false; }
  /// tau = h / l [-] when the model judges friction at the lighter axle (AdmissibleSet::
  /// friction_coupling()), 0 (the default) for the friction cone at the c.g.
  virtual double axle_load_transfer(const Vehicle&) const { return 0.0; }

 protected:
  /// Appends the model's own conditions (tip-over, pitch-over, ...) for
  /// `vehicle`, which is valid. Called once per admissible_set(), never per
  /// station.
  virtual void add_model_conditions(const Vehicle& vehicle, ForceConditions& out) const = 0;
};

/// The physics of `model`: the one place that maps the enum to a model.
const VehiclePhysics& vehicle_physics(VehicleModel model);

}  // namespace talus
