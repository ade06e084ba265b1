#pragma once
/// @file
/// The `talus plan` command's work, separate from argument parsing. Only the
/// global stage exists so far (`--stage global`): the minimum-time lattice
/// search of talus::global_search with distinct candidate corridors. The full
/// pipeline (`--stage full`: the local B-spline optimisation of each
/// candidate) belongs to a later issue.
#include <cstddef>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "talus/core/types.hpp"

namespace talus::experiments {

/// `talus plan --terrain T.asc --start X,Y --goal X,Y --vehicle V.yaml
/// --stage global [--candidates K] [--lattice-spacing M] [--connectivity C]
/// [--smoothing LAMBDA] --out DIR`.
struct PlanRequest {
  std::string terrain;           ///< ESRI ASCII grid
  std::string vehicle;           ///< vehicle YAML/JSON (load_vehicle); needs a finite max_speed
  std::string start;             ///< "X,Y" in the terrain's frame [m] (parse_point)
  std::string goal;              ///< "X,Y" [m]
  std::string stage = "global";  ///< only "global" for now
  std::string output_dir;        ///< --out: created if needed
  long long candidates = 3;      ///< distinct candidates wanted (>= 1)
  double lattice_spacing = 0.0;  ///< [m]; 0 = the terrain's cell size
  int connectivity = 16;         ///< 8, 16 or 32
  /// lambda of the smoothing fit; none = interpolating fit.
  std::optional<double> smoothing;
};

/// The stages `--stage` accepts now ("full" comes with the planning pipeline).
inline constexpr const char* kPlanStageGlobal = "global";

/// Exit code of `talus plan` when the goal cannot be reached from the start.
inline constexpr int kUnreachableExitCode = 2;

/// Lattices with more nodes than this get no fields.csv (it would be large).
inline constexpr std::size_t kMaxFieldNodes = 4'000'000;

/// The columns of DIR/candidates.csv and DIR/fields.csv, in order.
inline constexpr const char* kCandidatesCsvHeader = "candidate,x,y";
inline constexpr const char* kFieldsCsvHeader = "x,y,cost_from_start,cost_to_goal";

/// Parses "X,Y" (two finite numbers, optional spaces around them) given to
/// `option`; anything else is an InputError naming the option and the text.
Vec2 parse_point(const std::string& option, const std::string& text);

/// What `plan` returns: the JSON summary (also written to DIR/summary.json)
/// and whether the goal was reached.
struct PlanOutcome {
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
/// ([nx, ny]), connectivity, candidates_requested, stage, fit, smoothing,
/// vehicle_max_speed, files, fit_seconds and seconds.
///
/// Bad input (options, files, a vehicle without max_speed, a start or goal
/// off the map, on NODATA or on untraversable terrain) throws InputError and
/// writes nothing. An unreachable goal is not an error.
PlanOutcome plan(const PlanRequest& request);

}  // namespace talus::experiments
