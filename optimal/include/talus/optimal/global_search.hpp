#pragma once
/// @file
/// The global stage of the Shiller–Gwo planner: a minimum-time search over a
/// lattice on the terrain whose edge cost is the travel time at the velocity
/// limit, J = ∫ ds / v_max(s) (Iagnemma–Shimoda–Shiller 2008, eq. (6)), and the
/// extraction of several distinct good candidate paths for the local optimiser.
///
/// Edges are straight segments in (x, y) lifted onto the B-patch, sampled at
/// stations at most a quarter lattice spacing apart (Simpson's rule on
/// ds / v_max, see edge_stations()). An edge is untraversable in a direction if at some station
/// (a) no speed satisfies the speed limits (v_max = 0), or (b) the vehicle
/// could neither climb nor hold its speed — a_max < 0 at every admissible
/// speed (too steep to drive up) — or (c) could not brake — a_min > 0 at
/// every admissible speed (too steep to drive down and stop). J alone ignores
/// the tangential acceleration, so without (b) and (c) the search would route
/// straight up a cliff whose v_max is high because it is straight.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/termination.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus {

/// How the lattice is searched (GlobalSearchOptions::resolution).
enum class GlobalSearchResolution {
  /// Every node of the lattice (memory and time grow with the map).
  kFull,
  /// Coarse to fine: the same search on a lattice coarse_factor times coarser
  /// (the surface sampled at its nodes, edges sampled every quarter coarse
  /// spacing), then the fine lattice restricted to a corridor of 16 x 16-node
  /// tiles within corridor_width of the coarse candidates. The corridor is
  /// doubled while the fine search finds no route in it or its best route
  /// touches the corridor's edge (a better one may lie outside), up to the
  /// whole map, which is then exactly the full search. Memory and time grow
  /// with the corridor (plus the coarse lattice, 1/coarse_factor² of the map).
  ///
  /// Same best candidate as kFull whenever the full search's best route lies
  /// in the final corridor (the corridor numbers its nodes in the full
  /// lattice's order, so even ties break alike). They can differ when the
  /// coarse lattice misjudges the terrain so that the fine optimum lies in a
  /// corridor the coarse search did not find (a pass narrower than a coarse
  /// cell, an obstacle the coarse edges step over), while a route inside the
  /// corridor that keeps off its edge exists; further candidates can differ
  /// more (only routes in the corridor are candidates; distances near its
  /// edge are chamfer distances inside it). A coarse search that finds no
  /// route (or whose start or goal node is untraversable at the coarse
  /// scale) falls back to the full search. cost_from_start / cost_to_goal
  /// are not returned (they would be map-sized).
  ///
  /// Under a time budget (GlobalSearchOptions::termination), a route level
  /// comes first: the same search on a lattice of at most
  /// kRouteLevelNodes nodes (when that is coarser than the coarse one), run
  /// to its end whatever the budget (its size bounds its time: about 0.2 s).
  /// When the budget stops a finer level before it has a candidate, the
  /// coarsest level's candidates are returned with status kStopped (routes
  /// to fit and optimise, not fine-lattice paths): a time-limited plan of a
  /// tile-size DEM has a route whenever that level finds one.
  kMulti,
  /// kMulti when the lattice has more than kAutoMultiResolutionNodes nodes,
  /// else kFull (GlobalSearchResult::resolution says which ran): a tile-size
  /// DEM is searched coarse to fine without the user having to ask.
  kAuto,
};
/// Lattices with more nodes than this (1000 x 1000) are searched coarse to
/// fine under GlobalSearchResolution::kAuto: a 3601² DEM at 1 m in full takes
/// minutes and 3.3 GB; coarse to fine, seconds and under 1 GB.
inline constexpr std::size_t kAutoMultiResolutionNodes = 1'000'000;
/// The route level's largest lattice under a time budget (kMulti): 20,000
/// nodes, searched with its candidates in about 0.2 s on one core.
inline constexpr std::size_t kRouteLevelNodes = 20'000;
/// "full", "multi", "auto".
std::string_view to_string(GlobalSearchResolution resolution);
/// Inverse of to_string; throws InputError listing the choices.
GlobalSearchResolution parse_global_search_resolution(std::string_view name);

