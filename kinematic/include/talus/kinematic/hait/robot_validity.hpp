#pragma once
/// @file
/// Validity of a placement (Haït, Siméon and Taïx 2002, §3.2): stability and
/// mechanical limits, with a safety margin for the search's arc costs (§4.2.1),
/// their worst-case versions under terrain uncertainty (§5.1.2), and the
/// bodies' lower faces that the collision test (§3.3, kinematic quadtree) needs.
#include <array>
#include <vector>

#include "talus/core/types.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"
#include "talus/kinematic/hait/placement.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {

/// The check a placement failed first, in the order they are tested.
enum class ValidityCheck {
  kNone,                ///< valid
  kPlacement,           ///< no placement: a wheel off the map or on NODATA
  kRoll,                ///< stability: |φ| (rigid body) or |mean axle roll| (chassis) too large
  kPitch,               ///< stability: ψ (rigid body) or the global pitch (chassis) out of range
  kSpringExtension,     ///< mechanical: some |l_j| >= L_max (rigid body)
  kAxleRollDifference,  ///< mechanical: |φ_M - φ_F| or |φ_M - φ_R| >= φ_max (chassis)
  kBodyAngle,           ///< mechanical: π + ψ_F + ψ_R outside (ψ_Min, ψ_Max) (chassis)
};

/// Lower-case name ("none", "placement", "roll", "pitch", "spring_extension",
/// "axle_roll_difference", "body_angle").
const char* to_string(ValidityCheck check);

/// Outcome of a validity check.
struct Validity {
  ValidityCheck failed = ValidityCheck::kNone;  ///< first failed check, kNone if valid
  /// Distance to the nearest limit in [0, 1]: the smallest over all checks of
  /// the value's normalised distance to its limit, 1 at the nominal value
  /// (level, springs at rest, axles aligned, bodies straight), 0 on or past a
  /// limit. Always 0 when invalid.
  double margin = 1.0;
  bool valid() const { return failed == ValidityCheck::kNone; }
};

/// §3.2.1 and §3.2.2 for the rigid body: |φ| < φ_max, |ψ| < ψ_max, |l_j| < L_max.
Validity check_validity(const WheeledRobot& robot, const RobotPlacement& placement);
/// §3.2.1 and §3.2.2 for the chassis: |mean φ| < φ_StabMax, ψ_StabMin < pitch < ψ_StabMax,
/// |φ_M - φ_F|, |φ_M - φ_R| < φ_max, ψ_Min < π + ψ_F + ψ_R < ψ_Max.
Validity check_validity(const ArticulatedChassis& chassis, const ChassisPlacement& placement);

/// Worst case over the placement intervals (§5.1.2 for the chassis, the same
/// rule for the rigid body): every check must hold at the interval's extreme
/// values, so a configuration is accepted only if it is valid for any terrain
/// between the envelopes. The margin is taken at the same extremes.
Validity check_validity(const WheeledRobot& robot, const RobotPlacementInterval& interval);
/// §5.1.2: eq. 4 for the roll, the pitch range from the bounds of ψ_F and ψ_R
/// (the paper also fixes the middle axle on T_min; using the full ψ intervals
/// is more conservative), eqs. 5-6 and the body-angle bounds.
Validity check_validity(const ArticulatedChassis& chassis,
                        const ChassisPlacementInterval& interval);

/// A planar quadrilateral in the world frame, counter-clockwise seen from above.
using Quad = std::array<Vec3, 4>;

/// The rigid body's lower face (BodyBox) in the world frame. Empty if the
/// placement is unusable.
std::vector<Quad> lower_faces(const WheeledRobot& robot, const RobotPlacement& placement);
/// The two bodies' lower faces (front body first) in the world frame: each
/// spans from the middle axle to `overhang` beyond its outer axle along the
/// line through the axle centres, rolled by the mean roll of its two axles,
/// `clearance` above that line. Empty if the placement is unusable.
std::vector<Quad> lower_faces(const ArticulatedChassis& chassis, const ChassisPlacement& placement);

}  // namespace talus
