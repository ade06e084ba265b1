#include "plan_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

#include "cli_values.hpp"
#include "json_values.hpp"
#include "limits_command.hpp"
#include "plan_rasters.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/output_folder.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/dynamics/limit_summary.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/planner_parameters.hpp"
#include "talus/report/plan_figures.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/progress_line.hpp"
#include "terrain_input.hpp"

namespace talus::experiments {
namespace {

std::string format_point(const Vec2& p) {
  return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ")";
}

nlohmann::json point_json(const Vec2& p) {
  return nlohmann::json::array({p.x(), p.y()});
}

/// Checks of the request's own options (the planner's are checked by their
/// table as they are set, and again by PlannerOptions::validate()).
void check_plan_options(const PlanRequest& request) {
  if (request.stage != kPlanStageGlobal && request.stage != kPlanStageFull) {
    throw InputError("--stage must be full or global, got " + request.stage);
  }
  for (const auto& [option, speed] :
       {std::pair{"--v0", request.start_speed}, std::pair{"--v1", request.end_speed}}) {
    if (!(std::isfinite(speed) && speed >= 0.0)) {
      throw InputError(std::string(option) + " must be a finite speed >= 0 [m/s], got " +
                       format_number(speed));
    }
  }
  for (const auto& [option, heading] : {std::pair{"--start-heading", request.start_heading},
                                        std::pair{"--goal-heading", request.goal_heading}}) {
    if (heading && !std::isfinite(*heading)) {
      throw InputError(std::string(option) + " must be a finite angle [rad], got " +
                       format_number(*heading));
    }
  }
  planner_parameters().check(request.planner, ParameterSpelling::kCli);
  if (request.smoothing && !(std::isfinite(*request.smoothing) && *request.smoothing > 0.0)) {
    throw InputError("--smoothing must be a positive finite number (lambda), got " +
                     format_number(*request.smoothing));
  }
  if (request.surface_degree != 3 && request.surface_degree != 5) {
    throw InputError("--surface-degree must be 3 (bicubic) or 5 (biquintic), got " +
                     std::to_string(request.surface_degree));
  }
  if (request.surface_degree == 5 && request.smoothing) {
    throw InputError(
        "--surface-degree 5 is an interpolating fit: drop --smoothing (the "
        "smoothing fit is bicubic)");
  }
  if (request.output_dir.empty()) throw InputError("no output folder given (--out DIR)");
  std::error_code error;
  if (std::filesystem::exists(request.output_dir, error) &&
      !std::filesystem::is_directory(request.output_dir, error)) {
    throw InputError("--out " + request.output_dir + " exists and is not a folder");
  }
}

void check_in_domain(const char* option, const Vec2& p, const ElevationGrid& grid,
                     const std::string& terrain_file) {
  if (grid.contains(p)) return;
  throw InputError(std::string(option) + " " + format_point(p) + " is off the terrain " +
                   terrain_file + ", whose domain is [" + format_number(grid.x_min()) + ", " +
                   format_number(grid.x_max()) + "] x [" + format_number(grid.y_min()) + ", " +
                   format_number(grid.y_max()) + "]");
}

std::string candidates_csv(const GlobalSearchResult& result) {
  std::string csv = kCandidatesCsvHeader;
  csv += '\n';
  for (std::size_t c = 0; c < result.candidates.size(); ++c) {
    for (const Vec2& v : result.candidates[c].vertices) {
      csv += std::to_string(c);
      csv += ',';
      append_csv_number(csv, v.x());
      csv += ',';
      append_csv_number(csv, v.y());
      csv += '\n';
    }
  }
  return csv;
}

/// One row per lattice node, row by row from the south-west; a field that was
/// not computed is `nan`.
std::string fields_csv(const GlobalSearchResult& result) {
  const std::size_t n = result.nx * result.ny;
  const auto value = [](const std::vector<double>& field, std::size_t k) {
    return field.size() == 0 ? std::numeric_limits<double>::quiet_NaN() : field[k];
  };
  std::string csv = kFieldsCsvHeader;
  csv += '\n';
  csv.reserve(csv.size() + n * 48);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 p = result.origin + result.spacing * Vec2(static_cast<double>(k % result.nx),
                                                         static_cast<double>(k / result.nx));
    for (const double v : {p.x(), p.y(), value(result.cost_from_start, k)}) {
      append_csv_number(csv, v);
      csv += ',';
    }
    append_csv_number(csv, value(result.cost_to_goal, k));
    csv += '\n';
  }
  return csv;
}

/// Station indices of a profile with `n` stations, thinned to about `rows`.
std::vector<std::size_t> thinned(std::size_t n, std::size_t rows) {
  const std::size_t stride = std::max<std::size_t>(1, (n + rows - 1) / rows);
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < n; k += stride) out.push_back(k);
  if (n > 0 && out.back() != n - 1) out.push_back(n - 1);
  return out;
}

