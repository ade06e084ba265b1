#pragma once
/// @file
/// The validity oracle of the Haït–Siméon–Taïx planner for a real robot on a
/// ruled terrain (§3, §5.1): placement (Place_robot for the sprung rigid body,
/// the θ-sliced ChassisPlacementTable for the articulated chassis), stability
/// and mechanical limits with their margin, and collision of the lower faces
/// with the terrain through the quadtree.
///
/// With a terrain uncertainty δz > 0 the checks are the worst case of §5.1.2:
/// the placement intervals on T_min / T_max must satisfy every limit, and the
/// faces of the robot placed on T_min must clear T_max (the quadtree is built
/// on T_max). Position uncertainty is not handled here: neighbourhood_validity()
/// wraps this oracle.
#include <memory>

#include "talus/core/ruled_terrain.hpp"
#include "talus/dynamics/robot.hpp"
#include "talus/kinematic/configuration_space.hpp"

namespace talus {

/// Placement + validity + collision of one robot on one terrain; immutable
/// after construction, checks are thread-safe.
class HaitRobotValidity {
 public:
  /// Preprocesses (envelopes, quadtree, chassis table). Throws InputError for
  /// an invalid robot or a negative / non-finite δz [m].
  HaitRobotValidity(const RuledTerrain& terrain, const Robot& robot,
                    double terrain_uncertainty = 0.0);
  ~HaitRobotValidity();
  HaitRobotValidity(HaitRobotValidity&&) noexcept;
  HaitRobotValidity& operator=(HaitRobotValidity&&) noexcept;

  /// Valid / margin at q; `placements` counts robot placements made (one per
  /// placement; under δz the interval's runs plus the placement on T_min).
  ConfigurationCheck check(const SE2Pose& q) const;
  /// check() as a ValidityFunction (keeps a reference to *this).
  ValidityFunction function() const;
  /// Wall-clock time of the constructor [s].
  double preprocessing_seconds() const;
  /// A length scale of the robot: half its footprint's longest extent [m].
  double half_length() const;
  /// Radius of a disc holding the robot's footprint [m].
  double radius() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace talus
