#include "talus/kinematic/eldershaw_yim/legged_robot.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>

#include "talus/core/detail/strict_yaml.hpp"
#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"

namespace talus {
namespace {

constexpr std::size_t kMaxLegs = 16;
constexpr std::size_t kMaxRangeVertices = 64;
constexpr std::size_t kMaxFieldNodes = 100000;

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// True when the closed segments [a, b] and [c, d] intersect.
bool segments_intersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  auto on = [](const Vec2& p, const Vec2& q, const Vec2& r, double c) {
    return c == 0 && std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

void require_finite(const std::string& field, double v) {
  if (!std::isfinite(v)) throw InputError(field + " must be a finite number");
}

void validate_field(const BodyField& f, const std::string& field, bool positive) {
  auto check = [&](double v) {
    require_finite(field, v);
    if (positive && !(v > 0)) {
      std::ostringstream m;
      m << field << " must be > 0 m, got " << v;
      throw InputError(m.str());
    }
  };
  if (!f.is_grid()) {
    check(f.constant);
    return;
  }
  if (!(std::isfinite(f.spacing) && f.spacing > 0))
    throw InputError(field + ".spacing must be a positive finite number");
  if (!f.origin.allFinite()) throw InputError(field + ".origin must be finite numbers");
  if (f.nu < 2 || f.nv < 2 || f.values.size() != f.nu * f.nv)
    throw InputError(field + " must be a grid of at least 2 x 2 nodes, all rows of one length");
  for (double v : f.values) check(v);
}

// ---------------------------------------------------------------- YAML

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  void keys(const YAML::Node& n, const std::string& path, const std::set<std::string>& known,
            const std::set<std::string>& required) const {
    if (!n.IsMap())
      throw InputError(source_ + ": '" + path + "' must be a mapping of keys to values");
    for (const auto& item : n) {
      const std::string key = item.first.as<std::string>("");
      if (!known.count(key)) {
        std::string list;
        for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
        throw InputError(source_ + ": unknown key '" + join(path, printable(key, 60)) +
                         "' (known: " + list + ")");
      }
    }
    for (const auto& k : required) {
      if (!n[k]) throw InputError(source_ + ": missing required key '" + join(path, k) + "'");
    }
  }

  double number(const YAML::Node& n, const std::string& name) const {
    try {
      if (!n.IsScalar()) throw YAML::Exception(YAML::Mark::null_mark(), "not a scalar");
      return n.as<double>();
    } catch (const YAML::Exception&) {
      throw InputError(source_ + ": key '" + name + "' must be a number, got '" +
                       printable(n.as<std::string>("<not a scalar>"), 60) + "'");
    }
  }

  Vec2 pair(const YAML::Node& n, const std::string& name) const {
    if (!n.IsSequence() || n.size() != 2)
      throw InputError(source_ + ": key '" + name + "' must be a pair [u, v] in metres");
    return {number(n[0], name), number(n[1], name)};
  }

  /// A list of rows of numbers (a grid, row k at v0 + k h).
  void grid(const YAML::Node& n, const std::string& name, BodyField& f) const {
    if (!n.IsSequence() || n.size() < 2)
      throw InputError(source_ + ": key '" + name + "' must be a list of at least 2 rows");
    f.nv = n.size();
    for (std::size_t k = 0; k < n.size(); ++k) {
      const std::string row = name + "[" + std::to_string(k) + "]";
      if (!n[k].IsSequence() || n[k].size() < 2)
        throw InputError(source_ + ": key '" + row + "' must be a list of at least 2 numbers");
      if (k == 0) f.nu = n[k].size();
      if (n[k].size() != f.nu)
        throw InputError(source_ + ": key '" + row + "' has " + std::to_string(n[k].size()) +
                         " values, row 0 has " + std::to_string(f.nu));
      if (f.nu * f.nv > kMaxFieldNodes)
        throw InputError(source_ + ": key '" + name + "' has more than " +
                         std::to_string(kMaxFieldNodes) + " values");
      for (std::size_t i = 0; i < n[k].size(); ++i) f.values.push_back(number(n[k][i], row));
    }
  }

  /// {origin: [u0, v0], spacing: h, KEY: rows}.
  BodyField field_grid(const YAML::Node& n, const std::string& path,
                       const std::string& values_key) const {
    keys(n, path, {"origin", "spacing", values_key}, {"origin", "spacing", values_key});
    BodyField f;
    f.origin = pair(n["origin"], path + ".origin");
    f.spacing = number(n["spacing"], path + ".spacing");
    grid(n[values_key], path + "." + values_key, f);
    return f;
  }

  Leg leg(const YAML::Node& n, const std::string& path) const {
    keys(n, path, {"name", "attachment", "range", "reach"}, {"attachment", "range", "reach"});
    Leg leg;
    if (n["name"]) {
      if (!n["name"].IsScalar())
        throw InputError(source_ + ": key '" + path + ".name' must be a string");
      leg.name = n["name"].as<std::string>();
    }
    leg.attachment = pair(n["attachment"], path + ".attachment");
    const YAML::Node range = n["range"];
    if (!range.IsSequence() || range.size() < 3 || range.size() > kMaxRangeVertices)
      throw InputError(source_ + ": key '" + path + ".range' must be a list of 3 to " +
                       std::to_string(kMaxRangeVertices) + " [u, v] vertices");
    for (std::size_t k = 0; k < range.size(); ++k)
      leg.range.push_back(pair(range[k], path + ".range[" + std::to_string(k) + "]"));
    const YAML::Node reach = n["reach"];
    if (reach.IsScalar()) {
      leg.reach.constant = number(reach, path + ".reach");
    } else if (reach.IsMap()) {
      leg.reach = field_grid(reach, path + ".reach", "values");
    } else {
      throw InputError(source_ + ": key '" + path +
                       ".reach' must be a number [m] or {origin, spacing, values}");
    }
    return leg;
  }

  const std::string& source() const { return source_; }

 private:
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  std::string source_;
};

}  // namespace

bool BodyField::covers(const Vec2& uv) const {
  if (!is_grid()) return true;
  const double eps = 1e-9 * std::max(1.0, spacing);
  return uv.x() >= origin.x() - eps && uv.y() >= origin.y() - eps &&
         uv.x() <= origin.x() + static_cast<double>(nu - 1) * spacing + eps &&
         uv.y() <= origin.y() + static_cast<double>(nv - 1) * spacing + eps;
}

double BodyField::at(const Vec2& uv) const {
  if (!is_grid()) return constant;
  const double fu = std::clamp((uv.x() - origin.x()) / spacing, 0.0, static_cast<double>(nu - 1));
  const double fv = std::clamp((uv.y() - origin.y()) / spacing, 0.0, static_cast<double>(nv - 1));
  const std::size_t i = std::min(static_cast<std::size_t>(fu), nu - 2);
  const std::size_t k = std::min(static_cast<std::size_t>(fv), nv - 2);
  const double a = fu - static_cast<double>(i), b = fv - static_cast<double>(k);
  const double* r0 = &values[k * nu + i];
  const double* r1 = r0 + nu;
  return (1 - a) * (1 - b) * r0[0] + a * (1 - b) * r0[1] + (1 - a) * b * r1[0] + a * b * r1[1];
}

bool Leg::in_range(const Vec2& p) const {
  // Convex or not: the crossing-number test, boundary points counted inside.
  const std::size_t n = range.size();
  bool inside = false;
  for (std::size_t k = 0, m = n - 1; k < n; m = k++) {
    const Vec2& a = range[m];
    const Vec2& b = range[k];
    const Vec2 ab = b - a, ap = p - a;
    if (std::abs(cross(ab, ap)) <= 1e-12 * std::max(1.0, ab.squaredNorm()) && ap.dot(ab) >= 0 &&
        ap.dot(ab) <= ab.squaredNorm())
      return true;
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

void LeggedRobot::validate() const {
  if (legs.size() < 3 || legs.size() > kMaxLegs)
    throw InputError("legs must list 3 to " + std::to_string(kMaxLegs) + " legs, got " +
                     std::to_string(legs.size()));
  for (std::size_t l = 0; l < legs.size(); ++l) {
    const Leg& leg = legs[l];
    const std::string name = "legs[" + std::to_string(l) + "]";
    if (!leg.attachment.allFinite()) throw InputError(name + ".attachment must be finite numbers");
    const std::size_t n = leg.range.size();
    if (n < 3 || n > kMaxRangeVertices)
      throw InputError(name + ".range must have 3 to " + std::to_string(kMaxRangeVertices) +
                       " vertices");
    double area2 = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      if (!leg.range[k].allFinite()) throw InputError(name + ".range must be finite numbers");
      area2 += cross(leg.range[k], leg.range[(k + 1) % n]);
    }
    if (!(area2 > 0))
      throw InputError(name + ".range must be listed counter-clockwise with a positive area");
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = a + 1; b < n; ++b) {
        if (b == a + 1 || (a == 0 && b == n - 1)) continue;  // neighbouring edges
        if (segments_intersect(leg.range[a], leg.range[(a + 1) % n], leg.range[b],
                               leg.range[(b + 1) % n]))
          throw InputError(name + ".range must be a simple polygon (edges " + std::to_string(a) +
                           " and " + std::to_string(b) + " cross)");
      }
    }
    validate_field(leg.reach, name + ".reach", true);
    if (leg.reach.is_grid()) {
      for (std::size_t k = 0; k < n; ++k) {
        if (!leg.reach.covers(leg.range[k]))
          throw InputError(name + ".reach: the grid does not cover range vertex " +
                           std::to_string(k));
      }
    }
  }
  if (!under_carriage.depth.is_grid())
    throw InputError("under_carriage.depth must be a grid of at least 2 x 2 nodes");
  validate_field(under_carriage.depth, "under_carriage", false);
  if (!(std::isfinite(max_traction_slope) && max_traction_slope > 0 &&
        max_traction_slope < std::numbers::pi / 2)) {
    std::ostringstream m;
    m << "max_traction_slope must be in (0, pi/2) rad, got " << max_traction_slope;
    throw InputError(m.str());
  }
  if (!(std::isfinite(foot_print) && foot_print > 0)) {
    std::ostringstream m;
    m << "foot_print must be a positive finite number [m], got " << foot_print;
    throw InputError(m.str());
  }
}

