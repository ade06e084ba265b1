#include "talus/optimal/planner.hpp"
#include "talus/optimal/planner_parameters.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <utility>

#include "talus/bspline/curve_fit.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/stopwatch.hpp"

namespace talus {
namespace {

std::string point_text(const Vec2& p) {
  std::ostringstream text;
  text << "(" << p.x() << ", " << p.y() << ")";
  return text.str();
}

/// The optimiser's own initial fit to `polyline` with `control_points`:
/// used when the optimiser refused the candidate, so that its outcome still
/// says how the candidate itself drives.
/// Candidate `c` from the exact start to the exact goal (both snap to the
/// same node when they share a lattice cell: then the straight segment).
std::vector<Vec2> candidate_polyline(const PlanningProblem& problem,
                                     const GlobalSearchResult& global, std::size_t c) {
  std::vector<Vec2> polyline = global.candidates[c].vertices;
  if (polyline.size() < 2) polyline = {problem.start, problem.goal};
  polyline.front() = problem.start;
  polyline.back() = problem.goal;
  return polyline;
}

/// Step 3 of the file comment when the optimum disagrees: every other
/// attempt's point evaluated at the final stations, the fastest there
/// replacing outcome.trajectory.
void report_fastest_attempt(const PlanningProblem& problem, const TrajectoryOptions& evaluation,
                            const OptimizedPath& optimization, TimeOptimalProfileSolver& workspace,
                            CandidateOutcome& outcome) {
  for (std::size_t k = 0; k < optimization.attempts.size(); ++k) {
    const LocalAttempt& attempt = optimization.attempts[k];
    if (k == optimization.best_attempt || !attempt.curve) continue;
    Trajectory trajectory = evaluate_trajectory(*problem.surface, problem.vehicle, *attempt.curve,
                                                evaluation, &workspace);
    if (trajectory.travel_time() < outcome.trajectory.travel_time()) {
      outcome.trajectory = std::move(trajectory);
      outcome.reported_attempt = k;
    }
  }
}

/// Optimises candidate `c` (from `fit`, its followability check's fit, when
/// there was one) and evaluates the optimum and its initial fit.
CandidateOutcome optimise_candidate(const PlanningProblem& problem,
                                    const PathOptimizerOptions& local,
                                    const TrajectoryOptions& evaluation,
                                    const GlobalSearchResult& global, std::size_t c,
                                    const std::optional<InitialPath>& fit, bool certify,
                                    TimeOptimalProfileSolver& workspace, PlannerTimings& timings) {
  const auto started = Clock::now();
  CandidateOutcome outcome;
  outcome.candidate = c;
  const std::vector<Vec2> polyline = candidate_polyline(problem, global, c);
  // The check's fit is the nested formulation's start (the simultaneous one
  // stops growing its fit earlier).
  const bool reuse = local.formulation == PathFormulation::kNested;
  try {
    outcome.optimization.emplace(optimize_path(*problem.surface, problem.vehicle, polyline, local,
                                               reuse ? fit : std::nullopt));
  } catch (const InputError& error) {
    outcome.optimizer_message = error.what();
  }
  timings.local += seconds_since(started);

  const auto evaluation_started = Clock::now();
  const BPatch& surface = *problem.surface;
  outcome.initial = evaluate_trajectory(
      surface, problem.vehicle,
      outcome.optimization ? outcome.optimization->initial_curve
                           : fit_candidate(surface, polyline, local.control_points, local),
      evaluation, &workspace);
  if (outcome.optimization) {
    const OptimizedPath& optimization = *outcome.optimization;
    outcome.trajectory =
        evaluate_trajectory(surface, problem.vehicle, optimization.curve, evaluation, &workspace);
    outcome.reported_attempt = optimization.best_attempt;
    if (!(outcome.trajectory.travel_time() <=
          optimization.travel_time * (1.0 + kStageDisagreement))) {
      report_fastest_attempt(problem, evaluation, optimization, workspace, outcome);
    }
    if (certify) {
      outcome.certificate.emplace(
          certify_local_optimum(surface, problem.vehicle, optimization, local));
      if (outcome.certificate->better) {
        Trajectory better = evaluate_trajectory(
            surface, problem.vehicle, *outcome.certificate->better, evaluation, &workspace);
        if (better.travel_time() < outcome.trajectory.travel_time()) {
          outcome.trajectory = std::move(better);
          outcome.certificate_kept = true;
        }
      }
    }
  } else {
    outcome.trajectory.message = outcome.optimizer_message;
  }
  // A search coarser than the final spacing (a user's local.station_spacing,
  // or max_search_stations on a long path) can favour a path that is slower
  // there: never return one slower than its own initial fit.
  if (outcome.initial.feasible() &&
      !(outcome.trajectory.travel_time() <= outcome.initial.travel_time())) {
    outcome.trajectory = outcome.initial;
    outcome.kept_initial = true;
    outcome.reported_attempt.reset();
  }
  timings.evaluation += seconds_since(evaluation_started);
  outcome.seconds = seconds_since(started);
  return outcome;
}

}  // namespace

void PlanningProblem::validate() const {
  if (surface == nullptr) throw InputError("PlanningProblem.surface is null");
  vehicle.validate();
  if (!std::isfinite(vehicle.max_speed)) {
    throw InputError(
        "the planner needs a vehicle with a finite max_speed (the global cost is the travel "
        "time at the speed limit, and an unlimited straight road would cost nothing)");
  }
  for (const auto& [name, p] : {std::pair{"start", start}, std::pair{"goal", goal}}) {
    if (!surface->contains(p)) {
      std::ostringstream message;
      message << "PlanningProblem." << name << " " << point_text(p)
              << " is off the surface, whose domain is [" << surface->x_min() << ", "
              << surface->x_max() << "] x [" << surface->y_min() << ", " << surface->y_max() << "]";
      throw InputError(message.str());
    }
  }
  if (start == goal) {
    throw InputError("PlanningProblem: start and goal are the same point " + point_text(start) +
                     "; there is nothing to plan");
  }
  for (const auto& [name, heading] :
       {std::pair{"start_heading", start_heading}, std::pair{"goal_heading", goal_heading}}) {
    if (heading && !std::isfinite(*heading))
      throw InputError(std::string("PlanningProblem.") + name + " must be finite (radians)");
  }
  for (const auto& [name, speed] :
       {std::pair{"start_speed", start_speed}, std::pair{"end_speed", end_speed}}) {
    if (!(std::isfinite(speed) && speed >= 0.0 && speed <= vehicle.max_speed)) {
      std::ostringstream message;
      message << "PlanningProblem." << name << " must be in [0, max_speed = " << vehicle.max_speed
              << "] m/s, got " << speed;
      throw InputError(message.str());
    }
  }
}

std::string_view to_string(PlannerStage stage) {
  switch (stage) {
    case PlannerStage::kGlobalSearch:
      return "global search";
    case PlannerStage::kLocalOptimisation:
      return "local optimisation";
    case PlannerStage::kDone:
      return "done";
  }
  return "unknown";
}

std::string_view to_string(PlannerStatus status) {
  switch (status) {
    case PlannerStatus::kOk:
      return "ok";
    case PlannerStatus::kUnreachable:
      return "unreachable";
    case PlannerStatus::kInfeasible:
      return "infeasible";
    case PlannerStatus::kStopped:
      return "stopped";
    case PlannerStatus::kTimeLimit:
      return "time_limit";
  }
  return "unknown";
}

void PlannerOptions::validate() const {
  planner_parameters().check(*this);  // the declared bounds, named by field
  global.validate();
  local.validate();
  require_station_spacing(station_spacing, "PlannerOptions.station_spacing");
}

const Trajectory* PlannerResult::best() const {
  return best_candidate ? &candidates.at(*best_candidate).trajectory : nullptr;
}

double PlannerResult::travel_time() const {
  return best() != nullptr ? best()->travel_time() : std::numeric_limits<double>::infinity();
}

double PlannerResult::global_travel_time() const {
  double best_initial = std::numeric_limits<double>::infinity();
  for (const CandidateOutcome& c : candidates) {
    best_initial = std::min(best_initial, c.initial.travel_time());
  }
  return best_initial;
}

double PlannerResult::improvement_percent() const {
  const double global_time = global_travel_time(), best_time = travel_time();
  if (!(std::isfinite(global_time) && std::isfinite(best_time))) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return 100.0 * (global_time - best_time) / global_time;
}

std::string PlannerResult::brief_report() const {
  std::ostringstream report;
  report.precision(6);
  report << "Talus plan: " << to_string(status);
  if (!message.empty()) report << " (" << message << ")";
  report << "\n";
  if (const Trajectory* t = best()) {
    report << "  best: candidate " << *best_candidate << ", travel time " << t->travel_time()
           << " s over " << t->length() << " m; best global candidate " << global_travel_time()
           << " s (" << improvement_percent() << " % faster)\n";
  }
  report << "  global search: " << global.candidates.size() << " candidates, " << global.nodes
         << " nodes, " << global.edges_evaluated << " edges\n";
  if (feedback_rounds > 0) {
    report << "  feedback: " << feedback_rounds << " global search"
           << (feedback_rounds == 1 ? "" : "es") << " re-run, " << excluded.size() << " region"
           << (excluded.size() == 1 ? "" : "s") << " excluded\n";
  }
  for (const CandidateOutcome& c : candidates) {
    report << "  candidate " << c.candidate << ": ";
    if (c.feasible()) {
      report << c.trajectory.travel_time() << " s (initial fit " << c.initial.travel_time()
             << " s)";
    } else {
      report << "infeasible: " << c.trajectory.message;
    }
    if (c.optimization) {
      const OptimizedPath& o = *c.optimization;
      report << "; " << o.solver << " " << o.solver_status << ", " << o.iterations
             << " iterations, " << o.evaluations << " evaluations, optimality " << o.optimality
             << " s/m";
      if (o.attempts.size() > 1) {
        report << "; " << o.attempts.size() << " attempts, the best from the "
               << o.attempts[o.best_attempt].start;
      }
    }
    if (c.kept_initial) report << "; kept the initial fit";
    if (c.optimization && c.reported_attempt && *c.reported_attempt != c.optimization->best_attempt)
      report << "; the optimum disagreed at the final stations, reported attempt "
             << *c.reported_attempt;
    if (c.time_limited) report << "; cut short by the time limit";
    report << "\n";
  }
  if (!not_optimised.empty()) {
    report << "  time limit: " << not_optimised.size() << " candidate"
           << (not_optimised.size() == 1 ? "" : "s") << " not optimised:";
    for (const std::size_t c : not_optimised) report << " " << c;
    report << "\n";
  }
  report << "  seconds: global " << seconds.global << ", local " << seconds.local << ", evaluation "
         << seconds.evaluation << ", total " << seconds.total << "\n";
  return report.str();
}

namespace {

/// "1, 2 and 4".
std::string list_text(const std::vector<std::size_t>& items) {
  std::ostringstream text;
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (k > 0) text << (k + 1 == items.size() ? " and " : ", ");
    text << items[k];
  }
  return text.str();
}

/// The followability check of the file comment for every candidate of
/// `global`: the optimiser's own initial path (fit_initial_path: grown while
/// needed) has an admissible profile at the search's stations; if not, where
/// it fails (absent when the fit leaves the data). The fits are kept for the
/// local stage, which starts from them.
std::vector<InitialPath> check_candidates(const PlanningProblem& problem,
                                          const PathOptimizerOptions& local,
                                          const GlobalSearchResult& global) {
  std::vector<InitialPath> fits;
  for (std::size_t c = 0; c < global.candidates.size(); ++c)
    fits.push_back(fit_initial_path(*problem.surface, problem.vehicle,
                                    candidate_polyline(problem, global, c), local));
  return fits;
}

/// The feedback loop of the file comment, from the first global search in
/// result.global: re-runs the search with the failing stretches excluded
/// while some candidate is not followable and the budget lasts, keeps the
/// round with the most followable candidates in result.global (its
/// exclusions in result.excluded) and returns their followability checks' fits.
std::vector<InitialPath> feedback_rounds(const PlanningProblem& problem,
                                         const PlannerOptions& options,
                                         const PathOptimizerOptions& local,
                                         GlobalSearchOptions global,
                                         GlobalSearchWorkspace& workspace, PlannerResult& result) {
  const double spacing =
      result.global.spacing > 0.0 ? result.global.spacing : problem.surface->cellsize();
  const double radius = options.feedback_radius > 0.0 ? options.feedback_radius : 2.0 * spacing;
  std::vector<InitialPath> fits = check_candidates(problem, local, result.global);
  const auto count = [](const std::vector<InitialPath>& f) {
    return static_cast<std::size_t>(
        std::count_if(f.begin(), f.end(), [](const InitialPath& p) { return p.admissible(); }));
  };
  GlobalSearchResult kept_global = result.global;
  std::size_t edges_evaluated = result.global.edges_evaluated;
  std::vector<InitialPath> kept = fits;
  std::vector<ExcludedRegion> kept_excluded = global.excluded;
  while (count(fits) < fits.size() && result.feedback_rounds < options.feedback_rounds) {
    // A disc round each failure; near the start or the goal (whose nodes
    // are kept, and whose approach a disc would cut off) only the
    // candidate's own vertices near it, so that it must come another way.
    // A failure inside a disc of an earlier round means the search went
    // round the disc and the fit still fails there (a long stretch such as
    // a chute): that disc doubles instead.
    const std::vector<ExcludedRegion> before = global.excluded;
    std::vector<ExcludedRegion> added;
    bool widened = false;
    const auto inside = [](const Vec2& q, const std::vector<ExcludedRegion>& regions) {
      return std::any_of(regions.begin(), regions.end(), [&](const ExcludedRegion& e) {
        return (q - e.centre).norm() <= e.radius;
      });
    };
    const auto add = [&](const Vec2& centre, double r) {
      if (!inside(centre, global.excluded) && !inside(centre, added)) added.push_back({centre, r});
    };
    const auto add_or_widen = [&](const Vec2& centre, double r) {
      if (inside(centre, added)) return;
      for (std::size_t e = 0; e < before.size(); ++e) {
        if ((centre - before[e].centre).norm() <= before[e].radius) {
          global.excluded[e].radius = 2.0 * before[e].radius;
          widened = true;
          return;
        }
      }
      added.push_back({centre, r});
    };
    for (std::size_t c = 0; c < fits.size(); ++c) {
      if (fits[c].admissible() || !fits[c].failure_point) continue;
      const Vec2 p = *fits[c].failure_point;
      const double margin = radius + spacing;
      if ((p - problem.start).norm() > margin && (p - problem.goal).norm() > margin) {
        add_or_widen(p, radius);
        continue;
      }
      // Those within the radius, and at least the nearest (the last edge
      // into the goal can be longer than the radius).
      const std::vector<Vec2>& vertices = result.global.candidates[c].vertices;
      std::size_t nearest = 0;
      for (std::size_t v = 1; v + 1 < vertices.size(); ++v) {
        if ((vertices[v] - p).norm() <= radius) add(vertices[v], 0.5 * spacing);
        if (nearest == 0 || (vertices[v] - p).norm() < (vertices[nearest] - p).norm()) nearest = v;
      }
      if (nearest != 0) add(vertices[nearest], 0.5 * spacing);
    }
    if (added.empty() && !widened) break;
    global.excluded.insert(global.excluded.end(), added.begin(), added.end());
    ++result.feedback_rounds;
    // Discs round failures next to the start (or goal) can close every edge out of its
    // node: global_search reports that as unreachable, for the loop a closed corridor.
    const auto search_again = [&] {
      return global_search(*problem.surface, problem.vehicle, problem.start, problem.goal, global,
                           workspace);
    };
    GlobalSearchResult next = search_again();
    edges_evaluated += next.edges_evaluated;
    if (next.status == GlobalSearchStatus::kUnreachable) {
      // The new or widened discs closed the last corridor (a pass narrower
      // than they are): keep the earlier discs as they were and exclude
      // only the node nearest to each new failure instead.
      std::copy(before.begin(), before.end(), global.excluded.begin());
      if (added.empty()) break;
      bool shrunk = widened;
      for (auto r = global.excluded.end() - static_cast<long>(added.size());
           r != global.excluded.end(); ++r) {
        shrunk = shrunk || r->radius > 0.5 * spacing;
        r->radius = std::min(r->radius, 0.5 * spacing);
      }
      if (shrunk) {
        next = search_again();
        edges_evaluated += next.edges_evaluated;
      }
    }
    if (next.status != GlobalSearchStatus::kOk) break;  // no corridor left, or stopped
    fits = check_candidates(problem, local, next);
    if (count(fits) >= count(kept)) {
      kept_global = next;
      kept = fits;
      kept_excluded = global.excluded;
    }
    result.global = std::move(next);
  }
  result.global = std::move(kept_global);
  result.global.edges_evaluated = edges_evaluated;
  result.excluded = std::move(kept_excluded);
  return kept;
}

/// The local stage's options for `problem`: the problem's speeds and
/// headings, and the stations the result is reported at unless the user set
/// the search's own spacing.
PathOptimizerOptions local_stage_options(const PlanningProblem& problem,
                                         const PlannerOptions& options) {
  PathOptimizerOptions local = options.local;
  local.speeds = {problem.start_speed, problem.end_speed};
  local.start_heading = problem.start_heading;
  local.goal_heading = problem.goal_heading;
  // The local stage searches at the stations the result is reported at, so
  // an improvement it finds is one the final evaluation sees (on Mount St.
  // Helens the optimiser's default, five times coarser, found optima that
  // were slower at the final spacing, and every candidate kept its fit).
  // local.max_search_stations still coarsens the search on long paths.
  if (local.station_spacing == 0.0) {
    local.station_spacing =
        resolve_station_spacing(options.station_spacing, *problem.surface, problem.vehicle);
  }
  return local;
}

/// What the time limit cut: the global search, the candidates cut short,
/// those never optimised, and whether a trajectory is returned.
std::string time_limit_message(std::string message, bool global_cut,
                               const std::vector<std::size_t>& cut_short,
                               const PlannerResult& result) {
  if (global_cut) message += " in the global search (" + result.global.message + ")";
  if (!cut_short.empty()) {
    message += std::string(global_cut ? "; " : ": ") + "the optimisation of candidate" +
               (cut_short.size() == 1 ? " " : "s ") + list_text(cut_short) +
               " cut short (best point so far kept)";
  }
  if (!result.not_optimised.empty()) {
    message += std::string(global_cut || !cut_short.empty() ? "; " : ": ") + "candidate" +
               (result.not_optimised.size() == 1 ? " " : "s ") + list_text(result.not_optimised) +
               " not optimised";
  }
  message += result.best_candidate ? "; the best trajectory so far is returned"
                                   : "; no feasible trajectory found by then";
  return message;
}

std::string infeasible_message(const PlannerResult& result) {
  // The best corridor's failure by name (where and why); the others' in their own messages.
  std::string message = "no candidate has a feasible trajectory";
  if (!result.candidates.empty() && !result.candidates.front().trajectory.message.empty()) {
    message += ": candidate 0: " + result.candidates.front().trajectory.message;
    if (result.candidates.size() > 1) message += " (the others: see each candidate's message)";
  } else {
    message += " (see each candidate's message)";
  }
  if (result.feedback_rounds > 0) {
    message += "; the global search ran " + std::to_string(result.feedback_rounds + 1) +
               " times, excluding " + std::to_string(result.excluded.size()) +
               " stretches that could not be driven, and no drivable corridor remained";
  }
  return message;
}

}  // namespace

