#pragma once
/// @file
/// Placement of the three-axle articulated chassis (Haït, Siméon and Taïx 2002,
/// §3.1.2): Place_axle, Place_other_axle, the whole chassis, the θ-sliced
/// preprocessing into placement surfaces S_z, S_φ, and the placement intervals
/// under terrain uncertainty (§5.1.1). Angle conventions are those of
/// ArticulatedChassis (robot.hpp). A configuration (x, y, θ) is the middle
/// axle's centre and the heading, counter-clockwise from east.
///
/// An axle's elevation z is that of the midpoint between its two wheel contact
/// points (wheel radii are not modelled; fold them into the body clearances).
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/core/types.hpp"
#include "talus/kinematic/hait/placement.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {

/// Options of the axle iterations.
struct AxlePlacementOptions {
  double tolerance = 1e-6;  ///< [m] ε: stop when |F(φ)| (or |G(ψ)|) <= ε (> 0)
  int max_iterations = 20;  ///< secant steps at most (> 0)
  /// Throws InputError naming the field.
  void validate() const;
};

/// One axle on the terrain.
struct AxlePlacement {
  PlacementStatus status = PlacementStatus::kOffMap;
  double roll = 0.0;   ///< φ [rad], > 0 when the left wheel is higher
  double z = 0.0;      ///< elevation of the axle centre [m]
  int iterations = 0;  ///< secant steps (0 for table look-ups and one-shot solutions)
};

/// Place_axle (§3.1.2): the roll φ solving F(φ) = 2 l sin φ - (z_l(φ) - z_r(φ)) = 0
/// (eq. 2), the wheels at horizontal distance l cos φ either side of (x, y)
/// across heading θ. From φ_0 = 0, each step takes the slope α = atan((z_l - z_r)
/// / (2 l cos φ_i)) that a plane would give (eq. 3) and the secant through
/// (φ_i, F(φ_i)) and (α, F(α)); it stops when |F| <= tolerance. On a plane of
/// lateral slope α it ends after one step with φ = α.
AxlePlacement place_axle(const RuledTerrain& terrain, double half_axle_width, double x, double y,
                         double theta, const AxlePlacementOptions& options = {});
/// The same with the left wheel on `left` and the right wheel on `right` (§5.1.1).
AxlePlacement place_axle(const RuledTerrain& left, const RuledTerrain& right,
                         double half_axle_width, double x, double y, double theta,
                         const AxlePlacementOptions& options = {});

/// A front or rear axle placed while linked to the middle one.
struct OtherAxlePlacement {
  PlacementStatus status = PlacementStatus::kOffMap;
  double pitch = 0.0;          ///< ψ: elevation angle of the line from M to this axle [rad]
  AxlePlacement axle;          ///< the axle at its final position
  Vec2 center = Vec2::Zero();  ///< horizontal position of the axle centre [m]
  int iterations = 0;          ///< secant steps on G(ψ)
  int axle_placements = 0;     ///< Place_axle calls (or table look-ups) made
};

/// Place_other_axle (§3.1.2): with the middle axle centre at (x_M, y_M, z_M),
/// the front (`direction` = +1) or rear (-1) axle at distance d along the body
/// line of pitch ψ; solves G(ψ) = z_M + d sin ψ - z(ψ) = 0, z(ψ) being the
/// elevation Place_axle gives at that axle's position. Each step takes
/// β = atan((z(ψ_i) - z_M) / (d cos ψ_i)) and the secant through (ψ_i, G(ψ_i))
/// and (β, G(β)).
OtherAxlePlacement place_other_axle(const RuledTerrain& terrain, const ArticulatedChassis& chassis,
                                    double x_m, double y_m, double z_m, double theta, int direction,
                                    const AxlePlacementOptions& options = {});

/// Any axle placement at (x, y, θ): Place_axle on a terrain, a table look-up, or
/// a bound read from the min/max surfaces of §5.2.
using AxlePlacer = std::function<AxlePlacement(double x, double y, double theta)>;

/// Place_other_axle (§3.1.2) with z(ψ) read from `axle` instead of a terrain:
/// §5.1.1 and §5.2.1 apply it "to these surfaces" (the bounds of S_z) to get
/// the pitch bounds. Same iteration and result as the terrain version.
OtherAxlePlacement place_other_axle(const AxlePlacer& axle, const ArticulatedChassis& chassis,
                                    double x_m, double y_m, double z_m, double theta, int direction,
                                    const AxlePlacementOptions& options = {});

