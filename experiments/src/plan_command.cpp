#include "plan_command.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

#include "cli_values.hpp"
#include "limits_command.hpp"
#include "plan_figures.hpp"
#include "plot.hpp"
#include "stopwatch.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/curve_fit.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus::experiments {
namespace {

std::string format_point(const Vec2& p) {
  return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ")";
}

nlohmann::json point_json(const Vec2& p) {
  return nlohmann::json::array({p.x(), p.y()});
}

/// Option checks that need no file.
void check_plan_options(const PlanRequest& request) {
  if (request.stage != kPlanStageGlobal && request.stage != kPlanStageFull) {
    throw InputError("--stage must be full or global, got " + request.stage);
  }
  try {
    parse_path_solver(request.solver);
  } catch (const InputError& e) {
    throw InputError(std::string("--solver: ") + e.what());
  }
  if (request.control_points < 4 || request.control_points > kMaxPlanControlPoints) {
    throw InputError("--control-points must be in [4, " + std::to_string(kMaxPlanControlPoints) +
                     "], got " + std::to_string(request.control_points));
  }
  for (const auto& [option, speed] :
       {std::pair{"--v0", request.start_speed}, std::pair{"--v1", request.end_speed}}) {
    if (!(std::isfinite(speed) && speed >= 0.0)) {
      throw InputError(std::string(option) + " must be a finite speed >= 0 [m/s], got " +
                       format_number(speed));
    }
  }
  if (request.candidates < 1) {
    throw InputError("--candidates must be at least 1, got " + std::to_string(request.candidates));
  }
  if (!(std::isfinite(request.lattice_spacing) && request.lattice_spacing >= 0.0)) {
    throw InputError(
        "--lattice-spacing must be a finite number >= 0 [m] (0 = the terrain's "
        "cell size), got " +
        format_number(request.lattice_spacing));
  }
  if (request.connectivity != 8 && request.connectivity != 16 && request.connectivity != 32) {
    throw InputError("--connectivity must be 8, 16 or 32, got " +
                     std::to_string(request.connectivity));
  }
  if (request.smoothing && !(std::isfinite(*request.smoothing) && *request.smoothing > 0.0)) {
    throw InputError("--smoothing must be a positive finite number (lambda), got " +
                     format_number(*request.smoothing));
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

/// A path's time-optimal profile at kDefaultStationSpacing. The SurfacePath
/// lives on the heap: it must not move.
struct EvaluatedPath {
  std::unique_ptr<const SurfacePath> path;
  std::unique_ptr<const VelocityLimits> limits;
  TimeOptimalProfile profile;
  std::string message;  ///< why there is no profile
  bool feasible() const { return profile.status == ProfileStatus::kOk; }
  double travel_time() const {
    return feasible() ? profile.travel_time : std::numeric_limits<double>::infinity();
  }
};

EvaluatedPath evaluate_path(const BPatch& surface, const Vehicle& vehicle, const Curve2& curve,
                            const ProfileOptions& speeds, TimeOptimalProfileSolver& solver) {
  EvaluatedPath e;
  try {
    e.path = std::make_unique<const SurfacePath>(surface, curve);
    const auto stations = std::max<std::size_t>(
        static_cast<std::size_t>(std::ceil(e.path->length() / kDefaultStationSpacing)) + 1, 2);
    e.limits = std::make_unique<const VelocityLimits>(vehicle, *e.path, stations);
    solver.solve(*e.limits, speeds, e.profile);
    if (!e.feasible()) e.message = e.profile.message;
  } catch (const InputError& error) {
    e.profile.status = ProfileStatus::kInfeasible;
    e.message = error.what();
  }
  return e;
}

/// Station indices of a profile with `n` stations, thinned to about `rows`.
std::vector<std::size_t> thinned(std::size_t n, std::size_t rows) {
  const std::size_t stride = std::max<std::size_t>(1, (n + rows - 1) / rows);
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < n; k += stride) out.push_back(k);
  if (n > 0 && out.back() != n - 1) out.push_back(n - 1);
  return out;
}

std::string trajectory_csv(const EvaluatedPath* best) {
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

nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

/// The local stage: optimises every candidate, writes trajectory.csv,
/// optima.csv and the figures, and adds the local stage's fields to
/// `summary`. Returns whether a feasible trajectory exists.
bool run_full_stage(const PlanRequest& request, const BPatch& surface, const ElevationGrid& grid,
                    const Vehicle& vehicle, const Vec2& start, const Vec2& goal,
                    const GlobalSearchResult& result, const std::filesystem::path& dir,
                    nlohmann::json& summary, nlohmann::json& seconds) {
  PathOptimizerOptions options;
  options.solver = parse_path_solver(request.solver);
  options.control_points = static_cast<std::size_t>(request.control_points);
  options.max_control_points = std::max(options.max_control_points, options.control_points);
  options.speeds.start_speed = request.start_speed;
  options.speeds.end_speed = request.end_speed;
  TimeOptimalProfileSolver solver;

  std::vector<EvaluatedPath> optimised;
  nlohmann::json optima = nlohmann::json::array();
  double local_seconds = 0.0, profile_seconds = 0.0;
  double global_time = std::numeric_limits<double>::infinity();
  std::size_t best = result.candidates.size();
  for (std::size_t c = 0; c < result.candidates.size(); ++c) {
    std::vector<Vec2> polyline = result.candidates[c].vertices;
    polyline.front() = start;  // the exact start and goal, not the snapped nodes
    polyline.back() = goal;
    nlohmann::json entry;
    entry["candidate"] = c;

    const auto local_start = Clock::now();
    std::optional<OptimizedPath> local;
    std::string failure;
    try {
      local.emplace(optimize_path(surface, vehicle, polyline, options));
    } catch (const InputError& error) {
      failure = error.what();
    }
    local_seconds += seconds_since(local_start);

    // The candidate's own time before optimisation: the optimiser's initial
    // fit (with the control points it needed), at the final spacing.
    auto profile_start = Clock::now();
    const Curve2 initial =
        local ? local->initial_curve
              : fit_clamped_cubic(
                    resample_polyline(polyline, std::max<std::size_t>(10 * options.control_points,
                                                                      polyline.size())),
                    options.control_points);
    EvaluatedPath initial_path = evaluate_path(surface, vehicle, initial, options.speeds, solver);
    profile_seconds += seconds_since(profile_start);
    global_time = std::min(global_time, initial_path.travel_time());

    profile_start = Clock::now();
    EvaluatedPath path = failure.empty()
                             ? evaluate_path(surface, vehicle, local->curve, options.speeds, solver)
                             : EvaluatedPath{};
    if (failure.empty() && !path.feasible()) failure = path.message;
    // The search's coarser stations can favour a path that is slower at the
    // default spacing: never report one slower than its own initial fit.
    const bool kept_initial =
        initial_path.feasible() && !(path.travel_time() <= initial_path.travel_time());
    // Why the optimiser gave nothing, even when the initial fit stands in.
    entry["optimizer_message"] = local ? nlohmann::json(nullptr) : nlohmann::json(failure);
    if (kept_initial) {
      path = std::move(initial_path);
      failure.clear();
    }
    profile_seconds += seconds_since(profile_start);

    const bool ok = path.feasible();
    entry["status"] = ok ? "ok" : "infeasible";
    entry["message"] = ok ? nlohmann::json(nullptr) : nlohmann::json(failure);
    entry["travel_time"] = finite_or_null(path.travel_time());
    entry["initial_time"] =
        finite_or_null(kept_initial ? path.travel_time() : initial_path.travel_time());
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    entry["travel_time_search_spacing"] = finite_or_null(local ? local->travel_time : kNaN);
    entry["initial_time_search_spacing"] = finite_or_null(local ? local->initial_time : kNaN);
    entry["kept_initial"] = kept_initial;
    entry["solver"] = request.solver;
    entry["solver_status"] = local ? nlohmann::json(local->solver_status) : nlohmann::json(nullptr);
    entry["solver_failed"] = local ? local->solver_failed : false;
    entry["iterations"] = local ? local->iterations : 0;
    entry["evaluations"] = local ? local->evaluations : 0;
    entry["gradient_evaluations"] = local ? local->gradient_evaluations : 0;
    entry["finite_difference_gradients"] = local ? local->finite_difference_fallbacks : 0;
    entry["optimality"] = finite_or_null(local ? local->optimality : kNaN);
    entry["search_stations"] = local ? local->stations : 0;
    entry["control_points"] = local ? local->control_points : 0;
    entry["seconds"] = local ? local->seconds : 0.0;
    entry["length_m"] = ok ? nlohmann::json(path.path->length()) : nlohmann::json(nullptr);
    optima.push_back(std::move(entry));
    if (ok &&
        (best == result.candidates.size() || path.travel_time() < optimised[best].travel_time())) {
      best = c;
    }
    optimised.push_back(std::move(path));
  }
  const bool feasible = best < optimised.size();
  const EvaluatedPath* best_path = feasible ? &optimised[best] : nullptr;

  // Files.
  const std::string trajectory_file = (dir / "trajectory.csv").string();
  const std::string optima_file = (dir / "optima.csv").string();
  write_text_file(trajectory_file, trajectory_csv(best_path));
  std::string csv = kOptimaCsvHeader;
  csv += '\n';
  for (std::size_t c = 0; c < optimised.size(); ++c) {
    const EvaluatedPath& e = optimised[c];
    if (!e.feasible()) continue;
    for (const std::size_t k : thinned(e.limits->size(), kMaxOptimaRows)) {
      const PathFrame& f = e.limits->frame(k);
      csv += std::to_string(c);
      for (const double value : {f.s, f.point.x(), f.point.y(), e.profile.v[k]}) {
        csv += ',';
        append_csv_number(csv, value);
      }
      csv += '\n';
    }
  }
  write_text_file(optima_file, csv);

  const auto plots_start = Clock::now();
  const bool plots = feasible && gnuplot_available();
  std::error_code error;
  for (const char* name : {"plan.png", "profile.png"}) std::filesystem::remove(dir / name, error);
  if (plots) {
    PlanMapData map;
    map.surface = &surface;
    map.origin = Vec2(grid.x_min(), grid.y_min());
    map.width = grid.x_max() - grid.x_min();
    map.height = grid.y_max() - grid.y_min();
    for (const CandidatePath& c : result.candidates) map.candidates.push_back(c.vertices);
    for (const EvaluatedPath& e : optimised) {
      std::vector<Vec2> points;
      if (e.feasible()) {
        for (const std::size_t k : thinned(e.limits->size(), kMaxOptimaRows)) {
          points.push_back(e.limits->frame(k).point.head<2>());
        }
      }
      map.optimised.push_back(std::move(points));
      map.optimised_times.push_back(e.travel_time());
    }
    map.best = best;
    map.start = start;
    map.goal = goal;
    std::ostringstream title;
    title.precision(4);
    title << "talus plan: " << std::filesystem::path(request.terrain).filename().string() << ", "
          << result.candidates.size() << " global candidates, best optimised path "
          << best_path->travel_time() << " s (global " << global_time << " s)";
    map.title = title.str();
    render_plan_map(dir, map);

    PlanProfileData figure;
    const TimeOptimalProfile& p = best_path->profile;
    for (const std::size_t k : thinned(best_path->limits->size(), 20 * kMaxOptimaRows)) {
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
    profile_title << "best trajectory (candidate " << best << "): travel time " << p.travel_time
                  << " s, " << p.switching_points.size() << " switching points";
    figure.title = profile_title.str();
    render_plan_profile(dir, figure);
  }
  const double plots_seconds = seconds_since(plots_start);

  const double best_time =
      feasible ? best_path->travel_time() : std::numeric_limits<double>::quiet_NaN();
  if (!feasible) {
    summary["status"] = "infeasible";
    summary["message"] = "no candidate has a feasible trajectory (see optima[].message)";
  }
  summary["travel_time"] = finite_or_null(best_time);
  summary["global_travel_time"] = finite_or_null(global_time);
  summary["improvement_percent"] = finite_or_null(100.0 * (global_time - best_time) / global_time);
  summary["best_candidate"] = feasible ? nlohmann::json(best) : nlohmann::json(nullptr);
  // The best path itself, to rebuild it exactly: a clamped cubic on uniform
  // breakpoints in [0, 1] with these control points.
  nlohmann::json control = nlohmann::json::array();
  if (feasible) {
    for (const Vec2& c : best_path->path->curve().control_points())
      control.push_back(point_json(c));
  }
  summary["best_control_points"] = std::move(control);
  summary["length_m"] = feasible ? nlohmann::json(best_path->path->length()) : nullptr;
  summary["stations"] = feasible ? nlohmann::json(best_path->limits->size()) : nullptr;
  summary["switching_points"] =
      feasible ? nlohmann::json(best_path->profile.switching_points.size()) : nullptr;
  summary["optima"] = std::move(optima);
  summary["solver"] = request.solver;
  summary["optimality_note"] =
      "optima[].optimality: largest projected-gradient component of the travel time at the "
      "returned path [s/m], from the adjoint gradient (for every solver); the travel time is "
      "piecewise smooth, so a local optimum can sit on a kink with a non-zero value";
  summary["control_points"] = request.control_points;
  summary["start_speed"] = request.start_speed;
  summary["end_speed"] = request.end_speed;
  summary["station_spacing"] = kDefaultStationSpacing;
  summary["search_station_spacing"] = options.station_spacing;
  summary["max_evaluations"] = options.max_evaluations;
  summary["files"]["trajectory"] = trajectory_file;
  summary["files"]["optima"] = optima_file;
  summary["files"]["plan_png"] =
      plots ? nlohmann::json((dir / "plan.png").string()) : nlohmann::json(nullptr);
  summary["files"]["profile_png"] =
      plots ? nlohmann::json((dir / "profile.png").string()) : nlohmann::json(nullptr);
  seconds["local"] = local_seconds;
  seconds["profile"] = profile_seconds;
  seconds["plots"] = plots_seconds;
  return feasible;
}

}  // namespace

Vec2 parse_point(const std::string& option, const std::string& text) {
  if (const auto v = parse_numbers(text, 2)) return Vec2((*v)[0], (*v)[1]);
  throw InputError(option + " must be X,Y: two finite numbers [m] separated by a comma, got '" +
                   text + "'");
}

PlanOutcome plan(const PlanRequest& request) {
  const auto start_time = Clock::now();
  check_plan_options(request);
  const Vec2 start = parse_point("--start", request.start);
  const Vec2 goal = parse_point("--goal", request.goal);

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

  const ElevationGrid grid = read_esri_ascii(request.terrain);
  check_in_domain("--start", start, grid, request.terrain);
  check_in_domain("--goal", goal, grid, request.terrain);
  const auto fit_start = Clock::now();
  const BPatch surface = [&] {
    try {
      return request.smoothing ? BPatch::fit_smoothing(grid, *request.smoothing)
                               : BPatch::interpolate(grid);
    } catch (const InputError& e) {
      throw InputError(request.terrain + ": " + e.what());
    }
  }();
  const double fit_seconds = seconds_since(fit_start);

  GlobalSearchOptions options;
  options.lattice_spacing = request.lattice_spacing;
  options.connectivity = request.connectivity;
  options.candidates = static_cast<std::size_t>(request.candidates);
  options.cost_fields = true;
  const GlobalSearchResult result = global_search(surface, vehicle, start, goal, options);
  const bool reachable = result.status == GlobalSearchStatus::kOk;

  const std::filesystem::path dir(request.output_dir);
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) {
    throw InputError("--out " + request.output_dir + ": cannot create the folder (" +
                     error.message() + ")");
  }
  const std::string candidates_file = (dir / "candidates.csv").string();
  const std::string fields_file = (dir / "fields.csv").string();
  const std::string summary_file = (dir / "summary.json").string();
  write_text_file(candidates_file, candidates_csv(result));
  const bool write_fields = result.nx * result.ny <= kMaxFieldNodes;
  if (write_fields) {
    write_text_file(fields_file, fields_csv(result));
  } else {
    std::filesystem::remove(fields_file, error);  // never leave a stale one
  }

  nlohmann::json candidates = nlohmann::json::array();
  for (const CandidatePath& c : result.candidates) {
    candidates.push_back({{"cost_seconds", c.cost_seconds},
                          {"length_m", c.length_m},
                          {"vertices", c.vertices.size()}});
  }
  nlohmann::json summary;
  summary["status"] = reachable ? "ok" : "unreachable";
  summary["message"] = reachable ? nlohmann::json(nullptr) : nlohmann::json(result.message);
  summary["stage"] = request.stage;
  summary["candidates"] = std::move(candidates);
  summary["candidates_requested"] = request.candidates;
  summary["start"] = point_json(start);
  summary["goal"] = point_json(goal);
  summary["start_node"] = point_json(result.start_node);
  summary["goal_node"] = point_json(result.goal_node);
  summary["lattice_spacing"] = result.spacing;
  summary["lattice"] = nlohmann::json::array({result.nx, result.ny});
  summary["connectivity"] = request.connectivity;
  summary["nodes"] = result.nodes;
  summary["edges_evaluated"] = result.edges_evaluated;
  summary["expanded"] = result.expanded;
  summary["reachable_nodes"] = result.reachable_nodes;
  summary["vehicle_max_speed"] = vehicle.max_speed;
  summary["fit"] = request.smoothing ? "smoothing" : "interpolating";
  summary["smoothing"] =
      request.smoothing ? nlohmann::json(*request.smoothing) : nlohmann::json(nullptr);
  summary["files"] = {{"candidates", candidates_file},
                      {"fields", write_fields ? nlohmann::json(fields_file) : nullptr},
                      {"summary", summary_file}};
  summary["fit_seconds"] = fit_seconds;
  summary["search_seconds"] = result.search_seconds;
  if (request.stage == kPlanStageGlobal) {
    summary["seconds"] = seconds_since(start_time);
    write_text_file(summary_file, summary.dump(2) + "\n");
    return {std::move(summary), reachable};
  }
  nlohmann::json seconds = {{"fit", fit_seconds}, {"global", result.search_seconds}};
  const bool feasible = reachable && run_full_stage(request, surface, grid, vehicle, start, goal,
                                                    result, dir, summary, seconds);
  if (!reachable) {  // no trajectory: the full stage's fields are empty
    write_text_file((dir / "trajectory.csv").string(), trajectory_csv(nullptr));
    write_text_file((dir / "optima.csv").string(), std::string(kOptimaCsvHeader) + "\n");
    for (const char* name : {"plan.png", "profile.png"}) std::filesystem::remove(dir / name, error);
    for (const char* key : {"travel_time", "global_travel_time", "improvement_percent"}) {
      summary[key] = nullptr;
    }
    summary["optima"] = nlohmann::json::array();
    seconds["local"] = 0.0;
    seconds["profile"] = 0.0;
    seconds["plots"] = 0.0;
  }
  seconds["total"] = seconds_since(start_time);
  summary["seconds"] = std::move(seconds);
  write_text_file(summary_file, summary.dump(2) + "\n");
  return {std::move(summary), feasible};
}

}  // namespace talus::experiments
