#pragma once
/// @file
/// The legged-vehicle description of Eldershaw and Yim, "Motion planning of
/// legged vehicles in an unstructured environment" (ICRA 2001), §3.1: legs
/// with a range (where the foot may be put, a polygon in the body's xy frame)
/// and a reach (how far below the body's zero plane the foot can go), the
/// under-carriage as an inverse height map (its depth below the zero plane
/// over the body footprint), the foot's maximum traction slope and the
/// smallest foot print (which sets the CG-space resolution).
///
/// Body frame: origin at the centre of gravity (CG), u forward (along the
/// heading θ), v to the left, heights measured from the body's horizontal
/// zero plane, positive downwards for `reach` and `depth`. The paper assumes
/// zero roll and pitch, so the body frame is the world frame rotated by θ
/// about z. Units are SI: metres and radians. The YAML format is described in
/// data/robots/README.md (section `type: legged`).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "talus/core/types.hpp"

namespace talus {

/// A value over part of the body plane: a constant, or a grid of node values
/// (bilinear between nodes) over [u0, u0 + (nu-1) h] × [v0, v0 + (nv-1) h].
struct BodyField {
  double constant = 0.0;       ///< used when `values` is empty [m]
  Vec2 origin = Vec2::Zero();  ///< (u0, v0) of node (0, 0) [m]
  double spacing = 0.0;        ///< h [m] (> 0 when a grid)
  std::size_t nu = 0;          ///< nodes along u
  std::size_t nv = 0;          ///< nodes along v
  std::vector<double> values;  ///< row-major, row k = v0 + k h, column i = u0 + i h
  bool is_grid() const { return !values.empty(); }
  /// True when (u, v) lies in the grid's rectangle (always for a constant).
  bool covers(const Vec2& uv) const;
  /// The value at (u, v): the constant, or the bilinear interpolant of the
  /// grid (clamped to the rectangle's border).
  double at(const Vec2& uv) const;
};

/// One leg.
struct Leg {
  std::string name;                ///< free text, e.g. "front-left"
  Vec2 attachment = Vec2::Zero();  ///< hip in the body frame (u, v) [m] (for figures)
  std::vector<Vec2> range;         ///< counter-clockwise simple polygon (u, v) [m]
  BodyField reach;                 ///< depth below the zero plane the foot reaches [m], > 0
  /// True when the body-frame point (u, v) lies inside `range` (boundary included).
  bool in_range(const Vec2& uv) const;
};

/// The under-carriage as an inverse height map: a grid of depths below the
/// zero plane (a node value d means the body's underside is d metres below the
/// zero plane there), bilinear between nodes; the body footprint is the grid's
/// rectangle.
struct UnderCarriage {
  BodyField depth;  ///< always a grid
};

/// A legged vehicle (§3.1).
struct LeggedRobot {
  std::string name;
  std::vector<Leg> legs;            ///< 3 to 16 legs
  UnderCarriage under_carriage;     ///< the body's underside
  double max_traction_slope = 0.0;  ///< [rad] in (0, π/2): steepest ground a foot grips
  double foot_print = 0.0;          ///< [m] > 0: side of the smallest foot print
  /// Throws InputError naming the first invalid field (legs[k].range, ...):
  /// a range that is not a simple counter-clockwise polygon of ≥ 3 vertices, a
  /// reach ≤ 0 or a reach grid that does not cover its leg's range, a depth
  /// grid with fewer than 2 × 2 nodes, non-finite values, a slope out of
  /// (0, π/2), a foot print ≤ 0.
  void validate() const;
  /// Largest distance from the CG of any range vertex [m].
  double outer_radius() const;
  /// Largest reach over every leg (the constant, or the grid's largest node) [m].
  double max_reach() const;
};

/// Parses a `type: legged` robot file; InputError naming `source` and the key
/// for invalid YAML, an unknown or missing key, a value of the wrong type or
/// an invalid value (validate()).
LeggedRobot parse_legged_robot(std::string_view yaml_text, const std::string& source);
/// Reads and parses a robot file (bounded to 1 MiB, as every configuration file).
LeggedRobot load_legged_robot(const std::filesystem::path& path);

}  // namespace talus