/// A disc of the plane whose lattice nodes the search must not use
/// (GlobalSearchOptions::excluded).
struct ExcludedRegion {
  Vec2 centre = Vec2::Zero();  ///< [m]
  double radius = 0.0;         ///< [m], > 0
};

struct GlobalSearchOptions {
  double lattice_spacing = 0.0;  ///< node spacing [m]; 0 = the terrain's cell size
  int connectivity = 16;         ///< 8, 16 or 32 neighbours per node
  std::size_t candidates = 3;    ///< how many distinct candidates to return (>= 1)
  /// Separation d [m] of distinct candidates; 0 = 10 % of the start–goal
  /// distance, and at least 3 lattice spacings. A new path is distinct from
  /// an accepted one when some of its vertices are at least d away from it
  /// (directed Hausdorff distance) AND at most half of its vertices lie within
  /// d/2 of it (one bulge off the same corridor is not an alternative route).
  /// Distances are lattice chamfer distances (steps h and h sqrt 2: within 8 %
  /// of the Euclidean distance). Candidates are grown from the
  /// lattice nodes in increasing order of the best cost through them
  /// (cost_from_start + cost_to_goal), skipping nodes within d of an
  /// accepted candidate (Shiller, Fujita, Ophir, Nakamura 2004).
  double distinctness = 0.0;
  /// Candidates cost at most this multiple of the best (>= 1).
  double max_cost_ratio = 2.0;
  /// Compute both cost-to-go fields over the whole lattice (needed for more
  /// than one candidate, and for plots). false with candidates = 1 runs A*
  /// from start to goal with the admissible heuristic distance / max_speed,
  /// which evaluates only the edges it needs.
  bool cost_fields = true;
  /// kAuto (default: kFull up to kAutoMultiResolutionNodes lattice nodes,
  /// kMulti above), kFull or kMulti (coarse to fine, see GlobalSearchResolution).
  GlobalSearchResolution resolution = GlobalSearchResolution::kAuto;
  /// kMulti: coarse lattice spacing / fine lattice spacing (>= 2).
  int coarse_factor = 4;
  /// kMulti: the corridor's first half-width around the coarse candidates [m]
  /// (>= 0); 0 = 4 coarse lattice spacings.
  double corridor_width = 0.0;
  /// When to give up (core/termination.hpp; armed when the search starts):
  /// polled before the search starts and then every `stop_interval` node
  /// expansions (Dijkstra / A*, each with its lazily computed edge costs),
  /// node surface samples or candidate seeds; once it holds the search ends
  /// with status kStopped (the planner passes its own, armed, termination).
  /// So the search runs at most one batch of stop_interval expansions past
  /// the moment it first held (in the candidate extraction, one O(nodes)
  /// step: the sort of the seeds or one candidate's distance map).
  /// Default: never.
  Termination termination;
  std::size_t stop_interval = 1024;  ///< >= 1
  /// Threads computing the lattice's edge costs (0 = one per hardware
  /// thread). With more than one, and both cost fields wanted (cost_fields
  /// or candidates > 1), every edge is computed up front in parallel instead
  /// of lazily during the searches; the candidates, costs and fields are
  /// bit-identical for any count, but edges_evaluated then also counts the
  /// edges at nodes the searches never reach. The searches themselves stay
  /// serial. Default 1: one-core figures are the primary benchmark.
  std::size_t threads = 1;
  /// Lattice nodes within any of these discs are untraversable (every edge
  /// at them is), except the snapped start and goal nodes, which are always
  /// kept. The planner's feedback from the local stage
  /// (PlannerOptions::feedback_rounds) puts here the stretches of a
  /// candidate that no continuous profile can drive. Empty by default.
  std::vector<ExcludedRegion> excluded;
  /// Rule (c) of the file comment: an edge on which the vehicle could not
  /// brake at any admissible speed is untraversable. false leaves such edges
  /// to the local stage (the lattice then judges only speed limits and
  /// climbing): the initial fit of a candidate that takes one has no
  /// admissible profile, and the planner's feedback loop
  /// (PlannerOptions::feedback_rounds) excludes it and searches again. For
  /// studying the rule and the loop; default true.
  bool braking_rule = true;
  /// Keep the routes' turns within the vehicle's steering limit κ_max =
  /// Vehicle::max_curvature() (nothing to keep without one). A route may turn
  /// by Δθ at a node between edges of planar lengths L₁ and L₂ only when an
  /// arc of curvature κ_max tangent to both fits in their halves next to the
  /// node: tan(Δθ/2) <= κ_max min(L₁, L₂) / 2. Every route is then drivable
  /// within the limit as it stands (straight along its edges, each corner
  /// rounded by its arc), and none turns on the spot. The searches then run
  /// over (node, arrival direction) states. The rule is sufficient, not
  /// necessary: where it leaves the goal unreachable (a pass the lattice's
  /// 16 directions cross only in zig-zags, which a smooth path may still
  /// thread), the search is repeated without it and says so
  /// (GlobalSearchResult::turn_limit_relaxed), leaving the turns to the local
  /// stage, which keeps the limit exactly. Memory and expansions grow by
  /// connectivity + 1 (17 at 16-connectivity; InputError beyond the memory
  /// budget, memory_budget.hpp); edge costs
  /// are the node lattice's, each evaluated once. The first edge out of the
  /// start and the arrival at the goal are free: the lattice does not see
  /// PlanningProblem's headings. cost_from_start / cost_to_goal are a node's
  /// best over its arrival directions. false: position-only search. Default true.
  bool turn_limit = true;
  /// Throws InputError naming the field.
  void validate() const;
};

