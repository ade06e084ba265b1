#pragma once
/// @file
/// The local stage of the Shiller–Gwo planner: the control points of a
/// clamped cubic B-spline path, start and goal fixed, optimised for the
/// travel time of its exact time-optimal velocity profile
/// (PathTimeObjective), starting from a global candidate.
///
/// Solvers (PathOptimizerOptions::solver):
/// - ipopt: Ipopt 3.11 interior point, exact gradient (adjoint), L-BFGS
///   Hessian approximation; the primary solver.
/// - nlopt-lbfgs: NLopt's LD_LBFGS, exact gradient.
/// - nlopt-bobyqa: NLopt's LN_BOBYQA, derivative-free trust region.
/// The variables are bounded by the terrain's domain, which keeps the whole
/// path on the map (a B-spline lies in the convex hull of its control
/// points); paths over NODATA or without an admissible profile are
/// infeasible points the solvers step back from.
///
/// Formulations (PathOptimizerOptions::formulation):
/// - nested (default): T(control points), the exact profile solved inside
///   every evaluation, with the solver above. T is only piecewise smooth (it
///   kinks where a switching point crosses a station), so gradient solvers
///   stall on rough terrain; PathOptimizerOptions::polish then takes the
///   solver's point to one where Ipopt's own convergence test holds.
/// - simultaneous: direct transcription (as in minimum-lap-time planning,
///   Christ et al. 2019): a smooth NLP in the same control points and the
///   squared speed ṡ² at every search station, travel time as objective and
///   the vehicle's admissible set (friction cone and every ForceCondition of
///   AdmissibleSet: contact, tip-over, drive, brake; max speed as a bound) at
///   both ends of every step as smooth inequalities, exact sparse Jacobian,
///   finite-difference (or limited-memory) Hessian, Ipopt (MUMPS) with its
///   restoration phase, so the initial fit need not have an admissible
///   profile (it must stay on the data). The variables are the B-spline's
///   control points rather than a lateral offset from the candidate's centre
///   line: the same paths as the nested formulation (so the two compare on
///   one search space and the result is a Curve2 that evaluate_trajectory
///   takes as it is), exact geometry derivatives through the B-spline basis,
///   and no offset coordinate that folds where a winding candidate's
///   curvature radius is smaller than the offset. Two phases: each control
///   point moving along its own lateral direction first (robust from far),
///   then every coordinate free from there (the simultaneous_* options).
///   `solver` is ignored (always Ipopt). The result is re-evaluated with the
///   exact profile
///   solver at the search stations: travel_time is that, never the NLP's own
///   objective (nlp_travel_time, a diagnostic).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/core/termination.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus {

enum class PathSolver { kIpopt, kNloptLbfgs, kNloptBobyqa };
/// "ipopt", "nlopt-lbfgs", "nlopt-bobyqa".
std::string_view to_string(PathSolver solver);
/// Inverse of to_string; throws InputError listing the choices.
PathSolver parse_path_solver(std::string_view name);

enum class PathFormulation { kNested, kSimultaneous };
/// "nested", "simultaneous".
std::string_view to_string(PathFormulation formulation);
/// Inverse of to_string; throws InputError listing the choices.
PathFormulation parse_path_formulation(std::string_view name);

