#include "shiller_gwo_experiment.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "plan_command.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/optimal/local_stage_summary.hpp"
#include "talus/optimal/planner_parameters.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/report.hpp"

namespace talus::experiments {
namespace {

namespace fs = std::filesystem;

/// One planning problem: a terrain file, a start, a goal.
struct Case {
  std::string name;   ///< folder name
  std::string title;  ///< for the report
  std::string terrain;
  std::string start, goal;
};

/// The real DEM: NASADEM West Bijou escarpment (Colorado) at its 25 m
/// posting, corner to corner across the escarpment, as the README's main job.
Case west_bijou_case(const fs::path& data_dir) {
  const std::string file = (data_dir / "terrain" / "west_bijou_escarpment_nasadem25m.asc").string();
  const ElevationGrid grid = read_esri_ascii(file);
  const auto corner = [](double x, double y) { return fmt("%.6f", x) + "," + fmt("%.6f", y); };
  return {"west-bijou", "West Bijou escarpment, NASADEM 25 m, 3.0 km x 2.0 km", file,
          corner(grid.x_min(), grid.y_min()), corner(grid.x_max(), grid.y_max())};
}

/// The fractal terrain (Shiller & Gwo's test terrains were synthetic): fBm
/// of dimension 2.2 with 40 m relief over 320 m x 320 m at 2 m posting,
/// seed 11, written to the output folder.
Case fractal_case(const fs::path& dir, bool quick) {
  FractalTerrainOptions fractal;
  const std::size_t n = quick ? 81 : 161;
  fractal.shape = {n, n, 2.0, 0.0, 0.0};
  fractal.fractal_dimension = 2.2;
  fractal.height_scale = quick ? 20.0 : 40.0;
  fractal.seed = 11;
  const std::string file = (dir / "fractal.asc").string();
  write_esri_ascii(generate_fractal_terrain(fractal), file);
  const double far = 2.0 * static_cast<double>(n - 1) - 10.0;
  return {"fractal",
          "fractal (fBm, D = 2.2, " + sig3(fractal.height_scale) + " m relief, " +
              sig3(2.0 * static_cast<double>(n - 1)) + " m square, seed 11)",
          file, "10,10", fmt("%g", far) + "," + fmt("%g", far)};
}

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j.at(key).is_number() ? j.at(key).get<double>() : NAN;
}

double finite_or_nan(double value) {
  return std::isfinite(value) ? value : NAN;
}

struct Run {
  std::string case_name, solver;
  long long control_points = 0;
  PlanOutcome outcome;
  const PlannerResult& result() const { return outcome.result; }
  /// A stage's wall time [s] as `talus plan` reports it (fit and plots are the command's).
  double seconds(const char* stage) const { return number(outcome.summary.at("seconds"), stage); }
  double travel_time() const { return finite_or_nan(result().travel_time()); }
  double global_travel_time() const { return finite_or_nan(result().global_travel_time()); }
  LocalStageSummary local() const { return summarise_local_stage(result()); }
};

Run run_plan(const Case& c, const std::string& vehicle, const std::string& solver,
             long long control_points, long long candidates, const fs::path& dir) {
  PlanRequest request;
  request.terrain = c.terrain;
  request.vehicle = vehicle;
  request.start = c.start;
  request.goal = c.goal;
  const ParameterTable<PlannerOptions>& parameters = planner_parameters();
  parameters.set(request.planner, "candidates", candidates);
  request.smoothing = 1.0;  // DEM striping and fBm roughness: see global-search
  parameters.set(request.planner, "solver", solver);
  parameters.set(request.planner, "control_points", control_points);
  request.output_dir = dir.string();
  return {c.name, solver, control_points, plan(request)};
}

double optimality(const CandidateOutcome& c) {
  return c.optimization ? c.optimization->optimality : NAN;
}

/// Two significant digits, or "-" for a missing value.
std::string scientific(double value) {
  return std::isfinite(value) ? fmt("%.1e", value) : "-";
}

void draw_solver_figure(const fs::path& dir, const std::vector<std::string>& solvers) {
  const std::string columns =
      "for [c=1:" + std::to_string(solvers.size()) + "] 'solvers.csv' using ";
  GnuplotFigure figure(dir, "solvers");
  figure.describe("Local solvers compared, from `talus experiment shiller-gwo`.", "solvers.csv.")
          .canvas(1400, 600)
      << "set datafile separator ','\nset style data histograms\n"
      << "set style histogram clustered gap 1\nset style fill solid 0.8 border -1\n"
      << "set grid y lc rgb '#d8d8d8'\nset tics out nomirror\nset key top left\n"
      << "set yrange [0:*]\n"
      << "set multiplot layout 1,2 title 'Local stage: Ipopt against NLopt on the same "
         "candidates'\n"
      << "set title '(a) improvement over the best global candidate'\n"
      << "set ylabel 'improvement [%]'\n"
      << "plot " << columns << "(column(2+3*(c-1))):xtic(1) title columnhead(2+3*(c-1))\n"
      << "set title '(b) local-stage wall time, all candidates'\nset ylabel 'seconds'\n"
      << "plot " << columns << "(column(3+3*(c-1))):xtic(1) title columnhead(2+3*(c-1))\n"
      << "unset multiplot\n";
  if (gnuplot_available()) {
    figure.render();
  } else {
    figure.save();
  }
}

}  // namespace