enum class GlobalSearchStatus {
  kOk,           ///< at least one candidate
  kUnreachable,  ///< the goal cannot be reached from the start; see `message`
  /// GlobalSearchOptions::termination cut the search short; `candidates` holds what
  /// was found by then (possibly none, e.g. when it stopped before the goal
  /// was reached; a route found by a search stopped before its end is a real,
  /// not necessarily minimum-time, path), `message` says where it stopped.
  kStopped,
};
/// "ok", "unreachable", "stopped".
std::string_view to_string(GlobalSearchStatus status);

/// One candidate path: lattice vertices from start to goal.
struct CandidatePath {
  std::vector<Vec2> vertices;  ///< [m], first = start node, last = goal node
  double cost_seconds = 0.0;   ///< J along it [s]
  double length_m = 0.0;       ///< 3-D length on the surface [m]
};

/// Travel-time cost of one straight edge in each direction; +inf = untraversable.
struct EdgeCost {
  double forward = 0.0;   ///< a -> b [s]
  double backward = 0.0;  ///< b -> a [s]
  double length = 0.0;    ///< 3-D length [m]
};
/// Stations per lattice edge of planar length `planar_length` at lattice spacing `spacing`.
int edge_stations(double planar_length, double spacing);

/// J along the straight segment a -> b (and back) lifted onto `terrain`, with
/// the untraversability rules of the file comment. `stations` >= 3, odd.
EdgeCost edge_cost(const BPatch& terrain, const Vehicle& vehicle, const Vec2& a, const Vec2& b,
                   int stations);

struct GlobalSearchResult {
  GlobalSearchStatus status = GlobalSearchStatus::kUnreachable;
  std::string message;
  std::vector<CandidatePath> candidates;                     ///< ordered by cost, best first
  Vec2 start_node = Vec2::Zero(), goal_node = Vec2::Zero();  ///< the snapped start and goal
  // Diagnostics.
  std::size_t nodes = 0;            ///< lattice nodes
  std::size_t edges_evaluated = 0;  ///< undirected edges whose cost was computed
  std::size_t expanded = 0;         ///< nodes (with turn_limit: states) expanded by the searches
  std::size_t reachable_nodes = 0;  ///< nodes reachable from the start
  double search_seconds = 0.0;      ///< total time of the global stage
  // Multi-resolution diagnostics (resolution kMulti; nodes is then the final
  // corridor's node count, expanded and edges_evaluated count every search).
  GlobalSearchResolution resolution = GlobalSearchResolution::kFull;  ///< what ran (never kAuto)
  std::size_t coarse_nodes = 0;  ///< nodes of the coarse lattice
  std::size_t route_nodes = 0;   ///< nodes of the route level (0: none ran)
  /// The candidates are the route or coarse level's (a finer level was stopped first).
  bool coarse_candidates = false;
  std::size_t corridor_widenings = 0;  ///< times the corridor was doubled
  double corridor_width = 0.0;         ///< the final corridor's half-width [m]
  bool fell_back_to_full = false;      ///< the coarse search found no route: full search
  /// GlobalSearchOptions::turn_limit left the goal unreachable: the candidates are of the
  /// position-only search (their turns may exceed the steering limit; see `message`).
  bool turn_limit_relaxed = false;
  // The lattice and the two cost-to-go fields, for plots (row-major, +inf =
  // unreached; empty for kMulti).
  std::size_t nx = 0, ny = 0;
  double spacing = 0.0;
  Vec2 origin = Vec2::Zero();
  std::vector<double> cost_from_start, cost_to_goal;
};

