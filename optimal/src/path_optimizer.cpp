#include "talus/optimal/path_optimizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "local_solvers.hpp"
#include "simultaneous_path_solver.hpp"
#include "talus/bspline/curve_fit.hpp"
#include "talus/core/error.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/optimal/path_time_objective.hpp"
#include "talus/optimal/trajectory.hpp"

namespace talus {
namespace {

/// Largest |projected gradient| component over the box [lower, upper].
double projected_gradient_norm(const Eigen::VectorXd& z, const Eigen::VectorXd& gradient,
                               const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  double worst = 0.0;
  for (long i = 0; i < z.size(); ++i) {
    const double tolerance = 1e-9 * (1.0 + std::abs(z[i]));
    const double g = gradient[i];
    if (z[i] <= lower[i] + tolerance && g > 0.0) continue;  // bound holds the descent
    if (z[i] >= upper[i] - tolerance && g < 0.0) continue;
    worst = std::max(worst, std::abs(g));
  }
  return worst;
}

/// Every station of `curve` (N equally spaced in σ) lies on the measured data.
bool stays_on_data(const BPatch& terrain, const Curve2& curve, std::size_t stations) {
  for (std::size_t k = 0; k < stations; ++k) {
    const double sigma =
        (k + 1 == stations) ? 1.0 : static_cast<double>(k) / static_cast<double>(stations - 1);
    const Vec2 p = curve.evaluate(sigma);
    if (!terrain.contains(p) || !terrain.on_data(p)) return false;
  }
  return true;
}

/// "(x, y)" to the centimetre.
std::string point_text(const Vec2& p) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << "(" << p.x() << ", " << p.y() << ")";
  return text.str();
}

/// The solver's own statement that it converged (not a stop on a limit).
bool converged_status(const std::string& status) {
  return status == "success" || status == "stop_at_acceptable_point" || status == "ftol_reached" ||
         status == "xtol_reached";
}

/// `z` (the interior control points, x and y interleaved, between the fixed
/// `first` and `last`) with each point moved along its lateral direction
/// (normal to its neighbours' chord) by a normal deviate of `sigma`, clamped
/// into the box.
Eigen::VectorXd perturbed_laterally(const Eigen::VectorXd& z, const Vec2& first, const Vec2& last,
                                    double sigma, const detail::BoxProblem& box,
                                    std::mt19937_64& random) {
  std::normal_distribution<double> deviate(0.0, sigma);
  const long points = z.size() / 2;
  const auto point = [&](long i) {  // i in [-1, points]: the fixed ends outside z
    if (i < 0) return first;
    if (i >= points) return last;
    return Vec2(z[2 * i], z[2 * i + 1]);
  };
  Eigen::VectorXd out = z;
  for (long i = 0; i < points; ++i) {
    const Vec2 chord = point(i + 1) - point(i - 1);
    const double length = chord.norm();
    if (!(length > 0.0)) continue;
    const Vec2 normal(-chord.y() / length, chord.x() / length);
    const double offset = deviate(random);
    out[2 * i] += offset * normal.x();
    out[2 * i + 1] += offset * normal.y();
  }
  return out.cwiseMax(box.lower).cwiseMin(box.upper);
}

/// The start of restart `restart` (1-based) from `best`: `best` itself for
/// the first ("resume"), else a lateral perturbation of it with an
/// admissible profile (up to four draws, halving the deviation each time);
/// empty if no draw was admissible.
std::optional<Eigen::VectorXd> restart_point(std::size_t restart, const Eigen::VectorXd& best,
                                             PathTimeObjective& objective, const Vec2& first,
                                             const Vec2& last, double sigma,
                                             const detail::BoxProblem& box,
                                             std::mt19937_64& random) {
  if (restart == 1) return best;
  for (int draw = 0; draw < 4; ++draw, sigma *= 0.5) {
    Eigen::VectorXd z = perturbed_laterally(best, first, last, sigma, box, random);
    if (std::isfinite(objective.evaluate(z))) return z;
  }
  return std::nullopt;
}

/// The simultaneous NLP's fields shared by the polish and the simultaneous
/// formulation: `curve` with `stations` stations, within the box.
detail::SimultaneousProblem simultaneous_problem(const BPatch& terrain, const Vehicle& vehicle,
                                                 const Curve2& curve, std::size_t stations,
                                                 const detail::BoxProblem& box,
                                                 const PathOptimizerOptions& options) {
  detail::SimultaneousProblem nlp;
  nlp.terrain = &terrain;
  nlp.vehicle = vehicle;
  nlp.initial = &curve;
  nlp.stations = stations;
  nlp.speeds = options.speeds;
  nlp.lower = box.lower;
  nlp.upper = box.upper;
  nlp.tolerance = options.simultaneous_tolerance;
  nlp.termination = box.termination;
  return nlp;
}

/// The outcome of polishing a nested optimum (PathOptimizerOptions::polish).
struct Polish {
  detail::SimultaneousRun run;
  /// The exact travel time of the NLP's final path at the search stations
  /// [s]; +inf without one or without an admissible profile.
  double travel_time = std::numeric_limits<double>::infinity();
};

/// The simultaneous NLP in lateral offsets from `from`, warm-started with
/// the exact profile of `from` at the NLP's own stations;
/// `objective` (the search stations) re-evaluates its result.
Polish polish_nested_optimum(const BPatch& terrain, const Vehicle& vehicle,
                             PathTimeObjective& objective, const Eigen::VectorXd& from,
                             const detail::BoxProblem& box, std::size_t control_points,
                             std::size_t stations, const Vec2& first, const Vec2& last,
                             const PathOptimizerOptions& options) {
  const std::size_t nlp_stations =
      std::max<std::size_t>(16, (stations - 1) / options.polish_station_factor + 1);
  const Curve2 curve = objective.curve(from);
  detail::SimultaneousProblem nlp =
      simultaneous_problem(terrain, vehicle, curve, nlp_stations, box, options);
  nlp.lateral_offsets = true;
  nlp.warm_start = true;
  nlp.max_iterations = options.polish_max_iterations;
  // The profile solver's discrete model is the NLP's constraint set, so its
  // profile at the NLP's stations is a feasible start.
  PathTimeObjective coarse(terrain, vehicle, first, last, control_points, nlp_stations,
                           options.speeds);
  if (std::isfinite(coarse.evaluate(from))) {
    for (double v : coarse.profile().v) nlp.initial_squared_speeds.push_back(v * v);
  }
  Polish out;
  out.run = detail::run_simultaneous(nlp);
  if (out.run.variables.size() == from.size() && out.run.variables.allFinite())
    out.travel_time = objective.evaluate(out.run.variables);
  return out;
}

/// The simultaneous formulation from the box problem's start (the initial
/// fit); `objective` (the nested one, same stations)
/// re-evaluates the initial fit and the NLP's result exactly.
OptimizedPath optimize_simultaneous(const BPatch& terrain, const Vehicle& vehicle,
                                    PathTimeObjective& objective, const detail::BoxProblem& box,
                                    std::size_t control_points, std::size_t stations,
                                    const PathOptimizerOptions& options,
                                    std::chrono::steady_clock::time_point started) {
  const Curve2 initial_curve = objective.curve(box.start);
  detail::SimultaneousProblem nlp =
      simultaneous_problem(terrain, vehicle, initial_curve, stations, box, options);
  nlp.limited_memory_hessian = options.simultaneous_limited_memory;
  // Warm start from the initial fit's exact profile when it has one.
  const double initial_time = objective.evaluate(box.start);
  if (std::isfinite(initial_time)) {
    for (double v : objective.profile().v) nlp.initial_squared_speeds.push_back(v * v);
  }
  // Phase 1: lateral offsets of the control points (no tangential freedom:
  // it converges from far, through restoration when the fit is infeasible).
  nlp.lateral_offsets = true;
  nlp.max_iterations = options.simultaneous_lateral_iterations;
  const auto usable = [&](const detail::SimultaneousRun& r) {
    return r.variables.size() == box.start.size() && r.variables.allFinite();
  };
  detail::SimultaneousRun run = detail::run_simultaneous(nlp);
  std::size_t iterations = run.iterations, evaluations = run.evaluations,
              gradient_evaluations = run.gradient_evaluations;
  // Phase 2: every coordinate free (the nested formulation's search space)
  // from phase 1's point and speeds.
  std::optional<Curve2> lateral_curve;
  int phase = 1;
  if (usable(run) && !box.termination.should_stop()) {
    const double lateral_time = objective.evaluate(run.variables);
    lateral_curve.emplace(objective.curve(run.variables));
    nlp.initial = &*lateral_curve;
    nlp.initial_squared_speeds = run.squared_speeds;
    nlp.lateral_offsets = false;
    nlp.max_iterations = options.simultaneous_max_iterations;
    detail::SimultaneousRun free = detail::run_simultaneous(nlp);
    iterations += free.iterations;
    evaluations += free.evaluations;
    gradient_evaluations += free.gradient_evaluations;
    const double free_time =
        usable(free) ? objective.evaluate(free.variables) : std::numeric_limits<double>::infinity();
    // Keep phase 1's point only where phase 2 made it worse.
    if (std::isfinite(free_time) || !std::isfinite(lateral_time)) {
      if (!(free_time > lateral_time) || !std::isfinite(lateral_time)) {
        run = std::move(free);
        phase = 2;
      }
    }
  }
  // The exact profile of the NLP's path at the same stations.
  double result_time = std::numeric_limits<double>::infinity();
  if (run.variables.size() == box.start.size() && run.variables.allFinite()) {
    result_time = objective.evaluate(run.variables);
  }
  Eigen::VectorXd best;
  double best_time = std::numeric_limits<double>::infinity();
  if (std::isfinite(result_time) && !(result_time > initial_time)) {
    best = run.variables;
    best_time = result_time;
  } else if (std::isfinite(initial_time)) {
    best = box.start;
    best_time = initial_time;
  } else {
    throw InputError("the simultaneous stage (Ipopt: " + run.status +
                     ") found no path with an admissible profile from an initial fit (" +
                     std::to_string(control_points) + " control points) without one");
  }
  OptimizedPath out(objective.curve(best));
  out.initial_curve = initial_curve;
  out.control_points = control_points;
  out.travel_time = best_time;
  out.initial_time = initial_time;
  out.formulation = to_string(PathFormulation::kSimultaneous);
  out.solver = to_string(PathSolver::kIpopt);
  out.solver_status = run.status;
  out.solver_failed = run.failed;
  out.converged = run.converged;
  out.nlp_travel_time = run.nlp_time;
  out.phase = phase;
  out.iterations = iterations;
  out.evaluations = evaluations;
  out.gradient_evaluations = gradient_evaluations;
  out.stations = stations;
  Eigen::VectorXd gradient;
  const double check = objective.evaluate(best, &gradient);
  out.optimality = std::isfinite(check)
                       ? projected_gradient_norm(best, gradient, box.lower, box.upper)
                       : std::numeric_limits<double>::quiet_NaN();
  out.finite_difference_fallbacks = objective.finite_difference_fallbacks();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace

std::string_view to_string(PathFormulation formulation) {
  switch (formulation) {
    case PathFormulation::kNested:
      return "nested";
    case PathFormulation::kSimultaneous:
      return "simultaneous";
  }
  return "unknown";
}

PathFormulation parse_path_formulation(std::string_view name) {
  for (PathFormulation f : {PathFormulation::kNested, PathFormulation::kSimultaneous}) {
    if (name == to_string(f)) return f;
  }
  throw InputError("unknown formulation '" + std::string(name) +
                   "': choose nested or simultaneous");
}

std::string_view to_string(PathSolver solver) {
  switch (solver) {
    case PathSolver::kIpopt:
      return "ipopt";
    case PathSolver::kNloptLbfgs:
      return "nlopt-lbfgs";
    case PathSolver::kNloptBobyqa:
      return "nlopt-bobyqa";
  }
  return "unknown";
}

PathSolver parse_path_solver(std::string_view name) {
  for (PathSolver s : {PathSolver::kIpopt, PathSolver::kNloptLbfgs, PathSolver::kNloptBobyqa}) {
    if (name == to_string(s)) return s;
  }
  throw InputError("unknown solver '" + std::string(name) +
                   "': choose ipopt, nlopt-lbfgs or nlopt-bobyqa");
}

double search_station_spacing(const PathOptimizerOptions& options, const BPatch& terrain,
                              const Vehicle& vehicle) {
  return options.station_spacing > 0.0
             ? options.station_spacing
             : kSearchSpacingFactor * default_station_spacing(terrain, vehicle);
}

void PathOptimizerOptions::validate() const {
  if (control_points < 4) throw InputError("PathOptimizerOptions.control_points must be >= 4");
  require_station_spacing(station_spacing, "PathOptimizerOptions.station_spacing");
  if (max_control_points < control_points)
    throw InputError("PathOptimizerOptions.max_control_points must be >= control_points");
  if (max_search_stations < 8)
    throw InputError("PathOptimizerOptions.max_search_stations must be >= 8");
  if (max_iterations < 1) throw InputError("PathOptimizerOptions.max_iterations must be >= 1");
  if (max_evaluations < 10) throw InputError("PathOptimizerOptions.max_evaluations must be >= 10");
  if (!(relative_tolerance > 0.0))
    throw InputError("PathOptimizerOptions.relative_tolerance must be positive");
  if (simultaneous_max_iterations < 1)
    throw InputError("PathOptimizerOptions.simultaneous_max_iterations must be >= 1");
  if (simultaneous_lateral_iterations < 1)
    throw InputError("PathOptimizerOptions.simultaneous_lateral_iterations must be >= 1");
  if (!(simultaneous_tolerance > 0.0) || !std::isfinite(simultaneous_tolerance))
    throw InputError("PathOptimizerOptions.simultaneous_tolerance must be positive");
  for (const std::size_t m : more_control_points)
    if (m < 4) throw InputError("PathOptimizerOptions.more_control_points must each be >= 4");
  if (polish_station_factor < 1)
    throw InputError("PathOptimizerOptions.polish_station_factor must be >= 1");
  if (polish_max_iterations < 1)
    throw InputError("PathOptimizerOptions.polish_max_iterations must be >= 1");
  if (!(polish_tolerance >= 0.0) || !std::isfinite(polish_tolerance))
    throw InputError("PathOptimizerOptions.polish_tolerance must be >= 0");
  if (!(restart_perturbation >= 0.0) || !std::isfinite(restart_perturbation)) {
    throw InputError("PathOptimizerOptions.restart_perturbation must be >= 0 [m] (0 = two cells)");
  }
  speeds.validate();
  for (const auto& [heading, name] :
       {std::pair{start_heading, "start_heading"}, std::pair{goal_heading, "goal_heading"}}) {
    if (heading && !std::isfinite(*heading))
      throw InputError(std::string("PathOptimizerOptions.") + name + " must be finite");
  }
}

std::size_t control_point_limit(const PathOptimizerOptions& options, std::size_t vertices) {
  return std::max(options.max_control_points, std::min(vertices / 2, kMaxCorridorControlPoints));
}

namespace {

/// The fewest control points a fit may have: one free beyond the pinned ones.
std::size_t fewest_control_points(const PathOptimizerOptions& options) {
  return options.start_heading && options.goal_heading ? 5 : 4;
}

/// `points` (a clamped cubic's control points) with the end headings of
/// `options` imposed: P_1 on the ray from P_0 along the start heading, P_{M-2}
/// on the ray into P_{M-1} along the goal heading, each at the fit's own
/// distance from its end (at least `floor`).
std::vector<Vec2> with_end_headings(std::vector<Vec2> points, const PathOptimizerOptions& options,
                                    double floor) {
  const std::size_t m = points.size();
  if (options.start_heading) {
    const Vec2 h(std::cos(*options.start_heading), std::sin(*options.start_heading));
    points[1] = points[0] + std::max(floor, (points[1] - points[0]).norm()) * h;
  }
  if (options.goal_heading) {
    const Vec2 h(std::cos(*options.goal_heading), std::sin(*options.goal_heading));
    points[m - 2] = points[m - 1] - std::max(floor, (points[m - 1] - points[m - 2]).norm()) * h;
  }
  return points;
}

}  // namespace

Curve2 fit_candidate(const BPatch& terrain, const std::vector<Vec2>& polyline,
                     std::size_t control_points, const PathOptimizerOptions& options) {
  const Curve2 fit = fit_clamped_cubic(
      resample_polyline(polyline, std::max<std::size_t>(10 * control_points, polyline.size())),
      control_points);
  return Curve2(fit.knots(), with_end_headings(fit.control_points(), options, terrain.cellsize()));
}

InitialPath fit_initial_path(const BPatch& terrain, const Vehicle& vehicle,
                             const std::vector<Vec2>& polyline, const PathOptimizerOptions& options,
                             bool stop_on_data) {
  options.validate();
  if (polyline.size() < 2) throw InputError("the initial path needs at least 2 vertices");
  const double search_spacing = search_station_spacing(options, terrain, vehicle);
  const std::size_t limit = control_point_limit(options, polyline.size());
  std::size_t control_points = std::max(options.control_points, fewest_control_points(options));
  bool shrinking = false;  // once a fit turned too tightly, only coarser fits are tried
  while (true) {
    InitialPath out;
    Constraint binding = Constraint::kNone;
    out.control_points = control_points;
    out.curve.emplace(fit_candidate(terrain, polyline, control_points, options));
    // The station count is fixed for the whole search, from the initial
    // path's length: the objective must not jump when the length crosses a
    // multiple of the spacing.
    try {
      const double length = SurfacePath(terrain, *out.curve).length();
      out.stations = std::clamp<std::size_t>(static_cast<std::size_t>(length / search_spacing) + 1,
                                             8, options.max_search_stations);
      PathTimeObjective objective(terrain, vehicle, polyline.front(), polyline.back(),
                                  control_points, out.stations, options.speeds);
      out.travel_time = objective.evaluate(objective.variables(out.curve->control_points()));
      out.failure = objective.profile().message;
      out.on_data = stays_on_data(terrain, *out.curve, out.stations);
      if (!out.admissible()) {
        binding = objective.profile().infeasible_binding;
        std::size_t k = std::min(objective.profile().infeasible_station, out.stations - 1);
        // A start or end speed the path cannot connect to (reported at its
        // end) is caused where the vehicle must keep its speed up: the
        // station of the largest lower speed bound.
        const VelocityLimits& limits = objective.limits();
        if ((k == 0 || k + 1 == out.stations) && limits.size() == out.stations) {
          double largest = 0.0;
          for (std::size_t j = 0; j < limits.size(); ++j) {
            if (limits.limits(j).v_min > largest) {
              largest = limits.limits(j).v_min;
              k = j;
            }
          }
        }
        out.failure_point =
            out.curve->evaluate(static_cast<double>(k) / static_cast<double>(out.stations - 1));
        out.failure += " (near " + point_text(*out.failure_point) + ")";
      }
    } catch (const InputError& e) {
      out.travel_time = std::numeric_limits<double>::infinity();
      out.failure = e.what();
    }
    if (out.admissible() || (stop_on_data && out.on_data)) return out;
    if (!options.adaptive_control_points) return out;
    // A fit that turns tighter than the vehicle steers (often where the lattice path
    // leaves the start or meets the goal at a kink) needs fewer control points, not more:
    // more follow the kink more closely.
    if (binding == Constraint::kSteering || shrinking) {
      const std::size_t fewest = fewest_control_points(options);
      if (control_points <= fewest) return out;
      shrinking = true;
      control_points = std::max(fewest, control_points * 2 / 3);
      continue;
    }
    if (control_points >= limit) return out;
    control_points = std::min(limit, control_points + control_points / 2);
  }
}

namespace {

/// The narrowest side of `box` among its free coordinates (+inf when every
/// coordinate is pinned).
double narrowest_free_width(const detail::BoxProblem& box) {
  double narrowest = std::numeric_limits<double>::infinity();
  for (long i = 0; i < box.lower.size(); ++i) {
    const double width = box.upper[i] - box.lower[i];
    if (width > 0.0) narrowest = std::min(narrowest, width);
  }
  return narrowest;
}

/// The solvers' box round the fit's variables `start`: half a cell inside the
/// domain (grown to hold the fit), the heading points pinned, the budgets,
/// the expiry and BOBYQA's initial step.
detail::BoxProblem box_problem(const BPatch& terrain, const Eigen::VectorXd& start,
                               const std::vector<Vec2>& initial_polyline,
                               const PathOptimizerOptions& options) {
  detail::BoxProblem problem;
  problem.start = start;
  const long n = problem.start.size();
  problem.lower.resize(n);
  problem.upper.resize(n);
  // Half a cell inside the domain: every station's B-patch evaluation stays
  // well defined even where the solver sits on a bound.
  const double margin = 0.5 * terrain.cellsize();
  for (long i = 0; i < n; i += 2) {
    problem.lower[i] = terrain.x_min() + margin;
    problem.upper[i] = terrain.x_max() - margin;
    problem.lower[i + 1] = terrain.y_min() + margin;
    problem.upper[i + 1] = terrain.y_max() - margin;
  }
  // A candidate along the map's edge has fit control points outside that
  // margin: the box grows to hold them (the fit's profile was evaluated, so
  // its stations are on the data). Clamping them instead moved the path, and
  // on battery seed 1 with the rigid-body UGV two of three followable
  // candidates lost their admissible profile that way.
  problem.lower = problem.lower.cwiseMin(problem.start);
  problem.upper = problem.upper.cwiseMax(problem.start);
  // A heading pins its control point (the fit put it on the ray): equal
  // bounds, which every solver treats as a fixed variable.
  const auto pin = [&](long i) {
    problem.lower.segment<2>(i) = problem.upper.segment<2>(i) = problem.start.segment<2>(i);
  };
  if (options.start_heading) pin(0);
  if (options.goal_heading) pin(n - 2);
  problem.max_iterations = options.max_iterations;
  problem.max_evaluations = options.max_evaluations;
  problem.relative_tolerance = options.relative_tolerance;
  problem.termination = options.termination;  // armed by optimize_path
  // BOBYQA's trust region must fit in the box twice over (NLopt refuses
  // otherwise): elongated or tiny domains cap it.
  problem.initial_step =
      std::min(std::max(0.1 * (initial_polyline.back() - initial_polyline.front()).norm(),
                        terrain.cellsize()),
               0.45 * narrowest_free_width(problem));
  return problem;
}

/// Where the restarts come from: the path's ends, the perturbation's scale
/// and the seeded generator.
struct RestartSource {
  Vec2 first, last;
  double sigma;
  std::mt19937_64 random;
};

/// The simultaneous formulation: each attempt a whole simultaneous solve (both
/// phases) from its start, the fit's first.
OptimizedPath simultaneous_attempts(const BPatch& terrain, const Vehicle& vehicle,
                                    PathTimeObjective& objective, const detail::BoxProblem& problem,
                                    std::size_t control_points, std::size_t stations,
                                    const PathOptimizerOptions& options,
                                    std::chrono::steady_clock::time_point started,
                                    RestartSource& restarts) {
  OptimizedPath out = optimize_simultaneous(terrain, vehicle, objective, problem, control_points,
                                            stations, options, started);
  out.attempts.push_back(
      {"fit", out.solver_status, out.converged, out.travel_time, out.iterations, out.seconds});
  if (std::isfinite(out.travel_time)) out.attempts.back().curve = out.curve;
  for (std::size_t r = 1; r <= options.restarts && !out.attempts.back().converged; ++r) {
    if (problem.termination.should_stop()) break;
    detail::BoxProblem restart = problem;
    const auto point =
        restart_point(r, objective.variables(out.curve.control_points()), objective, restarts.first,
                      restarts.last, restarts.sigma, problem, restarts.random);
    if (!point) break;
    restart.start = *point;
    const auto attempt_started = std::chrono::steady_clock::now();
    OptimizedPath next = optimize_simultaneous(terrain, vehicle, objective, restart, control_points,
                                               stations, options, started);
    out.attempts.push_back({r == 1 ? "resume" : "perturbed", next.solver_status, next.converged,
                            next.travel_time, next.iterations, seconds_since(attempt_started)});
    if (std::isfinite(next.travel_time)) out.attempts.back().curve = next.curve;
    out.iterations += next.iterations;
    out.evaluations += next.evaluations;
    out.gradient_evaluations += next.gradient_evaluations;
    // Ties go to the later attempt: it converged (or not) at the same point.
    if (!(next.travel_time > out.travel_time)) {
      next.initial_curve = out.initial_curve;
      next.initial_time = out.initial_time;
      next.attempts = std::move(out.attempts);
      next.best_attempt = next.attempts.size() - 1;
      next.iterations = out.iterations;
      next.evaluations = out.evaluations;
      next.gradient_evaluations = out.gradient_evaluations;
      out = std::move(next);
    }
  }
  out.finite_difference_fallbacks = objective.finite_difference_fallbacks();
  out.seconds = seconds_since(started);
  return out;
}

/// The nested formulation's attempts so far and the best point among them.
struct NestedSearch {
  std::vector<LocalAttempt> attempts;
  std::vector<detail::SolverRun> runs;
  Eigen::VectorXd best;
  double best_time = std::numeric_limits<double>::infinity();
  std::size_t best_attempt = 0, iterations = 0;
  std::optional<Polish> polished;
};

detail::SolverRun run_solver(const PathOptimizerOptions& options, detail::TrackedObjective& tracked,
                             const detail::BoxProblem& box) {
  switch (options.solver) {
    case PathSolver::kIpopt:
      return detail::run_ipopt(tracked, box);
    case PathSolver::kNloptLbfgs:
      return detail::run_nlopt_lbfgs(tracked, box);
    case PathSolver::kNloptBobyqa:
      break;
  }
  return detail::run_nlopt_bobyqa(tracked, box);
}

/// The fit's attempt and the restarts (resume, then perturbed) until one
/// converges, the budget or the restarts run out; one tracker per attempt,
/// so each attempt's best point is its own.
void nested_attempts(PathTimeObjective& objective, const detail::BoxProblem& problem,
                     const PathOptimizerOptions& options, RestartSource& restarts,
                     NestedSearch& search) {
  for (std::size_t r = 0; r <= options.restarts; ++r) {
    detail::BoxProblem box = problem;
    if (r > 0) {
      if (search.attempts.back().converged || problem.termination.should_stop()) break;
      const auto point = restart_point(r, search.best, objective, restarts.first, restarts.last,
                                       restarts.sigma, problem, restarts.random);
      if (!point) break;
      box.start = *point;
    }
    const auto attempt_started = std::chrono::steady_clock::now();
    detail::TrackedObjective tracked(objective);
    tracked(box.start, nullptr);
    search.runs.push_back(run_solver(options, tracked, box));
    const detail::SolverRun& run = search.runs.back();
    search.iterations += run.iterations;
    search.attempts.push_back({r == 0 ? "fit" : (r == 1 ? "resume" : "perturbed"), run.status,
                               converged_status(run.status), tracked.best_value(), run.iterations,
                               seconds_since(attempt_started)});
    if (std::isfinite(tracked.best_value()) && tracked.best().size() == search.best.size())
      search.attempts.back().curve = objective.curve(tracked.best());
    // Ties go to the later attempt: it converged (or not) at the same point.
    if (!(tracked.best_value() > search.best_time) && tracked.best().size() == search.best.size()) {
      search.best = tracked.best();
      search.best_time = tracked.best_value();
      search.best_attempt = search.attempts.size() - 1;
    }
  }
}

/// The polish of the best nested point (PathOptimizerOptions::polish), kept
/// when faster, or converged and close without losing to the fit.
void polish_attempt(const BPatch& terrain, const Vehicle& vehicle, PathTimeObjective& objective,
                    const detail::BoxProblem& problem, std::size_t control_points,
                    std::size_t stations, const RestartSource& restarts,
                    const PathOptimizerOptions& options, double initial_time,
                    NestedSearch& search) {
  const auto polish_started = std::chrono::steady_clock::now();
  Polish p =
      polish_nested_optimum(terrain, vehicle, objective, search.best, problem, control_points,
                            stations, restarts.first, restarts.last, options);
  search.attempts.push_back({"polish", p.run.status, p.run.converged, p.travel_time,
                             p.run.iterations, seconds_since(polish_started)});
  if (std::isfinite(p.travel_time)) search.attempts.back().curve = objective.curve(p.run.variables);
  search.iterations += p.run.iterations;
  const bool faster = p.travel_time < search.best_time;
  const bool close = p.run.converged &&
                     p.travel_time <= search.best_time * (1.0 + options.polish_tolerance) &&
                     p.travel_time <= initial_time;
  if (faster || close) {
    search.best = p.run.variables;
    search.best_time = p.travel_time;
    search.best_attempt = search.attempts.size() - 1;
    search.polished.emplace(std::move(p));
  }
}

/// The nested search's result: the best point's path, its solver's status,
/// the attempts and the optimality measure at the best point.
OptimizedPath nested_result(PathTimeObjective& objective, const detail::BoxProblem& problem,
                            std::size_t control_points, std::size_t stations,
                            const PathOptimizerOptions& options, double initial_time,
                            NestedSearch& search) {
  OptimizedPath out(objective.curve(search.best));
  out.initial_curve = objective.curve(problem.start);
  out.control_points = control_points;
  out.travel_time = search.best_time;
  out.initial_time = initial_time;
  out.formulation = to_string(options.formulation);
  out.solver = to_string(options.solver);
  if (search.polished) {
    out.solver_status = search.polished->run.status;
    out.converged = search.polished->run.converged;
    out.solver_failed = search.polished->run.failed;
    out.nlp_travel_time = search.polished->run.nlp_time;
  } else {
    const detail::SolverRun& run = search.runs[search.best_attempt];
    out.solver_status = run.status;
    out.converged = converged_status(run.status);
    out.solver_failed = run.failed;
  }
  out.attempts = std::move(search.attempts);
  out.best_attempt = search.best_attempt;
  out.iterations = search.iterations;
  out.stations = stations;
  Eigen::VectorXd gradient;
  const double check = objective.evaluate(search.best, &gradient);
  out.optimality = std::isfinite(check) ? projected_gradient_norm(search.best, gradient,
                                                                  problem.lower, problem.upper)
                                        : std::numeric_limits<double>::quiet_NaN();
  out.evaluations = objective.evaluations();
  out.gradient_evaluations = objective.gradient_evaluations();
  out.finite_difference_fallbacks = objective.finite_difference_fallbacks();
  return out;
}

/// optimize_path() from one fit (options.control_points; more_control_points
/// ignored): `known_fit` when given, else computed here.
OptimizedPath optimize_from_one_fit(const BPatch& terrain, const Vehicle& vehicle,
                                    const std::vector<Vec2>& initial_polyline,
                                    const PathOptimizerOptions& options,
                                    const std::optional<InitialPath>& known_fit) {
  const auto started = std::chrono::steady_clock::now();
  if (initial_polyline.size() < 2) throw InputError("the initial path needs at least 2 vertices");
  // The initial path: a least-squares fit to the candidate, grown while a
  // winding candidate needs more control points (fit_initial_path).
  const bool simultaneous = options.formulation == PathFormulation::kSimultaneous;
  const InitialPath fit =
      known_fit ? *known_fit
                : fit_initial_path(terrain, vehicle, initial_polyline, options, simultaneous);
  // The simultaneous NLP starts from an infeasible profile (restoration).
  if (!(fit.admissible() || (simultaneous && fit.on_data))) {
    throw InputError(
        "the initial path (" + std::to_string(fit.control_points) +
        " control points) cannot be driven: " +
        (fit.failure.empty() ? std::string("it has no admissible profile") : fit.failure));
  }
  const std::size_t control_points = fit.control_points, stations = fit.stations;
  PathTimeObjective objective(terrain, vehicle, initial_polyline.front(), initial_polyline.back(),
                              control_points, stations, options.speeds);
  const Eigen::VectorXd start = objective.variables(fit.curve->control_points());
  const double initial_time = objective.evaluate(start);
  const detail::BoxProblem problem = box_problem(terrain, start, initial_polyline, options);
  RestartSource restarts{
      initial_polyline.front(), initial_polyline.back(),
      options.restart_perturbation > 0.0 ? options.restart_perturbation : 2.0 * terrain.cellsize(),
      std::mt19937_64(options.seed)};
  if (simultaneous) {
    return simultaneous_attempts(terrain, vehicle, objective, problem, control_points, stations,
                                 options, started, restarts);
  }
  // The fit is the solvers' first point (the box holds it).
  if (!std::isfinite(initial_time)) {
    throw InputError("the initial path has no admissible profile at the search's stations");
  }
  NestedSearch search;
  search.best = problem.start;
  search.best_time = initial_time;
  nested_attempts(objective, problem, options, restarts, search);
  if (options.polish && !problem.termination.should_stop()) {
    polish_attempt(terrain, vehicle, objective, problem, control_points, stations, restarts,
                   options, initial_time, search);
  }
  OptimizedPath out =
      nested_result(objective, problem, control_points, stations, options, initial_time, search);
  out.seconds = seconds_since(started);
  return out;
}

/// Every attempt of `path` tagged with its fit's control-point count.
OptimizedPath tagged(OptimizedPath path) {
  for (LocalAttempt& a : path.attempts) a.control_points = path.control_points;
  return path;
}

}  // namespace

OptimizedPath optimize_path(const BPatch& terrain, const Vehicle& vehicle,
                            const std::vector<Vec2>& initial_polyline,
                            const PathOptimizerOptions& options,
                            const std::optional<InitialPath>& fit) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  // Armed once: every fit, attempt and solver below polls the same deadline.
  PathOptimizerOptions armed = options;
  armed.termination = options.termination.start();
  OptimizedPath best =
      tagged(optimize_from_one_fit(terrain, vehicle, initial_polyline, armed, fit));
  for (const std::size_t m : options.more_control_points) {
    if (armed.termination.should_stop()) break;
    PathOptimizerOptions further = armed;
    further.more_control_points.clear();
    further.control_points = m;
    further.max_control_points = std::max(further.max_control_points, m);
    std::optional<OptimizedPath> next;
    try {
      next.emplace(
          tagged(optimize_from_one_fit(terrain, vehicle, initial_polyline, further, std::nullopt)));
    } catch (const InputError&) {
      continue;  // no admissible fit at this count
    }
    std::vector<LocalAttempt> attempts = std::move(best.attempts);
    const std::size_t offset = attempts.size();
    attempts.insert(attempts.end(), next->attempts.begin(), next->attempts.end());
    const std::size_t iterations = best.iterations + next->iterations;
    const std::size_t evaluations = best.evaluations + next->evaluations;
    const std::size_t gradients = best.gradient_evaluations + next->gradient_evaluations;
    // The first fit stays the start every result is compared with.
    if (next->travel_time < best.travel_time) {
      next->initial_curve = best.initial_curve;
      next->initial_time = best.initial_time;
      next->best_attempt += offset;
      best = std::move(*next);
    }
    best.attempts = std::move(attempts);
    best.iterations = iterations;
    best.evaluations = evaluations;
    best.gradient_evaluations = gradients;
  }
  best.seconds = seconds_since(started);
  return best;
}

void LocalCertificateOptions::validate() const {
  if (!(std::isfinite(radius) && radius >= 0.0))
    throw InputError("LocalCertificateOptions.radius must be a finite number >= 0 [m]");
  if (!(std::isfinite(tolerance) && tolerance >= 0.0))
    throw InputError("LocalCertificateOptions.tolerance must be a finite number >= 0");
  if (rounds < 1) throw InputError("LocalCertificateOptions.rounds must be >= 1");
}

LocalCertificate certify_local_optimum(const BPatch& terrain, const Vehicle& vehicle,
                                       const OptimizedPath& optimum,
                                       const PathOptimizerOptions& options,
                                       const LocalCertificateOptions& certificate) {
  const auto started = std::chrono::steady_clock::now();
  certificate.validate();
  options.validate();
  LocalCertificate out;
  out.radius = certificate.radius > 0.0 ? certificate.radius : 0.25 * terrain.cellsize();
  out.tolerance = certificate.tolerance;
  const std::vector<Vec2>& points = optimum.curve.control_points();
  PathTimeObjective objective(terrain, vehicle, points.front(), points.back(), points.size(),
                              optimum.stations, options.speeds);
  detail::TrackedObjective tracked(objective);
  const Eigen::VectorXd z = objective.variables(points);
  out.travel_time = out.best_time = tracked(z, nullptr);
  if (!std::isfinite(out.travel_time)) {
    out.solver_status = "infeasible";
    out.seconds = seconds_since(started);
    return out;
  }
  // Rounds: the optimiser's own box (domain, pinned headings) cut to the radius round the
  // best point so far; a round that improves by more than the tolerance moves the box there
  // and searches again. The last round's improvement decides the certificate.
  Eigen::VectorXd centre = z;
  const std::size_t n = objective.dimension();
  const std::size_t budget =
      certificate.max_evaluations > 0 ? certificate.max_evaluations : 10 * (n + 1);
  for (std::size_t round = 0; round < certificate.rounds; ++round) {
    detail::BoxProblem box = box_problem(terrain, centre, {points.front(), points.back()}, options);
    box.lower = box.lower.cwiseMax((centre.array() - out.radius).matrix());
    box.upper = box.upper.cwiseMin((centre.array() + out.radius).matrix());
    const double narrowest = narrowest_free_width(box);
    if (!std::isfinite(narrowest)) {  // nothing free: the optimum is the only point
      out.certified = true;
      out.solver_status = "no free coordinate";
      break;
    }
    box.initial_step = 0.25 * narrowest;  // half the radius where the box is not cut
    box.max_evaluations = budget;
    box.relative_tolerance = 0.1 * certificate.tolerance;
    const double before = tracked.best_value();
    const detail::SolverRun run = detail::run_nlopt_bobyqa(tracked, box);
    out.solver_status = run.status;
    ++out.rounds;
    const double gain = (before - tracked.best_value()) / before;
    out.certified = gain <= certificate.tolerance;
    if (out.certified || run.status == "time_limit") break;
    centre = tracked.best();
  }
  out.evaluations = tracked.evaluations();
  out.best_time = tracked.best_value();
  out.improvement = (out.travel_time - out.best_time) / out.travel_time;
  if (out.best_time < out.travel_time) out.better.emplace(objective.curve(tracked.best()));
  out.seconds = seconds_since(started);
  return out;
}

}  // namespace talus