std::string trajectory_csv(const Trajectory* best) {
  std::string csv = kTrajectoryCsvHeader;
  csv += '\n';
  if (best == nullptr) return csv;
  const VelocityLimits& limits = *best->limits;
  const TimeOptimalProfile& p = best->profile;
  for (std::size_t k = 0; k < limits.size(); ++k) {
    const PathFrame& f = limits.frame(k);
    const SpeedLimits& l = limits.limits(k);
    for (const double value :
         {f.s, f.point.x(), f.point.y(), f.point.z(), p.v[k], p.a[k], p.t[k], l.v_max}) {
      append_csv_number(csv, value);
      csv += ',';
    }
    csv += to_string(l.upper_binding);
    csv += '\n';
  }
  return csv;
}

std::string optima_csv(const PlannerResult& result) {
  std::string csv = kOptimaCsvHeader;
  csv += '\n';
  for (const CandidateOutcome& c : result.candidates) {
    if (!c.feasible()) continue;
    const VelocityLimits& limits = *c.trajectory.limits;
    for (const std::size_t k : thinned(limits.size(), kMaxOptimaRows)) {
      const PathFrame& f = limits.frame(k);
      csv += std::to_string(c.candidate);
      for (const double value : {f.s, f.point.x(), f.point.y(), c.trajectory.profile.v[k]}) {
        csv += ',';
        append_csv_number(csv, value);
      }
      csv += '\n';
    }
  }
  return csv;
}

/// optima[] of the summary: one entry per candidate of the local stage.
nlohmann::json optimum_json(const CandidateOutcome& c, const std::string& solver) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const OptimizedPath* o = c.optimization ? &*c.optimization : nullptr;
  nlohmann::json entry;
  entry["candidate"] = c.candidate;
  entry["optimizer_message"] = o ? nlohmann::json(nullptr) : nlohmann::json(c.optimizer_message);
  entry["status"] = c.feasible() ? "ok" : "infeasible";
  entry["message"] = c.feasible() ? nlohmann::json(nullptr) : nlohmann::json(c.trajectory.message);
  entry["travel_time"] = finite_or_null(c.trajectory.travel_time());
  entry["initial_time"] = finite_or_null(c.initial.travel_time());
  entry["travel_time_search_spacing"] = finite_or_null(o ? o->travel_time : kNaN);
  entry["initial_time_search_spacing"] = finite_or_null(o ? o->initial_time : kNaN);
  entry["kept_initial"] = c.kept_initial;
  entry["reported_attempt"] =
      c.reported_attempt ? nlohmann::json(*c.reported_attempt) : nlohmann::json(nullptr);
  entry["followable"] = c.followable;
  entry["solver"] = solver;
  entry["solver_status"] = o ? nlohmann::json(o->solver_status) : nlohmann::json(nullptr);
  entry["solver_failed"] = o ? o->solver_failed : false;
  entry["formulation"] = o ? nlohmann::json(o->formulation) : nlohmann::json(nullptr);
  entry["converged"] = o ? o->converged : false;
  entry["phase"] = o ? o->phase : 0;
  entry["nlp_travel_time"] = finite_or_null(o ? o->nlp_travel_time : kNaN);
  entry["iterations"] = o ? o->iterations : 0;
  entry["evaluations"] = o ? o->evaluations : 0;
  entry["gradient_evaluations"] = o ? o->gradient_evaluations : 0;
  entry["finite_difference_gradients"] = o ? o->finite_difference_fallbacks : 0;
  entry["optimality"] = finite_or_null(o ? o->optimality : kNaN);
  entry["search_stations"] = o ? o->stations : 0;
  entry["control_points"] = o ? o->control_points : 0;
  entry["seconds"] = o ? o->seconds : 0.0;
  nlohmann::json attempts = nlohmann::json::array();
  if (o) {
    for (const LocalAttempt& a : o->attempts) {
      attempts.push_back({{"start", a.start},
                          {"solver_status", a.solver_status},
                          {"converged", a.converged},
                          {"travel_time_search_spacing", finite_or_null(a.travel_time)},
                          {"iterations", a.iterations},
                          {"seconds", a.seconds},
                          {"control_points", a.control_points}});
    }
  }
  entry["attempts"] = std::move(attempts);
  entry["best_attempt"] = o ? nlohmann::json(o->best_attempt) : nlohmann::json(nullptr);
  entry["length_m"] = c.feasible() ? nlohmann::json(c.trajectory.length()) : nullptr;
  // --certify: the optimum's local-optimality certificate.
  entry["certificate"] = nullptr;
  if (c.certificate) {
    const LocalCertificate& k = *c.certificate;
    entry["certificate"] = {{"certified", k.certified},
                            {"radius_m", k.radius},
                            {"tolerance", k.tolerance},
                            {"improvement_percent", 100.0 * k.improvement},
                            {"evaluations", k.evaluations},
                            {"rounds", k.rounds},
                            {"solver_status", k.solver_status},
                            {"kept", c.certificate_kept},
                            {"seconds", k.seconds}};
  }
  return entry;
}

