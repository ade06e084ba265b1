#include "talus/kinematic/hait/robot.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>

#include "talus/core/detail/strict_yaml.hpp"
#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

/// Throws unless lo < value < hi (value finite); `field` names the key.
void require_open_range(const std::string& field, double value, double lo, double hi,
                        const char* expected) {
  if (!(std::isfinite(value) && value > lo && value < hi)) {
    std::ostringstream msg;
    msg << field << " must be " << expected << ", got " << value;
    throw InputError(msg.str());
  }
}

void require_positive(const std::string& field, double value) {
  require_open_range(field, value, 0.0, std::numeric_limits<double>::infinity(),
                     "a positive finite number");
}

/// One YAML mapping read strictly: every key must be known, required keys present.
class StrictMap {
 public:
  StrictMap(const YAML::Node& node, std::string path, std::string source,
            std::set<std::string> known)
      : node_(node), path_(std::move(path)), source_(std::move(source)), known_(std::move(known)) {
    if (!node_.IsMap()) throw InputError(where("") + " must be a mapping of keys to values");
    for (const auto& item : node_) {
      const std::string key = item.first.as<std::string>("");
      if (!known_.count(key)) {
        std::string list;
        for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
        throw InputError(source_ + ": unknown key '" + qualified(key) + "' (known: " + list + ")");
      }
    }
  }

  bool has(const std::string& key) const { return static_cast<bool>(node_[key]); }

  const YAML::Node require(const std::string& key) const {
    if (!has(key)) throw InputError(source_ + ": missing required key '" + qualified(key) + "'");
    return node_[key];
  }

  double number(const std::string& key) const { return as_number(require(key), qualified(key)); }
  void optional_number(const std::string& key, double& out) const {
    if (has(key)) out = as_number(node_[key], qualified(key));
  }
  std::string string(const std::string& key) const {
    const YAML::Node n = require(key);
    if (!n.IsScalar())
      throw InputError(source_ + ": key '" + qualified(key) + "' must be a string");
    return n.as<std::string>();
  }

  double as_number(const YAML::Node& n, const std::string& name) const {
    try {
      if (!n.IsScalar()) throw YAML::Exception(YAML::Mark::null_mark(), "not a scalar");
      return n.as<double>();
    } catch (const YAML::Exception&) {
      throw InputError(source_ + ": key '" + name + "' must be a number, got '" +
                       n.as<std::string>("<not a scalar>") + "'");
    }
  }

  std::string qualified(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  std::string where(const std::string& key) const {
    return source_ + ": " +
           (key.empty() ? (path_.empty() ? "a robot file" : "'" + path_ + "'")
                        : "'" + qualified(key) + "'");
  }

 private:
  YAML::Node node_;
  std::string path_, source_;
  std::set<std::string> known_;
};

BodyBox parse_body_box(const YAML::Node& node, const std::string& source) {
  const StrictMap m(node, "body", source, {"front", "rear", "half_width", "clearance"});
  BodyBox b;
  b.front = m.number("front");
  b.rear = m.number("rear");
  b.half_width = m.number("half_width");
  b.clearance = m.number("clearance");
  return b;
}

ChassisBody parse_chassis_body(const YAML::Node& node, const std::string& source) {
  const StrictMap m(node, "body", source, {"half_width", "clearance", "overhang"});
  ChassisBody b;
  b.half_width = m.number("half_width");
  b.clearance = m.number("clearance");
  b.overhang = m.number("overhang");
  return b;
}

WheeledRobot parse_wheeled(const StrictMap& m, const std::string& source) {
  WheeledRobot r;
  if (m.has("name")) r.name = m.string("name");
  const YAML::Node wheels = m.require("wheels");
  if (!wheels.IsSequence())
    throw InputError(source + ": key 'wheels' must be a list of [u, v] pairs");
  for (std::size_t j = 0; j < wheels.size(); ++j) {
    const std::string name = "wheels[" + std::to_string(j) + "]";
    const YAML::Node w = wheels[j];
    if (!w.IsSequence() || w.size() != 2)
      throw InputError(source + ": key '" + name + "' must be a pair [u, v] in metres");
    r.wheels.emplace_back(m.as_number(w[0], name), m.as_number(w[1], name));
  }
  r.cg_height = m.number("cg_height");
  r.max_spring_extension = m.number("max_spring_extension");
  r.max_roll = m.number("max_roll");
  r.max_pitch = m.number("max_pitch");
  r.body = parse_body_box(m.require("body"), source);
  return r;
}

ArticulatedChassis parse_chassis(const StrictMap& m, const std::string& source) {
  ArticulatedChassis c;
  if (m.has("name")) c.name = m.string("name");
  c.half_axle_width = m.number("half_axle_width");
  c.axle_spacing = m.number("axle_spacing");
  c.max_axle_roll_difference = m.number("max_axle_roll_difference");
  c.max_roll = m.number("max_roll");
  c.min_pitch = m.number("min_pitch");
  c.max_pitch = m.number("max_pitch");
  c.min_body_angle = m.number("min_body_angle");
  c.max_body_angle = m.number("max_body_angle");
  c.body = parse_chassis_body(m.require("body"), source);
  return c;
}

}  // namespace