struct PathOptimizerOptions {
  PathFormulation formulation = PathFormulation::kNested;
  /// Of the nested formulation. With a steering limit (Vehicle::max_steering)
  /// Ipopt keeps it as smooth constraints (PathTimeObjective::curvature_samples(),
  /// as the simultaneous formulation does); NLopt's L-BFGS and BOBYQA take no
  /// constraints and see it only as an infeasible (+inf) travel time.
  PathSolver solver = PathSolver::kIpopt;
  /// Of the clamped cubic path (>= 4). 16 with two restarts (below): in
  /// `talus experiment optimiser-quality` (25 fractal seeds) that plan is
  /// within 1 % of the multistart reference on 18 seeds, against 12 for the
  /// former default, an 8-point fit with a further start at 16 (median
  /// excess 0.29 % against 1.07 %, worst 5.3 % against 5.7 %), at a median
  /// plan time of 1.3 s against 0.9 s; on the README's Mount St. Helens plan it
  /// was 3 % faster (1075 s against 1109 s) and took less time. Winding
  /// candidates get more (adaptive_control_points).
  std::size_t control_points = 16;
  /// Grow M by half (up to max_control_points) while the fit to the
  /// candidate has no admissible profile: winding candidates need more (a fit
  /// that turns tighter than the vehicle steers gets fewer: fit_initial_path).
  /// Simultaneous formulation: only while the fit leaves the measured data
  /// (it starts from a fit without an admissible profile).
  bool adaptive_control_points = true;
  /// The growth limit (>= control_points), raised for long candidates to
  /// half their vertex count (at most kMaxCorridorControlPoints), so that a
  /// fit to a long winding corridor can follow it (see
  /// control_point_limit()).
  std::size_t max_control_points = 48;
  /// Profile stations during the search [m] (>= 0); 0 = kSearchSpacingFactor
  /// (5) times default_station_spacing(terrain, vehicle): 0.5 m at 1 m cells.
  double station_spacing = 0.0;
  /// At most this many stations during the search (>= 8): long paths get a
  /// coarser search spacing; callers re-evaluate the result at their own.
  std::size_t max_search_stations = 3000;
  std::size_t max_iterations = 40;  ///< Ipopt iterations (>= 1)
  /// Objective evaluations, all solvers (>= 10). 150: on the bench_plan case
  /// 400 gained 0.05 % of travel time at 2.3x the local-stage time.
  std::size_t max_evaluations = 150;
  double relative_tolerance = 1e-5;  ///< stop when the travel time changes less than this
  /// Simultaneous formulation, phase 1: Ipopt iterations (>= 1) with each
  /// interior control point moving only along its lateral direction (normal
  /// to its neighbours' chord in the initial control polygon). Without
  /// tangential freedom this phase converges from far (on the tests' smooth
  /// hill in 28 iterations, where all coordinates free from the fit took
  /// over 1000), but its optimum is restricted (3.5 % slower there).
  std::size_t simultaneous_lateral_iterations = 300;
  /// Simultaneous formulation, phase 2: Ipopt iterations (>= 1) with every
  /// coordinate free (the nested formulation's search space), from phase 1's
  /// point and speeds. The evaluation budget max_evaluations does not apply
  /// (no profile is solved inside either phase).
  std::size_t simultaneous_max_iterations = 300;
  /// Simultaneous formulation: Ipopt's tol on the scaled KKT error (> 0);
  /// 100 times it is the acceptable level.
  double simultaneous_tolerance = 1e-6;
  /// Simultaneous formulation: Ipopt's limited-memory quasi-Newton Hessian
  /// instead of the default, forward differences of the Lagrangian's exact
  /// gradient (one probe per group of coordinates that share no Hessian row,
  /// about nine for lateral offsets, and three for all the speeds).
  /// With L-BFGS phase 2 stalled on the tests' flat plane and smooth hill
  /// (1000 iterations without convergence).
  bool simultaneous_limited_memory = false;
  /// When to give up (core/termination.hpp), armed when optimize_path
  /// starts (a time budget counts from there; the planner passes its own,
  /// armed, termination). Polled at every Ipopt iteration (both
  /// formulations) and every NLopt evaluation: once it holds the solver stops
  /// there with the best path evaluated so far (at least the initial fit) and
  /// solver_status "time_limit". The initial fit itself is not interrupted.
  /// Default: never.
  Termination termination;
  /// Restarts (>= 0) after a solve that ends without converging (on an
  /// iteration or evaluation cap, or a solver error), within the termination:
  /// the first from the best point so far with fresh solver state (Ipopt's
  /// barrier parameter and quasi-Newton memory, NLopt's trust region), each
  /// further one from that point with every interior control point moved
  /// along its lateral direction by a normal deviate of
  /// restart_perturbation (seeded by `seed`; a draw without an admissible
  /// profile is drawn again at half the size, up to four times). Restarting
  /// stops at the first attempt that converges. The best point over every
  /// attempt is the result; OptimizedPath::attempts lists them. 2 by default
  /// (see control_points): the nested objective's kinks stop Ipopt on a cap
  /// at a point from which a fresh start, and a perturbed one, often go on.
  std::size_t restarts = 2;
  /// Standard deviation of the restarts' lateral moves [m] (>= 0); 0 = two
  /// cells of the terrain.
  double restart_perturbation = 0.0;
  std::uint64_t seed = 1;  ///< of the restarts' perturbations
  /// Nested formulation: polish the solver's best point (after any
  /// restarts) with the simultaneous NLP in lateral offsets of its control
  /// points, warm-started there with the exact profile at the NLP's
  /// stations (so it starts feasible for its own discretisation). The nested
  /// objective kinks wherever a switching point crosses a station, so its
  /// solvers stop on a cap near an optimum without ever meeting a
  /// first-order test; the smooth NLP converges from there by Ipopt's own
  /// status. Its point replaces the nested one when its exact travel time is
  /// lower, or when Ipopt converged and it is at most polish_tolerance
  /// slower (and never slower than the initial fit); otherwise the nested
  /// point stays, with its status. OptimizedPath::attempts lists the polish
  /// (start "polish"). Ignored by the simultaneous formulation. Off by
  /// default for its cost: on the fractal battery (8-point fits only) it
  /// converged on 49 of 75 candidates (none converge without it; 55 at 300
  /// iterations, where the rest still stall with the limits binding on rough
  /// ground: the bicubic surface's curvature has a gradient that jumps at
  /// every knot line; on the biquintic BPatch::interpolate(grid, 5) 67 of 74
  /// converge) for 0.3-2.1 s per candidate (median 0.7 s), which tripled the
  /// median planning time (1.1 to 3.2 s, two plans sharing two cores); on the
  /// README's Mount St. Helens plan (1400 NLP stations) it took 26 s for no gain.
  bool polish = false;
  /// The polish NLP's stations: the search's stations / this (>= 1), at
  /// least 16. 4: on the fractal battery (0.024 m search spacing) the NLP
  /// then has 400-480 stations and converges in 30-90 iterations;
  /// at 8 it took more iterations and its optima were 0.4-1.1 % slower at
  /// the search stations, at 2 the iterations cost twice as much.
  std::size_t polish_station_factor = 4;
  std::size_t polish_max_iterations = 100;  ///< Ipopt iterations of the polish (>= 1)
  /// Relative travel-time loss (>= 0) accepted from a converged polish: its
  /// optimum at the NLP's coarser stations can be slightly slower at the
  /// search stations than the nested point (0.05-0.6 % on the battery).
  double polish_tolerance = 0.01;
  /// Further starts (each >= 4): the whole local stage (fit, solver,
  /// restarts, polish) again from a fit with each of these control-point
  /// counts; the fastest result is returned and OptimizedPath::attempts lists
  /// every start's solves (LocalAttempt::control_points). A count whose fit
  /// leaves the data or has no admissible profile is skipped. None by
  /// default: against optimiser-quality's reference, a start at 24 after the
  /// default's (16, two restarts each) was within 1 % on 22 seeds instead of
  /// 17 but took 2.5 s per plan instead of 1.3 s; one at 8 before it, 18
  /// seeds in 2.5 s.
  std::vector<std::size_t> more_control_points = {};
  ProfileOptions speeds;  ///< start and end speeds
  /// The path's heading at its start and at its goal [rad], counter-clockwise
  /// from east (the direction of travel in the plane); empty = free. A given
  /// heading pins the second (next-to-last) control point on the ray from
  /// the start (to the goal) along it, at the initial fit's own distance
  /// (at least a cell): the clamped cubic's end tangent is along P_1 − P_0,
  /// so the heading holds exactly at every iterate of every solver; the
  /// distance itself is not optimised. With both headings a fit has at least
  /// 5 control points (one free).
  std::optional<double> start_heading;
  std::optional<double> goal_heading;
  /// Throws InputError naming the field.
  void validate() const;
};