/// plan.png and profile.png of a plan with a best trajectory.
void render_plan_figures(const PlanRequest& request, const ElevationGrid& grid,
                         const PlanningProblem& problem, const PlannerResult& result,
                         const std::filesystem::path& dir) {
  const Trajectory& best = *result.best();
  PlanMapData map;
  map.surface = *problem.surface;
  map.origin = Vec2(grid.x_min(), grid.y_min());
  map.width = grid.x_max() - grid.x_min();
  map.height = grid.y_max() - grid.y_min();
  for (const CandidatePath& c : result.global.candidates) map.candidates.push_back(c.vertices);
  for (const CandidateOutcome& c : result.candidates) {
    std::vector<Vec2> points;
    if (c.feasible()) {
      for (const std::size_t k : thinned(c.trajectory.limits->size(), kMaxOptimaRows)) {
        points.push_back(c.trajectory.limits->frame(k).point.head<2>());
      }
    }
    map.optimised.push_back(std::move(points));
    map.optimised_times.push_back(c.trajectory.travel_time());
  }
  map.best = *result.best_candidate;
  map.start = problem.start;
  map.goal = problem.goal;
  std::ostringstream title;
  title.precision(4);
  title << "talus plan: " << std::filesystem::path(request.terrain).filename().string() << ", "
        << result.global.candidates.size() << " global candidates, best optimised path "
        << best.travel_time() << " s (global " << result.global_travel_time() << " s)";
  map.title = title.str();
  render_plan_map(dir, map);

  PlanProfileData figure;
  const TimeOptimalProfile& p = best.profile;
  for (const std::size_t k : thinned(best.limits->size(), 20 * kMaxOptimaRows)) {
    figure.s.push_back(p.s[k]);
    figure.v.push_back(p.v[k]);
    figure.v_max.push_back(p.v_max[k]);
  }
  for (const SwitchingPoint& sp : p.switching_points) {
    figure.switch_s.push_back(sp.s);
    figure.switch_v.push_back(p.v[sp.station]);
  }
  std::ostringstream profile_title;
  profile_title.precision(4);
  profile_title << "best trajectory (candidate " << *result.best_candidate << "): travel time "
                << p.travel_time << " s, " << p.switching_points.size() << " switching points";
  figure.title = profile_title.str();
  render_plan_profile(dir, figure);
}