PlannerResult plan(const PlanningProblem& problem, const PlannerOptions& options) {
  const auto started = Clock::now();
  problem.validate();
  options.validate();
  PlannerResult result;
  // Armed once: the global search and every candidate's solvers poll the same deadline.
  const Termination termination = options.termination.start();
  const auto keep_going = [&](PlannerStage stage, std::size_t candidate) {
    if (!options.progress) return true;
    const PlannerProgress progress{stage, candidate, result.global.candidates.size(),
                                   seconds_since(started)};
    return options.progress(progress);
  };
  const auto finish = [&](PlannerStatus status, std::string message) {
    result.surface = problem.surface;  // the paths hold it too (a BPatch copy shares it)
    result.status = status;
    result.message = std::move(message);
    result.seconds.total = seconds_since(started);
    if (options.progress) {
      options.progress(
          {PlannerStage::kDone, 0, result.global.candidates.size(), result.seconds.total});
    }
    return std::move(result);
  };
  constexpr const char* kStopMessage = "stopped by the progress callback";
  constexpr const char* kRequestMessage = "stopped by PlannerOptions::termination (stop requested)";
  std::ostringstream limit_text;
  limit_text << "time limit of " << termination.smallest_budget() << " s reached";

  if (!keep_going(PlannerStage::kGlobalSearch, 0))
    return finish(PlannerStatus::kStopped, kStopMessage);
  const auto global_started = Clock::now();
  GlobalSearchOptions global = options.global;
  global.termination = options.global.termination | termination;
  // The feedback rounds search the same lattice again: its edge costs are kept.
  GlobalSearchWorkspace search_workspace;
  result.global = global_search(*problem.surface, problem.vehicle, problem.start, problem.goal,
                                global, search_workspace);

  PathOptimizerOptions local = local_stage_options(problem, options);
  local.termination = options.local.termination | termination;
  TimeOptimalProfileSolver workspace;
  std::vector<InitialPath> fits;  // each candidate's followability check
  if (options.optimize && result.global.status == GlobalSearchStatus::kOk) {
    fits = feedback_rounds(problem, options, local, global, search_workspace, result);
  }
  result.seconds.global = seconds_since(global_started);
  bool global_cut = false;
  if (result.global.status == GlobalSearchStatus::kStopped) {
    if (termination.check() != TerminationReason::kTimeLimit)
      return finish(PlannerStatus::kStopped, result.global.message);
    global_cut = true;
    if (result.global.candidates.empty()) {
      return finish(PlannerStatus::kTimeLimit, limit_text.str() +
                                                   " in the global search before it found a "
                                                   "route: no candidate, no trajectory (" +
                                                   result.global.message + ")");
    }
  } else if (result.global.status != GlobalSearchStatus::kOk) {
    return finish(PlannerStatus::kUnreachable, result.global.message);
  }
  if (!options.optimize) {
    if (global_cut) {
      return finish(PlannerStatus::kTimeLimit,
                    limit_text.str() + " in the global search: " + result.global.message);
    }
    return finish(PlannerStatus::kOk, "");
  }

  TrajectoryOptions evaluation;
  evaluation.speeds = local.speeds;
  evaluation.station_spacing =
      resolve_station_spacing(options.station_spacing, *problem.surface, problem.vehicle);
  std::vector<std::size_t> cut_short;
  for (std::size_t c = 0; c < result.global.candidates.size(); ++c) {
    // Past the limit, only until one trajectory is feasible (its fit alone).
    const TerminationReason reason = termination.check();
    if (reason == TerminationReason::kStopRequested)
      return finish(PlannerStatus::kStopped, kRequestMessage);
    const bool late = reason == TerminationReason::kTimeLimit;
    if (late && result.best_candidate) {
      for (std::size_t k = c; k < result.global.candidates.size(); ++k) {
        result.not_optimised.push_back(k);
      }
      break;
    }
    if (!keep_going(PlannerStage::kLocalOptimisation, c)) {
      return finish(PlannerStatus::kStopped, kStopMessage);
    }
    const std::optional<InitialPath> fit =
        c < fits.size() ? std::optional<InitialPath>(fits[c]) : std::nullopt;
    result.candidates.push_back(optimise_candidate(problem, local, evaluation, result.global, c,
                                                   fit, options.certify, workspace,
                                                   result.seconds));
    CandidateOutcome& outcome = result.candidates.back();
    outcome.followable = fit && fit->admissible();
    outcome.time_limited =
        late || (outcome.optimization && outcome.optimization->solver_status == "time_limit");
    if (outcome.time_limited) cut_short.push_back(c);
    if (outcome.feasible() &&
        (!result.best_candidate || outcome.trajectory.travel_time() < result.travel_time())) {
      result.best_candidate = c;
    }
  }
  if (termination.check() == TerminationReason::kStopRequested)
    return finish(PlannerStatus::kStopped, kRequestMessage);
  if (global_cut || !cut_short.empty() || !result.not_optimised.empty()) {
    return finish(PlannerStatus::kTimeLimit,
                  time_limit_message(limit_text.str(), global_cut, cut_short, result));
  }
  if (!result.best_candidate) return finish(PlannerStatus::kInfeasible, infeasible_message(result));
  return finish(PlannerStatus::kOk, "");
}

}  // namespace talus