/// The whole chassis: the middle axle by Place_axle, then the front and rear
/// axles by Place_other_axle.
struct ChassisPlacement {
  PlacementStatus status = PlacementStatus::kOffMap;            ///< the worst of the three axles'
  double x = 0.0, y = 0.0, theta = 0.0;                         ///< configuration
  double z = 0.0;                                               ///< z_M, middle axle centre [m]
  double roll_front = 0.0, roll_middle = 0.0, roll_rear = 0.0;  ///< φ_F, φ_M, φ_R [rad]
  double pitch_front = 0.0, pitch_rear = 0.0;                   ///< ψ_F, ψ_R [rad]
  int axle_placements = 0;  ///< Place_axle calls (or table look-ups) made

  /// Global roll, the mean axle roll (§3.2.1) [rad].
  double roll() const { return (roll_front + roll_middle + roll_rear) / 3.0; }
  /// Global pitch, the slope angle of the line through F and R (nose up > 0) [rad].
  double pitch() const { return 0.5 * (pitch_front - pitch_rear); }
  /// Angle between the bodies under the chassis, π + ψ_F + ψ_R (§3.2.2) [rad].
  double body_angle() const;
};

/// Places the chassis directly on the terrain (no preprocessing).
ChassisPlacement place_chassis(const ArticulatedChassis& chassis, const RuledTerrain& terrain,
                               double x, double y, double theta,
                               const AxlePlacementOptions& options = {});

/// The footprint of one chassis body swept by the §5.2 uncertainty domain (a
/// segment of ±`rho` [m] normal to the heading times headings ±`dtheta` [rad]
/// about the middle axle), for the moved faces of §5.2.2. Body frame: s along
/// the body from the middle axle, l to its left; the body is the rectangle
/// s ∈ [0, `length`], l ∈ [−`half_width`, `half_width`]. Returns a convex
/// polygon, counter-clockwise in (s, l), that holds every footprint of the
/// domain and hugs their convex hull: the near edge s = −w sin Δθ, the sides
/// of the body turned by ±Δθ, and around the far end the arc of radius
/// √(L² + w²) swept by the far corners, circumscribed by 5 tangent segments
/// (8 vertices; 4, the body grown by ρ sideways, when Δθ = 0). Everything
/// shifted by ±ρ sideways. Its area is within a few per cent of the hull's
/// (the tangent segments overshoot the arc by 1/cos(β/5) − 1 in radius, β =
/// Δθ + atan(w/L) the arc's half-angle: 0.6 % at Δθ = 40° for the bundled
/// chassis, 6 % in area at Δθ = 1.5). Throws InputError unless length > 0,
/// half_width > 0, rho >= 0 and dtheta in [0, π/2).
std::vector<Vec2> swept_body_outline(double length, double half_width, double rho, double dtheta);

/// Placement intervals of the chassis under terrain uncertainty (§5.1.1).
struct ChassisPlacementInterval {
  PlacementStatus status = PlacementStatus::kOffMap;
  Interval z;                                   ///< z_M [m]
  Interval roll_front, roll_middle, roll_rear;  ///< φ_F, φ_M, φ_R [rad]
  Interval pitch_front, pitch_rear;             ///< ψ_F, ψ_R [rad]
  int axle_placements = 0;
  /// The zero-width interval of one placement: where every uncertain
  /// interval starts, so that it always holds the nominal placement.
  static ChassisPlacementInterval around(const ChassisPlacement& nominal);
};

/// §5.1.1 directly on the terrains: z_M from both wheels on T_min / T_max; φ
/// from left on T_min and right on T_max (and conversely); ψ_F, ψ_R minimal
/// with the middle axle at its highest and the outer axle on T_min (and
/// conversely); the outer axles' roll bounds at those positions. Every interval
/// also holds the nominal placement on `terrain`.
ChassisPlacementInterval place_chassis_interval(const ArticulatedChassis& chassis,
                                                const RuledTerrain& terrain,
                                                const RuledTerrain& lower,
                                                const RuledTerrain& upper, double x, double y,
                                                double theta,
                                                const AxlePlacementOptions& options = {});