void WheeledRobot::validate() const {
  const int n = static_cast<int>(wheels.size());
  if (n < 3 || n > kMaxWheels) {
    throw InputError("wheels must list 3 to " + std::to_string(kMaxWheels) +
                     " contact points, got " + std::to_string(n));
  }
  for (int j = 0; j < n; ++j) {
    if (!wheels[j].allFinite())
      throw InputError("wheels[" + std::to_string(j) + "] must be finite numbers");
  }
  // The least-squares contact plane needs wheels that span a plane: the 2x2
  // scatter matrix of the (u, v) points must be non-singular.
  Vec2 mean = Vec2::Zero();
  for (const Vec2& w : wheels) mean += w;
  mean /= n;
  Mat2 scatter = Mat2::Zero();
  for (const Vec2& w : wheels) scatter += (w - mean) * (w - mean).transpose();
  const double span = std::sqrt(std::abs(scatter.determinant()));
  if (!(span > 1e-6 * std::max(1.0, scatter.trace())))
    throw InputError("wheels must not be collinear (the contact plane would be undefined)");
  require_positive("cg_height", cg_height);
  require_positive("max_spring_extension", max_spring_extension);
  require_open_range("max_roll", max_roll, 0.0, kPi / 2, "in (0, pi/2) rad");
  require_open_range("max_pitch", max_pitch, 0.0, kPi / 2, "in (0, pi/2) rad");
  require_positive("body.front", body.front);
  require_positive("body.rear", body.rear);
  require_positive("body.half_width", body.half_width);
  require_positive("body.clearance", body.clearance);
}

void ArticulatedChassis::validate() const {
  require_positive("half_axle_width", half_axle_width);
  require_positive("axle_spacing", axle_spacing);
  require_open_range("max_axle_roll_difference", max_axle_roll_difference, 0.0, kPi,
                     "in (0, pi) rad");
  require_open_range("max_roll", max_roll, 0.0, kPi / 2, "in (0, pi/2) rad");
  require_open_range("min_pitch", min_pitch, -kPi / 2, 0.0, "in (-pi/2, 0) rad");
  require_open_range("max_pitch", max_pitch, 0.0, kPi / 2, "in (0, pi/2) rad");
  require_open_range("min_body_angle", min_body_angle, 0.0, kPi, "in (0, pi) rad");
  require_open_range("max_body_angle", max_body_angle, kPi, 2 * kPi, "in (pi, 2 pi) rad");
  require_positive("body.half_width", body.half_width);
  require_positive("body.clearance", body.clearance);
  if (!(std::isfinite(body.overhang) && body.overhang >= 0.0)) {
    std::ostringstream msg;
    msg << "body.overhang must be a finite number >= 0, got " << body.overhang;
    throw InputError(msg.str());
  }
}

void validate(const Robot& robot) {
  std::visit([](const auto& r) { r.validate(); }, robot);
}

Robot parse_robot(std::string_view yaml_text, const std::string& source) {
  const YAML::Node root = detail::load_strict_yaml(std::string(yaml_text), source);
  if (!root.IsMap())
    throw InputError(source + ": a robot file must be a mapping of keys to values");
  const YAML::Node type_node = root["type"];
  if (!type_node)
    throw InputError(source + ": missing required key 'type' (wheeled or articulated_chassis)");
  const std::string type = type_node.as<std::string>("");
  Robot robot;
  if (type == "wheeled") {
    const StrictMap m(root, "", source,
                      {"type", "name", "wheels", "cg_height", "max_spring_extension", "max_roll",
                       "max_pitch", "body"});
    robot = parse_wheeled(m, source);
  } else if (type == "articulated_chassis") {
    const StrictMap m(
        root, "", source,
        {"type", "name", "half_axle_width", "axle_spacing", "max_axle_roll_difference", "max_roll",
         "min_pitch", "max_pitch", "min_body_angle", "max_body_angle", "body"});
    robot = parse_chassis(m, source);
  } else {
    throw InputError(source + ": key 'type' must be wheeled or articulated_chassis, got '" +
                     printable(type) + "'");
  }
  try {
    validate(robot);
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  return robot;
}

Robot load_robot(const std::filesystem::path& path) {
  return parse_robot(read_input_file(path.string(), kMaxConfigFileBytes),
                     printable(path.string(), 200));
}

}  // namespace talus
