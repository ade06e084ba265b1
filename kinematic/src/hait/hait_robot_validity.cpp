#include "talus/kinematic/hait/hait_robot_validity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <variant>

#include "talus/core/error.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"
#include "talus/kinematic/hait/chassis_uncertainty_table.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"
#include "talus/kinematic/hait/placement.hpp"
#include "talus/kinematic/hait/robot_validity.hpp"
#include "talus/kinematic/hait/terrain_quadtree.hpp"

namespace talus {

namespace {
constexpr double kPi = std::numbers::pi;

void require(bool ok, const char* field, double value, const char* expected) {
  if (ok) return;
  std::ostringstream msg;
  msg << "HaitValidityOptions." << field << " must be " << expected << ", got " << value;
  throw InputError(msg.str());
}
}  // namespace

void HaitValidityOptions::validate() const {
  require(terrain_uncertainty >= 0.0 && std::isfinite(terrain_uncertainty), "terrain_uncertainty",
          terrain_uncertainty, "finite and >= 0 [m]");
  require(position_uncertainty >= 0.0 && std::isfinite(position_uncertainty),
          "position_uncertainty", position_uncertainty, "finite and >= 0 [m]");
  require(heading_uncertainty >= 0.0 && heading_uncertainty < kPi, "heading_uncertainty",
          heading_uncertainty, "in [0, pi) [rad]");
  require(sample_spacing > 0.0 && std::isfinite(sample_spacing), "sample_spacing", sample_spacing,
          "positive and finite [m]");
  require(sample_angle_step > 0.0 && std::isfinite(sample_angle_step), "sample_angle_step",
          sample_angle_step, "positive and finite [rad]");
  require(theta_slices >= 4, "theta_slices", theta_slices, ">= 4");
  if (terrain_uncertainty_map && terrain_uncertainty > 0.0) {
    throw InputError(
        "HaitValidityOptions: terrain_uncertainty and terrain_uncertainty_map are both set; set "
        "one (the map holds every node's delta z)");
  }
}

struct HaitRobotValidity::Impl {
  Impl(const RuledTerrain& t, const Robot& r, const HaitValidityOptions& o)
      : terrain(t),
        robot(r),
        opt(o),
        uncertain(o.terrain_uncertainty > 0.0 || o.terrain_uncertainty_map != nullptr),
        lower(o.terrain_uncertainty_map ? t.lower_envelope(*o.terrain_uncertainty_map)
              : uncertain               ? t.lower_envelope(o.terrain_uncertainty)
                                        : t),
        upper(o.terrain_uncertainty_map ? t.upper_envelope(*o.terrain_uncertainty_map)
              : uncertain               ? t.upper_envelope(o.terrain_uncertainty)
                                        : t),
        quadtree(upper) {}
  RuledTerrain terrain;
  Robot robot;
  HaitValidityOptions opt;
  bool uncertain;             ///< δz > 0 somewhere: the worst-case checks of §5.1.2
  RuledTerrain lower, upper;  ///< T_min, T_max (copies of the terrain when certain)
  TerrainQuadtree quadtree;   ///< on T_max (§5.1.2)
  std::optional<ChassisPlacementTable> table;          ///< chassis without ρ, Δθ
  std::optional<ChassisUncertaintyTable> uncertainty;  ///< chassis with ρ or Δθ
  ValidityFunction sampled;  ///< rigid body with ρ or Δθ: the sampled neighbourhood
  HaitValidityDiagnostics diagnostics;
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
    if (uncertain) {
      const RobotPlacementInterval in =
          place_robot_interval(r, terrain, lower, upper, q.x, q.y, q.theta);
      out.placements += static_cast<std::size_t>(in.placements);
      v = check_validity(r, in);
      if (!v.valid()) return out;
    }
    // Collision: placed on T_min (the terrain itself when certain), against T_max.
    const RobotPlacement p = place_robot(r, lower, q.x, q.y, q.theta);
    ++out.placements;
    if (!uncertain) {
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
    if (uncertainty) {
      // §5.2: intervals over the whole domain (and both envelopes), then the
      // moved faces, which already sit at the lowest elevations, against T_max.
      const ChassisPlacementInterval in = uncertainty->place_interval(q.x, q.y, q.theta);
      ++out.placements;
      v = check_validity(c, in);
      if (!v.valid()) return out;
      if (collides(moved_lower_faces(c, in, q.x, q.y, q.theta, opt.position_uncertainty,
                                     opt.heading_uncertainty))) {
        return out;
      }
      return {true, v.margin, out.placements};
    }
    if (uncertain) {
      const ChassisPlacementInterval in = table->place_interval(q.x, q.y, q.theta);
      ++out.placements;
      v = check_validity(c, in);
      if (!v.valid()) return out;
      // Worst case for collision: on T_min, placed directly (no table holds the whole
      // chassis on T_min): each of its Place_axle runs, the middle axle's and every
      // Place_other_axle iteration's, is a placement made for this check.
      p = place_chassis(c, lower, q.x, q.y, q.theta);
      out.placements += static_cast<std::size_t>(p.axle_placements);
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
                                     double terrain_uncertainty)
    : HaitRobotValidity(terrain, robot, [terrain_uncertainty] {
        HaitValidityOptions o;
        o.terrain_uncertainty = terrain_uncertainty;
        return o;
      }()) {}

HaitRobotValidity::HaitRobotValidity(const RuledTerrain& terrain, const Robot& robot,
                                     const HaitValidityOptions& options) {
  options.validate();
  validate(robot);
  const bool positional = options.position_uncertainty > 0.0 || options.heading_uncertainty > 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  impl_ = std::make_unique<Impl>(terrain, robot, options);
  HaitValidityDiagnostics& diag = impl_->diagnostics;
  if (const auto* c = std::get_if<ArticulatedChassis>(&robot)) {
    ChassisTableOptions o;
    o.terrain_uncertainty = options.terrain_uncertainty;
    o.terrain_uncertainty_map = options.terrain_uncertainty_map;
    o.theta_slices = options.theta_slices;
    if (positional) {
      if (!(options.heading_uncertainty < 0.5 * kPi)) {
        std::ostringstream msg;
        msg << "HaitRobotValidity: the articulated chassis needs heading_uncertainty in [0, pi/2) "
               "[rad] (the moved faces of s5.2.2), got "
            << options.heading_uncertainty;
        throw InputError(msg.str());
      }
      ChassisUncertaintyOptions u;
      u.position_uncertainty = options.position_uncertainty;
      u.heading_uncertainty = options.heading_uncertainty;
      impl_->uncertainty.emplace(*c, terrain, o, u);
      diag.table_seconds = impl_->uncertainty->diagnostics().base_seconds;
      diag.minmax_seconds = impl_->uncertainty->diagnostics().minmax_seconds;
      diag.table_placements = impl_->uncertainty->diagnostics().placements;
      diag.method = PositionUncertaintyMethod::kMinMaxSurfaces;
    } else {
      impl_->table.emplace(*c, terrain, o);
      diag.table_seconds = impl_->table->diagnostics().seconds;
      diag.table_placements = impl_->table->diagnostics().placements;
    }
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
    if (positional) {
      const Impl* impl = impl_.get();
      impl_->sampled = neighbourhood_validity(
          [impl](const SE2Pose& q) { return impl->check(std::get<WheeledRobot>(impl->robot), q); },
          options.position_uncertainty, options.heading_uncertainty, options.sample_spacing,
          options.sample_angle_step);
      diag.method = PositionUncertaintyMethod::kSampled;
    }
  }
  diag.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

HaitRobotValidity::~HaitRobotValidity() = default;
HaitRobotValidity::HaitRobotValidity(HaitRobotValidity&&) noexcept = default;
HaitRobotValidity& HaitRobotValidity::operator=(HaitRobotValidity&&) noexcept = default;

ConfigurationCheck HaitRobotValidity::check(const Impl& impl, const SE2Pose& q) {
  if (!impl.terrain.has_data(q.position())) return {false, 0.0, 0};
  if (impl.sampled) return impl.sampled(q);
  return std::visit([&](const auto& r) { return impl.check(r, q); }, impl.robot);
}

ConfigurationCheck HaitRobotValidity::check(const SE2Pose& q) const {
  return check(*impl_, q);
}

ValidityFunction HaitRobotValidity::function() const {
  const Impl* impl = impl_.get();
  return [impl](const SE2Pose& q) { return check(*impl, q); };
}

double HaitRobotValidity::preprocessing_seconds() const {
  return impl_->diagnostics.seconds;
}
const HaitValidityDiagnostics& HaitRobotValidity::diagnostics() const {
  return impl_->diagnostics;
}
double HaitRobotValidity::half_length() const {
  return impl_->half_length;
}
double HaitRobotValidity::radius() const {
  return impl_->radius;
}

}  // namespace talus