/// One solve of optimize_path(): the first from the initial fit, then the
/// restarts (PathOptimizerOptions::restarts).
struct LocalAttempt {
  /// "fit" (the initial fit), "resume" (the best point so far, fresh solver
  /// state), "perturbed" (the best point so far moved laterally) or
  /// "polish" (the simultaneous NLP from the best point,
  /// PathOptimizerOptions::polish).
  std::string start;
  std::string solver_status;  ///< the solver's return code as text
  bool converged = false;     ///< by the solver's own status (OptimizedPath::converged)
  /// The exact travel time at the search stations of this attempt's best
  /// point [s]; +inf when it evaluated none with an admissible profile.
  double travel_time = std::numeric_limits<double>::infinity();
  std::size_t iterations = 0;  ///< Ipopt iterations; NLopt: objective evaluations
  double seconds = 0.0;        ///< wall time of this attempt
  /// M of the fit this attempt started from (more_control_points).
  std::size_t control_points = 0;
  /// This attempt's best point; empty when it evaluated none with an
  /// admissible profile. The planner re-evaluates these at its own stations
  /// when the returned point disagrees there (planner.hpp).
  std::optional<Curve2> curve = std::nullopt;
};

/// A locally optimised path with the solver's diagnostics.
/// The search's default spacing in units of default_station_spacing().
inline constexpr double kSearchSpacingFactor = 5.0;
/// `options.station_spacing` when > 0, else kSearchSpacingFactor ×
/// default_station_spacing(terrain, vehicle) [m].
double search_station_spacing(const PathOptimizerOptions& options, const BPatch& terrain,
                              const Vehicle& vehicle);

