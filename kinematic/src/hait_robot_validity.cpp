#include "talus/kinematic/hait_robot_validity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <variant>

#include "talus/core/error.hpp"
#include "talus/dynamics/chassis_placement.hpp"
#include "talus/dynamics/placement.hpp"
#include "talus/dynamics/robot_validity.hpp"
#include "talus/kinematic/terrain_quadtree.hpp"

namespace talus {

struct HaitRobotValidity::Impl {
  Impl(const RuledTerrain& t, const Robot& r, double dz)
      : terrain(t),
        robot(r),
        dz(dz),
        lower(dz > 0.0 ? t.lower_envelope(dz) : t),
        upper(dz > 0.0 ? t.upper_envelope(dz) : t),
        quadtree(upper) {}
  RuledTerrain terrain;
  Robot robot;
  double dz;
  RuledTerrain lower, upper;  ///< T_min, T_max (copies of the terrain when δz = 0)
  TerrainQuadtree quadtree;   ///< on T_max (§5.1.2)
  std::optional<ChassisPlacementTable> table;
  double seconds = 0.0;
  double half_length = 0.0, radius = 0.0;

  bool collides(const std::vector<Quad>& faces) const {
    for (const Quad& f : faces) {
      if (quadtree.collides(std::span<const Vec3>(f.data(), f.size()))) return true;
    }
    return false;
  }

  ConfigurationCheck check(const WheeledRobot& r, const SE2Pose& q) const {
    ConfigurationCheck out{false, 0.0, 0};
    Validity v;
    if (dz > 0.0) {
      const RobotPlacementInterval in =
          place_robot_interval(r, terrain, lower, upper, q.x, q.y, q.theta);
      out.placements += static_cast<std::size_t>(in.placements);
      v = check_validity(r, in);
      if (!v.valid()) return out;
    }
    // Collision: placed on T_min (the terrain itself when certain), against T_max.
    const RobotPlacement p = place_robot(r, lower, q.x, q.y, q.theta);
    ++out.placements;
    if (dz == 0.0) {
      v = check_validity(r, p);
      if (!v.valid()) return out;
    } else if (!usable(p.status)) {
      return out;
    }
    if (collides(lower_faces(r, p))) return out;
    return {true, v.margin, out.placements};
  }

  ConfigurationCheck check(const ArticulatedChassis& c, const SE2Pose& q) const {
    ConfigurationCheck out{false, 0.0, 0};
    Validity v;
    ChassisPlacement p;
    if (dz > 0.0) {
      const ChassisPlacementInterval in = table->place_interval(q.x, q.y, q.theta);
      ++out.placements;
      v = check_validity(c, in);
      if (!v.valid()) return out;
      p = place_chassis(c, lower, q.x, q.y, q.theta);  // worst case for collision: on T_min
      ++out.placements;
      if (!usable(p.status)) return out;
    } else {
      p = table->place(q.x, q.y, q.theta);
      ++out.placements;
      v = check_validity(c, p);
      if (!v.valid()) return out;
    }
    if (collides(lower_faces(c, p))) return out;
    return {true, v.margin, out.placements};
  }
};

HaitRobotValidity::HaitRobotValidity(const RuledTerrain& terrain, const Robot& robot,
                                     double terrain_uncertainty) {
  if (!(terrain_uncertainty >= 0.0) || !std::isfinite(terrain_uncertainty)) {
    std::ostringstream msg;
    msg << "HaitRobotValidity: terrain uncertainty must be >= 0 and finite, got "
        << terrain_uncertainty;
    throw InputError(msg.str());
  }
  validate(robot);
  const auto t0 = std::chrono::steady_clock::now();
  impl_ = std::make_unique<Impl>(terrain, robot, terrain_uncertainty);
  if (const auto* c = std::get_if<ArticulatedChassis>(&robot)) {
    ChassisTableOptions o;
    o.terrain_uncertainty = terrain_uncertainty;
    impl_->table.emplace(*c, terrain, o);
    const double reach = c->axle_spacing + c->body.overhang;
    const double width = std::max(c->half_axle_width, c->body.half_width);
    impl_->half_length = reach;
    impl_->radius = std::hypot(reach, width);
  } else {
    const auto& w = std::get<WheeledRobot>(robot);
    double front = w.body.front, rear = w.body.rear, width = w.body.half_width;
    for (const Vec2& p : w.wheels) {
      front = std::max(front, p.x());
      rear = std::max(rear, -p.x());
      width = std::max(width, std::abs(p.y()));
    }
    impl_->half_length = 0.5 * (front + rear);
    impl_->radius = std::hypot(std::max(front, rear), width);
  }
  impl_->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

HaitRobotValidity::~HaitRobotValidity() = default;
HaitRobotValidity::HaitRobotValidity(HaitRobotValidity&&) noexcept = default;
HaitRobotValidity& HaitRobotValidity::operator=(HaitRobotValidity&&) noexcept = default;

ConfigurationCheck HaitRobotValidity::check(const SE2Pose& q) const {
  if (!impl_->terrain.has_data(q.position())) return {false, 0.0, 0};
  return std::visit([&](const auto& r) { return impl_->check(r, q); }, impl_->robot);
}

ValidityFunction HaitRobotValidity::function() const {
  return [this](const SE2Pose& q) { return check(q); };
}

double HaitRobotValidity::preprocessing_seconds() const {
  return impl_->seconds;
}
double HaitRobotValidity::half_length() const {
  return impl_->half_length;
}
double HaitRobotValidity::radius() const {
  return impl_->radius;
}

}  // namespace talus
