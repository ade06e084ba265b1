#pragma once
/// @file
/// One robot's placement at given configurations, for users and tests (`talus
/// placement`): the Haït–Siméon–Taïx placement of either robot model
/// (place_robot for the sprung rigid body, place_chassis for the articulated
/// chassis, computed directly: no θ table), its attitude, its per-contact
/// quantities, and whether it is valid (limits of §3.2, then collision of the
/// lower faces with the terrain, §3.3) with the first reason it is not.
///
/// Reported quantities (SI units, angles as in placement.hpp):
/// - z: sprung rigid body: G's height, so on level ground at height h with
///   every spring at rest z = h + cg_height; chassis: the middle axle centre's
///   height, z = h on level ground (the model has no wheel radius);
/// - roll, pitch: rigid body φ, ψ; chassis: the mean axle roll and the global
///   pitch (ChassisPlacement::roll(), pitch());
/// - contacts, one per contact_names() entry: rigid body: the spring extension
///   l_j of each wheel ("extension_1" … "extension_n", wheel order of the
///   file; > 0 = extended); chassis, which has no springs: each axle's roll
///   ("roll_front", "roll_middle", "roll_rear") and the outer axles' pitches
///   ("pitch_front", "pitch_rear").
/// An unusable placement (a wheel off the map or on NODATA) has NaN values.
#include <string>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/hait/placement.hpp"
#include "talus/kinematic/hait/robot.hpp"
#include "talus/kinematic/hait/terrain_quadtree.hpp"

namespace talus {

/// The placement of one configuration.
struct ConfigurationPlacement {
  SE2Pose q;
  PlacementStatus status = PlacementStatus::kOffMap;
  double z = 0.0;                ///< [m], see the file comment
  double roll = 0.0;             ///< [rad]
  double pitch = 0.0;            ///< [rad]
  std::vector<double> contacts;  ///< one per PlacementQuery::contact_names() [m or rad]
  bool valid = false;
  /// "none" when valid, else the first failed test: "off_map", "no_data"
  /// (placement), "roll", "pitch", "spring_extension", "axle_roll_difference",
  /// "body_angle" (to_string(ValidityCheck)) or "collision".
  std::string reason = "off_map";
};

/// Placements of one robot on one terrain (the collision quadtree is built
/// once). Immutable after construction; place() is thread-safe.
class PlacementQuery {
 public:
  /// Throws InputError for an invalid robot.
  PlacementQuery(const RuledTerrain& terrain, Robot robot);

  /// The names of ConfigurationPlacement::contacts, in order.
  std::vector<std::string> contact_names() const;
  /// The placement at q. Throws InputError if q is not finite or its (x, y)
  /// is outside the terrain's domain; a configuration on the map whose wheels
  /// leave it, or on NODATA, is an invalid placement, not an error.
  ConfigurationPlacement place(const SE2Pose& q) const;

  const RuledTerrain& terrain() const { return quadtree_.terrain(); }
  const Robot& robot() const { return robot_; }

 private:
  Robot robot_;
  TerrainQuadtree quadtree_;
};

}  // namespace talus
