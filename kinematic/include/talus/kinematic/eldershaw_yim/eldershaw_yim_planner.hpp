#pragma once
/// @file
/// The high-level CG path planner of Eldershaw and Yim 2001 §3.1 and §4.2:
/// the tree-PRM over CGspace with the A* local planner (cg_local_planner.hpp),
/// or, in the direct mode the paper recommends on a large compute server, one
/// A* over the whole CGspace from the start cell to the goal cell.
///
/// Tree-PRM (§3.1), with the choices the paper leaves open stated:
/// - points are inserted one by one: the start, the goal, then up to
///   prm_points random valid CG cells (uniform over the lattice, each draw a
///   cell index from mt19937_64(seed); invalid or repeated cells are redrawn,
///   at most sample_attempts × prm_points draws in all);
/// - each inserted point starts its own tree (a separate list); it is tried
///   against every other tree in order of creation, never against a tree it
///   has joined: against that tree's members within connect_radius (xy
///   distance of cell centres), nearest first (ties: earlier member), at most
///   connect_attempts of them; the first success adds the edge and
///   concatenates the two lists;
/// - done when the start's and the goal's lists are one: the tree path
///   start → goal (the unique one) is recreated by re-running the local
///   planner on each edge in travel order, and the pieces are concatenated.
///
/// Parallel local planning (the paper's distributed planning on PolyBot):
/// the local-planner calls of one inserted point are made in rounds, round k
/// being the k-th nearest member of every tree still unjoined (the members
/// tried are fixed when the point is inserted: a join only changes trees
/// already visited), and the re-creation of the path's edges is one batch.
/// The calls of a batch run on `workers` threads, each on its own overlay of
/// the shared CGspace (CgSpace(const CgSpace&)), and their results are
/// applied in the serial order afterwards, so the plan and every counter are
/// the same for any worker count. Counters are per call: a call's cells
/// evaluated are the blocks missing from the CGspace when its batch began,
/// and its budget is what was left then; cells_materialised counts each
/// block once. Calls of a round after one that spent the budget are still
/// counted (local_planner_calls, expansions) though their results are unused.
///
/// The work budget counts CG cells evaluated plus A* expansions (work, not
/// time, so results are deterministic). The CG path is a 6-connected sequence
/// of valid CG cells; as poses it is the start, the centres of the inner
/// cells (θ unwrapped to stay continuous), then the goal. When a CG path is
/// found the foot-level planner runs along it (plan_feet), outside
/// search_seconds.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/eldershaw_yim/cg_local_planner.hpp"
#include "talus/kinematic/eldershaw_yim/cg_space.hpp"
#include "talus/kinematic/eldershaw_yim/foot_planner.hpp"
#include "talus/kinematic/eldershaw_yim/legged_robot.hpp"

