#include "talus/kinematic/hait/placement_query.hpp"

#include <cmath>
#include <limits>
#include <span>
#include <sstream>
#include <variant>

#include "talus/core/error.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"
#include "talus/kinematic/hait/robot_validity.hpp"

namespace talus {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool collides(const TerrainQuadtree& tree, const std::vector<Quad>& faces) {
  for (const Quad& f : faces) {
    if (tree.collides(std::span<const Vec3>(f.data(), f.size()))) return true;
  }
  return false;
}

/// The reason of an invalid placement (status first, then the failed check).
std::string reason(PlacementStatus status, const Validity& v) {
  if (!usable(status)) return to_string(status);
  return to_string(v.failed);
}

}  // namespace

PlacementQuery::PlacementQuery(const RuledTerrain& terrain, Robot robot)
    : robot_(std::move(robot)), quadtree_(terrain) {
  validate(robot_);
}

std::vector<std::string> PlacementQuery::contact_names() const {
  if (const auto* w = std::get_if<WheeledRobot>(&robot_)) {
    std::vector<std::string> names;
    for (std::size_t j = 0; j < w->wheels.size(); ++j)
      names.push_back("extension_" + std::to_string(j + 1));
    return names;
  }
  return {"roll_front", "roll_middle", "roll_rear", "pitch_front", "pitch_rear"};
}

ConfigurationPlacement PlacementQuery::place(const SE2Pose& q) const {
  if (!(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.theta))) {
    throw InputError("PlacementQuery::place: the configuration must be finite");
  }
  const RuledTerrain& t = terrain();
  if (!t.contains(q.position())) {
    std::ostringstream msg;
    msg.precision(10);
    msg << "PlacementQuery::place: (" << q.x << ", " << q.y << ") is off the terrain";
    throw InputError(msg.str());
  }
  ConfigurationPlacement out;
  out.q = q;
  if (const auto* w = std::get_if<WheeledRobot>(&robot_)) {
    const RobotPlacement p = place_robot(*w, t, q.x, q.y, q.theta);
    out.status = p.status;
    const bool ok = usable(p.status);
    out.z = ok ? p.position.z() : kNaN;
    out.roll = ok ? p.roll : kNaN;
    out.pitch = ok ? p.pitch : kNaN;
    for (std::size_t j = 0; j < w->wheels.size(); ++j)
      out.contacts.push_back(ok ? p.extensions[j] : kNaN);
    const Validity v = ok ? check_validity(*w, p) : Validity{ValidityCheck::kPlacement, 0.0};
    out.reason = reason(p.status, v);
    if (v.valid()) out.reason = collides(quadtree_, lower_faces(*w, p)) ? "collision" : "none";
  } else {
    const auto& c = std::get<ArticulatedChassis>(robot_);
    const ChassisPlacement p = place_chassis(c, t, q.x, q.y, q.theta);
    out.status = p.status;
    const bool ok = usable(p.status);
    out.z = ok ? p.z : kNaN;
    out.roll = ok ? p.roll() : kNaN;
    out.pitch = ok ? p.pitch() : kNaN;
    for (double v : {p.roll_front, p.roll_middle, p.roll_rear, p.pitch_front, p.pitch_rear})
      out.contacts.push_back(ok ? v : kNaN);
    const Validity v = ok ? check_validity(c, p) : Validity{ValidityCheck::kPlacement, 0.0};
    out.reason = reason(p.status, v);
    if (v.valid()) out.reason = collides(quadtree_, lower_faces(c, p)) ? "collision" : "none";
  }
  out.valid = out.reason == "none";
  return out;
}

}  // namespace talus
