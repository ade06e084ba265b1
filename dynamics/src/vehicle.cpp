#include "talus/dynamics/vehicle.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>

#include "talus/core/detail/strict_yaml.hpp"
#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"

namespace talus {
namespace {

void require_positive(const char* field, double value, bool allow_infinity = false) {
  const bool ok = value > 0.0 && (std::isfinite(value) || (allow_infinity && std::isinf(value)));
  if (!ok) {
    std::ostringstream msg;
    msg << "Vehicle." << field << " must be a positive" << (allow_infinity ? "" : " finite")
        << " number, got " << value;
    throw InputError(msg.str());
  }
}

double read_number(const YAML::Node& node, const std::string& key, const std::string& source) {
  try {
    const double value = node.as<double>();
    return value;
  } catch (const YAML::Exception&) {
    throw InputError(source + ": key '" + key + "' must be a number, got '" +
                     printable(node.as<std::string>("<not a scalar>")) + "'");
  }
}

void require_non_negative(const char* field, double value) {
  if (!(value >= 0.0 && std::isfinite(value))) {
    std::ostringstream msg;
    msg << "VehicleBody." << field << " must be a finite number >= 0, got " << value;
    throw InputError(msg.str());
  }
}

}  // namespace

void VehicleBody::validate() const {
  const auto positive = [](const char* field, double value) {
    if (!(value > 0.0 && std::isfinite(value))) {
      std::ostringstream msg;
      msg << "VehicleBody." << field << " must be a positive finite number, got " << value;
      throw InputError(msg.str());
    }
  };
  positive("mass", mass);
  positive("inertia_roll", inertia_roll);
  positive("inertia_pitch", inertia_pitch);
  positive("inertia_yaw", inertia_yaw);
  positive("wheel_radius", wheel_radius);
  positive("suspension_stiffness", suspension_stiffness);
  require_non_negative("suspension_damping", suspension_damping);
  positive("cornering_stiffness", cornering_stiffness);
  // Documented ranges (data/vehicles/README.md): beyond them the tyre or the suspension is
  // stiffer than any vehicle, and the simulation's stiff integration crawls (1e300 took 42 s).
  if (cornering_stiffness > kMaxCorneringStiffness) {
    std::ostringstream msg;
    msg << "VehicleBody.cornering_stiffness must be in (0, " << kMaxCorneringStiffness
        << "] 1/rad (tyres have about 5-30), got " << cornering_stiffness;
    throw InputError(msg.str());
  }
  const double ride_frequency =
      std::sqrt(suspension_stiffness / (0.25 * mass)) / (2.0 * std::numbers::pi);
  if (ride_frequency > kMaxRideFrequency) {
    std::ostringstream msg;
    msg << "VehicleBody.suspension_stiffness gives a ride frequency of " << ride_frequency
        << " Hz for mass " << mass << " kg; it must be at most " << kMaxRideFrequency
        << " Hz (vehicles ride at about 1-5 Hz), i.e. suspension_stiffness <= "
        << 0.25 * mass * std::pow(2.0 * std::numbers::pi * kMaxRideFrequency, 2) << " N/m";
    throw InputError(msg.str());
  }
}

VehicleBody default_vehicle_body(double mass, double half_wheelbase, double half_track,
                                 double cg_height) {
  VehicleBody b;
  b.mass = mass;
  const double length = 2.0 * half_wheelbase, width = 2.0 * half_track, height = 2.0 * cg_height;
  b.inertia_roll = mass * (width * width + height * height) / 12.0;
  b.inertia_pitch = mass * (length * length + height * height) / 12.0;
  b.inertia_yaw = mass * (length * length + width * width) / 12.0;
  b.wheel_radius = 0.5 * cg_height;
  const double omega = 2.0 * 3.14159265358979323846 * 3.0;  // 3 Hz ride frequency
  b.suspension_stiffness = 0.25 * mass * omega * omega;
  b.suspension_damping = 2.0 * 0.4 * std::sqrt(b.suspension_stiffness * 0.25 * mass);
  b.cornering_stiffness = 8.0;
  return b;
}

void Vehicle::validate() const {
  require_positive("gravity", gravity);
  require_positive("friction", friction);
  require_positive("cg_height", cg_height);
  require_positive("half_track", half_track);
  require_positive("half_wheelbase", half_wheelbase);
  require_positive("max_speed", max_speed, true);
  require_positive("max_accel", max_accel, true);
  require_positive("max_decel", max_decel, true);
  const bool unlimited = max_steering == std::numeric_limits<double>::infinity();
  if (!unlimited && !(max_steering > 0.0 && max_steering < 0.5 * std::numbers::pi)) {
    std::ostringstream msg;
    msg << "Vehicle.max_steering must be in (0, pi/2) rad (or +inf: none), got " << max_steering;
    throw InputError(msg.str());
  }
  for (const auto& [name, value] : {std::pair{"contact_reserve", contact_reserve},
                                    std::pair{"friction_reserve", friction_reserve},
                                    std::pair{"drive_reserve", drive_reserve}}) {
    if (!(value >= 0.0 && value < 1.0)) {
      std::ostringstream msg;
      msg << "Vehicle." << name << " must be in [0, 1), got " << value;
      throw InputError(msg.str());
    }
  }
  if (axle_friction && model != VehicleModel::kRigidBody)
    throw InputError("Vehicle.axle_friction needs model rigid_body (the point mass has no axles)");
  if (body) body->validate();
}

double Vehicle::max_curvature() const {
  if (!std::isfinite(max_steering)) return std::numeric_limits<double>::infinity();
  return std::tan(max_steering) / (2.0 * half_wheelbase);
}

Vehicle parse_vehicle(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = detail::load_strict_yaml(yaml_text, source);
  if (!root.IsMap())
    throw InputError(source + ": a vehicle file must be a mapping of keys to values");

  static const std::set<std::string> kKnown = {"model",
                                               "gravity",
                                               "friction",
                                               "cg_height",
                                               "half_track",
                                               "half_wheelbase",
                                               "max_speed",
                                               "max_accel",
                                               "max_decel",
                                               "max_steering",
                                               "contact_reserve",
                                               "friction_reserve",
                                               "drive_reserve",
                                               "axle_friction",
                                               "mass",
                                               "inertia_roll",
                                               "inertia_pitch",
                                               "inertia_yaw",
                                               "wheel_radius",
                                               "suspension_stiffness",
                                               "suspension_damping",
                                               "cornering_stiffness"};
  static const std::set<std::string> kBodyKeys = {
      "inertia_roll",         "inertia_pitch",      "inertia_yaw",        "wheel_radius",
      "suspension_stiffness", "suspension_damping", "cornering_stiffness"};
  std::set<std::string> seen;
  for (const auto& item : root) {
    const std::string key = item.first.as<std::string>("");
    if (!kKnown.count(key)) {
      throw InputError(
          source + ": unknown key '" + printable(key) +
          "' (known: model, gravity, friction, cg_height, half_track, "
          "half_wheelbase, max_speed, max_accel, max_decel, max_steering, "
          "contact_reserve, friction_reserve, drive_reserve, axle_friction; and for "
          "the simulation mass, inertia_roll, inertia_pitch, inertia_yaw, wheel_radius, "
          "suspension_stiffness, suspension_damping, cornering_stiffness)");
    }
    seen.insert(key);
  }
  Vehicle v;
  if (!seen.count("model"))
    throw InputError(source + ": missing required key 'model' (point_mass or rigid_body)");
  const std::string model = root["model"].as<std::string>("");
  if (model == "point_mass") {
    v.model = VehicleModel::kPointMass;
  } else if (model == "rigid_body") {
    v.model = VehicleModel::kRigidBody;
  } else {
    throw InputError(source + ": key 'model' must be point_mass or rigid_body, got '" +
                     printable(model) + "'");
  }
  std::vector<std::string> required = {"friction", "cg_height", "half_track"};
  if (v.model == VehicleModel::kRigidBody || seen.count("max_steering"))
    required.push_back("half_wheelbase");
  for (const std::string& key : required) {
    if (!seen.count(key)) {
      const bool for_steering = key == "half_wheelbase" && v.model == VehicleModel::kPointMass;
      throw InputError(source + ": missing required key '" + key + "' for model " + model +
                       (for_steering ? " with max_steering" : ""));
    }
  }
  const auto number = [&](const char* key, double& field) {
    if (seen.count(key)) field = read_number(root[key], key, source);
  };
  number("gravity", v.gravity);
  number("friction", v.friction);
  number("cg_height", v.cg_height);
  number("half_track", v.half_track);
  number("half_wheelbase", v.half_wheelbase);
  number("max_speed", v.max_speed);
  number("max_accel", v.max_accel);
  number("max_decel", v.max_decel);
  number("max_steering", v.max_steering);
  number("contact_reserve", v.contact_reserve);
  number("friction_reserve", v.friction_reserve);
  number("drive_reserve", v.drive_reserve);
  if (seen.count("axle_friction")) {
    try {
      v.axle_friction = root["axle_friction"].as<bool>();
    } catch (const YAML::Exception&) {
      throw InputError(source + ": key 'axle_friction' must be true or false, got '" +
                       printable(root["axle_friction"].as<std::string>("<not a scalar>")) + "'");
    }
  }
  if (seen.count("mass")) {
    double mass = 0.0;
    number("mass", mass);
    if (!(mass > 0.0 && std::isfinite(mass)))
      throw InputError(source + ": key 'mass' must be a positive finite number, got " +
                       std::to_string(mass));
    VehicleBody body = default_vehicle_body(mass, v.half_wheelbase, v.half_track, v.cg_height);
    number("inertia_roll", body.inertia_roll);
    number("inertia_pitch", body.inertia_pitch);
    number("inertia_yaw", body.inertia_yaw);
    number("wheel_radius", body.wheel_radius);
    number("suspension_stiffness", body.suspension_stiffness);
    if (seen.count("suspension_stiffness") && !seen.count("suspension_damping") &&
        body.suspension_stiffness > 0.0)
      body.suspension_damping = 2.0 * 0.4 * std::sqrt(body.suspension_stiffness * 0.25 * mass);
    number("suspension_damping", body.suspension_damping);
    number("cornering_stiffness", body.cornering_stiffness);
    v.body = body;
  } else {
    for (const std::string& key : kBodyKeys) {
      if (seen.count(key))
        throw InputError(source + ": key '" + key +
                         "' describes the simulated body and needs 'mass' as well");
    }
  }
  try {
    v.validate();
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  return v;
}

Vehicle load_vehicle(const std::string& path) {
  return parse_vehicle(read_input_file(path, kMaxConfigFileBytes), printable(path, 200));
}

}  // namespace talus
