#pragma once
/// @file
/// The two-stage time-optimal planner in one call (Shiller & Gwo 1991;
/// Iagnemma, Shimoda & Shiller 2008):
/// 1. global_search(): distinct minimum-time candidate corridors on a lattice
///    (edge cost J = ∫ ds / v_max);
/// 2. optimize_path() of each candidate (its end vertices replaced by the
///    exact start and goal): a clamped cubic B-spline minimising the travel
///    time of its exact time-optimal profile (PlannerOptions::local.formulation:
///    the nested formulation, or the simultaneous NLP in the control points
///    and the squared speeds), at the final station spacing unless
///    local.station_spacing says otherwise (local.max_search_stations still
///    coarsens it on long paths);
/// 3. every optimum and its initial fit re-evaluated with
///    evaluate_trajectory() at PlannerOptions::station_spacing; an optimum
///    more than kStageDisagreement slower there than at the search's
///    stations (or without an admissible profile there) gives way to the
///    fastest there of every attempt's point (LocalAttempt::curve), and one
///    slower than its own initial fit is replaced by the fit, so no
///    candidate's result is slower than where it started;
/// 4. the fastest feasible trajectory is the result.
///
/// Stages that agree (feedback from the local stage to the global one): the
/// lattice judges each straight edge alone, so it can accept a corridor that
/// no continuous path drives — a hairpin on a steep slope, a stretch only
/// traversable at a speed the vehicle cannot reach or shed in time. Before
/// the local stage every candidate's followability is checked: the
/// optimiser's own initial path (fit_initial_path(), grown while needed, up
/// to control_point_limit()) must have an admissible profile at the search's
/// stations (the final ones, by default). While some candidate fails and the budget
/// (feedback_rounds) lasts, a disc of feedback_radius round the station where
/// its profile fails is excluded from the lattice (GlobalSearchOptions::
/// excluded) and the global search runs again; a failure inside a disc of an
/// earlier round (the search went round it and the fit still fails there, as
/// down a long chute) doubles that disc instead. The round with the most
/// followable candidates is kept (the last of equals); the result reports
/// the rounds run and the regions excluded.
///
/// Expected outcomes (an unreachable goal, no feasible candidate, a solver
/// failure, a stop request, the time limit) are statuses; only invalid input
/// throws InputError.
///
/// The termination (PlannerOptions::termination: a time limit, a stop
/// request, or both; core/termination.hpp) is armed once when plan() starts
/// and checked by the global
/// search every GlobalSearchOptions::stop_interval node expansions, before
/// each candidate's optimisation and at every solver iteration (Ipopt) or
/// evaluation (NLopt). On it plan() returns status kTimeLimit with the best
/// feasible trajectory found so far: if the limit falls in the global stage
/// after a route was found, or before any local result is feasible, the
/// next candidate still gets its initial fit evaluated (no optimisation) until
/// one is feasible, so a time-limited plan has a trajectory whenever the
/// global stage found a route; if the global stage is cut before any route
/// exists there is no trajectory (global.status kStopped). The overrun is
/// bounded by one batch of expansions, one solver iteration and the
/// evaluation of the candidate in hand (its initial fit and result at
/// station_spacing).
///
/// Example:
///   const BPatch surface = BPatch::interpolate(read_esri_ascii("dem.asc"));
///   const PlanningProblem problem(surface, load_vehicle("rover.yaml"), {x0, y0}, {x1, y1});
///   const PlannerResult result = plan(problem, PlannerOptions{});
///   std::cout << result.brief_report();
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/termination.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "talus/optimal/trajectory.hpp"

