#pragma once
/// @file
/// Position uncertainty for the articulated chassis (Haït, Siméon and Taïx
/// 2002, §5.2): the min/max placement surfaces over the modified neighbourhood
/// N', the placement intervals read from them in O(1) (§5.2.1, used as in
/// §5.1.1), and the moved lower faces for collision (§5.2.2).
///
/// The uncertainty domain of a configuration q = (x, y, θ) is the paper's
/// modified domain (Fig. 25 b): the middle axle anywhere on the segment of
/// ±ρ normal to the heading, the heading anywhere in θ ± Δθ. The front and
/// rear axles, linked to the middle one at distance d cos ψ, then move by up to
/// ρ + d sin Δθ across the heading and d (1 − cos Δθ) along it. N' (Fig. 26) is
/// the single box, in the frame of the heading, that holds the union of the
/// three axles' neighbourhoods: half extents Δx = d (1 − cos Δθ) along the
/// heading and Δy = ρ + d sin Δθ across it.
///
/// Preprocessing (§5.2.1, combined with terrain uncertainty as in §5.2.3): for
/// every θ slice and terrain node, the min and max of S_z and S_φ over N' and
/// over the slices that θ ± Δθ reaches. With terrain uncertainty the minima
/// are taken on S_z_min (both wheels on T_min) and S_φ_min (left wheel on
/// T_min, right on T_max), the maxima on S_z_max and S_φ_max, giving the
/// paper's S'_z_min … S'_φ_max.
///
/// Choices the paper leaves open, made here so that the bounds provably hold
/// between nodes and slices, not only at them:
/// - Queries interpolate the min/max surfaces bilinearly (and linearly in θ)
///   like S_z and S_φ, and S_z, S_φ themselves are bilinear between nodes, so
///   by default each node's window is N' grown by two lattice spacings (a
///   Minkowski sum with the square [−2h, 2h]²) and by one slice's rotation;
///   `lattice_slack = false` takes the plain nodes inside N' instead (the
///   paper's surfaces, tighter, exact only at nodes).
/// - Each slice merges the slices within Δθ plus one either side, since a
///   heading between two slices reads both.
/// - A window that holds an off-map or NODATA placement makes the bound
///   unusable: part of the domain has no placement.
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"
#include "talus/kinematic/hait/placement.hpp"
#include "talus/kinematic/hait/robot.hpp"
#include "talus/kinematic/hait/robot_validity.hpp"

namespace talus {

/// Size of the position-uncertainty domain and how its surfaces are built.
struct ChassisUncertaintyOptions {
  double position_uncertainty = 0.3;  ///< ρ, half-length of the lateral segment [m] (>= 0)
  double heading_uncertainty = 0.7;   ///< Δθ [rad] in [0, π/2) (the paper's example: 40°)
  bool lattice_slack = true;          ///< grow windows so bounds hold between nodes (see file)
  /// Throws InputError naming the field, its value and the accepted range.
  void validate() const;
};

/// Build-time diagnostics of a ChassisUncertaintyTable.
struct ChassisUncertaintyDiagnostics {
  double base_seconds = 0.0;    ///< the θ-slice table (§3.1.2 / §5.1.1 sets) [s]
  double minmax_seconds = 0.0;  ///< the min/max pass of §5.2.1 [s]
  double seconds = 0.0;         ///< both [s]
  long long placements = 0;     ///< Place_axle calls of the base table
  double half_length = 0.0;     ///< Δx of N' [m]
  double half_width = 0.0;      ///< Δy of N' [m]
  int slice_reach = 0;          ///< slices merged on either side of each slice
  int max_window_nodes = 0;     ///< lattice offsets in the largest spatial window
};

/// Min/max bounds of an axle's placement over the uncertainty domain.
struct AxleBounds {
  PlacementStatus status = PlacementStatus::kOffMap;  ///< unusable if any of the domain is
  Interval z;                                         ///< elevation of the axle centre [m]
  Interval roll;                                      ///< φ [rad]
};

/// The min/max placement surfaces of §5.2.1 over a ChassisPlacementTable it
/// owns; immutable once built, queries are thread-safe.
class ChassisUncertaintyTable {
 public:
  /// Builds the θ-slice table (with the §5.1.1 sets when table.terrain_uncertainty > 0),
  /// then the min/max surfaces. Throws InputError on an invalid chassis or options.
  ChassisUncertaintyTable(const ArticulatedChassis& chassis, const RuledTerrain& terrain,
                          const ChassisTableOptions& table,
                          const ChassisUncertaintyOptions& uncertainty);

  /// Bounds of z and φ of an axle whose nominal centre is (x, y) with heading θ,
  /// over N' and θ ± Δθ (and both envelopes under terrain uncertainty).
  AxleBounds axle_bounds(double x, double y, double theta) const;
  /// §5.2.1: intervals of z_M, φ_F, φ_M, φ_R, ψ_F, ψ_R holding every placement of
  /// the domain. z_M and φ_M are the middle axle's bounds; ψ_F (ψ_R) is bounded by
  /// Place_other_axle on S'_z_min with the middle axle at its highest and on
  /// S'_z_max with it at its lowest; the outer axles' rolls are the bounds along
  /// the body line over that pitch range. Every interval also holds the
  /// nominal placement (base().place()).
  ChassisPlacementInterval place_interval(double x, double y, double theta) const;

  /// The θ-slice table the surfaces derive from.
  const ChassisPlacementTable& base() const { return base_; }
  const ChassisUncertaintyOptions& options() const { return options_; }
  const ChassisUncertaintyDiagnostics& diagnostics() const { return diagnostics_; }

 private:
  ChassisPlacementTable base_;
  ChassisUncertaintyOptions options_;
  std::vector<double> z_lo_, z_hi_, roll_lo_, roll_hi_;  ///< [slice][row][column]
  std::vector<std::uint8_t> status_;                     ///< worst PlacementStatus in the window
  ChassisUncertaintyDiagnostics diagnostics_;
};

/// §5.2.2, the moved robot faces: lower boundaries of the two bodies over the
/// uncertainty domain, for the quadtree collision test. For each body and each
/// extreme of its mean axle roll (lo, hi) one planar face: it lies `clearance`
/// above the body line that starts at the lowest middle-axle elevation
/// (interval.z.lo) and climbs at the body's lowest pitch, hence under the
/// nominal face; and its outline is the body's footprint swept by the domain
/// (swept_body_outline: an 8-gon hugging the swept footprint, cut into three
/// convex quads; one quad when Δθ = 0). The two roll extremes bound every roll
/// in between from below at each lateral offset. Empty if the interval is unusable.
std::vector<Quad> moved_lower_faces(const ArticulatedChassis& chassis,
                                    const ChassisPlacementInterval& interval, double x, double y,
                                    double theta, double rho, double dtheta);

}  // namespace talus
