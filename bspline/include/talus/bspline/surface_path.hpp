#pragma once
/// @file
/// Geometry of a planar curve (x(σ), y(σ)) lifted onto a BPatch: the 3-D
/// point, arc length, Darboux frame and curvatures that the vehicle-dynamics
/// layer needs.
///
/// Conventions (defined once, here):
/// - t: unit tangent of the 3-D curve, in the direction of increasing σ.
/// - r: upward unit surface normal, (-z_x, -z_y, 1) / |·| (r_z > 0 always).
/// - q = r × t: lateral unit vector in the tangent plane, pointing to the
///   **left** of the direction of travel when seen from above.
/// - The 3-D curvature vector d²P/ds² = κ_n r + κ_g q:
///   κ_n > 0 where the path bends upwards (dip, valley, bowl) and κ_n < 0 on
///   a crest (sphere cap of radius R: κ_n = −1/R in every direction);
///   κ_g > 0 when the path turns left (counter-clockwise circle of radius ρ on
///   flat ground: κ_g = 1/ρ).
/// - k_t, k_q, k_r: components of the upward vertical unit vector (0, 0, 1) in
///   the frame (t, q, r). k_t > 0 when driving uphill; k_q > 0 when the
///   ground rises to the left; k_r = cos(slope) > 0.
#include <cstddef>
#include <vector>

#include "talus/bspline/arc_length.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// Geometry at one station of a path on the surface.
struct PathFrame {
  double parameter = 0.0;   ///< curve parameter σ
  double s = 0.0;           ///< 3-D arc length from the start [m] (0 from lift_to_surface)
  double speed = 0.0;       ///< ds/dσ [m per unit σ]
  double speed_rate = 0.0;  ///< d²s/dσ², for arc-length quadrature between stations
  Vec3 point = Vec3::Zero();
  Vec3 tangent = Vec3::Zero();             ///< t
  Vec3 lateral = Vec3::Zero();             ///< q = r × t
  Vec3 normal = Vec3::Zero();              ///< r
  double kappa_n = 0.0;                    ///< normal curvature [1/m]
  double kappa_g = 0.0;                    ///< geodesic curvature [1/m]
  double k_t = 0.0, k_q = 0.0, k_r = 0.0;  ///< vertical unit vector in (t, q, r)
  /// Signed curvature of the planar (horizontal) curve [1/m], > 0 turning left: what a
  /// steering angle turns in plan (Vehicle::max_steering).
  double kappa_planar = 0.0;
};

/// Frame of the lifted curve at a point with planar position `position`,
/// planar derivatives d1 = (x', y') and d2 = (x'', y'') with respect to any
/// parameter, and surface derivatives `surface` there. Throws InputError if
/// the planar velocity d1 is zero.
PathFrame lift_to_surface(const Vec2& position, const SurfacePoint& surface, const Vec2& d1,
                          const Vec2& d2);

/// A planar B-spline curve lifted onto a BPatch, with its 3-D arc-length map.
/// Holds the surface itself (a BPatch copy shares its coefficients), so the
/// path stays valid whatever happens to the caller's surface object.
class SurfacePath {
 public:
  /// Builds the arc-length table: breakpoints at the curve's knots and where
  /// the curve crosses a cell edge of the surface, Chebyshev series refined
  /// to about 1e-14 relative in between (ArcLengthTable). Throws InputError if
  /// the curve leaves the surface's domain (checked at the table's Chebyshev
  /// points, at least 16 per knot span and per cell crossed).
  SurfacePath(const BPatch& surface, Curve2 curve);

  const Curve2& curve() const { return curve_; }
  const BPatch& surface() const { return surface_; }
  /// 3-D length of the lifted curve [m].
  double length() const { return arc_length_.length(); }

  PathFrame frame_at_parameter(double sigma) const;
  /// Frame at arc length s in [0, length()].
  PathFrame frame_at_arc_length(double s) const;
  /// `stations` (>= 2) frames equally spaced in arc length, first and last at
  /// the ends (inverse arc-length map: Newton on the table's series, bracket
  /// carried from station to station, no quadrature).
  std::vector<PathFrame> sample(std::size_t stations) const;
  /// `stations` (>= 2) frames equally spaced in the curve parameter σ (nearly
  /// uniform in planar arc length for chord-length curves), with s from the
  /// arc-length table (the same 1e-14-relative values at any station count).
  /// Costs one curve and one surface evaluation plus one table look-up per
  /// station, whatever the count. Writes into `frames`.
  void sample_uniform_parameter(std::size_t stations, std::vector<PathFrame>& frames) const;

 private:
  BPatch surface_;
  Curve2 curve_;
  ArcLengthTable arc_length_;
};

}  // namespace talus