struct OptimizedPath {
  explicit OptimizedPath(Curve2 path) : curve(path), initial_curve(std::move(path)) {}
  Curve2 curve;                    ///< the best path found (never slower than the initial one)
  Curve2 initial_curve;            ///< the initial fit to the candidate
  std::size_t control_points = 0;  ///< M used (more than asked when the fit needed them)
  double travel_time = 0.0;        ///< its travel time at the search's station spacing [s]
  double initial_time = 0.0;       ///< the initial path's travel time, same stations [s]
  std::string formulation;         ///< to_string(PathFormulation)
  std::string solver;              ///< to_string(PathSolver); "ipopt" when simultaneous
  /// The solver's return code as text (Ipopt / NLopt names), of the attempt
  /// whose point is returned.
  std::string solver_status;
  /// Ipopt's Solve_Succeeded ("success") or Solved_To_Acceptable_Level
  /// ("stop_at_acceptable_point"); NLopt: a tolerance stop (not a limit); of
  /// the attempt whose point is returned.
  bool converged = false;
  /// Every solve in order (the first from the initial fit, then restarts).
  std::vector<LocalAttempt> attempts;
  /// Index into attempts of the one whose point is returned.
  std::size_t best_attempt = 0;
  /// Simultaneous formulation, or a nested one whose polish point was
  /// returned: the NLP's own travel time at its final iterate [s] (a
  /// diagnostic; travel_time is the exact re-evaluation). NaN otherwise.
  double nlp_travel_time = std::numeric_limits<double>::quiet_NaN();
  /// Simultaneous formulation: the phase whose point is returned (1 lateral
  /// offsets, 2 every coordinate; 2 unless its exact time is worse), and
  /// solver_status / converged are that phase's; iterations and evaluations
  /// count both. 0 for the nested formulation.
  int phase = 0;
  bool solver_failed = false;   ///< an error return; the best point seen is still reported
  std::size_t iterations = 0;   ///< Ipopt iterations; NLopt: objective evaluations (all attempts)
  std::size_t evaluations = 0;  ///< objective evaluations (all attempts)
  std::size_t gradient_evaluations = 0;
  std::size_t finite_difference_fallbacks = 0;  ///< gradients taken by finite differences
  /// First-order optimality at the returned path: the largest component of
  /// the projected gradient (zero where a bound is active and the gradient
  /// pushes into it) [s/m]; NaN if the gradient there is unavailable.
  double optimality = 0.0;
  std::size_t stations = 0;  ///< profile stations used during the search
  double seconds = 0.0;      ///< wall time of this optimisation
};

/// The most control points a long candidate's fit may grow to.
inline constexpr std::size_t kMaxCorridorControlPoints = 256;

/// How far the initial fit to a polyline of `vertices` vertices may grow:
/// max(options.max_control_points, min(vertices / 2, kMaxCorridorControlPoints)).
/// One control point per two lattice edges rounds the candidate's corners
/// over about two cells (a fit with as many control points as vertices would
/// reproduce the lattice's kinks, with their unbounded curvature) while
/// keeping it in the corridor.
std::size_t control_point_limit(const PathOptimizerOptions& options, std::size_t vertices);

/// The clamped cubic least-squares fit with `control_points` (>= 4) to
/// `polyline` resampled at 10 points per control point, ends exact, with the
/// end headings of `options` pinned (PathOptimizerOptions::start_heading).
Curve2 fit_candidate(const BPatch& terrain, const std::vector<Vec2>& polyline,
                     std::size_t control_points, const PathOptimizerOptions& options);

