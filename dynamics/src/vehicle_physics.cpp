#include "talus/dynamics/vehicle_physics.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "vehicle_models.hpp"

namespace talus {

AdmissibleSet VehiclePhysics::admissible_set(const Vehicle& vehicle) const {
  vehicle.validate();
  ForceConditions conditions;
  // R >= r g (r = contact_reserve, 0 by default).
  conditions.add({Constraint::kContact, 0.0, 0.0, 1.0, -vehicle.contact_reserve * vehicle.gravity});
  const double friction = (1.0 - vehicle.friction_reserve) * vehicle.friction;
  add_model_conditions(vehicle, conditions);
  // planned_max_accel − f_t >= 0 and planned_max_decel + f_t >= 0 (the drive reserve kept).
  if (std::isfinite(vehicle.max_accel))
    conditions.add({Constraint::kDrive, -1.0, 0.0, 0.0, vehicle.planned_max_accel()});
  if (std::isfinite(vehicle.max_decel))
    conditions.add({Constraint::kBrake, 1.0, 0.0, 0.0, vehicle.planned_max_decel()});
  // Contract: finite coefficients; sliding and max speed are the cone's and
  // the speed limit's own names; a traction condition holds at f_t = 0
  // wherever the lateral part of sliding does (R >= 0, |f_q| <= mu R), so it
  // removes no speed.
  for (const ForceCondition& c : conditions.all()) {
    const bool finite =
        std::isfinite(c.t) && std::isfinite(c.q) && std::isfinite(c.r) && std::isfinite(c.c);
    const bool reserved = c.constraint == Constraint::kNone ||
                          c.constraint == Constraint::kSliding ||
                          c.constraint == Constraint::kMaxSpeed;
    if (!finite || reserved || (c.t != 0.0 && !(c.c >= 0.0 && c.r >= friction * std::abs(c.q)))) {
      throw std::logic_error("vehicle model " + std::string(name()) + ": condition '" +
                             std::string(to_string(c.constraint)) +
                             "' breaks the ForceCondition contract (admissible_set.hpp)");
    }
  }
  return AdmissibleSet(vehicle.gravity, friction, axle_load_transfer(vehicle), vehicle.max_speed,
                       vehicle.max_curvature(), conditions,
                       contact_at_wheels() ? std::optional(wheel_layout(vehicle)) : std::nullopt);
}

const VehiclePhysics& vehicle_physics(VehicleModel model) {
  switch (model) {
    case VehicleModel::kPointMass:
      return detail::point_mass_physics();
    case VehicleModel::kRigidBody:
      return detail::rigid_body_physics();
  }
  throw std::logic_error("vehicle_physics: unknown VehicleModel " +
                         std::to_string(static_cast<int>(model)));
}

}  // namespace talus