namespace talus {

/// What to plan: a vehicle from `start` to `goal` on a fitted surface.
struct PlanningProblem {
  /// Shares `terrain` (not null): the problem, its copies and every result
  /// planned from it keep it alive.
  PlanningProblem(std::shared_ptr<const BPatch> terrain, Vehicle model, const Vec2& from,
                  const Vec2& to)
      : surface(std::move(terrain)), vehicle(std::move(model)), start(from), goal(to) {}
  /// Takes `terrain` into a shared surface: a temporary is moved, a named
  /// surface copied (pass a shared_ptr to share one without the copy).
  PlanningProblem(BPatch terrain, Vehicle model, const Vec2& from, const Vec2& to)
      : PlanningProblem(std::make_shared<const BPatch>(std::move(terrain)), std::move(model), from,
                        to) {}
  /// The fitted surface; the trajectories of a result refer to it and keep it
  /// alive (PlannerResult::surface and each trajectory's path).
  std::shared_ptr<const BPatch> surface;
  Vehicle vehicle;           ///< needs a finite max_speed (the global cost is time at the limit)
  Vec2 start;                ///< [m], in the surface's domain
  Vec2 goal;                 ///< [m], in the surface's domain
  double start_speed = 0.0;  ///< ṡ at the start [m/s], in [0, max_speed]
  double end_speed = 0.0;    ///< ṡ at the goal [m/s], in [0, max_speed]
  /// The heading the path leaves the start with and arrives at the goal with
  /// [rad], counter-clockwise from east (finite; any value, taken modulo 2π);
  /// empty = free. The local stage keeps them exactly (the fit's end control
  /// points pinned: PathOptimizerOptions::start_heading); the global stage's
  /// corridors do not see them.
  std::optional<double> start_heading;
  std::optional<double> goal_heading;
  /// Throws InputError naming what is wrong.
  void validate() const;
};

/// Which stage the planner is in, for progress reports.
enum class PlannerStage { kGlobalSearch, kLocalOptimisation, kDone };
std::string_view to_string(PlannerStage stage);

/// A progress report: sent before the global search, before each
/// candidate's optimisation and at the end.
struct PlannerProgress {
  PlannerStage stage = PlannerStage::kGlobalSearch;
  std::size_t candidate = 0;   ///< the candidate about to be optimised (local stage)
  std::size_t candidates = 0;  ///< candidates from the global stage (0 before it)
  double seconds = 0.0;        ///< since plan() started
};

struct PlannerOptions {
  /// The global stage. Its `candidates` (3) is how many corridors are
  /// optimised. Its threads stay 1 by default: more threads each reserve a
  /// malloc arena, and under an address-space limit (ulimit -v, common on
  /// clusters) the failed reservations made a 1 s plan run past 20 s.
  GlobalSearchOptions global;
  /// The local stage. Its `speeds` are ignored: the problem's start and end
  /// speeds are used.
  PathOptimizerOptions local;
  /// false: stop after the global stage (no trajectories; status kOk when the
  /// goal is reachable; no feedback rounds).
  bool optimize = true;
  /// Feedback rounds (>= 0): how many times the global search may be re-run
  /// with the stretches where candidates cannot be followed excluded (see
  /// the file comment); 0 = the global stage's candidates as they are.
  std::size_t feedback_rounds = 8;
  /// Radius of each excluded disc [m] (>= 0) when first excluded (it doubles
  /// each round a failure falls inside it again); 0 = two lattice spacings.
  double feedback_radius = 0.0;
  /// Station spacing [m] of the final evaluation of every path (>= 0);
  /// 0 = default_station_spacing(surface, vehicle) (trajectory.hpp), one
  /// tenth of the larger of the cell size and the vehicle's half-track.
  double station_spacing = 0.0;
  /// Certify each candidate's optimum (certify_local_optimum with its
  /// defaults: a quarter-cell box, 0.05 %), keeping the faster path a
  /// certificate finds; CandidateOutcome::certificate reports it. On by
  /// default (issue #36): on optimiser-quality's 25 battery terrains and 6
  /// DEMs it certified 89 of 93 optima and added 0.15 s to the battery's
  /// median plan (1.33 -> 1.52 s; Mount St. Helens 2.1 -> 3.9 s), keeping a
  /// faster path on 16 of 31 cases (at most 0.76 % faster).
  bool certify = true;
  /// Called at each PlannerProgress; returning false stops the plan before
  /// its next step (status kStopped, what was done so far kept). A step is
  /// one candidate's optimisation, bounded by local.max_evaluations.
  std::function<bool(const PlannerProgress&)> progress;
  /// When the whole plan gives up (see the file comment): for example
  /// Termination::time_budget(10.0) for a 10 s limit (status kTimeLimit),
  /// Termination::when(flag) for a stop request (status kStopped), or both
  /// with `|`. Armed when plan() starts; global.termination and
  /// local.termination still apply to their own stage (a local time budget
  /// per candidate). A generous limit changes nothing (bit-identical
  /// results). Default: never.
  Termination termination;
  /// Throws InputError naming the field.
  void validate() const;
};

enum class PlannerStatus {
  kOk,           ///< a best trajectory exists (or, with optimize = false, candidates)
  kUnreachable,  ///< the global search found no route from start to goal
  kInfeasible,   ///< candidates exist, but none has a feasible trajectory
  kStopped,      ///< the progress callback or a stop request in the termination said stop
  /// The termination's time budget ran out: the best feasible trajectory
  /// found by then, if any; `message` and not_optimised say what was left.
  kTimeLimit,
};
std::string_view to_string(PlannerStatus status);

/// One candidate through the local stage.
/// Relative excess of a local optimum's travel time at the final stations
/// over its time at the search's stations beyond which the two are said to
/// disagree (step 3 of the file comment). The search spaces its stations
/// equally in the curve parameter, the final evaluation in arc length: on
/// the fractal battery an optimum's two times differ by 0.02-0.2 % where
/// they agree, while an optimum pushed onto the edge of admissibility can
/// lose its profile altogether (seed 14: 13.02 s at the search's stations,
/// none at the final ones).
inline constexpr double kStageDisagreement = 0.005;

struct CandidateOutcome {
  std::size_t candidate = 0;  ///< index into GlobalSearchResult::candidates
  /// The optimiser's result with its diagnostics; empty when it refused the
  /// candidate (its fit leaves the data or has no admissible profile), see
  /// optimizer_message.
  std::optional<OptimizedPath> optimization;
  std::string optimizer_message;  ///< why optimization is empty
  /// The optimiser's initial fit to the candidate, at station_spacing.
  Trajectory initial;
  /// The result: the optimum, or the initial fit where that is faster (or
  /// the optimiser failed), at station_spacing.
  Trajectory trajectory;
  bool kept_initial = false;  ///< trajectory is the initial fit
  /// Index into optimization->attempts of the point trajectory is: the
  /// optimiser's best_attempt unless that one disagreed at station_spacing
  /// (step 3 of the file comment); empty when trajectory is the initial fit
  /// or there is no optimisation.
  std::optional<std::size_t> reported_attempt;
  /// The followability check passed: the optimiser's initial path
  /// (fit_initial_path) has an admissible profile at the search's stations.
  bool followable = false;
  /// The termination stopped this candidate's optimisation (solver_status
  /// "time_limit"), or it had passed before it began (only its initial fit).
  bool time_limited = false;
  double seconds = 0.0;  ///< this candidate's local stage and evaluations [s]
  /// PlannerOptions::certify: the optimum's local-optimality certificate
  /// (certify_local_optimum); empty without one or without an optimum.
  std::optional<LocalCertificate> certificate;
  /// The certificate found a faster path and `trajectory` is it.
  bool certificate_kept = false;
  bool feasible() const { return trajectory.feasible(); }
};

/// Wall-clock time of each stage [s].
struct PlannerTimings {
  double global = 0.0;      ///< global_search
  double local = 0.0;       ///< optimize_path, all candidates
  double evaluation = 0.0;  ///< the re-evaluations at station_spacing
  double total = 0.0;
};

struct PlannerResult {
  PlannerStatus status = PlannerStatus::kUnreachable;
  /// The problem's surface, which every trajectory below refers to: the
  /// result (and each trajectory's path, even copied out of it) keeps it alive.
  std::shared_ptr<const BPatch> surface;
  std::string message;  ///< why, when not kOk; empty otherwise
  /// The global search whose candidates were optimised (after feedback
  /// rounds, the kept round's); its edges_evaluated counts the edge costs
  /// computed by every search of the plan (the rounds share them).
  GlobalSearchResult global;
  std::vector<CandidateOutcome> candidates;   ///< in the global search's order
  std::optional<std::size_t> best_candidate;  ///< the fastest feasible one
  PlannerTimings seconds;
  /// Status kTimeLimit: global candidates the local stage never reached.
  std::vector<std::size_t> not_optimised;
  /// Global searches re-run because some candidate could not be followed
  /// (0 when every first candidate was followable or feedback_rounds = 0).
  std::size_t feedback_rounds = 0;
  /// The regions the kept global search excluded (its options' `excluded`).
  std::vector<ExcludedRegion> excluded;

  /// The best trajectory; null without one.
  const Trajectory* best() const;
  /// Its travel time [s]; +inf without one.
  double travel_time() const;
  /// The fastest initial fit's travel time [s] (the global stage's answer at
  /// the same stations); +inf without one.
  double global_travel_time() const;
  /// 100 (global − best) / global; NaN unless both are finite.
  double improvement_percent() const;
  /// A few lines: status, best time against the global candidates', each
  /// candidate's outcome and solver, stage timings.
  std::string brief_report() const;
};

/// Plans `problem` with `options` (both validated first: InputError).
/// Invalid input also includes a start or goal on NODATA or untraversable
/// ground (from global_search).
PlannerResult plan(const PlanningProblem& problem, const PlannerOptions& options);

}  // namespace talus
