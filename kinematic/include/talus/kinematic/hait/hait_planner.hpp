#pragma once
/// @file
/// The rough-terrain planner of A. Haït, T. Siméon, M. Taïx, "Algorithms for
/// rough terrain trajectory planning", Advanced Robotics 16(8), 2002, §4–§5.
///
/// Search (§4.1–4.2): the configuration space (x, y, θ) is cut into cells of
/// `cell_size` × `cell_size` × 2π/`theta_bins`. From a node, each of the six
/// controls (v, ω) ∈ {−V, V} × {−Ω, 0, Ω} is applied over `step` metres of
/// travel (a straight segment or an arc of radius `turning_radius`). The arc
/// is checked for validity at discrete configurations at most `check_spacing`
/// apart; a node is created only if its cell has never held one (at most one
/// node per cell, the cells are marked for the whole search) and the arc is
/// valid. A* develops the open node of least cost + heuristic.
///
/// Arc cost (§4.2.1, weighting ours): each sub-step of length Δs between two
/// checked configurations costs Δs · (1 + margin_weight · (1 − m)), m ∈ [0, 1]
/// the validity margin at its end (0 at a limit), so the cost is the distance
/// when the placement is far from its limits and up to (1 + margin_weight)
/// times the distance near them.
///
/// Heuristics (§4.2.2): `kEuclidean` is the straight-line distance to the
/// goal; `kPotential` is, as in Barraquand–Latombe [3] to which the paper
/// refers, a linear combination (the mean, times `potential_weight`) of the
/// potentials at two control points of the robot, `control_point_offset`
/// ahead of and behind its reference point, each read on a potential bitmap
/// whose wave started at that control point's goal position; `kPotentialRs`
/// adds the goal orientation "close to the goal" with the Reeds–Shepp distance
/// (OMPL's ReedsSheppStateSpace, see reeds_shepp.hpp). The paper gives no
/// rule for "close" nor for the combination; ours: within `rs_switch_distance`
/// d_s of the goal position the heuristic is the potential plus
/// (1 − d/d_s) times the Reeds–Shepp distance's excess over the straight-line
/// distance d (the detour the goal heading costs, 0 when aligned), so h is
/// continuous at the region's edge (a step there makes A* develop the band
/// outside the region first). The blend was tuned on the hait-heuristics
/// problem (seed 7) with `connect_goal`; on its five seeded variants it
/// creates fewer nodes than kPotential on four (equal on the fifth) with the
/// connection, but fewer on only one without it (the paper's configuration),
/// because our potential is nearly exact near the goal and any added term
/// raises f above that of nodes far behind (see the experiment's report).
///
/// Goal (§4.2): reached by a node within `goal_position_tolerance` and
/// `goal_heading_tolerance` of the goal, or, when `connect_goal`, by a valid
/// Reeds–Shepp curve to the exact goal from a developed node within
/// `rs_switch_distance`.
///
/// Uncertainty (§5): δz builds the envelopes T_min/T_max and the validity is
/// checked in the worst case (placement on the envelopes, collision against
/// T_max); the position uncertainty (ρ, Δθ) requires the whole modified
/// neighbourhood of §5.2 (a segment of ±ρ normal to the heading × θ ± Δθ) to
/// be valid, sampled every check_spacing and every heading cell (the paper
/// precomputes min/max placement surfaces over it instead; sampling checks the
/// same set directly, at more placements per configuration); the cost bitmap is grown by ρ before
/// the wave propagation (§5.3.1).
///
/// Error policy: malformed input (bad options, start or goal off the map or
/// on NODATA) throws InputError; a start or goal configuration that is not
/// valid for the robot is the status kStartInvalid / kGoalInvalid with a
/// message naming the configuration, since it is an expected outcome of a
/// query on rough terrain.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/hait/hait_robot_validity.hpp"
#include "talus/kinematic/hait/hait_smoothing.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {

/// Search guidance (§4.2.2, §4.3); names as on the CLI.
enum class HaitHeuristic {
  kEuclidean,    ///< "euclidean": straight-line distance
  kPotential,    ///< "potential": potential bitmap at two control points
  kPotentialRs,  ///< "potential-rs": potential, Reeds–Shepp near the goal
};
/// "euclidean", "potential" or "potential-rs".
std::string heuristic_name(HaitHeuristic h);
/// Inverse of heuristic_name(); throws InputError listing the accepted names.
HaitHeuristic parse_heuristic(const std::string& name);

/// Options of the planner; defaults in the struct (SI units).
struct HaitOptions {
  // --- configuration-space cells and controls (§4.1)
  double cell_size = 0.25;  ///< x–y cell edge [m] (> 0); the paper's terrains are 0.25 m grids
  int theta_bins = 32;      ///< heading cells over 2π (>= 4)
  double step = 0.4;        ///< travel per control application [m] (> 0)
  double turning_radius = 1.0;  ///< minimum turning radius V/Ω of the arcs [m] (> 0)
  double check_spacing = 0.1;   ///< validity checks along an arc at most this far apart [m] (> 0)
  double margin_weight = 1.0;   ///< arc-cost penalty near the limits (>= 0), see the file comment
  std::size_t max_nodes = 2'000'000;  ///< node budget; exceeding it is status kNodeLimit

  // --- guidance (§4.2.2)
  HaitHeuristic heuristic = HaitHeuristic::kPotentialRs;
  double potential_weight = 1.0;  ///< scale of the potential heuristic (> 0)
  double control_point_offset =
      0.0;  ///< control points ± this along the heading [m]; 0 = robot's half length
  double rs_switch_distance = 0.0;  ///< Reeds–Shepp region radius [m]; 0 = 3 × turning_radius