/// Options of the preprocessing.
struct ChassisTableOptions {
  int theta_slices = 72;             ///< n_θ slices over [0, 2π) (>= 4)
  double terrain_uncertainty = 0.0;  ///< δz [m] (>= 0); > 0 adds the four §5.1.1 runs
  /// Per-node δz [m] instead of the constant (same shape as the terrain's grid,
  /// >= 0, NODATA = 0); set, it adds the four §5.1.1 runs on its envelopes and
  /// terrain_uncertainty must be 0. Null = the constant.
  std::shared_ptr<const ElevationGrid> terrain_uncertainty_map;
  AxlePlacementOptions axle;  ///< for every Place_axle
  /// Throws InputError naming the field.
  void validate() const;
};

/// Build-time diagnostics of a ChassisPlacementTable.
struct ChassisTableDiagnostics {
  long long placements = 0;  ///< Place_axle calls made
  double seconds = 0.0;      ///< wall-clock build time [s]
  int slices = 0;            ///< n_θ
  int surface_sets = 0;      ///< 1, or 5 with terrain uncertainty
};

/// The preprocessing of §3.1.2: for every θ slice θ_k = 2πk/n_θ, Place_axle at
/// every terrain node gives the surfaces S_z and S_φ (and, with δz > 0, the four
/// sets on T_min/T_max of §5.1.1). Queries read them bilinearly in (x, y) on
/// the terrain's lattice and linearly in θ between neighbouring slices (with
/// wrap-around). Immutable once built; queries are thread-safe.
class ChassisPlacementTable {
 public:
  /// Builds every surface; throws InputError on invalid chassis or options.
  ChassisPlacementTable(const ArticulatedChassis& chassis, const RuledTerrain& terrain,
                        const ChassisTableOptions& options = {});

  /// The axle placement read from S_z, S_φ at (x, y, θ).
  AxlePlacement axle(double x, double y, double theta) const;
  /// The chassis: middle axle from the surfaces, Place_other_axle on the surfaces.
  ChassisPlacement place(double x, double y, double theta) const;
  /// §5.1.1 intervals from the surfaces. Throws InputError unless built with δz > 0.
  ChassisPlacementInterval place_interval(double x, double y, double theta) const;

  bool has_uncertainty() const { return sets_.size() > 1; }
  /// θ_k [rad].
  double slice_angle(int k) const;
  const ChassisTableDiagnostics& diagnostics() const { return diagnostics_; }
  const ArticulatedChassis& chassis() const { return chassis_; }

  /// Which wheels stand on which envelope for a surface set (internal layout, public for the
  /// implementation).
  enum class Set : int {
    kNominal = 0,
    kBothLower,
    kBothUpper,
    kLeftLowerRightUpper,
    kLeftUpperRightLower
  };
  /// The axle placement from one surface set.
  AxlePlacement axle(Set set, double x, double y, double theta) const;

  /// Node values of one surface set at slice k, indexed row * ncols + column
  /// (the input of derived surfaces such as ChassisUncertaintyTable's).
  struct NodeValues {
    std::span<const double> z, roll;       ///< [m], [rad]; meaningless where status is unusable
    std::span<const std::uint8_t> status;  ///< PlacementStatus per node
  };
  /// Throws InputError for a set the table does not hold or k outside [0, slices()).
  NodeValues nodes(Set set, int k) const;
  /// n_θ.
  int slices() const { return slices_; }
  /// The terrain the surfaces were built on.
  const RuledTerrain& terrain() const { return terrain_; }
  /// The options of every Place_axle and Place_other_axle iteration.
  const AxlePlacementOptions& axle_options() const { return axle_options_; }

 private:
  struct Surfaces {
    std::vector<double> z, roll;       ///< [slice][row][column]
    std::vector<std::uint8_t> status;  ///< PlacementStatus per node
  };
  ArticulatedChassis chassis_;
  AxlePlacementOptions axle_options_;
  RuledTerrain terrain_;  ///< the terrain the surfaces were built on (its lattice locates queries)
  int slices_ = 0;
  std::vector<Surfaces> sets_;
  ChassisTableDiagnostics diagnostics_;
};

}  // namespace talus
