#pragma once
/// @file
/// The validity oracle of the Haït–Siméon–Taïx planner for a real robot on a
/// ruled terrain (§3, §5.1): placement (Place_robot for the sprung rigid body,
/// the θ-sliced ChassisPlacementTable for the articulated chassis), stability
/// and mechanical limits with their margin, and collision of the lower faces
/// with the terrain through the quadtree.
///
/// With a terrain uncertainty δz > 0 (a constant, or a per-node map) the checks are the worst case
/// of §5.1.2: the placement intervals on T_min / T_max must satisfy every limit, and the faces of
/// the robot placed on T_min must clear T_max (the quadtree is built on T_max).
///
/// Position uncertainty (ρ, Δθ, §5.2) takes one of two paths:
/// - articulated chassis: the paper's method, the min/max placement surfaces
///   over the modified neighbourhood N' (ChassisUncertaintyTable), whose
///   intervals get the worst-case checks of §5.1.2 in O(1) per configuration,
///   and collision of the moved lower faces of §5.2.2 (moved_lower_faces);
/// - sprung rigid body: the paper gives no surfaces for it (Place_robot has no
///   θ-sliced table), so the domain is sampled: neighbourhood_validity() over
///   lateral offsets every `sample_spacing` and headings every
///   `sample_angle_step`, each configuration checked as above.
#include <memory>
#include <numbers>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {

/// How position uncertainty is handled (see the file comment).
enum class PositionUncertaintyMethod {
  kNone,            ///< ρ = Δθ = 0
  kMinMaxSurfaces,  ///< chassis: §5.2 min/max placement surfaces and moved faces
  kSampled,         ///< rigid body: the sampled neighbourhood
};

/// Uncertainties and preprocessing choices of HaitRobotValidity (SI units).
struct HaitValidityOptions {
  double terrain_uncertainty = 0.0;  ///< δz [m] (>= 0), the same at every node
  /// Per-node δz [m] (§5.1: "an interval δz associated with each point of the
  /// grid"): a grid of the terrain's shape, >= 0, NODATA = 0. Null (default) =
  /// the constant terrain_uncertainty; set, terrain_uncertainty must be 0 and
  /// the envelopes are z ∓ δz(i, j). A shape mismatch throws InputError.
  std::shared_ptr<const ElevationGrid> terrain_uncertainty_map;
  double position_uncertainty = 0.0;  ///< ρ [m] (>= 0)
  /// Δθ [rad]: [0, π/2) for the chassis (the moved faces need it), [0, π) for the rigid body.
  double heading_uncertainty = 0.0;
  double sample_spacing = 0.1;  ///< rigid body: lateral step of the sampled domain [m] (> 0)
  double sample_angle_step = 2.0 * std::numbers::pi / 32;  ///< rigid body: heading step [rad] (> 0)
  int theta_slices = 72;  ///< chassis: θ slices of the placement table (>= 4)
  /// Throws InputError naming the field, its value and the accepted range.
  void validate() const;
};

/// Preprocessing diagnostics of HaitRobotValidity.
struct HaitValidityDiagnostics {
  double seconds = 0.0;            ///< the whole constructor [s]
  double table_seconds = 0.0;      ///< chassis: the θ-slice table [s]
  double minmax_seconds = 0.0;     ///< chassis with ρ or Δθ: the §5.2.1 min/max pass [s]
  long long table_placements = 0;  ///< chassis: Place_axle calls of the table
  PositionUncertaintyMethod method = PositionUncertaintyMethod::kNone;
};

/// Placement + validity + collision of one robot on one terrain; immutable
/// after construction, checks are thread-safe.
class HaitRobotValidity {
 public:
  /// Preprocesses (envelopes, quadtree, chassis table). Throws InputError for
  /// an invalid robot or a negative / non-finite δz [m].
  HaitRobotValidity(const RuledTerrain& terrain, const Robot& robot,
                    double terrain_uncertainty = 0.0);
  /// The same with every uncertainty; throws InputError for invalid options
  /// (naming the field) or an invalid robot.
  HaitRobotValidity(const RuledTerrain& terrain, const Robot& robot,
                    const HaitValidityOptions& options);
  ~HaitRobotValidity();
  HaitRobotValidity(HaitRobotValidity&&) noexcept;
  HaitRobotValidity& operator=(HaitRobotValidity&&) noexcept;

  /// Valid / margin at q, for the whole uncertainty domain when ρ or Δθ > 0;
  /// `placements` counts robot placements made (one per placement or table
  /// interval; under δz the interval's runs plus the placement on T_min, which
  /// for the chassis is placed directly and counts its Place_axle runs).
  ConfigurationCheck check(const SE2Pose& q) const;
  /// check() as a ValidityFunction (keeps a pointer to the shared state, so
  /// it stays valid when this object is moved, not when it is destroyed).
  ValidityFunction function() const;
  /// Wall-clock time of the constructor [s].
  double preprocessing_seconds() const;
  /// Preprocessing costs and the position-uncertainty path taken.
  const HaitValidityDiagnostics& diagnostics() const;
  /// A length scale of the robot: half its footprint's longest extent [m].
  double half_length() const;
  /// Radius of a disc holding the robot's footprint [m].
  double radius() const;

 private:
  struct Impl;
  static ConfigurationCheck check(const Impl& impl, const SE2Pose& q);
  std::unique_ptr<Impl> impl_;
};

}  // namespace talus
