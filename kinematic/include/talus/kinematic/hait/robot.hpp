#pragma once
/// @file
/// Robot models of Haït, Siméon and Taïx, "Algorithms for rough terrain
/// trajectory planning" (Advanced Robotics 16(8), 2002), §3.1: a rigid body on
/// n sprung wheels and a three-axle articulated chassis, loaded from YAML with
/// strict validation. The YAML format is documented in data/robots/README.md.
#include <filesystem>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "talus/core/types.hpp"

namespace talus {

/// Lower face of a rigid body: the rectangle u ∈ [-rear, front], v ∈ [-half_width,
/// half_width] in the body frame, `clearance` above the wheels' rest plane.
struct BodyBox {
  double front = 0.5;       ///< [front] extent ahead of G along u [m] (> 0)
  double rear = 0.5;        ///< [rear] extent behind G along u [m] (> 0)
  double half_width = 0.4;  ///< [half_width] lateral half extent [m] (> 0)
  double clearance = 0.2;   ///< [clearance] height above the wheel rest plane [m] (> 0)
};

/// §3.1.1: a rigid body on n wheels with vertical springs (vertical in the body
/// frame). Wheel j touches the ground at (u_j, v_j, -cg_height + l_j) in the
/// body frame (u forward, v left, w up, origin at the centre of gravity G);
/// l_j is the paper's algebraic spring extension, 0 at rest and > 0 when the
/// ground pushes the wheel up toward the body.
struct WheeledRobot {
  /// Most wheels a robot may have; placements keep per-wheel data in fixed arrays of this size.
  static constexpr int kMaxWheels = 8;

  std::string name;          ///< [name] free text (optional)
  std::vector<Vec2> wheels;  ///< [wheels] contact points (u, v) [m], 3..kMaxWheels, not collinear
  double cg_height =
      0.5;  ///< [cg_height] G above the wheels' rest plane, w0 = -cg_height [m] (> 0)
  double max_spring_extension = 0.1;  ///< [max_spring_extension] L_max, |l_j| < L_max [m] (> 0)
  double max_roll = 0.35;             ///< [max_roll] stability limit |φ| < φ_max [rad], (0, π/2)
  double max_pitch = 0.35;  ///< [max_pitch] stability limit |ψ| < ψ_max [rad], (0, π/2)
  BodyBox body;             ///< [body] lower face for collision

  /// Throws InputError naming the field, its value and what is expected.
  void validate() const;
};

/// Lower faces of the chassis bodies: each body (middle→front, middle→rear) is a
/// rectangle from the middle axle to `overhang` beyond the outer axle, `half_width`
/// to each side, `clearance` above the line through the axle centres.
struct ChassisBody {
  double half_width = 0.4;  ///< [half_width] [m] (> 0)
  double clearance = 0.25;  ///< [clearance] [m] (> 0)
  double overhang = 0.1;    ///< [overhang] beyond the outer axle [m] (>= 0)
};

/// §3.1.2: three axles (front F, middle M, rear R) that roll freely about the
/// longitudinal axis, joined by two bodies that pitch about the lateral axis.
/// Angle conventions (ours, documented where the paper's signs are ambiguous):
/// an axle's roll φ > 0 when its left wheel is higher; a body's pitch ψ_F (ψ_R)
/// is the elevation angle of the line from M to F (to R), > 0 when that axle is
/// above M. The global pitch (nose up > 0) is (ψ_F - ψ_R)/2 and the angle
/// between the bodies, measured under the chassis, is π + ψ_F + ψ_R (§3.2.2).
struct ArticulatedChassis {
  std::string name;              ///< [name] free text (optional)
  double half_axle_width = 0.5;  ///< [half_axle_width] l, axle centre to wheel contact [m] (> 0)
  double axle_spacing = 0.6;     ///< [axle_spacing] d, middle axle to front/rear axle [m] (> 0)
  double max_axle_roll_difference =
      0.3;  ///< [max_axle_roll_difference] φ_max, |φ_M - φ_F|, |φ_M - φ_R| [rad] (0, π)
  double max_roll = 0.35;       ///< [max_roll] φ_StabMax on the mean axle roll [rad] (0, π/2)
  double min_pitch = -0.35;     ///< [min_pitch] ψ_StabMin on the global pitch [rad] (-π/2, 0)
  double max_pitch = 0.35;      ///< [max_pitch] ψ_StabMax on the global pitch [rad] (0, π/2)
  double min_body_angle = 2.6;  ///< [min_body_angle] ψ_Min on π + ψ_F + ψ_R [rad] (0, π)
  double max_body_angle = 3.7;  ///< [max_body_angle] ψ_Max on π + ψ_F + ψ_R [rad] (π, 2π)
  ChassisBody body;             ///< [body] lower faces for collision

  /// Throws InputError naming the field, its value and what is expected.
  void validate() const;
};

/// Either robot model of the paper.
using Robot = std::variant<WheeledRobot, ArticulatedChassis>;

/// Reads a robot file (YAML or JSON). The key `type` (wheeled | articulated_chassis)
/// selects the model; unknown keys, missing keys, wrong types and invalid values
/// are InputErrors naming the file and the key.
Robot load_robot(const std::filesystem::path& path);
/// The same from YAML text; `source_name` appears in error messages.
Robot parse_robot(std::string_view yaml_text, const std::string& source_name = "<robot>");

/// Calls the model's validate().
void validate(const Robot& robot);

}  // namespace talus
