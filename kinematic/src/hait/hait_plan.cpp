// plan_hait(): the Haït–Siméon–Taïx planner on a real robot and terrain —
// the robot validity oracle (with the §5 uncertainties), the potential
// bitmaps of the two control points, then hait_search(). The preprocessing
// time includes the chassis table and, under position uncertainty, its
// min/max surfaces (the paper: 12 s without uncertainty, 72 s with, §5.4).
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <variant>

#include "talus/core/error.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"
#include "talus/kinematic/hait/hait_robot_validity.hpp"
#include "talus/kinematic/hait/potential_bitmap.hpp"

namespace talus {

namespace {

void require_on_map(const RuledTerrain& terrain, const SE2Pose& q, const char* what) {
  if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.theta)) {
    throw InputError(std::string("plan_hait: ") + what + " configuration is not finite");
  }
  if (!terrain.has_data(q.position())) {
    std::ostringstream msg;
    msg << "plan_hait: " << what << " position (" << q.x << ", " << q.y << ") is "
        << (terrain.contains(q.position()) ? "on NODATA terrain" : "off the map");
    throw InputError(msg.str());
  }
}

/// The bitmap's slope and roughness limits from the robot's own limits: the
/// steepest slope it may stand on and the largest bump its body clears.
PotentialBitmapOptions bitmap_options(const Robot& robot, double radius, double rho) {
  PotentialBitmapOptions o;
  o.robot_radius = radius;
  o.position_uncertainty = rho;
  if (const auto* w = std::get_if<WheeledRobot>(&robot)) {
    o.max_slope = std::min(w->max_roll, w->max_pitch);
    o.max_roughness = w->body.clearance;
  } else {
    const auto& c = std::get<ArticulatedChassis>(robot);
    o.max_slope = std::min({c.max_roll, c.max_pitch, -c.min_pitch});
    o.max_roughness = c.body.clearance;
  }
  return o;
}

}  // namespace

HaitValidityOptions hait_validity_options(const HaitOptions& options) {
  HaitValidityOptions vo;
  vo.terrain_uncertainty = options.terrain_uncertainty;
  vo.terrain_uncertainty_map = options.terrain_uncertainty_map;
  vo.position_uncertainty = options.position_uncertainty;
  vo.heading_uncertainty = options.heading_uncertainty;
  vo.sample_spacing = options.check_spacing;
  vo.sample_angle_step = 2.0 * std::numbers::pi / options.theta_bins;
  return vo;
}

HaitResult plan_hait(const RuledTerrain& terrain, const Robot& robot, const SE2Pose& start,
                     const SE2Pose& goal, const HaitOptions& options) {
  options.validate();
  validate(robot);
  require_on_map(terrain, start, "start");
  require_on_map(terrain, goal, "goal");
  // A neighbourhood wider than the map leaves it from every configuration,
  // and its sampling grows as rho^2: refuse it while it is one comparison.
  const ElevationGrid& grid = terrain.grid();
  const double extent = std::hypot(grid.x_max() - grid.x_min(), grid.y_max() - grid.y_min());
  if (options.position_uncertainty > extent) {
    std::ostringstream msg;
    msg << "plan_hait: position uncertainty " << options.position_uncertainty
        << " m is larger than the terrain's diagonal " << extent
        << " m: no configuration's neighbourhood stays on the map";
    throw InputError(msg.str());
  }
  const auto t0 = std::chrono::steady_clock::now();

  // Position uncertainty (§5.2): the chassis takes the paper's min/max
  // placement surfaces and moved faces; the sprung rigid body, for which the
  // paper gives no surfaces, its sampled neighbourhood (every check_spacing
  // across, every heading cell), both inside HaitRobotValidity.
  const HaitRobotValidity model(terrain, robot, hait_validity_options(options));
  const ValidityFunction validity = model.function();

  // Two control points ahead of and behind the reference point (§4.2.2 after
  // Barraquand–Latombe), each with the wave started at its own goal position.
  PotentialFunction potential;
  std::shared_ptr<PotentialBitmap> front, rear;
  if (options.heuristic != HaitHeuristic::kEuclidean) {
    const double offset =
        options.control_point_offset > 0.0 ? options.control_point_offset : model.half_length();
    const Vec2 dir(std::cos(goal.theta), std::sin(goal.theta));
    Vec2 goal_front = goal.position() + offset * dir;
    Vec2 goal_rear = goal.position() - offset * dir;
    double used_offset = offset;
    if (!terrain.has_data(goal_front) || !terrain.has_data(goal_rear)) {
      // A control point's goal falls off the data: both points then aim at the goal itself.
      goal_front = goal_rear = goal.position();
      used_offset = 0.0;
    }
    std::shared_ptr<const ElevationGrid> dz = options.terrain_uncertainty_map;
    if (!dz && options.terrain_uncertainty > 0.0) {
      const ElevationGrid& g = terrain.grid();
      dz = std::make_shared<const ElevationGrid>(g.ncols(), g.nrows(), g.cellsize(), g.x_min(),
                                                 g.y_min(), options.terrain_uncertainty);
    }
    const PotentialBitmapOptions bo =
        bitmap_options(robot, model.radius(), options.position_uncertainty);
    front = std::make_shared<PotentialBitmap>(terrain, goal_front, bo, dz.get());
    rear = used_offset > 0.0 ? std::make_shared<PotentialBitmap>(terrain, goal_rear, bo, dz.get())
                             : front;
    // A control point past the map's edge (the robot's overhang can reach beyond
    // it while its wheels stand on the map) reads the potential at the nearest
    // point of the map: an infinite value there would deny every configuration
    // near the edge a node although its validity was checked.
    const Vec2 lo(grid.x_min(), grid.y_min()), hi(grid.x_max(), grid.y_max());
    potential = [front, rear, used_offset, lo, hi](const SE2Pose& q) {
      const Vec2 d(std::cos(q.theta), std::sin(q.theta));
      const Vec2 pf = (q.position() + used_offset * d).cwiseMax(lo).cwiseMin(hi);
      const Vec2 pr = (q.position() - used_offset * d).cwiseMax(lo).cwiseMin(hi);
      return 0.5 * (front->potential(pf) + rear->potential(pr));
    };
  }
  const double preprocessing =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  HaitResult result = hait_search(validity, potential, start, goal, options);
  result.preprocessing_seconds = preprocessing;
  return result;
}

}  // namespace talus