/// The local stage's files (trajectory.csv, optima.csv, the figures) and
/// summary fields.
void write_full_stage(const PlanRequest& request, const ElevationGrid& grid,
                      const PlanningProblem& problem, const PlannerOptions& options,
                      const PlannerResult& result, const OutputFolder& out, nlohmann::json& summary,
                      nlohmann::json& seconds) {
  const Trajectory* best = result.best();
  const std::filesystem::path& dir = out.staging();
  write_text_file(dir / "trajectory.csv", trajectory_csv(best));
  write_text_file(dir / "optima.csv", optima_csv(result));

  const auto plots_start = Clock::now();
  // Past the time limit the figures (the slowest output of a tile-size plan) are left out:
  // the limit bounds the command, and the data files carry the plan.
  const bool late = options.termination.check() == TerminationReason::kTimeLimit;
  const bool plots = request.figures && best != nullptr && !late && gnuplot_available();
  if (plots) render_plan_figures(request, grid, problem, result, dir);
  summary["figures_skipped"] = request.figures && best != nullptr && late
                                   ? nlohmann::json("the time limit had passed")
                                   : nlohmann::json(nullptr);
  const double plots_seconds = seconds_since(plots_start);

  nlohmann::json optima = nlohmann::json::array();
  for (const CandidateOutcome& c : result.candidates) {
    optima.push_back(optimum_json(c, std::string(to_string(options.local.solver))));
  }
  if (result.status == PlannerStatus::kInfeasible) {
    summary["status"] = "infeasible";
    summary["message"] = result.message;  // names the best corridor's failure and its point
  }
  if (result.status == PlannerStatus::kTimeLimit) {
    summary["status"] = "time_limit";
    summary["message"] = result.message;
  }
  summary["not_optimised"] = result.not_optimised;
  summary["feedback_rounds"] = result.feedback_rounds;
  nlohmann::json excluded = nlohmann::json::array();
  for (const ExcludedRegion& region : result.excluded) {
    excluded.push_back(
        {{"x", region.centre.x()}, {"y", region.centre.y()}, {"radius", region.radius}});
  }
  summary["excluded_regions"] = std::move(excluded);
  summary["travel_time"] = finite_or_null(best ? best->travel_time() : NAN);
  summary["global_travel_time"] = finite_or_null(result.global_travel_time());
  summary["improvement_percent"] = finite_or_null(result.improvement_percent());
  summary["best_candidate"] = best ? nlohmann::json(*result.best_candidate) : nullptr;
  // What sets the speed limit along the best path: fractions of its stations.
  const std::optional<LimitSummary> best_limits =
      best && best->limits ? std::optional(summarise_limits(*best->limits)) : std::nullopt;
  for (const Constraint c :
       {Constraint::kSliding, Constraint::kTipover, Constraint::kContact, Constraint::kMaxSpeed}) {
    summary["binding_share_" + std::string(to_string(c))] =
        best_limits ? nlohmann::json(best_limits->upper_share(c)) : nlohmann::json(nullptr);
  }
  // The best path itself, to rebuild it exactly: a clamped cubic on uniform
  // breakpoints in [0, 1] with these control points.
  nlohmann::json control = nlohmann::json::array();
  if (best) {
    for (const Vec2& c : best->path->curve().control_points()) control.push_back(point_json(c));
  }
  summary["best_control_points"] = std::move(control);
  summary["length_m"] = best ? nlohmann::json(best->length()) : nullptr;
  summary["stations"] = best ? nlohmann::json(best->limits->size()) : nullptr;
  summary["switching_points"] =
      best ? nlohmann::json(best->profile.switching_points.size()) : nullptr;
  summary["optima"] = std::move(optima);
  // The local stage's entries of the echo that summary.json has always had at its top level.
  for (const char* key :
       {"solver", "formulation", "restarts", "polish", "control_points", "more_control_points"})
    summary[key] = summary.at("options").at(key);
  summary["optimality_note"] =
      "optima[].optimality: largest projected-gradient component of the travel time at the "
      "returned path [s/m], from the adjoint gradient (for every solver); the travel time is "
      "piecewise smooth, so a local optimum can sit on a kink with a non-zero value";
  summary["start_speed"] = request.start_speed;
  summary["end_speed"] = request.end_speed;
  summary["start_heading"] =
      request.start_heading ? nlohmann::json(*request.start_heading) : nlohmann::json(nullptr);
  summary["goal_heading"] =
      request.goal_heading ? nlohmann::json(*request.goal_heading) : nlohmann::json(nullptr);
  summary["station_spacing"] =
      resolve_station_spacing(options.station_spacing, *problem.surface, problem.vehicle);
  summary["search_station_spacing"] =
      search_station_spacing(options.local, *problem.surface, problem.vehicle);
  summary["max_evaluations"] = options.local.max_evaluations;
  summary["files"]["trajectory"] = out.final_path("trajectory.csv").string();
  summary["files"]["optima"] = out.final_path("optima.csv").string();
  summary["files"]["plan_png"] =
      plots ? nlohmann::json(out.final_path("plan.png").string()) : nlohmann::json(nullptr);
  summary["files"]["profile_png"] =
      plots ? nlohmann::json(out.final_path("profile.png").string()) : nlohmann::json(nullptr);
  seconds["local"] = result.seconds.local;
  seconds["profile"] = result.seconds.evaluation;
  seconds["plots"] = plots_seconds;
}