/// The optimiser's initial path for a candidate polyline: the clamped cubic
/// least-squares fit (to the polyline resampled at 10 points per control
/// point, ends exact, end headings pinned when given) with
/// options.control_points, grown by half up to
/// control_point_limit() (when adaptive_control_points) while its profile
/// at the search's stations is not admissible; once a fit fails on the
/// vehicle's steering limit (Constraint::kSteering), shrunk by a third (down
/// to 4, or 5 with both headings) instead, while it still fails: a fit that turns too tightly
/// follows the lattice's kinks, and more control points follow them closer.
struct InitialPath {
  std::optional<Curve2> curve;     ///< the last fit tried; empty if none was lifted
  std::size_t control_points = 0;  ///< its M
  std::size_t stations = 0;        ///< search stations (fixed from its length)
  double travel_time = std::numeric_limits<double>::infinity();  ///< [s]; +inf: not admissible
  bool on_data = false;  ///< every station lies on the measured data
  std::string failure;   ///< why the last fit has no admissible profile
  /// Where the last fit's profile fails (its failing station) [m]; empty when
  /// admissible or when the fit could not be lifted.
  std::optional<Vec2> failure_point;
  bool admissible() const { return std::isfinite(travel_time); }
};

/// The initial path of optimize_path(); growth stops early at the first fit
/// on the data when `stop_on_data` (the simultaneous formulation starts from
/// a fit without an admissible profile). Throws InputError for invalid
/// options or a polyline of fewer than 2 vertices.
InitialPath fit_initial_path(const BPatch& terrain, const Vehicle& vehicle,
                             const std::vector<Vec2>& polyline, const PathOptimizerOptions& options,
                             bool stop_on_data = false);

/// Fits the initial path to `initial_polyline` (fit_clamped_cubic to the
/// polyline resampled at 10 points per control point, ends exact) and
/// minimises its travel time with the chosen formulation and solver. Throws
/// InputError if the initial path is off the data or (nested) has no
/// admissible profile, or (simultaneous) neither it nor the NLP's result has
/// one; a solver failure is reported in the result (status, best point), not
/// thrown. `fit`, when given, is fit_initial_path(terrain, vehicle,
/// initial_polyline, options, simultaneous formulation) already computed by
/// the caller (the planner's followability check): it is not computed again.
OptimizedPath optimize_path(const BPatch& terrain, const Vehicle& vehicle,
                            const std::vector<Vec2>& initial_polyline,
                            const PathOptimizerOptions& options,
                            const std::optional<InitialPath>& fit = std::nullopt);

/// Options of certify_local_optimum().
struct LocalCertificateOptions {
  /// Half-width [m] of the box round every free control point that the
  /// search explores; 0 = a quarter of the terrain's cell size.
  double radius = 0.0;
  /// A relative improvement at most this (0.05 %) certifies the optimum.
  double tolerance = 5e-4;
  /// Travel-time evaluations each round may spend; 0 = 10 (n + 1) for n
  /// free coordinates.
  std::size_t max_evaluations = 0;
  /// Rounds (>= 1): a round that improves by more than the tolerance moves
  /// the box to its best point and searches again.
  std::size_t rounds = 3;
  /// Throws InputError naming the field.
  void validate() const;
};

/// Whether a local optimum is one, kinks or not (issue #36): the travel time
/// is piecewise smooth (it kinks where a switching point appears), so a
/// solver's status cannot certify it. From the optimum a derivative-free
/// trust-region search (NLopt BOBYQA, initial radius half the box) explores
/// the box of half-width `radius` round every free control point at the
/// optimum's own stations; finding nothing faster by more than `tolerance`
/// certifies a local minimum of the travel time to that tolerance within
/// that radius. A faster point it finds is returned: it is a better path,
/// and the search is repeated round it (up to `rounds`); the certificate is
/// the last round's.
struct LocalCertificate {
  bool certified = false;
  std::size_t rounds = 0;    ///< searches run
  double radius = 0.0;       ///< [m] the box's half-width used
  double tolerance = 0.0;    ///< the relative tolerance used
  double travel_time = 0.0;  ///< the optimum's, at its search stations [s]
  double best_time = 0.0;    ///< the fastest found within the box, same stations [s]
  /// (travel_time - best_time) / travel_time >= 0, over every round.
  double improvement = 0.0;
  std::size_t evaluations = 0;
  std::string solver_status;     ///< BOBYQA's return code as text
  std::optional<Curve2> better;  ///< the faster path, when improvement > 0
  double seconds = 0.0;
};

/// Certifies `optimum` (a result of optimize_path with `options`, whose
/// speeds and headings it keeps). An optimum without an admissible profile
/// at its stations is not certified (solver_status "infeasible").
LocalCertificate certify_local_optimum(const BPatch& terrain, const Vehicle& vehicle,
                                       const OptimizedPath& optimum,
                                       const PathOptimizerOptions& options,
                                       const LocalCertificateOptions& certificate = {});

}  // namespace talus
