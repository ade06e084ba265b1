#include "optimiser_quality_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/sample_statistics.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/verify_profile.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/report.hpp"
#include "talus/scenarios/fractal_battery.hpp"

namespace talus::experiments {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Reference configurations planned on a DEM case (the first of
/// reference_configurations(): the default with the polish). A DEM plan
/// takes up to minutes (Big Tujunga with its feedback rounds), and the
/// issue's travel-time target is the battery's.
constexpr std::size_t kDemConfigurations = 1;

/// The targets.
constexpr double kCertifiedTarget = 0.9;  ///< fraction of the default plan's optima
constexpr double kWithinPercent = 1.0;    ///< of the stored reference [%]
constexpr double kWithinTarget = 0.9;     ///< fraction of battery cases
constexpr double kSecondsTarget = 2.0;    ///< median planning time on the battery [s]

/// The default without its certificate (PlannerOptions::certify false), as runs.csv and
/// reference.json name it.
constexpr const char* kUncertifiedName = "default, uncertified";

/// Planner options without the certificate: the reference configurations are planned as the
/// stored reference's were (issue #36 item 2), and the default is planned once so too.
PlannerOptions uncertified_options() {
  PlannerOptions options;
  options.certify = false;
  return options;
}

/// One planning problem.
struct Problem {
  std::string name;  ///< "fractal seed 3", a DEM's file stem
  bool battery = false;
  std::shared_ptr<const BPatch> surface;
  /// The biquintic B-patch through the same nodes (battery cases only).
  std::shared_ptr<const BPatch> quintic_surface;
  Vehicle vehicle;
  Vec2 start, goal;
  double start_speed = 0.0;  ///< [m/s]; the control case's (no_corridor_problem)
  bool is_control = false;   ///< no_corridor_problem: no corridor exists
};

/// A local-stage configuration of the planner.
struct Configuration {
  std::string name;
  PathOptimizerOptions local;
  /// Of the B-patch planned on (BPatch::interpolate): 5 plans on another
  /// terrain model, so its travel times join neither the reference nor the
  /// comparison with it (battery cases only).
  int surface_degree = 3;
  bool in_reference() const { return surface_degree == 3; }
};

Configuration configuration(PathFormulation formulation, PathSolver solver,
                            std::size_t control_points, std::size_t restarts, bool polish = true) {
  Configuration c;
  c.local.more_control_points.clear();  // one control-point count per configuration
  c.local.formulation = formulation;
  c.local.solver = solver;
  c.local.control_points = control_points;
  c.local.max_control_points = std::max(c.local.max_control_points, control_points);
  c.local.restarts = restarts;
  c.local.polish = polish;
  c.name = formulation == PathFormulation::kSimultaneous
               ? std::string("simultaneous")
               : "nested " + std::string(to_string(solver));
  c.name += ", M " + std::to_string(control_points) + ", " + std::to_string(restarts) +
            (restarts == 1 ? " restart" : " restarts");
  if (formulation == PathFormulation::kNested) c.name += polish ? ", polished" : ", no polish";
  // 100 iterations per phase, as the polish: on the battery the free phase
  // never converged in 300 and took most of a case's time.
  c.local.simultaneous_lateral_iterations = c.local.simultaneous_max_iterations = 100;
  return c;
}

/// The default local stage with the polish.
Configuration polished_default() {
  Configuration c;
  c.local.polish = true;
  c.name = "default, polished";
  return c;
}

/// The default with the polish on the biquintic B-patch through the same
/// nodes (BPatch::interpolate(grid, 5)): the polish NLP's constraint Jacobian
/// holds the curvature's gradient, which the bicubic's third derivatives make
/// jump at every knot line; on the C4 biquintic it is continuous.
Configuration polished_default_biquintic() {
  Configuration c = polished_default();
  c.surface_degree = 5;
  c.name = "default, polished, biquintic B-patch (another terrain model: not in the reference)";
  return c;
}

/// The local stage that was the default before 16 control points with two
/// restarts: an 8-point fit and a further start at 16, no restart.
Configuration former_default() {
  Configuration c = configuration(PathFormulation::kNested, PathSolver::kIpopt, 8, 0, false);
  c.local.more_control_points = {16};
  c.name = "nested ipopt, M 8 and a start at 16, 0 restarts, no polish (the former default)";
  return c;
}

/// The configurations planned besides the default (the stored reference is the best over
/// one full run of them): the default (16 control points, 2 restarts)
/// with the polish, the nested Ipopt stage with 2 restarts at 8 control
/// points with the polish and at 24 without it, the former default, NLopt's
/// LBFGS with 2 restarts and the polish at 8, and the simultaneous NLP alone
/// at 8 and 16; the default itself joins it (run_case). Besides the
/// reference, the polished default on the biquintic B-patch. The
/// simultaneous NLP searches at the optimiser's own default spacing
/// (kSearchSpacingFactor times the final one): at the final spacing its
/// finite-difference Hessian takes minutes per candidate on the battery. 32
/// control points and BOBYQA are left out: with them one case took over 4
/// CPU-minutes. Quick mode: the default with the polish.
std::vector<Configuration> reference_configurations(bool quick) {
  const Configuration polished = polished_default();
  if (quick) return {polished};
  return {polished,
          configuration(PathFormulation::kNested, PathSolver::kIpopt, 8, 2),
          configuration(PathFormulation::kNested, PathSolver::kIpopt, 24, 2, false),
          former_default(),
          configuration(PathFormulation::kNested, PathSolver::kNloptLbfgs, 8, 2),
          configuration(PathFormulation::kSimultaneous, PathSolver::kIpopt, 8, 0),
          configuration(PathFormulation::kSimultaneous, PathSolver::kIpopt, 16, 0),
          polished_default_biquintic()};
}

/// One plan of one problem with one configuration.
struct Run {
  PlannerStatus status = PlannerStatus::kUnreachable;
  std::string message;
  double travel_time = kInf;  ///< the best trajectory's [s]
  double seconds = 0.0;       ///< plan() wall time
  std::size_t optimisations = 0, converged = 0;
  /// PlannerOptions::certify: optima with a certificate, and those it certified (issue #36
  /// item 1); the certificates that found a faster path (kept), their time, and the largest
  /// relative improvement any found.
  std::size_t certificates = 0, certified = 0, certificates_kept = 0;
  double certificate_seconds = 0.0, best_improvement = 0.0;
  std::size_t feedback_rounds = 0;
  bool verified = false;  ///< verify_profile and a fresh evaluation agree
  std::string verification;
  /// Planned on the reference's terrain model (Configuration::in_reference).
  bool comparable = true;
  bool feasible() const { return std::isfinite(travel_time); }
};

/// The best trajectory passes verify_profile against its own limits, and a
/// fresh evaluation of its curve gives the same travel time (1e-9 relative).
void verify(const Problem& p, const BPatch& surface, const PlannerOptions& options,
            const Trajectory& best, Run& run) {
  const ProfileVerification check = verify_profile(*best.limits, best.profile);
  if (!check.passed()) {
    run.verification = "verify_profile: " + std::string(to_string(check.status));
    return;
  }
  TrajectoryOptions evaluation;
  evaluation.station_spacing = resolve_station_spacing(options.station_spacing, surface, p.vehicle);
  const Trajectory fresh = evaluate_trajectory(surface, p.vehicle, best.path->curve(), evaluation);
  const double difference = std::abs(fresh.travel_time() - best.travel_time());
  if (!fresh.feasible() || !(difference <= 1e-9 * best.travel_time())) {
    run.verification = "fresh evaluation: " + sig3(fresh.travel_time()) + " s against " +
                       sig3(best.travel_time()) + " s";
    return;
  }
  run.verified = true;
}

Run run_plan(const Problem& p, const Configuration& configuration, PlannerOptions options = {}) {
  const PathOptimizerOptions& local = configuration.local;
  const std::shared_ptr<const BPatch>& shared =
      configuration.in_reference() ? p.surface : p.quintic_surface;
  const BPatch& surface = *shared;
  options.local = local;
  if (local.formulation == PathFormulation::kSimultaneous && local.station_spacing == 0.0) {
    options.local.station_spacing = search_station_spacing(local, surface, p.vehicle);
  }
  PlanningProblem problem(shared, p.vehicle, p.start, p.goal);
  problem.start_speed = p.start_speed;
  const PlannerResult result = plan(problem, options);
  Run run;
  run.comparable = configuration.in_reference();
  run.status = result.status;
  run.message = result.message;
  run.seconds = result.seconds.total;
  run.feedback_rounds = result.feedback_rounds;
  for (const CandidateOutcome& c : result.candidates) {
    if (!c.optimization) continue;
    ++run.optimisations;
    run.converged += c.optimization->converged ? 1 : 0;
    if (!c.certificate) continue;
    ++run.certificates;
    run.certified += c.certificate->certified ? 1 : 0;
    run.certificates_kept += c.certificate_kept ? 1 : 0;
    run.certificate_seconds += c.certificate->seconds;
    run.best_improvement = std::max(run.best_improvement, c.certificate->improvement);
  }
  if (const Trajectory* best = result.best()) {
    run.travel_time = best->travel_time();
    verify(p, surface, options, *best, run);
  }
  return run;
}

/// The independent check of a default plan without a trajectory (issue #36 item 5): the same
/// query with kCheckFeedbackFactor times the feedback rounds on a lattice twice as fine. A
/// feasible plan there means the default missed a drivable corridor; none agrees that the
/// default's "no trajectory" stands.
constexpr std::size_t kCheckFeedbackFactor = 4;

Run independent_check(const Problem& p) {
  PlannerOptions options;
  options.feedback_rounds *= kCheckFeedbackFactor;
  options.global.lattice_spacing = 0.5 * p.surface->cellsize();
  return run_plan(p, Configuration{}, options);
}

/// One problem: the default plan and the reference plans.
struct Case {
  Problem problem;
  Run default_run;
  /// independent_check(), when the default plan has no trajectory.
  std::optional<Run> check;
  /// The default without its certificate (issue #36 item 1: what the certificate costs and
  /// gains), for a case whose default plan has a trajectory.
  std::optional<Run> uncertified;
  /// No trajectory by default, and none in the independent check either.
  bool agreed_no_corridor() const { return !default_run.feasible() && check && !check->feasible(); }
  std::vector<Run> reference;  ///< one per reference configuration
  /// This run's best travel time over the default and every reference plan [s], and the
  /// configuration that gave it ("default" or a configuration's name).
  double run_best = kInf;
  std::string run_best_configuration;
  /// What the plans are compared with [s]: the stored reference's time when the case is in it
  /// (stored_reference), else run_best.
  double reference_time = kInf;
  bool stored_reference = false;
  std::string reference_configuration;  ///< the configuration that gave reference_time
  /// 100 (default / reference − 1); NaN unless both are feasible.
  double above_reference_percent() const { return above_percent(default_run); }
  double above_percent(const Run& r) const {
    return r.feasible() && r.comparable && std::isfinite(reference_time)
               ? 100.0 * (r.travel_time / reference_time - 1.0)
               : kNaN;
  }
};

/// The default plan and one plan per configuration of `reference` up to
/// `configurations` of them (the DEM cases take only the first: a plan of
/// one of them takes minutes).
Case run_case(Problem problem, const std::vector<Configuration>& reference,
              std::size_t configurations) {
  Case c;
  c.problem = std::move(problem);
  c.default_run = run_plan(c.problem, Configuration{});
  if (!c.default_run.feasible()) c.check = independent_check(c.problem);
  c.run_best = c.default_run.travel_time;
  c.run_best_configuration = "default";
  // The default's trajectory is this one's or faster (a certificate keeps only a faster
  // path), so it never beats the default; it is planned for the comparison.
  if (c.default_run.feasible())
    c.uncertified = run_plan(c.problem, Configuration{}, uncertified_options());
  for (std::size_t k = 0; k < std::min(configurations, reference.size()); ++k) {
    c.reference.push_back(run_plan(c.problem, reference[k], uncertified_options()));
    const Run& r = c.reference.back();
    if (r.comparable && r.travel_time < c.run_best) {
      c.run_best = r.travel_time;
      c.run_best_configuration = reference[k].name;
    }
  }
  c.reference_time = c.run_best;
  c.reference_configuration = c.run_best_configuration;
  return c;
}

/// The fixed reference (issue #36 item 2): the best travel time per case of one heavy run of
/// this experiment, frozen in data/references/optimiser_quality.json with the commit and the
/// configurations that produced it, so that a configuration added later, or a lucky run, does
/// not move the target. Each run writes its own best per case as reference.json in the same
/// format; freezing a new reference is copying that file (data/references/README.md).
struct StoredCase {
  double travel_time = kInf;  ///< [s]
  std::string configuration;  ///< the configuration that gave it
};
struct StoredReference {
  std::string commit;                       ///< the commit whose run produced it
  std::vector<std::string> configurations;  ///< the configurations that took part
  std::vector<std::pair<std::string, StoredCase>> cases;
  const StoredCase* find(const std::string& name) const {
    for (const auto& [case_name, stored] : cases)
      if (case_name == name) return &stored;
    return nullptr;
  }
};

constexpr const char* kStoredReferenceFile = "references/optimiser_quality.json";

/// Reads `path` (InputError naming the file and what is wrong).
StoredReference read_stored_reference(const fs::path& path) {
  const auto fail = [&](const std::string& what) -> StoredReference {
    throw InputError(path.string() + ": " + what +
                     " (optimiser-quality's fixed reference; data/references/README.md)");
  };
  if (!fs::exists(path)) return fail("no such file");
  Json json;
  try {
    std::ifstream in(path);
    json = Json::parse(in);
  } catch (const Json::exception& e) {
    return fail(std::string("not JSON: ") + e.what());
  }
  StoredReference out;
  try {
    out.commit = json.at("commit").get<std::string>();
    out.configurations = json.at("configurations").get<std::vector<std::string>>();
    for (const Json& c : json.at("cases")) {
      StoredCase stored{c.at("travel_time").get<double>(),
                        c.at("configuration").get<std::string>()};
      if (!(stored.travel_time > 0.0 && std::isfinite(stored.travel_time)))
        return fail("case '" + c.at("case").get<std::string>() + "' has travel_time " +
                    csv_number(stored.travel_time) + ", expected a positive number of seconds");
      out.cases.emplace_back(c.at("case").get<std::string>(), stored);
    }
  } catch (const Json::exception& e) {
    return fail(std::string("expected the keys commit, configurations and cases[] with case, "
                            "travel_time, configuration: ") +
                e.what());
  }
  if (out.cases.empty()) return fail("no cases");
  return out;
}

/// This run's best per case, in the stored reference's format (commit left empty: whoever
/// freezes it names the commit that built the binary).
std::string reference_json(const std::vector<Case>& cases,
                           const std::vector<Configuration>& configurations) {
  Json json;
  json["description"] =
      "Best travel time per case over the configurations below, on the interpolating bicubic "
      "B-patch: the fixed reference of talus experiment optimiser-quality (issue #36 item 2)";
  json["commit"] = "";
  json["command"] =
      "talus experiment optimiser-quality --out DIR; DIR/optimiser-quality/reference.json";
  Json names = Json::array({"default", kUncertifiedName});
  for (const Configuration& c : configurations)
    if (c.in_reference()) names.push_back(c.name);
  json["configurations"] = names;
  json["cases"] = Json::array();
  for (const Case& c : cases) {
    if (!std::isfinite(c.run_best)) continue;
    json["cases"].push_back({{"case", c.problem.name},
                             {"travel_time", c.run_best},
                             {"configuration", c.run_best_configuration}});
  }
  return json.dump(2) + "\n";
}

/// Compares every case that the stored reference holds with it instead of this run's best.
/// Returns how many plans of this run are faster than their stored reference by more than
/// 1e-6 (relative): a sign that the reference should be refreshed.
std::size_t apply_stored_reference(std::vector<Case>& cases, const StoredReference& stored) {
  std::size_t faster = 0;
  for (Case& c : cases) {
    const StoredCase* s = stored.find(c.problem.name);
    if (s == nullptr) continue;
    c.reference_time = s->travel_time;
    c.reference_configuration = s->configuration;
    c.stored_reference = true;
    const auto count = [&](const Run& r) {
      faster += r.comparable && r.travel_time < s->travel_time * (1.0 - 1e-6) ? 1 : 0;
    };
    count(c.default_run);
    if (c.uncertified) count(*c.uncertified);
    for (const Run& r : c.reference) count(r);
  }
  return faster;
}

std::vector<Problem> battery_problems(std::size_t seeds) {
  std::vector<Problem> out;
  for (std::size_t seed = 1; seed <= seeds; ++seed) {
    Problem p;
    p.name = "fractal seed " + std::to_string(seed);
    p.battery = true;
    const ElevationGrid grid = generate_fractal_terrain(scenarios::battery_terrain(seed));
    p.surface = std::make_shared<const BPatch>(BPatch::interpolate(grid));
    p.quintic_surface = std::make_shared<const BPatch>(BPatch::interpolate(grid, 5));
    p.vehicle = scenarios::battery_point_mass_ugv();
    p.start = scenarios::kBatteryStart;
    p.goal = scenarios::kBatteryGoal;
    out.push_back(std::move(p));
  }
  return out;
}

/// The control case of the honest exits: a query with no drivable corridor, so the plan must
/// end without a trajectory, say why, and the independent check must agree. The battery's UGV
/// starts at 6.5 m/s on top of a dome of radius 3 m: every direction there curves down at
/// 1/3 m⁻¹, so the point mass keeps contact only up to sqrt(g R) = 5.42 m/s on any path.
Problem no_corridor_problem() {
  Problem p;
  p.name = "control: 6.5 m/s on a 3 m dome";
  SphereCapOptions dome;
  dome.shape = {17, 17, 0.25, 0.0, 0.0};
  dome.radius = 3.0;
  p.surface = std::make_shared<const BPatch>(BPatch::interpolate(generate_sphere_cap(dome)));
  p.vehicle = scenarios::battery_point_mass_ugv();
  p.start = Vec2(2.0, 2.0);
  p.goal = Vec2(3.2, 2.0);
  p.start_speed = 6.5;
  p.is_control = true;
  return p;
}

/// Every bundled DEM with the documented rover, 10 % -> 90 % of its diagonal.
std::vector<Problem> dem_problems(const fs::path& data_dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(data_dir / "terrain")) {
    if (entry.path().extension() == ".asc") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  const Vehicle rover = load_vehicle((data_dir / "vehicles" / "rover.yaml").string());
  std::vector<Problem> out;
  for (const fs::path& file : files) {
    const ElevationGrid grid = read_esri_ascii(file.string());
    Problem p;
    p.name = file.stem().string();
    p.surface = std::make_shared<const BPatch>(BPatch::interpolate(grid));
    p.vehicle = rover;
    const Vec2 low(grid.x_min(), grid.y_min()), high(grid.x_max(), grid.y_max());
    p.start = low + 0.1 * (high - low);
    p.goal = low + 0.9 * (high - low);
    out.push_back(std::move(p));
  }
  return out;
}

double fraction(std::size_t part, std::size_t whole) {
  return whole == 0 ? kNaN : static_cast<double>(part) / static_cast<double>(whole);
}

std::string percent_text(double f) {
  return std::isfinite(f) ? fmt("%.1f", 100.0 * f) + " %" : "–";
}

/// ", further starts at 16" for more_control_points {16}; empty for none.
std::string more_text(const std::vector<std::size_t>& more) {
  if (more.empty()) return "";
  std::string text = ", further starts at";
  for (std::size_t k = 0; k < more.size(); ++k) text += (k ? ", " : " ") + std::to_string(more[k]);
  return text;
}

std::string pass_text(bool pass) {
  return pass ? "**met**" : "**not met**";
}

/// Statistics of one configuration (or the default) over a set of cases.
struct Stats {
  std::size_t cases = 0, feasible = 0, verified = 0, optimisations = 0, converged = 0;
  std::size_t certificates = 0, certified = 0, certificates_kept = 0;
  std::size_t within = 0;  ///< feasible and within kWithinPercent of the reference
  double best_improvement = 0.0;
  std::vector<double> certificate_seconds;  ///< per plan with a certificate [s]
  double median_above = kNaN, worst_above = kNaN, median_seconds = kNaN;
};

/// `run_of(case)` is the run to count, or nullptr where the case has none.
template <class RunOf>
Stats stats(const std::vector<Case>& cases, bool battery_only, RunOf run_of) {
  Stats s;
  std::vector<double> above, seconds;
  for (const Case& c : cases) {
    if (battery_only && !c.problem.battery) continue;
    const Run* run = run_of(c);
    if (run == nullptr) continue;
    const Run& r = *run;
    ++s.cases;
    s.optimisations += r.optimisations;
    s.converged += r.converged;
    s.certificates += r.certificates;
    s.certified += r.certified;
    s.certificates_kept += r.certificates_kept;
    s.best_improvement = std::max(s.best_improvement, r.best_improvement);
    if (r.certificates > 0) s.certificate_seconds.push_back(r.certificate_seconds);
    seconds.push_back(r.seconds);
    if (!r.feasible()) continue;
    ++s.feasible;
    s.verified += r.verified ? 1 : 0;
    const double a = c.above_percent(r);
    if (!std::isfinite(a)) continue;  // another terrain model
    above.push_back(a);
    s.within += a <= kWithinPercent ? 1 : 0;
  }
  if (!above.empty()) {
    s.median_above = upper_median(above);
    s.worst_above = *std::max_element(above.begin(), above.end());
  }
  if (!seconds.empty()) s.median_seconds = upper_median(seconds);
  return s;
}

/// Percent above the reference per case, for the default and every
/// reference configuration (one column each).
FigureLink spread_figure(const std::vector<Case>& cases,
                         const std::vector<Configuration>& configurations, const fs::path& dir) {
  GnuplotFigure plot(dir, "spread_above_reference");
  auto data = open_output_file(plot.file(".dat"));
  data << "# column: 0 = default, k = reference configuration k; y: percent above the "
          "reference (feasible plans)\n";
  for (const Case& c : cases) {
    if (const double a = c.above_reference_percent(); std::isfinite(a))
      data << 0 << " " << csv_number(a) << "\n";
    for (std::size_t k = 0; k < c.reference.size(); ++k)
      if (const double a = c.above_percent(c.reference[k]); std::isfinite(a))
        data << k + 1 << " " << csv_number(a) << "\n";
  }
  close_output_file(data, plot.file(".dat"));
  // One row per configuration, its whole name as the row's label (gnuplot
  // sizes the left margin to it): rotated under the axis they were cut off.
  std::string tics = "set ytics (\"default\" 0";
  for (std::size_t k = 0; k < configurations.size(); ++k)
    tics += ", " + gnuplot_string(configurations[k].name) + " " + std::to_string(k + 1);
  tics += ")\n";
  const int height = 160 + 50 * static_cast<int>(configurations.size() + 1);
  plot.describe("travel time above the fixed reference per case and configuration",
                plot.name(".dat"))
      .canvas(1400, height)
      .title("Travel time above the fixed reference, every case");
  plot << tics << "set yrange [" + std::to_string(configurations.size()) + ".5:-0.5]\n"
       << "set xlabel 'above the reference [%]'\nset grid xtics\nset key off\n"
       << "set xrange [-0.1:*]\n";
  plot.plot({gnuplot_string(plot.name(".dat")) + " using 2:1 with points pt 7 ps 1.2"});
  plot.render();
  return {"Travel time above the fixed reference, every case and configuration", plot.name(".png")};
}

/// One row per plan (the default, then each configuration planned on the
/// case) at full precision, so a new local stage can be compared against a
/// stored reference without re-running it. Configuration 0 is the default,
/// k the k-th reference configuration, as in spread_above_reference.dat, and
/// the last (one past them) the default with the certificate.
std::string runs_csv(const std::vector<Case>& cases,
                     const std::vector<Configuration>& configurations) {
  std::string csv =
      "case,configuration,name,status,travel_time,reference_time,above_reference_percent,"
      "converged,optimisations,plan_seconds,feedback_rounds,verified,certified,certificates,"
      "certificate_seconds\n";
  const auto row = [&](const Case& c, std::size_t k, const std::string& name, const Run& r) {
    csv += "\"" + c.problem.name + "\"," + std::to_string(k) + ",\"" + name + "\"," +
           std::string(to_string(r.status)) + "," + csv_number(r.travel_time, 10) + "," +
           csv_number(c.reference_time, 10) + "," + csv_number(c.above_percent(r)) + "," +
           std::to_string(r.converged) + "," + std::to_string(r.optimisations) + "," +
           csv_number(r.seconds, 4) + "," + std::to_string(r.feedback_rounds) + "," +
           (r.verified ? "1" : "0") + "," + std::to_string(r.certified) + "," +
           std::to_string(r.certificates) + "," + csv_number(r.certificate_seconds, 4) + "\n";
  };
  for (const Case& c : cases) {
    row(c, 0, "default", c.default_run);
    for (std::size_t k = 0; k < c.reference.size(); ++k)
      row(c, k + 1, configurations[k].name, c.reference[k]);
    if (c.uncertified) row(c, configurations.size() + 1, kUncertifiedName, *c.uncertified);
  }
  return csv;
}

}  // namespace

void run_optimiser_quality(const ExperimentContext& context) {
  require_gnuplot();
  const auto start = Clock::now();
  const bool quick = context.quick;
  const StoredReference stored = read_stored_reference(context.data_dir / kStoredReferenceFile);
  std::vector<Problem> problems = battery_problems(quick ? 2 : 25);  // issue #12: seeds 1-25
  if (!quick) {
    for (Problem& p : dem_problems(context.data_dir)) problems.push_back(std::move(p));
  }
  problems.push_back(no_corridor_problem());
  const std::vector<Configuration> reference = reference_configurations(quick);
  std::vector<Case> cases;
  // One line per case on stderr: the full run takes tens of minutes.
  ProgressLine& progress = *context.progress;
  for (std::size_t k = 0; k < problems.size(); ++k) {
    // The control case has no trajectory to compare: its default plan and its check only.
    const std::size_t configurations = problems[k].battery      ? reference.size()
                                       : problems[k].is_control ? 0
                                                                : kDemConfigurations;
    progress.update("optimiser-quality: case " + std::to_string(k + 1) + " of " +
                        std::to_string(problems.size()) + " (" + problems[k].name + ")",
                    k, problems.size());
    cases.push_back(run_case(std::move(problems[k]), reference, configurations));
    const Case& c = cases.back();
    progress.note("optimiser-quality: case " + std::to_string(k + 1) + "/" +
                  std::to_string(problems.size()) + " (" + c.problem.name + "): default " +
                  sig3(c.default_run.travel_time) + " s in " + sig3(c.default_run.seconds) +
                  " s, best of this run " + sig3(c.run_best) + " s, " + sig3(seconds_since(start)) +
                  " s so far");
  }
  const std::size_t faster_than_stored = apply_stored_reference(cases, stored);
  std::size_t stored_cases = 0;
  double stored_battery_total = 0.0;
  for (const Case& c : cases) {
    stored_cases += c.stored_reference ? 1 : 0;
    if (c.stored_reference && c.problem.battery) stored_battery_total += c.reference_time;
  }

  const auto default_of = [](const Case& c) -> const Run* { return &c.default_run; };
  const Stats all = stats(cases, false, default_of);
  const Stats battery = stats(cases, true, default_of);
  const double converged = fraction(all.converged, all.optimisations);
  const double within = fraction(battery.within, battery.cases);
  // Issue #36 item 1: the default's certificates, and the default without them.
  const auto uncertified_of = [](const Case& c) -> const Run* {
    return c.uncertified ? &*c.uncertified : nullptr;
  };
  const Stats uncertified_all = stats(cases, false, uncertified_of);
  const Stats uncertified_battery = stats(cases, true, uncertified_of);
  const double certified = fraction(all.certified, all.certificates);
  const double uncertified_within = fraction(uncertified_battery.within, uncertified_battery.cases);
  std::size_t certified_slower = 0;  // a certificate keeps only a faster path: must stay 0
  for (const Case& c : cases)
    certified_slower +=
        c.uncertified && c.default_run.travel_time > c.uncertified->travel_time * (1.0 + 1e-9) ? 1
                                                                                               : 0;
  const double certificate_seconds =
      all.certificate_seconds.empty() ? kNaN : upper_median(all.certificate_seconds);

  // Issue #36 item 5: plans without a trajectory, and whether a drivable corridor existed.
  std::size_t without = 0, check_feasible = 0, agreed = 0, named = 0, control_agreed = 0;
  for (const Case& c : cases) {
    if (c.default_run.feasible()) continue;
    ++without;
    check_feasible += c.check && c.check->feasible() ? 1 : 0;
    agreed += c.agreed_no_corridor() ? 1 : 0;
    named += c.default_run.message.find("near (") != std::string::npos ? 1 : 0;
    control_agreed += c.problem.is_control && c.agreed_no_corridor() ? 1 : 0;
  }

  ExperimentSummary& summary = *context.summary;
  summary.set("cases", static_cast<double>(all.cases), "count");
  summary.set("default_without_trajectory", static_cast<double>(without), "count",
              "cases whose default plan has no trajectory (the control case among them)");
  summary.set("default_without_trajectory_named", static_cast<double>(named), "count",
              "of those, the message names the point where the best corridor fails");
  summary.set("independent_check_feasible", static_cast<double>(check_feasible), "count",
              "of those, the independent check (4x the feedback rounds, a lattice twice as "
              "fine) found a trajectory: a corridor the default missed");
  summary.set("independent_check_agrees", static_cast<double>(agreed), "count",
              "of those, the independent check found none either");
  summary.set("control_case_agrees", static_cast<double>(control_agreed), "count",
              "the no-corridor control case: no trajectory, and the check agrees");
  summary.set("battery_cases", static_cast<double>(battery.cases), "count");
  summary.set("default_feasible", static_cast<double>(all.feasible), "count");
  summary.set("default_verified", static_cast<double>(all.verified), "count",
              "best trajectories accepted by verify_profile and a fresh evaluation");
  summary.set("default_local_optimisations", static_cast<double>(all.optimisations), "count");
  summary.set("default_converged_fraction", converged, "1",
              "local optimisations converged by the solver's own status, every case");
  summary.set("battery_within_1pct_fraction", within, "1",
              "battery cases whose default plan is within 1 % of the fixed reference");
  summary.set("battery_median_above_reference_percent", battery.median_above, "%");
  summary.set("battery_worst_above_reference_percent", battery.worst_above, "%");
  summary.set("battery_median_plan_seconds", battery.median_seconds, "s");
  summary.set("certificate_optima", static_cast<double>(all.certificates), "count",
              "optima of the default plan with a certificate (PlannerOptions::certify, on by "
              "default), every case (issue #36 item 1)");
  summary.set("certified_optima", static_cast<double>(all.certified), "count",
              "of those, certified: no faster path within a quarter cell by more than 0.05 %");
  summary.set("certified_fraction", certified, "1");
  summary.set("certificates_kept", static_cast<double>(all.certificates_kept), "count",
              "certificates that found a faster path, which the plan keeps");
  summary.set("certificate_best_improvement_percent", 100.0 * all.best_improvement, "%",
              "the largest improvement a certificate found");
  summary.set("certificate_median_seconds", certificate_seconds, "s",
              "the certificates' time per plan (every optimum's), median over the cases");
  summary.set("certified_slower_than_uncertified", static_cast<double>(certified_slower), "count",
              "cases whose default plan is slower than the same plan without the certificate "
              "(1e-9)");
  summary.set("uncertified_battery_median_plan_seconds", uncertified_battery.median_seconds, "s",
              "median planning time on the battery without the certificate");
  summary.set("uncertified_battery_within_1pct_fraction", uncertified_within, "1",
              "battery cases whose plan without the certificate is within 1 % of the fixed "
              "reference");
  summary.set("reference_configurations", static_cast<double>(reference.size()), "count",
              "configurations this run plans besides the default");
  summary.set("stored_reference_cases", static_cast<double>(stored_cases), "count",
              "cases compared with the fixed reference of " + std::string(kStoredReferenceFile));
  summary.set("stored_reference_battery_total_seconds", stored_battery_total, "s",
              "sum of the stored reference's travel times over the battery cases run");
  summary.set("runs_faster_than_stored_reference", static_cast<double>(faster_than_stored), "count",
              "plans of this run faster than the stored reference (1e-6): refresh it");

  Table targets({"target (issue #12)", "measured", ""});
  targets.row(
      {"every case a feasible, verified trajectory, or no trajectory with the "
       "independent check agreeing that no corridor exists",
       std::to_string(all.verified) + " verified, " + std::to_string(agreed) +
           " agreed without, of " + std::to_string(all.cases),
       pass_text(all.verified + agreed == all.cases)});
  // The issue retired "converged by the solver's status" (the nested objective kinks at
  // switching points by construction) for the certificate; the status stays reported below.
  targets.row({">= 90 % of the default plan's optima certified (battery and DEMs)",
               percent_text(certified) + " (" + std::to_string(all.certified) + " of " +
                   std::to_string(all.certificates) + ")",
               pass_text(certified >= kCertifiedTarget)});
  targets.row({"default within 1 % of the fixed reference on >= 90 % of the battery",
               percent_text(within) + " (" + std::to_string(battery.within) + " of " +
                   std::to_string(battery.cases) + ")",
               pass_text(within >= kWithinTarget)});
  targets.row({"median planning time on the battery <= 2 s, the certificate included",
               sig3(battery.median_seconds) + " s (certificates " + sig3(certificate_seconds) +
                   " s per plan, median; without them " + sig3(uncertified_battery.median_seconds) +
                   " s)",
               pass_text(battery.median_seconds <= kSecondsTarget)});

  Table per_configuration({"configuration", "feasible", "verified", "converged", "certified",
                           "within 1 % (battery)", "median above ref. [%]", "worst above ref. [%]",
                           "median plan time [s]"});
  const auto config_row = [&](const std::string& name, const Stats& s, const Stats& b,
                              bool comparable) {
    per_configuration.row(
        {name, std::to_string(s.feasible) + " / " + std::to_string(s.cases),
         std::to_string(s.verified), percent_text(fraction(s.converged, s.optimisations)),
         s.certificates == 0 ? "–"
                             : std::to_string(s.certified) + " / " + std::to_string(s.certificates),
         comparable ? std::to_string(b.within) + " / " + std::to_string(b.cases) : "–",
         sig3(s.median_above), sig3(s.worst_above), sig3(s.median_seconds)});
  };
  config_row("default (PlannerOptions{})", all, battery, true);
  config_row("default without the certificate (certify false)", uncertified_all,
             uncertified_battery, true);
  for (std::size_t k = 0; k < reference.size(); ++k) {
    const auto of = [k](const Case& c) -> const Run* {
      return k < c.reference.size() ? &c.reference[k] : nullptr;
    };
    config_row(reference[k].name, stats(cases, false, of), stats(cases, true, of),
               reference[k].in_reference());
  }

  Table per_case({"case", "status", "travel time [s]", "reference [s]", "reference from",
                  "above ref. [%]", "converged", "feedback rounds", "plan time [s]", "verified",
                  "certified", "certificates [s]", "without them [s]"});
  for (const Case& c : cases) {
    const Run& r = c.default_run;
    per_case.row(
        {c.problem.name, std::string(to_string(r.status)), r.feasible() ? sig3(r.travel_time) : "–",
         std::isfinite(c.reference_time) ? sig3(c.reference_time) : "–",
         !std::isfinite(c.reference_time) ? "–"
         : c.stored_reference             ? "stored: " + c.reference_configuration
                                          : "this run: " + c.reference_configuration,
         sig3(c.above_reference_percent()),
         std::to_string(r.converged) + " / " + std::to_string(r.optimisations),
         std::to_string(r.feedback_rounds), sig3(r.seconds),
         r.feasible() ? (r.verified ? "yes" : "no: " + r.verification) : "–",
         std::to_string(r.certified) + " / " + std::to_string(r.certificates),
         sig3(r.certificate_seconds), c.uncertified ? sig3(c.uncertified->travel_time) : "–"});
  }

  const PathOptimizerOptions defaults;
  Report report("optimiser-quality: the planner's local stage against a fixed reference");
  report
      .paragraph(
          "Cases: " + std::to_string(battery.cases) +
          " terrains of the fractal battery of issue #12 (Iagnemma, Shimoda & Shiller, IROS "
          "2008, §V: 129 × 129 nodes at 0.24 m, D 2.05, height scale 4.2 m, a 1 m undulation "
          "over 30 m, six 1 m peaks; point-mass UGV with μ 0.7, h 0.06 m, b 0.124 m, 7 m/s, "
          "drive 3, brake 5 m/s²; from (2, 2) to (28.5, 28.5))" +
          (quick ? std::string(" (quick mode: no DEMs).")
                 : " and every bundled DEM with `data/vehicles/rover.yaml` from 10 % to 90 % "
                   "of its diagonal, on the interpolating B-patch."))
      .paragraph(
          "The default plan is `talus::plan` with `PlannerOptions{}` (local stage: " +
          std::string(to_string(defaults.formulation)) + " formulation, " +
          std::string(to_string(defaults.solver)) + ", " + std::to_string(defaults.control_points) +
          " control points" + more_text(defaults.more_control_points) + ", " +
          std::to_string(defaults.restarts) + " restarts, " +
          (defaults.polish ? "polished by the simultaneous NLP" : "no polish") +
          "). The reference of a case is fixed: the fastest trajectory of one heavy run of this "
          "experiment, stored in `data/" +
          std::string(kStoredReferenceFile) + "` (commit " + stored.commit + "; configurations: " +
          [&] {
            std::string names;
            for (std::size_t k = 0; k < stored.configurations.size(); ++k)
              names += (k ? "; " : "") + stored.configurations[k];
            return names;
          }() +
          "), so that adding a configuration does not move the target; a case it does not hold "
          "is compared with this run's best. This run plans the default and the configurations "
          "below on the same bicubic B-patch (the same global stage each time; the biquintic "
          "configuration plans on another terrain model and counts only for convergence and "
          "time); on the DEMs only the first configuration is planned (a DEM plan takes up to "
          "minutes, and the travel-time target is the battery's). " +
          std::to_string(faster_than_stored) +
          " plans of this run are faster than their stored reference (a reason to refresh "
          "it: copy this run's reference.json). A local "
          "optimisation converges when the solver says so: Ipopt Solve_Succeeded or "
          "Solved_To_Acceptable_Level, NLopt a tolerance stop. Every best trajectory is checked "
          "by `verify_profile` against its own limits and by a fresh `evaluate_trajectory` of "
          "its curve (same travel time to 1e-9). The default certifies each optimum "
          "(`PlannerOptions::certify`, `talus plan --certify`, on by default; issue #36 item "
          "1): a BOBYQA search of the box of a quarter cell round every free control point "
          "certifies it when it finds nothing faster by more than 0.05 %, and a faster path it "
          "finds is kept. The default is planned a second time without the certificates, to "
          "show what they cost and gain; the reference configurations are planned without "
          "them, as the stored reference was.")
      .heading("Targets")
      .table(targets)
      .heading("Per configuration (nested against simultaneous)")
      .table(per_configuration)
      .heading("Per case, default plan")
      .table(per_case);
  report.heading("Plans without a trajectory")
      .paragraph(
          "Each default plan without a trajectory, with the reason it gives, and the independent "
          "check: the same query with " +
          std::to_string(kCheckFeedbackFactor) +
          " times the feedback rounds on a lattice twice as fine. A trajectory there means the "
          "default missed a drivable corridor. The last case is a control with no corridor.");
  for (const Case& c : cases) {
    if (c.default_run.feasible()) continue;
    const std::string check =
        !c.check ? "no check"
        : c.check->feasible()
            ? "the check found one: " + sig3(c.check->travel_time) + " s"
            : "the check agrees (" + std::string(to_string(c.check->status)) + ")";
    report.bullet(c.problem.name + ": " + std::string(to_string(c.default_run.status)) + ": " +
                  c.default_run.message + "; " + check);
  }
  const std::vector<FigureLink> links = {spread_figure(cases, reference, context.output_dir)};
  write_text_file(context.output_dir / "runs.csv", runs_csv(cases, reference));
  write_text_file(context.output_dir / "reference.json", reference_json(cases, reference));
  summary.set("wall_seconds", seconds_since(start), "s");
  report.paragraph("Wall time: " + sig3(seconds_since(start)) + " s.");
  report.write(context.output_dir,
               "runs.csv (every plan: travel time, reference, status, "
               "convergence, time), reference.json (this run's best per case, the stored "
               "reference's format), spread_above_reference.dat",
               links);
}

}  // namespace talus::experiments