/// The request's options as the library planner's, reporting on `line`.
PlannerOptions planner_options(const PlanRequest& request, ProgressLine& line) {
  PlannerOptions options = request.planner;
  options.global.cost_fields = true;  // fields.csv
  options.optimize = request.stage == kPlanStageFull;
  options.progress = [&line](const PlannerProgress& p) {
    if (p.stage == PlannerStage::kGlobalSearch) line.update("global search");
    if (p.stage == PlannerStage::kLocalOptimisation)
      line.update("local optimisation, candidate " + std::to_string(p.candidate + 1) + " of " +
                      std::to_string(p.candidates),
                  p.candidate, p.candidates);
    if (p.stage == PlannerStage::kDone) line.update("writing the outputs");
    return true;
  };
  return options;
}

}  // namespace

Vec2 parse_point(const std::string& option, const std::string& text) {
  if (const auto v = parse_numbers(text, 2)) return Vec2((*v)[0], (*v)[1]);
  throw InputError(option + " must be X,Y: two finite numbers [m] separated by a comma, got '" +
                   text + "'");
}

namespace {

/// The files `talus plan` may write for `request` (a user's file of one of these names is
/// refused before planning, not after).
std::vector<std::string> plan_output_names(const PlanRequest& request) {
  std::vector<std::string> names = {"summary.json", "candidates.csv", "fields.csv"};
  if (request.rasters) {
    names.push_back("cost_to_go.tif");
    names.push_back("trajectory.geojson");
  }
  if (request.stage == kPlanStageFull) {
    names.push_back("trajectory.csv");
    names.push_back("optima.csv");
    if (request.figures) {
      names.push_back("plan.png");
      names.push_back("profile.png");
    }
  }
  return names;
}

}  // namespace