/// Runs the global stage from `start` to `goal` [m]. Throws InputError for an
/// invalid vehicle (it needs a finite max_speed: J is the time at the speed
/// limit, and an unlimited straight road would cost nothing) or a start or
/// goal off the map or on NODATA. An unreachable goal is a status
/// (kUnreachable, `message` saying why), and so is a start or goal node on
/// untraversable terrain (no lattice edge leaves or enters it): expected
/// outcomes on steep ground, not bad input.
/// The candidates' separation when GlobalSearchOptions::distinctness is 0: a tenth of the
/// start-goal distance between lattice nodes, at least three lattice spacings [m].
inline double default_candidate_separation(const Vec2& start_node, const Vec2& goal_node,
                                           double spacing) {
  return std::max(0.1 * (goal_node - start_node).norm(), 3.0 * spacing);
}

GlobalSearchResult global_search(const BPatch& terrain, const Vehicle& vehicle, const Vec2& start,
                                 const Vec2& goal, const GlobalSearchOptions& options);

/// Edge costs kept between global searches (a per-query workspace; the
/// terrain and vehicle stay immutable). Searches on one terrain and vehicle
/// with the same lattice spacing, connectivity and braking rule share their
/// lattice's surface samples and edge costs: only the excluded regions,
/// start, goal and extraction options may differ. The planner's feedback
/// rounds use one, so each round after the first is a graph search over
/// known costs (Big Tujunga with the rover: 8 rounds, each a 2 s search
/// from scratch without it). Results are exactly those of searches without
/// a workspace; GlobalSearchResult::edges_evaluated counts only the edges
/// the search itself computed. Lattices of the whole map are kept (with
/// kMulti: the coarse one; the corridors are not). It holds its own copy of
/// the terrain (BPatch copies share their coefficients), so nothing it keeps
/// depends on the caller's surface object. A workspace used with another
/// terrain (BPatch::identity(), never its address: a new fit at a destroyed
/// one's address is another terrain; a copy is the same one), vehicle,
/// connectivity or braking rule drops what it held. Not for concurrent use
/// from several threads.
class GlobalSearchWorkspace {
 public:
  GlobalSearchWorkspace();
  ~GlobalSearchWorkspace();
  GlobalSearchWorkspace(GlobalSearchWorkspace&&) noexcept;
  GlobalSearchWorkspace& operator=(GlobalSearchWorkspace&&) noexcept;
  GlobalSearchWorkspace(const GlobalSearchWorkspace&) = delete;
  GlobalSearchWorkspace& operator=(const GlobalSearchWorkspace&) = delete;

  /// Lattices held (one per lattice spacing searched in full).
  std::size_t lattices() const;
  /// Drops every lattice.
  void clear();

  struct Impl;  ///< defined in global_search.cpp

 private:
  std::unique_ptr<Impl> impl_;
  friend GlobalSearchResult global_search(const BPatch&, const Vehicle&, const Vec2&, const Vec2&,
                                          const GlobalSearchOptions&, GlobalSearchWorkspace&);
};

/// global_search() reusing `workspace`'s edge costs (same result).
GlobalSearchResult global_search(const BPatch& terrain, const Vehicle& vehicle, const Vec2& start,
                                 const Vec2& goal, const GlobalSearchOptions& options,
                                 GlobalSearchWorkspace& workspace);

}  // namespace talus
