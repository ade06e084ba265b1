#pragma once
/// @file
/// The `talus plan` command's work, separate from argument parsing. Two
/// stages: `--stage global`, the minimum-time lattice search of
/// talus::global_search with distinct candidate corridors, and `--stage full`
/// (the default), which then optimises each candidate locally
/// (talus::optimize_path: a clamped cubic B-spline minimising the exact
/// time-optimal profile's travel time, Ipopt or NLopt) and keeps the best.
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/core/types.hpp"
#include "talus/optimal/planner.hpp"

namespace talus::experiments {

/// `talus plan --terrain T.asc --start X,Y --goal X,Y --vehicle V.yaml
/// [--stage full|global] [--smoothing LAMBDA | --surface-degree 5]
/// [--v0 A] [--v1 B] [--start-heading H] [--goal-heading H] [PLANNER OPTIONS] --out DIR`,
/// the planner options being those of talus::planner_parameters()
/// (planner_parameters.hpp), generated from its table.
struct PlanRequest {
  std::string terrain;             ///< DEM (load_terrain)
  std::string reproject = "none";  ///< --reproject: none | auto (load_terrain)
  int band = 0;                    ///< --band: the DEM's elevation band (0 = its only band)
  std::string vehicle;             ///< vehicle YAML/JSON (load_vehicle); needs a finite max_speed
  std::string start;               ///< "X,Y" in the terrain's frame [m] (parse_point)
  std::string goal;                ///< "X,Y" [m]
  std::string stage = "full";      ///< "full" or "global" (PlannerOptions::optimize)
  std::string output_dir;          ///< --out: created if needed
  /// The planner's options as planner_parameters() sets them (the CLI's
  /// defaults are the library's); `optimize` follows `stage` and the
  /// global search always computes the cost fields (fields.csv).
  PlannerOptions planner;
  /// lambda of the smoothing fit; none = interpolating fit.
  std::optional<double> smoothing;
  /// Degree of the interpolating B-patch: 3 (bicubic) or 5 (biquintic, no smoothing).
  int surface_degree = 3;
  double start_speed = 0.0;             ///< --v0 [m/s] (finite, >= 0, <= max_speed)
  double end_speed = 0.0;               ///< --v1 [m/s]
  std::optional<double> start_heading;  ///< --start-heading [rad] (finite)
  std::optional<double> goal_heading;   ///< --goal-heading [rad] (finite)
  /// --rasters: also write cost_to_go.tif and trajectory.geojson (see plan()).
  bool rasters = false;
  /// false (--no-figures): no plan.png and profile.png (sweeps draw their own).
  bool figures = true;
  /// false (--quiet): no progress line on stderr (there is none unless stderr
  /// is a terminal).
  bool progress = true;
};

/// The stages `--stage` accepts.
inline constexpr const char* kPlanStageGlobal = "global";
inline constexpr const char* kPlanStageFull = "full";

/// At most about this many rows per candidate in DIR/optima.csv.
inline constexpr std::size_t kMaxOptimaRows = 2000;

/// Exit code of `talus plan` when the goal cannot be reached from the start
/// (or, with --stage full, when no candidate has a feasible trajectory).
inline constexpr int kUnreachableExitCode = 2;

/// Lattices with more nodes than this get no fields.csv (it would be large).
inline constexpr std::size_t kMaxFieldNodes = 4'000'000;

/// The columns of DIR/candidates.csv and DIR/fields.csv, in order.
inline constexpr const char* kCandidatesCsvHeader = "candidate,x,y";
inline constexpr const char* kFieldsCsvHeader = "x,y,cost_from_start,cost_to_goal";
/// The columns of DIR/trajectory.csv (as `talus profile`) and DIR/optima.csv.
inline constexpr const char* kTrajectoryCsvHeader = "s,x,y,z,v,a,t,v_max,binding";
inline constexpr const char* kOptimaCsvHeader = "candidate,s,x,y,v";

/// Parses "X,Y" (two finite numbers, optional spaces around them) given to
/// `option`; anything else is an InputError naming the option and the text.
Vec2 parse_point(const std::string& option, const std::string& text);

/// What `plan` returns: the JSON summary (also written to DIR/summary.json)
/// and whether a result exists (the goal was reached; with --stage full, a
/// feasible trajectory was found too).
struct PlanOutcome {
  std::shared_ptr<const BPatch> surface;  ///< the fitted terrain the result's paths lie on
  PlannerResult result;                   ///< the library planner's result (talus::plan)
  nlohmann::json summary;
  bool reachable = false;
};

/// Checks the options, loads the vehicle and the terrain, fits the B-patch
/// (interpolating, or the smoothing fit with lambda `smoothing`), runs
/// talus::global_search with both cost-to-go fields and writes, in
/// request.output_dir:
/// - candidates.csv: `candidate,x,y`, the lattice vertices of each candidate
///   from the start node to the goal node, candidate 0 the best (header only
///   when the goal is unreachable);
/// - fields.csv: `x,y,cost_from_start,cost_to_goal` [m, m, s, s] at every
///   lattice node, row by row from the south-west; `inf` = not reachable,
///   `nan` = not computed (cost_to_goal when the goal is unreachable); skipped
///   when the lattice has more than kMaxFieldNodes nodes;
/// - summary.json: the returned summary.
///
/// The summary holds status ("ok" | "unreachable"), message (null when ok),
/// candidates [{cost_seconds, length_m, vertices}], nodes, edges_evaluated,
/// expanded, reachable_nodes, search_seconds, start_node and goal_node ([x, y]
/// of the snapped lattice nodes), start, goal, lattice_spacing, lattice
/// ([nx, ny]), connectivity, candidates_requested, stage, fit, surface_degree, smoothing,
/// vehicle_max_speed, files, fit_seconds, seconds and `options`: every
/// planner parameter's value by its name (planner_parameters(), generated).
///
/// With --stage full, each candidate (its first and last vertices replaced by
/// the exact start and goal) is optimised with optimize_path (--solver, M control
/// points, start and goal speeds v0, v1, the optimiser's search station
/// spacing), and every path's profile is then recomputed at
/// kDefaultStationSpacing (an optimised path slower there than its initial
/// fit is replaced by the initial fit). It also writes trajectory.csv (the
/// best trajectory, kTrajectoryCsvHeader), optima.csv (kOptimaCsvHeader, each
/// optimised candidate's profile thinned to about kMaxOptimaRows rows),
/// plan.png and profile.png (with their gnuplot scripts and data; skipped
/// when gnuplot is not installed), and the summary adds travel_time,
/// global_travel_time (the best candidate's initial fit, same spacing),
/// improvement_percent, optima [{candidate, status, message, travel_time,
/// initial_time, solver, solver_status, solver_failed, iterations,
/// evaluations, gradient_evaluations, finite_difference_gradients,
/// optimality (projected-gradient norm [s/m]), search_stations, seconds,
/// ...}], best_candidate, best_control_points ([[x, y], ...] of the best
/// clamped cubic, uniform breakpoints on [0, 1]) and `seconds` becomes
/// an object {fit, global, local, profile, plots, total}. No feasible
/// trajectory gives status "infeasible" (reachable = false).
///
/// Bad input (options, files, a vehicle without max_speed, a start or goal
/// off the map or on NODATA) throws InputError and writes nothing. An
/// unreachable goal is not an error, nor is a start or goal on untraversable
/// terrain (status "unreachable", the message naming it).
PlanOutcome plan(const PlanRequest& request);

}  // namespace talus::experiments
