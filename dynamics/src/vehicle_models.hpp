#pragma once
// The model instances vehicle_physics() hands out; each is defined in its own
// file under dynamics/src/models/.
#include "talus/dynamics/vehicle_physics.hpp"

namespace talus::detail {

const VehiclePhysics& point_mass_physics();
const VehiclePhysics& rigid_body_physics();

}  // namespace talus::detail