PlanOutcome plan(const PlanRequest& request) {
  const auto start_time = Clock::now();
  check_plan_options(request);
  OutputFolder out(request.output_dir);  // locked for the whole run
  out.refuse_foreign_files(plan_output_names(request));
  const Vec2 start = parse_point("--start", request.start);
  const Vec2 goal = parse_point("--goal", request.goal);
  if (start == goal) {
    throw InputError("--start and --goal are the same point " + format_point(start) +
                     ": there is nothing to plan");
  }

  const Vehicle vehicle = load_vehicle(request.vehicle);
  if (!std::isfinite(vehicle.max_speed)) {
    throw InputError(request.vehicle +
                     ": the global search needs a vehicle with a finite max_speed (its cost is "
                     "the travel time at the speed limit, and an unlimited straight road would "
                     "cost nothing); add `max_speed: V` [m/s]");
  }

  if (request.stage == kPlanStageFull) {
    for (const auto& [option, speed] :
         {std::pair{"--v0", request.start_speed}, std::pair{"--v1", request.end_speed}}) {
      if (speed > vehicle.max_speed) {
        throw InputError(std::string(option) + " " + format_number(speed) +
                         " m/s is above the vehicle's max_speed " +
                         format_number(vehicle.max_speed) + " m/s");
      }
    }
  }

  const TerrainRaster terrain = load_terrain(request.terrain, request.reproject, request.band);
  const ElevationGrid& grid = terrain.grid;
  check_in_domain("--start", start, grid, request.terrain);
  check_in_domain("--goal", goal, grid, request.terrain);
  ProgressLine line("talus plan", request.progress);
  // --time-limit bounds everything after reading: its budget is armed here, before the fit
  // (the planner keeps a deadline armed before it starts).
  PlannerOptions options = planner_options(request, line);
  options.termination = options.termination.start();
  const double read_seconds = seconds_since(start_time);
  line.update("fitting the surface");
  const auto fit_start = Clock::now();
  PlanOutcome outcome;
  outcome.surface = std::make_shared<const BPatch>([&] {
    try {
      return request.smoothing ? BPatch::fit_smoothing(grid, *request.smoothing)
                               : BPatch::interpolate(grid, request.surface_degree);
    } catch (const InputError& e) {
      throw InputError(request.terrain + ": " + e.what());
    }
  }());
  const double fit_seconds = seconds_since(fit_start);

  PlanningProblem problem(outcome.surface, vehicle, start, goal);
  if (request.stage == kPlanStageFull) {  // the global stage ignores speeds
    problem.start_speed = request.start_speed;
    problem.end_speed = request.end_speed;
    problem.start_heading = request.start_heading;
    problem.goal_heading = request.goal_heading;
  }
  outcome.result = talus::plan(problem, options);
  const auto write_start = Clock::now();
  const PlannerResult& planned = outcome.result;
  const GlobalSearchResult& result = planned.global;
  // A search cut by the time limit after it found a route counts as reaching the goal.
  const bool reachable =
      result.status == GlobalSearchStatus::kOk ||
      (result.status == GlobalSearchStatus::kStopped && !result.candidates.empty());
  const bool time_limited = planned.status == PlannerStatus::kTimeLimit;

  const std::filesystem::path& dir = out.staging();
  write_text_file(dir / "candidates.csv", candidates_csv(result));
  // No fields without a full-resolution search that computed them.
  const bool write_fields =
      result.nx * result.ny <= kMaxFieldNodes && !result.cost_from_start.empty();
  if (write_fields) write_text_file(dir / "fields.csv", fields_csv(result));
  if (request.rasters) {  // in the DEM's CRS
    write_geotiff(cost_to_go_layers(result, terrain.crs), (dir / "cost_to_go.tif").string());
    write_text_file(dir / "trajectory.geojson", plan_geojson(planned, terrain.crs));
  }
  const std::string summary_file = out.final_path("summary.json").string();

  nlohmann::json candidates = nlohmann::json::array();
  for (const CandidatePath& c : result.candidates) {
    candidates.push_back({{"cost_seconds", c.cost_seconds},
                          {"length_m", c.length_m},
                          {"vertices", c.vertices.size()}});
  }
  nlohmann::json summary;
  summary["status"] = time_limited ? "time_limit" : reachable ? "ok" : "unreachable";
  summary["message"] = time_limited ? nlohmann::json(planned.message)
                       : reachable  ? nlohmann::json(nullptr)
                                    : nlohmann::json(result.message);
  summary["coarse_nodes"] = result.coarse_nodes;
  summary["route_nodes"] = result.route_nodes;  // the route level's, under a time limit
  // The candidates are a coarser level's routes: the time limit stopped the finer search.
  summary["coarse_candidates"] = result.coarse_candidates;
  // What the search ran (the option may be auto).
  summary["search_resolution"] = std::string(to_string(result.resolution));
  summary["corridor_widenings"] = result.corridor_widenings;
  summary["stage"] = request.stage;
  // The best corridor's lattice travel time: monotone in the vehicle's limits
  // (every edge's cost is), unlike the locally optimised time.
  summary["search_cost"] = result.candidates.empty()
                               ? nlohmann::json(nullptr)
                               : nlohmann::json(result.candidates.front().cost_seconds);
  summary["candidates"] = std::move(candidates);
  summary["candidates_requested"] = options.global.candidates;
  summary["start"] = point_json(start);
  summary["goal"] = point_json(goal);
  summary["start_node"] = point_json(result.start_node);
  summary["goal_node"] = point_json(result.goal_node);
  summary["lattice_spacing"] = result.spacing;
  summary["lattice"] = nlohmann::json::array({result.nx, result.ny});
  summary["turn_limit_relaxed"] = result.turn_limit_relaxed;
  summary["search_message"] = result.message;
  summary["nodes"] = result.nodes;
  summary["edges_evaluated"] = result.edges_evaluated;
  summary["expanded"] = result.expanded;
  summary["reachable_nodes"] = result.reachable_nodes;
  summary["vehicle_max_speed"] = vehicle.max_speed;
  summary["fit"] = request.smoothing ? "smoothing" : "interpolating";
  summary["surface_degree"] = request.surface_degree;
  summary["crs"] = terrain.crs.known() ? nlohmann::json(terrain.crs.label()) : nullptr;
  summary["smoothing"] =
      request.smoothing ? nlohmann::json(*request.smoothing) : nlohmann::json(nullptr);
  summary["files"] = {
      {"candidates", out.final_path("candidates.csv").string()},
      {"fields", write_fields ? nlohmann::json(out.final_path("fields.csv").string()) : nullptr},
      {"cost_to_go",
       request.rasters ? nlohmann::json(out.final_path("cost_to_go.tif").string()) : nullptr},
      {"geojson",
       request.rasters ? nlohmann::json(out.final_path("trajectory.geojson").string()) : nullptr},
      {"summary", summary_file}};
  summary["options"] = parameters_json(planner_parameters(), options);
  // The global stage's entries of the echo that summary.json has always had at its top level.
  for (const char* key : {"time_limit", "resolution", "connectivity", "braking_rule", "turn_limit"})
    summary[key] = summary["options"].at(key);
  summary["read_seconds"] = read_seconds;
  summary["fit_seconds"] = fit_seconds;
  summary["search_seconds"] = result.search_seconds;
  if (request.stage == kPlanStageGlobal) {
    summary["write_seconds"] = seconds_since(write_start);
    summary["seconds"] = seconds_since(start_time);
    write_text_file(dir / "summary.json", summary.dump(2) + "\n");
    out.commit();
    outcome.summary = std::move(summary);
    outcome.reachable = reachable;
    return outcome;
  }
  // Every stage, so that they add up to the total: reading (and checking) the inputs, the fit,
  // the global and local stages, the final profiles, the figures and the other outputs.
  nlohmann::json seconds = {
      {"read", read_seconds}, {"fit", fit_seconds}, {"global", planned.seconds.global}};
  if (reachable) {
    write_full_stage(request, grid, problem, options, planned, out, summary, seconds);
  } else {  // no trajectory: the full stage's fields are empty
    summary["not_optimised"] = nlohmann::json::array();
    write_text_file(dir / "trajectory.csv", trajectory_csv(nullptr));
    write_text_file(dir / "optima.csv", std::string(kOptimaCsvHeader) + "\n");
    for (const char* key : {"travel_time", "global_travel_time", "improvement_percent"}) {
      summary[key] = nullptr;
    }
    summary["optima"] = nlohmann::json::array();
    seconds["local"] = 0.0;
    seconds["profile"] = 0.0;
    seconds["plots"] = 0.0;
  }
  // The files and this summary (the figures are `plots`), up to its own writing.
  seconds["write"] = seconds_since(write_start) - seconds["plots"].get<double>();
  const double total = seconds_since(start_time);
  double named = 0.0;
  for (const auto& [stage, value] : seconds.items()) named += value.get<double>();
  // The planner's own work between its stages (its candidate loop, the certificate).
  seconds["other"] = std::max(0.0, total - named);
  seconds["total"] = total;
  summary["seconds"] = std::move(seconds);
  write_text_file(dir / "summary.json", summary.dump(2) + "\n");
  out.commit();
  outcome.summary = std::move(summary);
  outcome.reachable = planned.status == PlannerStatus::kOk || (time_limited && planned.best());
  return outcome;
}

}  // namespace talus::experiments