/// The headline numbers of summary.json. The planner keeps the initial fit when the optimum is
/// slower, so no run's travel time exceeds its best global candidate's.
void summarise(const std::vector<Run>& runs, const std::vector<Run>& study,
               ExperimentSummary& summary) {
  double worst_ratio = 0.0, best = INFINITY, worst = 0.0;
  std::size_t failed = 0;
  for (const std::vector<Run>* set : {&runs, &study}) {
    for (const Run& r : *set) {
      if (!std::isfinite(r.travel_time())) {
        ++failed;
        continue;
      }
      worst_ratio = std::max(worst_ratio, r.travel_time() / r.global_travel_time());
      best = std::min(best, r.travel_time());
      worst = std::max(worst, r.travel_time());
    }
  }
  summary.set("plans_without_trajectory", static_cast<double>(failed), "count");
  summary.set("max_travel_time_over_global", worst_ratio, "1",
              "<= 1: never slower than the best global candidate");
  summary.set("best_travel_time_s", best, "s");
  summary.set("solver_and_control_point_spread", worst / best, "1");
}

void run_shiller_gwo(const ExperimentContext& context) {
  const fs::path& out = context.output_dir;
  const bool quick = context.quick;
  const std::string vehicle = (context.data_dir / "vehicles" / "rover.yaml").string();
  if (!fs::exists(vehicle)) throw InputError("shiller-gwo needs " + vehicle);
  std::vector<Case> cases;
  if (!quick) cases.push_back(west_bijou_case(context.data_dir));
  cases.push_back(fractal_case(out, quick));
  const std::vector<std::string> solvers =
      quick ? std::vector<std::string>{"ipopt", "nlopt-bobyqa"}
            : std::vector<std::string>{"ipopt", "nlopt-lbfgs", "nlopt-bobyqa"};
  const std::vector<long long> control_points =
      quick ? std::vector<long long>{5, 8} : std::vector<long long>{5, 8, 12, 16};
  const long long candidates = quick ? 2 : 3;

  // 1. The solver comparison at the default M = 8 (the Ipopt runs are the
  //    reproduction itself: their folders hold plan.png and profile.png).
  std::vector<Run> runs;
  for (const Case& c : cases) {
    for (const std::string& solver : solvers) {
      runs.push_back(run_plan(c, vehicle, solver, 8, candidates, out / c.name / solver));
    }
  }
  // 2. The control-point study, Ipopt.
  std::vector<Run> study;
  for (const Case& c : cases) {
    for (const long long m : control_points) {
      if (m == 8) continue;  // that run is above
      study.push_back(run_plan(c, vehicle, "ipopt", m, candidates,
                               out / c.name / ("ipopt-m" + std::to_string(m))));
    }
  }

  // Tables.
  std::ostringstream results;
  results << "case,solver,control_points,status,travel_time,global_travel_time,"
             "improvement_percent,local_seconds,total_seconds,evaluations,iterations,"
             "max_optimality,finite_difference_gradients\n";
  std::ostringstream solver_csv;
  solver_csv << "case";
  for (const std::string& s : solvers) solver_csv << "," << s << "," << s << "_s," << s << "_t";
  solver_csv << "\n";
  Report report("shiller-gwo: the two-stage time-optimal planner");
  report.paragraph(
      "Reproduces the method of Shiller & Gwo (1991), *Dynamic motion planning of autonomous "
      "vehicles*, IEEE T-RA 7(2): a global search for the minimum-time corridors (edge cost = "
      "travel time at the speed limit), then a local optimisation of the B-spline path's control "
      "points for the motion time of the exact time-optimal velocity profile. Vehicle: "
      "`data/vehicles/rover.yaml` (point mass, mu 0.7, b/h 1.2, 15 m/s, drive 3 m/s², brakes "
      "6 m/s²). Smoothing B-patch (lambda 1), " +
      std::to_string(candidates) + " global candidates, 16-connected lattice at the cell size.");
  const auto add_row = [&](const Run& r) {
    results << r.case_name << "," << r.solver << "," << r.control_points << ","
            << to_string(r.result().status) << "," << csv_number(r.travel_time()) << ","
            << csv_number(r.global_travel_time()) << ","
            << csv_number(r.result().improvement_percent()) << "," << csv_number(r.seconds("local"))
            << "," << csv_number(r.seconds("total")) << ","
            << csv_number(static_cast<double>(r.local().evaluations)) << ","
            << csv_number(static_cast<double>(r.local().iterations)) << ","
            << csv_number(r.local().worst_optimality) << ","
            << csv_number(static_cast<double>(r.local().finite_difference_fallbacks)) << "\n";
  };
  for (const Run& r : runs) add_row(r);
  for (const Run& r : study) add_row(r);
  write_text_file(out / "results.csv", results.str());

  for (const Case& c : cases) {
    report.heading(c.title)
        .paragraph("Start " + c.start + ", goal " + c.goal + ". Figures of the Ipopt run: [plan](" +
                   c.name +
                   "/ipopt/plan.png) (relief, global candidates, optimised paths, best "
                   "highlighted) and [profile](" +
                   c.name + "/ipopt/profile.png) (best velocity profile under its limit curve).")
        .figure("plan", c.name + "/ipopt/plan.png");
    Table solver_table({"solver", "travel time [s]", "best global candidate [s]", "improvement",
                        "local stage [s]", "whole plan [s]", "evaluations",
                        "max optimality [s/m]"});
    solver_csv << c.name;
    for (const Run& r : runs) {
      if (r.case_name != c.name) continue;
      solver_table.row({r.solver, fmt("%.2f", r.travel_time()), fmt("%.2f", r.global_travel_time()),
                        fmt("%.2f %%", r.result().improvement_percent()),
                        fmt("%.2f", r.seconds("local")), fmt("%.2f", r.seconds("total")),
                        fmt("%.0f", static_cast<double>(r.local().evaluations)),
                        scientific(r.local().worst_optimality)});
      solver_csv << "," << csv_number(r.result().improvement_percent()) << ","
                 << csv_number(r.seconds("local")) << "," << csv_number(r.travel_time());
    }
    solver_csv << "\n";
    report.table(solver_table)
        .paragraph("Local optima of the Ipopt run (one per global candidate):");
    for (const Run& r : runs) {
      if (r.case_name != c.name || r.solver != "ipopt") continue;
      Table optima({"candidate", "initial fit [s]", "optimum [s]", "solver status", "iterations",
                    "optimality [s/m]"});
      for (const CandidateOutcome& o : r.result().candidates) {
        optima.row({std::to_string(o.candidate),
                    fmt("%.2f", finite_or_nan(o.initial.travel_time())),
                    fmt("%.2f", finite_or_nan(o.trajectory.travel_time())),
                    o.optimization ? o.optimization->solver_status : std::string("-"),
                    std::to_string(o.optimization ? o.optimization->iterations : 0),
                    scientific(optimality(o))});
      }
      std::string timings = "Stage timings [s]: ";
      for (const char* stage : {"fit", "global", "local", "profile", "plots", "total"}) {
        timings += std::string(stage) + " " + fmt("%.2f", r.seconds(stage)) + "; ";
      }
      report.table(optima).paragraph(timings);
    }
    Table study_table({"M", "travel time [s]", "local stage [s]"});
    for (const long long m : control_points) {
      for (const std::vector<Run>* set : {&runs, &study}) {
        for (const Run& r : *set) {
          if (r.case_name != c.name || r.solver != "ipopt" || r.control_points != m) continue;
          study_table.row(
              {std::to_string(m), fmt("%.2f", r.travel_time()), fmt("%.2f", r.seconds("local"))});
        }
      }
    }
    report.paragraph("Control points (Ipopt):").table(study_table);
  }
  write_text_file(out / "solvers.csv", solver_csv.str());
  summarise(runs, study, *context.summary);
  draw_solver_figure(out, solvers);
  report.heading("Solvers")
      .figure("solvers", "solvers.png")
      .paragraph(
          "All three solvers start from the same global candidates and minimise the same "
          "objective (the travel time at a fixed count of stations, 0.5 m apart, at most 3000); "
          "Ipopt and LBFGS use its exact adjoint gradient, BOBYQA none. Optimality is the largest "
          "projected-gradient component at the returned path. The travel time is piecewise smooth "
          "(it kinks where a switching point crosses a station), so gradient methods can stop on "
          "a kink with a small but non-zero gradient. Every reported path is re-evaluated at 0.1 m "
          "stations; the numbers above are those. Raw data: results.csv.")
      .write(out);
}

}  // namespace talus::experiments
