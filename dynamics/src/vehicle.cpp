#include "talus/dynamics/vehicle.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
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

}  // namespace

void Vehicle::validate() const {
  require_positive("gravity", gravity);
  require_positive("friction", friction);
  require_positive("cg_height", cg_height);
  require_positive("half_track", half_track);
  require_positive("half_wheelbase", half_wheelbase);
  require_positive("max_speed", max_speed, true);
  require_positive("max_accel", max_accel, true);
  require_positive("max_decel", max_decel, true);
}

Vehicle parse_vehicle(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = detail::load_strict_yaml(yaml_text, source);
  if (!root.IsMap())
    throw InputError(source + ": a vehicle file must be a mapping of keys to values");

  static const std::set<std::string> kKnown = {"model",     "gravity",    "friction",
                                               "cg_height", "half_track", "half_wheelbase",
                                               "max_speed", "max_accel",  "max_decel"};
  std::set<std::string> seen;
  for (const auto& item : root) {
    const std::string key = item.first.as<std::string>("");
    if (!kKnown.count(key)) {
      throw InputError(source + ": unknown key '" + printable(key) +
                       "' (known: model, gravity, friction, cg_height, half_track, "
                       "half_wheelbase, max_speed, max_accel, max_decel)");
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
  if (v.model == VehicleModel::kRigidBody) required.push_back("half_wheelbase");
  for (const std::string& key : required) {
    if (!seen.count(key)) {
      throw InputError(source + ": missing required key '" + key + "' for model " + model);
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