  // --- goal (§4.2)
  double goal_position_tolerance = 0.0;  ///< [m]; 0 = cell_size
  double goal_heading_tolerance = 0.0;   ///< [rad]; 0 = one heading cell, 2π / theta_bins
  bool connect_goal = true;              ///< try a valid Reeds–Shepp curve to the exact goal

  // --- smoothing (§4.4)
  bool smooth = false;
  HaitSmoothingOptions smoothing;  ///< its check_spacing is replaced by this struct's

  // --- uncertainty (§5)
  double terrain_uncertainty = 0.0;  ///< δz, elevation interval half-width at every node [m] (>= 0)
  /// Per-node δz [m] instead (HaitValidityOptions::terrain_uncertainty_map: the
  /// terrain grid's shape, >= 0); set, terrain_uncertainty must be 0. The
  /// validity uses its envelopes and the cost bitmap its local δz (§5.3.1).
  std::shared_ptr<const ElevationGrid> terrain_uncertainty_map;
  double position_uncertainty = 0.0;  ///< ρ [m] (>= 0)
  double heading_uncertainty = 0.0;   ///< Δθ [rad] in [0, π)

  // --- guide (Dacre-Wright–Siméon 1993, §1: a coarse free-space structure guiding a finer planner)
  /// The configurations the search may use; empty (the default) = every one.
  /// A configuration outside it is treated as not valid (zero placements
  /// computed), everywhere the search checks validity: arcs, the Reeds–Shepp
  /// connection and the smoothing; a start or goal outside it is
  /// kStartInvalid / kGoalInvalid. Must be deterministic. Filled from a
  /// Dacre-Wright voxel channel by dacre_wright_channel_region()
  /// (dacre_wright/channel_region.hpp).
  std::function<bool(const SE2Pose&)> allowed_region;

  /// Throws InputError naming the field, its value and the accepted range.
  void validate() const;
};

/// Termination of a query.
enum class HaitStatus {
  kFound,         ///< a path from start to goal
  kNoPath,        ///< every reachable cell explored without reaching the goal
  kStartInvalid,  ///< the start configuration is not valid (see message)
  kGoalInvalid,   ///< the goal configuration is not valid (see message)
  kNodeLimit,     ///< max_nodes created before the goal was reached
};
/// "found", "no_path", "start_invalid", "goal_invalid", "node_limit".
std::string status_name(HaitStatus s);

/// Result and diagnostics of a query (the paper's table, §4.3).
struct HaitResult {
  HaitStatus status = HaitStatus::kNoPath;
  std::string message;  ///< human-readable outcome
  /// The path as dense configurations (every checked one), start first, each
  /// with the control reaching it; smoothed when options.smooth.
  std::vector<PathPoint> path;
  std::vector<PathPoint> unsmoothed_path;  ///< the searched path (== path when not smoothing)
  bool connected_to_goal = false;          ///< ends with a Reeds–Shepp curve to the exact goal
  std::size_t nodes_created = 0;           ///< including the start node
  std::size_t nodes_developed = 0;         ///< nodes whose successors were generated
  std::size_t placements = 0;              ///< robot placements computed (search + smoothing)
  double preprocessing_seconds = 0.0;      ///< bitmaps, placement tables, quadtree
  double search_seconds = 0.0;             ///< the A* (and goal connection)
  double smoothing_seconds = 0.0;
  double length_m = 0.0;                       ///< length of `path` [m]
  std::size_t control_changes = 0;             ///< along `path`
  std::size_t control_changes_unsmoothed = 0;  ///< along `unsmoothed_path`
};

/// A potential over configurations, lower = closer to the goal (see kPotential).
using PotentialFunction = std::function<double(const SE2Pose&)>;

/// The search of §4 over any validity oracle: the core that plan_hait() runs
/// with the robot's placement and validity, usable with synthetic validity.
/// `potential` is needed by kPotential and kPotentialRs (InputError if empty)
/// and is ignored by kEuclidean. Uncertainty options are ignored here (they
/// live in the oracle and the potential); smoothing is applied when
/// options.smooth. Throws InputError for invalid options or non-finite poses.
HaitResult hait_search(const ValidityFunction& validity, const PotentialFunction& potential,
                       const SE2Pose& start, const SE2Pose& goal, const HaitOptions& options);

/// The §5.2 position-uncertainty wrapper: q is valid only if `base` accepts
/// every sampled configuration of its modified neighbourhood, lateral offsets
/// in [−rho, rho] (normal to the heading, at most `spacing` [m] apart) times
/// headings θ + [−dtheta, dtheta] (at most `angle_step` [rad] apart), the
/// extremes included. The margin is the least one met. rho = dtheta = 0
/// returns `base` unchanged.
ValidityFunction neighbourhood_validity(ValidityFunction base, double rho, double dtheta,
                                        double spacing, double angle_step);

/// The validity options plan_hait() gives HaitRobotValidity: the options'
/// uncertainties, sampled (rigid body under ρ or Δθ) every check_spacing
/// across and every heading cell, 2π / theta_bins.
HaitValidityOptions hait_validity_options(const HaitOptions& options);

/// The full planner: placement and validity of `robot` on `terrain` (with the
/// worst-case checks of §5 when uncertainties are set), collision through the
/// quadtree, potential bitmaps (a control point past the map's edge reads
/// the potential at the nearest point of the map), then hait_search(). A
/// valid child whose heuristic is infinite gets no node but its cell is
/// marked like any other (§4.1). Throws InputError for an
/// invalid robot or options, a start or goal off the map or on NODATA.
HaitResult plan_hait(const RuledTerrain& terrain, const Robot& robot, const SE2Pose& start,
                     const SE2Pose& goal, const HaitOptions& options);

}  // namespace talus