namespace talus {

/// Processes sharing the local-planner calls of one query (file comment);
/// the CLI implements it on its MPI session.
class CgRankGroup {
 public:
  virtual ~CgRankGroup() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// `values` (the same length on every rank) replaced by their element-wise
  /// maximum over the ranks; a collective call.
  virtual void max_all(std::vector<double>& values) const = 0;
};

/// Options of plan_eldershaw_yim.
struct EldershawYimPlannerOptions {
  int theta_slices = 16;             ///< n_θ: 1 (no rotation) or 8..1024
  bool direct = false;               ///< one A* over the whole CGspace instead of the tree-PRM
  std::size_t prm_points = 200;      ///< random points of the tree-PRM (>= 0)
  double connect_radius = 0.0;       ///< [m] neighbours tried; 0 = 40 foot prints
  std::size_t connect_attempts = 3;  ///< members of one tree tried per new point (>= 1)
  std::size_t sample_attempts = 20;  ///< draws per wanted random point (>= 1)
  CgLocalPlannerOptions local;      ///< margin; heading_weight <= 0 here = the robot's outer radius
  int block_side = 16;              ///< CGspace block side in cells (>= 1)
  std::uint64_t seed = 1;           ///< of the PRM's random points
  std::size_t budget = 50'000'000;  ///< CG cells evaluated + A* expansions (>= 1)
  /// Run the foot-level planner (§3.2, foot_planner.hpp) along a found CG
  /// path; its outcome does not change the status (the CG path is the result).
  bool plan_feet = true;
  FootPlannerOptions feet{20000};  ///< its options (budget: search nodes)
  /// §3.3 feedback (not implemented in the paper): when the foot plan fails
  /// (search exhausted or its budget spent) the CG cell after the furthest
  /// one it reached is marked invalid and the CG path is searched again, at
  /// most this many times (0 = no feedback). The CGspace already materialised
  /// is kept; the foot plan keeps its steps on the leading cells the new CG
  /// path shares with the old one and walks on from there (planned afresh
  /// from the start only if that fails).
  std::size_t feedback_rounds = 3;
  /// Threads of the local-planner calls (1..256; file comment). The result
  /// does not depend on it; 1 runs them on the calling thread.
  int workers = 1;
  /// The ranks sharing the calls (not owned; null = this process alone).
  const CgRankGroup* ranks = nullptr;
  /// Throws InputError naming the field.
  void validate() const;
};

/// How a query ended.
enum class EldershawYimStatus {
  kFound,           ///< a CG path
  kNoPath,          ///< direct: no path in CGspace; PRM: start and goal not joined
  kStartInvalid,    ///< the start's CG cell is invalid
  kGoalInvalid,     ///< the goal's CG cell is invalid
  kBudgetExceeded,  ///< the work budget ran out
};
/// "found", "no_path", "start_invalid", "goal_invalid", "budget_exceeded".
const char* to_string(EldershawYimStatus status);

/// Result of one query.
struct EldershawYimResult {
  EldershawYimStatus status = EldershawYimStatus::kNoPath;
  std::string message = "plan_eldershaw_yim was not called";
  std::vector<CgCell> cells;  ///< the CG path, start cell … goal cell (6-connected)
  std::vector<SE2Pose> path;  ///< the CG path as poses (file comment)
  double length_m = 0.0;      ///< xy length of `path` [m]
  CgState start_state = CgState::kUnknown, goal_state = CgState::kUnknown;
  std::vector<CgCell> prm_points;  ///< every PRM point, start and goal first (empty if direct)
  std::vector<std::pair<std::size_t, std::size_t>> prm_edges;  ///< (new, old) point indices
  std::size_t prm_trees = 0;                                   ///< distinct trees at the end
  std::size_t local_planner_calls = 0;  ///< connection attempts (plus 1 in the direct mode)
  std::size_t local_planner_successes = 0;
  std::size_t recreate_calls = 0;  ///< local-planner calls re-creating the path's edges
  std::size_t expansions = 0;      ///< A* expansions in all
  std::size_t cells_materialised = 0;
  std::size_t blocks_materialised = 0;
  std::size_t cg_cells = 0;          ///< cells in the whole lattice (for comparison)
  std::size_t samples_drawn = 0;     ///< random draws of the PRM
  double footmap_seconds = 0.0;      ///< [s]
  double materialise_seconds = 0.0;  ///< cell evaluation, part of the stages below [s]
  double sample_seconds = 0.0;       ///< drawing random valid points [s]
  double connect_seconds = 0.0;      ///< local-planner calls of the roadmap (or the direct A*) [s]
  double recreate_seconds = 0.0;     ///< re-running the path's edges [s]
  double search_seconds = 0.0;       ///< all of the query after the footmap [s]
  bool feet_planned = false;         ///< the foot planner ran (a CG path was found and plan_feet)
  FootPlan foot_plan;                ///< the last foot plan: its steps and outcome
  std::size_t feedback_events = 0;   ///< CG cells marked invalid by the foot planner (§3.3)
  std::vector<CgCell> feedback_cells;  ///< those cells, in order
  /// Steps of the last foot plan taken over from the plan before it (§3.3 reuse; 0 = none).
  std::size_t foot_steps_reused = 0;
  /// Foot-planner nodes over every round (a feedback round runs the resumed
  /// plan and, when it fails, a fresh one).
  std::size_t foot_planner_nodes = 0;
  double foot_planner_seconds = 0.0;  ///< foot-planner time over every round [s]
  bool found() const { return status == EldershawYimStatus::kFound; }
  /// One line: status, path, counters, times, message.
  std::string brief_report() const;
};

/// The query on `terrain` for `robot` (validated; InputError if invalid, or
/// for invalid options). Start and goal must lie on the terrain.
EldershawYimResult plan_eldershaw_yim(const RuledTerrain& terrain, const LeggedRobot& robot,
                                      const SE2Pose& start, const SE2Pose& goal,
                                      const EldershawYimPlannerOptions& options = {});

/// Poses of a CG cell path (file comment): `start`, the inner cells' centres, `goal`.
std::vector<SE2Pose> cg_path_poses(const CgLattice& lattice, const std::vector<CgCell>& cells,
                                   const SE2Pose& start, const SE2Pose& goal);

}  // namespace talus