double LeggedRobot::outer_radius() const {
  double r = 0.0;
  for (const Leg& leg : legs)
    for (const Vec2& p : leg.range) r = std::max(r, p.norm());
  return r;
}

double LeggedRobot::max_reach() const {
  double r = 0.0;
  for (const Leg& leg : legs) {
    if (leg.reach.is_grid()) {
      for (double v : leg.reach.values) r = std::max(r, v);
    } else {
      r = std::max(r, leg.reach.constant);
    }
  }
  return r;
}

LeggedRobot parse_legged_robot(std::string_view yaml_text, const std::string& source) {
  const YAML::Node root = detail::load_strict_yaml(std::string(yaml_text), source);
  const Reader rd(source);
  if (!root.IsMap())
    throw InputError(source + ": a robot file must be a mapping of keys to values");
  const YAML::Node type = root["type"];
  if (!type || !type.IsScalar() || type.as<std::string>() != "legged")
    throw InputError(source + ": key 'type' must be legged, got '" +
                     printable(type ? type.as<std::string>("<not a scalar>") : "<missing>", 60) +
                     "'");
  rd.keys(root, "", {"type", "name", "legs", "under_carriage", "max_traction_slope", "foot_print"},
          {"type", "legs", "under_carriage", "max_traction_slope", "foot_print"});
  LeggedRobot r;
  if (root["name"]) {
    if (!root["name"].IsScalar()) throw InputError(source + ": key 'name' must be a string");
    r.name = root["name"].as<std::string>();
  }
  const YAML::Node legs = root["legs"];
  if (!legs.IsSequence()) throw InputError(source + ": key 'legs' must be a list of legs");
  if (legs.size() > kMaxLegs)
    throw InputError(source + ": legs must list 3 to " + std::to_string(kMaxLegs) + " legs");
  for (std::size_t l = 0; l < legs.size(); ++l)
    r.legs.push_back(rd.leg(legs[l], "legs[" + std::to_string(l) + "]"));
  r.under_carriage.depth = rd.field_grid(root["under_carriage"], "under_carriage", "depth");
  r.max_traction_slope = rd.number(root["max_traction_slope"], "max_traction_slope");
  r.foot_print = rd.number(root["foot_print"], "foot_print");
  try {
    r.validate();
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  return r;
}

LeggedRobot load_legged_robot(const std::filesystem::path& path) {
  return parse_legged_robot(read_input_file(path.string(), kMaxConfigFileBytes),
                            printable(path.string(), 200));
}

}  // namespace talus
