#include "sweep_experiments.hpp"

#include "sweep_command.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/sample_statistics.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/report.hpp"
#include "talus/sweep/sweep_config.hpp"
#include "talus/sweep/sweep_runner.hpp"

namespace talus::experiments {
namespace {

using Json = nlohmann::ordered_json;
constexpr double kInf = std::numeric_limits<double>::infinity();

double number_or(const Json& figures, const char* key, double fallback) {
  return figures.contains(key) && figures.at(key).is_number() ? figures.at(key).get<double>()
                                                              : fallback;
}

/// data/sweeps/`name`.yaml (its `quick:` values in quick runs), relative files taken from the
/// repository (the data folder's parent).
SweepConfig load_experiment_sweep(const ExperimentContext& context, const std::string& name) {
  SweepConfig config =
      load_sweep_config(context.data_dir / "sweeps" / (name + ".yaml"), context.quick);
  config.base_dir = context.data_dir.parent_path();
  return config;
}

/// Runs `config` through the CLI's dispatcher (threads = the core count) into `dir`, then
/// writes its results.csv and report.md there.
SweepResult run_experiment_sweep(const ExperimentContext& context, const SweepConfig& config,
                                 const std::filesystem::path& dir) {
  SweepOptions options;
  options.output_dir = dir;
  options.run_command = context.run_command;
  options.check_command = context.check_command;
  options.check_vehicle = check_sweep_vehicle;
  const SweepResult result = run_sweep(config, options);
  write_sweep_report(config, dir);
  return result;
}

/// One case of the friction-stability sweep.
struct Outcome {
  double roughness = 0.0, cg_height = 0.0, friction = 0.0;
  std::string status;
  double search_cost = kInf;  ///< the lattice's minimum time; +inf when unreachable
  double travel_time = kInf;  ///< the plan's; +inf without one
  double sliding = 0.0, tipover = 0.0, contact = 0.0, max_speed = 0.0;  ///< binding shares
};

std::vector<Outcome> outcomes(const SweepConfig& config, const std::filesystem::path& dir) {
  std::map<std::string, Json> by_id;
  for (Json& r : read_sweep_records(dir)) by_id[r.at("case_id").get<std::string>()] = r;
  std::vector<Outcome> all;
  for (const SweepCase& c : config.cases) {
    const auto it = by_id.find(c.id);
    if (it == by_id.end()) throw Error("sweep-friction-stability: case " + c.id + " has no result");
    const Json& f = it->second.at("figures");
    Outcome o;
    o.roughness = c.parameters.at("terrain.height_scale").get<double>();
    o.cg_height = c.parameters.at("vehicle.cg_height").get<double>();
    o.friction = c.parameters.at("vehicle.friction").get<double>();
    o.status = it->second.at("status").get<std::string>();
    o.search_cost = number_or(f, "search_cost", kInf);
    o.travel_time = number_or(f, "travel_time", kInf);
    o.sliding = number_or(f, "binding_share_sliding", 0.0);
    o.tipover = number_or(f, "binding_share_tipover", 0.0);
    o.contact = number_or(f, "binding_share_contact", 0.0);
    o.max_speed = number_or(f, "binding_share_max_speed", 0.0);
    all.push_back(o);
  }
  return all;
}

/// Pairs of cases that differ only in one parameter where the lattice's
/// minimum time moved against the physics: up with more friction, or down
/// with a higher centre of mass (every edge's time at the limit moves the
/// same way). 1e-9 relative slack for round-off.
struct Violations {
  std::size_t friction = 0, cg_height = 0, pairs = 0;
};

Violations monotonicity(const std::vector<Outcome>& all) {
  Violations v;
  const auto worse = [](double a, double b) {  // a > b beyond round-off (inf handled)
    if (std::isinf(b)) return false;
    return std::isinf(a) || a > b * (1.0 + 1e-9);
  };
  for (const Outcome& a : all) {
    for (const Outcome& b : all) {
      if (a.roughness != b.roughness) continue;
      if (a.cg_height == b.cg_height && a.friction < b.friction) {
        ++v.pairs;
        if (worse(b.search_cost, a.search_cost)) ++v.friction;
      }
      if (a.friction == b.friction && a.cg_height < b.cg_height) {
        ++v.pairs;
        if (worse(a.search_cost, b.search_cost)) ++v.cg_height;
      }
    }
  }
  return v;
}

/// Success rate, mean travel time of the plans and mean binding shares of
/// the cases with the same value of one parameter.
Table marginal_table(const std::vector<Outcome>& all, const std::string& name,
                     double Outcome::*parameter) {
  std::set<double> values;
  for (const Outcome& o : all) values.insert(o.*parameter);
  Table table({name, "cases", "planned", "mean travel time [s]", "sliding", "tip-over", "contact",
               "max speed"});
  for (double value : values) {
    std::size_t cases = 0, planned = 0;
    double time = 0.0, sliding = 0.0, tipover = 0.0, contact = 0.0, max_speed = 0.0;
    for (const Outcome& o : all) {
      if (o.*parameter != value) continue;
      ++cases;
      if (!std::isfinite(o.travel_time)) continue;
      ++planned;
      time += o.travel_time;
      sliding += o.sliding;
      tipover += o.tipover;
      contact += o.contact;
      max_speed += o.max_speed;
    }
    const auto mean = [planned](double sum) {
      return planned == 0 ? std::string("–") : sig3(sum / static_cast<double>(planned));
    };
    table.row({sig3(value), std::to_string(cases), std::to_string(planned), mean(time),
               mean(sliding), mean(tipover), mean(contact), mean(max_speed)});
  }
  return table;
}

/// The plans' travel times against μ, one line per (h, height scale).
FigureLink travel_time_figure(const std::vector<Outcome>& all, const std::filesystem::path& dir) {
  GnuplotFigure plot(dir, "travel_time_vs_friction");
  std::set<std::pair<double, double>> series;
  for (const Outcome& o : all) series.insert({o.roughness, o.cg_height});
  auto data = open_output_file(plot.file(".dat"));
  PlotItems items;
  std::size_t block = 0;
  for (const auto& [roughness, cg_height] : series) {
    data << "# height scale " << roughness << " m, h " << cg_height << " m: mu travel_time\n";
    for (const Outcome& o : all) {
      if (o.roughness != roughness || o.cg_height != cg_height) continue;
      data << o.friction << " "
           << (std::isfinite(o.travel_time) ? csv_number(o.travel_time) : "NaN") << "\n";
    }
    data << "\n\n";
    items.push_back(
        gnuplot_string(plot.name(".dat")) + " index " + std::to_string(block++) +
        " using 1:2 with linespoints pt 7 title " +
        gnuplot_string("height scale " + sig3(roughness) + " m, h " + sig3(cg_height) + " m"));
  }
  close_output_file(data, plot.file(".dat"));
  plot.describe("the rover's planned travel time against friction, one line per h and roughness",
                plot.name(".dat"))
      .canvas(900, 600)
      .title("Travel time of the plan against friction");
  plot << "set xlabel 'friction coefficient μ'\nset ylabel 'travel time [s]'\nset grid\n"
       << "set key outside right\nset offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n";
  plot.plot(items);
  plot.render();
  return {"Travel time of the plan against friction", plot.name(".png")};
}

}  // namespace

void run_sweep_friction_stability(const ExperimentContext& context) {
  if (!context.run_command) throw Error("sweep-friction-stability needs the CLI's command runner");
  require_gnuplot();
  const SweepConfig config = load_experiment_sweep(context, "sweep-friction-stability");
  const SweepResult result = run_experiment_sweep(context, config, context.output_dir / "sweep");
  const std::vector<Outcome> all = outcomes(config, context.output_dir / "sweep");
  const Violations violations = monotonicity(all);
  std::size_t planned = 0, unreachable = 0;
  for (const Outcome& o : all) {
    planned += std::isfinite(o.travel_time) ? 1 : 0;
    unreachable += std::isinf(o.search_cost) ? 1 : 0;
  }

  Report report("Sweep: friction and stability against roughness");
  report.paragraph(
      "The documented rover (`data/vehicles/rover.yaml`, half-track b = 0.6 m) plans across a "
      "seeded fractal terrain (`talus terrain generate fractal`, 1 m cells) for every "
      "combination of friction μ, centre-of-mass height h (b/h = 0.6/h) and roughness (the "
      "fractal's height scale). Configuration: `sweep-friction-stability.yaml`" +
      std::string(context.quick ? " with its `quick:` values" : "") +
      "; every case's files, results.csv and a figure per parameter are in `sweep/` "
      "(`sweep/report.md`).");
  report.heading("What was run")
      .bullet(std::to_string(all.size()) + " cases, " + std::to_string(planned) + " with a plan, " +
              std::to_string(unreachable) +
              " with the goal unreachable on the "
              "lattice")
      .bullet(result.brief_report());
  const FigureLink figure = travel_time_figure(all, context.output_dir);
  report.figure(figure.caption, figure.file);
  report.heading("By friction μ").table(marginal_table(all, "μ", &Outcome::friction));
  report.heading("By centre-of-mass height h")
      .table(marginal_table(all, "h [m]", &Outcome::cg_height));
  report.heading("By roughness (height scale)")
      .table(marginal_table(all, "height scale [m]", &Outcome::roughness));
  report.paragraph(
      "Binding shares are the fractions of the best trajectory's stations whose speed limit is "
      "set by each constraint, averaged over the planned cases.");
  report.heading("Invariants")
      .paragraph(
          "Every edge's time at the speed limit can only fall when μ grows (the sliding limit "
          "rises, the others do not change) and only rise when h grows (the tip-over limit b/h "
          "falls), so the lattice's minimum time between the same start and goal must do the "
          "same; unreachable counts as +∞. Over " +
          std::to_string(violations.pairs) +
          " pairs of cases that differ in one of them: " + std::to_string(violations.friction) +
          " violations in μ, " + std::to_string(violations.cg_height) + " in h.");
  report.write(context.output_dir);

  ExperimentSummary& summary = *context.summary;
  summary.set("cases", static_cast<double>(all.size()), "cases");
  summary.set("planned_cases", static_cast<double>(planned), "cases");
  summary.set("monotonicity_pairs", static_cast<double>(violations.pairs), "pairs");
  summary.set("friction_monotonicity_violations", static_cast<double>(violations.friction),
              "pairs");
  summary.set("cg_height_monotonicity_violations", static_cast<double>(violations.cg_height),
              "pairs");
  summary.set("failed_cases", static_cast<double>(result.failed), "cases");
}

namespace {

// ---- sweep-dynamic-vs-kinematic ----

/// One terrain and friction: the Haït path at its own time-optimal profile and Talus's plan.
struct Comparison {
  long long seed = 0;
  double roughness = 0.0, friction = 0.0;
  std::string hait_status, talus_status;
  double hait_length = kInf, hait_time = kInf, hait_planning = kInf;     ///< [m], [s], [s]
  double talus_length = kInf, talus_time = kInf, talus_planning = kInf;  ///< [m], [s], [s]
  bool compared() const { return std::isfinite(hait_time) && std::isfinite(talus_time); }
  double time_ratio() const { return hait_time / talus_time; }
  double planning_ratio() const { return hait_planning / talus_planning; }
};

/// The terrain.* and vehicle.* parameters of a case: what pairs a kinematic case with a Talus one.
std::string pairing_key(const SweepCase& c) {
  Json key = Json::object();
  for (const auto& [name, value] : c.parameters.items()) {
    if (name.rfind("terrain.", 0) == 0 || name.rfind("vehicle.", 0) == 0) key[name] = value;
  }
  return key.dump();
}

/// The summary.json a case's job wrote (an empty object when it wrote none: an input error).
Json case_summary(const std::filesystem::path& dir, const SweepCase& c) {
  const std::filesystem::path file = dir / "cases" / c.id / "out" / "summary.json";
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return Json::object();
  Json parsed = Json::parse(read_input_file(file.string(), kMaxConfigFileBytes), nullptr, false);
  return parsed.is_object() ? parsed : Json::object();
}

double json_number(const Json& object, const char* key) {
  return object.contains(key) && object.at(key).is_number() ? object.at(key).get<double>() : kInf;
}

std::vector<Comparison> comparisons(const SweepConfig& kinematic, const SweepConfig& talus,
                                    const std::filesystem::path& kinematic_dir,
                                    const std::filesystem::path& talus_dir) {
  std::map<std::string, const SweepCase*> talus_by_key;
  for (const SweepCase& c : talus.cases) talus_by_key[pairing_key(c)] = &c;
  if (talus.cases.size() != kinematic.cases.size() || talus_by_key.size() != talus.cases.size()) {
    throw InputError("sweep-dynamic-vs-kinematic: the two configurations have " +
                     std::to_string(kinematic.cases.size()) + " and " +
                     std::to_string(talus.cases.size()) + " cases; keep their terrain.* and " +
                     "vehicle.* parameters (and quick:) the same");
  }
  std::vector<Comparison> all;
  for (const SweepCase& k : kinematic.cases) {
    const auto it = talus_by_key.find(pairing_key(k));
    if (it == talus_by_key.end()) {
      throw InputError("sweep-dynamic-vs-kinematic: kinematic case " + k.id +
                       " has no Talus case with the same terrain.* and vehicle.* parameters");
    }
    const SweepCase& t = *it->second;
    Comparison c;
    c.seed = k.parameters.at("terrain.seed").get<long long>();
    c.roughness = k.parameters.at("terrain.height_scale").get<double>();
    c.friction = k.parameters.at("vehicle.friction").get<double>();
    const Json hait = case_summary(kinematic_dir, k), plan = case_summary(talus_dir, t);
    c.hait_status = hait.value("status", std::string("error"));
    c.talus_status = plan.value("status", std::string("error"));
    c.hait_length = json_number(hait, "length_m");
    c.hait_time = json_number(hait, "profile_travel_time");
    // The planner's own work: preprocessing, search and smoothing (no figure, no profile).
    c.hait_planning =
        json_number(hait, "preprocessing_seconds") + json_number(hait, "search_seconds") +
        (hait.contains("smoothing_seconds") ? json_number(hait, "smoothing_seconds") : 0.0);
    c.talus_length = json_number(plan, "length_m");
    c.talus_time = json_number(plan, "travel_time");
    if (plan.contains("seconds") && plan.at("seconds").is_object()) {
      c.talus_planning = json_number(plan.at("seconds"), "total");
    }
    all.push_back(c);
  }
  return all;
}

/// The kinematic planner never sees the vehicle: its path on one terrain must be the same for
/// every μ (`length_spread` [m], the largest spread of its length), and the profile along that
/// one path cannot be slower with more friction (the admissible set only grows; 1e-9 relative
/// slack for the profile solver's round-off).
struct KinematicInvariants {
  double length_spread = 0.0;
  std::size_t pairs = 0, violations = 0;
};

KinematicInvariants kinematic_invariants(const std::vector<Comparison>& all) {
  KinematicInvariants v;
  for (const Comparison& a : all) {
    for (const Comparison& b : all) {
      if (a.seed != b.seed || a.roughness != b.roughness || !(a.friction < b.friction)) continue;
      if (std::isfinite(a.hait_length) && std::isfinite(b.hait_length)) {
        v.length_spread = std::max(v.length_spread, std::abs(a.hait_length - b.hait_length));
      }
      if (!std::isfinite(b.hait_length)) continue;
      ++v.pairs;
      if (std::isinf(b.hait_time) ? std::isfinite(a.hait_time)
                                  : b.hait_time > a.hait_time * (1.0 + 1e-9)) {
        ++v.violations;
      }
    }
  }
  return v;
}

std::string ratio_text(double value) {
  return std::isfinite(value) ? fmt("%.3f", value) : "–";
}

/// Median time and planning-time ratios of the compared cases with one value of a parameter.
Table ratio_table(const std::vector<Comparison>& all, const std::string& name,
                  double Comparison::*parameter) {
  std::set<double> values;
  for (const Comparison& c : all) values.insert(c.*parameter);
  Table table({name, "cases", "both planned", "median time ratio", "median planning-time ratio"});
  for (double value : values) {
    std::vector<double> times, planning;
    std::size_t cases = 0;
    for (const Comparison& c : all) {
      if (c.*parameter != value) continue;
      ++cases;
      if (!c.compared()) continue;
      times.push_back(c.time_ratio());
      planning.push_back(c.planning_ratio());
    }
    table.row({sig3(value), std::to_string(cases), std::to_string(times.size()),
               times.empty() ? "–" : ratio_text(upper_median(times)),
               planning.empty() ? "–" : ratio_text(upper_median(planning))});
  }
  return table;
}

/// One ratio of the compared cases against μ, one line per terrain (seed, roughness).
FigureLink ratio_figure(const std::vector<Comparison>& all, const std::filesystem::path& dir,
                        const std::string& stem, double (Comparison::*ratio)() const,
                        const std::string& label) {
  GnuplotFigure plot(dir, stem);
  std::set<std::pair<double, long long>> terrains;
  for (const Comparison& c : all) terrains.insert({c.roughness, c.seed});
  auto data = open_output_file(plot.file(".dat"));
  PlotItems items;
  std::size_t block = 0;
  for (const auto& [roughness, seed] : terrains) {
    data << "# height scale " << roughness << " m, seed " << seed << ": mu " << stem << "\n";
    for (const Comparison& c : all) {
      if (c.roughness != roughness || c.seed != seed) continue;
      data << c.friction << " " << (c.compared() ? csv_number((c.*ratio)()) : "NaN") << "\n";
    }
    data << "\n\n";
    items.push_back(
        gnuplot_string(plot.name(".dat")) + " index " + std::to_string(block++) +
        " using 1:2 with linespoints pt 7 title " +
        gnuplot_string("height scale " + sig3(roughness) + " m, seed " + std::to_string(seed)));
  }
  close_output_file(data, plot.file(".dat"));
  plot.describe(label + " against friction, one line per terrain", plot.name(".dat"))
      .canvas(900, 600)
      .title(label + " against friction");
  plot << "set xlabel 'friction coefficient μ'\nset ylabel " << gnuplot_plain_text(label)
       << "\nset grid\nset key outside right\n"
       << "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n";
  plot.plot(items);
  plot.render();
  return {label + " against friction", plot.name(".png")};
}

/// What a family of comparisons amounts to.
struct FamilyStats {
  std::vector<double> time_ratios, planning_ratios;  ///< of the compared cases
  /// Smallest time ÷ (length ÷ top speed) of the compared cases' kinematic paths and plans.
  double kinematic_over_top_speed = kInf, talus_over_top_speed = kInf;
  std::size_t found = 0, planned = 0;  ///< kinematic paths found, Talus plans
};

FamilyStats family_stats(const std::vector<Comparison>& all, double max_speed) {
  FamilyStats f;
  for (const Comparison& c : all) {
    f.found += std::isfinite(c.hait_length) ? 1 : 0;
    f.planned += std::isfinite(c.talus_time) ? 1 : 0;
    if (!c.compared()) continue;
    f.time_ratios.push_back(c.time_ratio());
    f.planning_ratios.push_back(c.planning_ratio());
    f.kinematic_over_top_speed =
        std::min(f.kinematic_over_top_speed, c.hait_time / (c.hait_length / max_speed));
    f.talus_over_top_speed =
        std::min(f.talus_over_top_speed, c.talus_time / (c.talus_length / max_speed));
  }
  return f;
}

/// The top speed of the point mass matched to the chassis, which both halves drive.
double matched_max_speed(const ExperimentContext& context) {
  return load_vehicle(context.data_dir / "vehicles" / "marsokhod_point_mass.yaml").max_speed;
}

double median_or_nan(const std::vector<double>& values) {
  return values.empty() ? std::numeric_limits<double>::quiet_NaN() : upper_median(values);
}

}  // namespace

void run_sweep_dynamic_vs_kinematic(const ExperimentContext& context) {
  if (!context.run_command) {
    throw Error("sweep-dynamic-vs-kinematic needs the CLI's command runner");
  }
  require_gnuplot();
  const SweepConfig kinematic = load_experiment_sweep(context, "sweep-dynamic-vs-kinematic");
  const SweepConfig talus = load_experiment_sweep(context, "sweep-dynamic-vs-kinematic-talus");
  const std::filesystem::path kinematic_dir = context.output_dir / "kinematic";
  const std::filesystem::path talus_dir = context.output_dir / "talus";
  const SweepResult kinematic_result = run_experiment_sweep(context, kinematic, kinematic_dir);
  const SweepResult talus_result = run_experiment_sweep(context, talus, talus_dir);
  const std::vector<Comparison> all = comparisons(kinematic, talus, kinematic_dir, talus_dir);
  const KinematicInvariants invariants = kinematic_invariants(all);

  const FamilyStats stats = family_stats(all, matched_max_speed(context));
  const std::vector<double>& time_ratios = stats.time_ratios;
  const std::vector<double>& planning_ratios = stats.planning_ratios;
  const double hait_over_top_speed = stats.kinematic_over_top_speed;
  const double talus_over_top_speed = stats.talus_over_top_speed;
  const std::size_t hait_found = stats.found, talus_planned = stats.planned;

  Report report("Sweep: the kinematic path at its own profile against Talus's plan");
  report.paragraph(
      "Path–velocity decomposition measured over a family of terrains: on each seeded fractal "
      "terrain (10 m × 10 m, 0.25 m cells, roughness = the fractal's height scale) and for each "
      "friction μ, the Haït–Siméon–Taïx planner (`talus baseline hait`, articulated chassis "
      "`marsokhod_chassis.yaml`, potential-rs, smoothed) plans a path, which is then driven at "
      "its own time-optimal profile (`--vehicle`: split at cusps, rest to rest, along its own "
      "segments and arcs, a station at every configuration; `talus::driven_path_time`). Talus "
      "plans the same query (`talus plan`, one global candidate, then the local optimiser). "
      "Both use the point mass matched to the chassis (`data/vehicles/marsokhod_point_mass."
      "yaml`, μ swept) on the terrain's interpolating B-patch. Start and goal face the straight "
      "line between them; the kinematic planner must meet the goal heading, Talus leaves both "
      "ends free. Time ratio = kinematic path's time ÷ Talus's; planning-time ratio = the "
      "kinematic planner's preprocessing + search + smoothing ÷ Talus's whole planner "
      "(machine-dependent: the ratio of two timings in one run). Configurations: "
      "`sweep-dynamic-vs-kinematic.yaml` and `sweep-dynamic-vs-kinematic-talus.yaml`" +
      std::string(context.quick ? " with their `quick:` values" : "") +
      "; each sweep's cases, results.csv and report.md are in `kinematic/` and `talus/`.");
  report.heading("What was run")
      .bullet(std::to_string(all.size()) +
              " terrain × friction cases: the kinematic planner "
              "found " +
              std::to_string(hait_found) + " paths, Talus planned " +
              std::to_string(talus_planned) + ", both (and the kinematic path had a profile) in " +
              std::to_string(time_ratios.size()))
      .bullet("kinematic: " + kinematic_result.brief_report())
      .bullet("Talus: " + talus_result.brief_report());
  Table cases({"seed", "height scale [m]", "μ", "kinematic length [m]", "kinematic time [s]",
               "Talus length [m]", "Talus time [s]", "time ratio", "kinematic planning [s]",
               "Talus planning [s]", "planning-time ratio"});
  const auto cell = [](double value, const char* format) {
    return std::isfinite(value) ? fmt(format, value) : std::string("–");
  };
  for (const Comparison& c : all) {
    cases.row(
        {std::to_string(c.seed), sig3(c.roughness), sig3(c.friction), cell(c.hait_length, "%.2f"),
         std::isfinite(c.hait_length) ? cell(c.hait_time, "%.2f") : c.hait_status,
         cell(c.talus_length, "%.2f"),
         std::isfinite(c.talus_time) ? cell(c.talus_time, "%.2f") : c.talus_status,
         c.compared() ? ratio_text(c.time_ratio()) : "–", cell(c.hait_planning, "%.3g"),
         cell(c.talus_planning, "%.3g"), c.compared() ? ratio_text(c.planning_ratio()) : "–"});
  }
  report.heading("Every case").table(cases);
  report.paragraph(
      "A dash: no time (the kinematic path has no admissible profile for the point mass, or "
      "Talus refused the query, e.g. a start on terrain too steep for the vehicle: "
      "`talus/results.csv` gives the reason).");
  report.heading("By roughness (height scale)")
      .table(ratio_table(all, "height scale [m]", &Comparison::roughness));
  report.heading("By friction μ").table(ratio_table(all, "μ", &Comparison::friction));
  report.figure("Time ratio against friction",
                ratio_figure(all, context.output_dir, "time_ratio_vs_friction",
                             &Comparison::time_ratio, "time ratio (kinematic / Talus)")
                    .file);
  report.figure("Planning-time ratio against friction",
                ratio_figure(all, context.output_dir, "planning_ratio_vs_friction",
                             &Comparison::planning_ratio, "planning-time ratio (kinematic / Talus)")
                    .file);
  report.heading("Invariants")
      .paragraph(
          "The kinematic planner never sees the vehicle, so on one terrain its path is the same "
          "for every μ (largest length spread: " +
          fmt("%.3g", invariants.length_spread) +
          " m), and the profile along that one path cannot be slower with more friction (the "
          "point mass's admissible set only grows with μ): " +
          std::to_string(invariants.violations) + " violations over " +
          std::to_string(invariants.pairs) +
          " pairs. No profile beats its own length at the top speed: the smallest time ÷ "
          "(length ÷ top speed) is " +
          ratio_text(hait_over_top_speed) + " for the kinematic paths and " +
          ratio_text(talus_over_top_speed) + " for Talus's.");
  report.paragraph(
      "Reading: a time ratio above 1 is the price of planning the path without the dynamics. "
      "The two profiles are discretised differently (stations at the kinematic path's "
      "configurations, 0.1 m apart; Talus's scale-aware spacing), and the scheme is first "
      "order in the spacing, so ratios this close to 1 are ties.");
  report.write(context.output_dir);

  ExperimentSummary& summary = *context.summary;
  summary.set("cases", static_cast<double>(all.size()), "cases");
  summary.set("kinematic_paths_found", static_cast<double>(hait_found), "cases");
  summary.set("talus_plans", static_cast<double>(talus_planned), "cases");
  summary.set("compared_cases", static_cast<double>(time_ratios.size()), "cases");
  summary.set("failed_cases", static_cast<double>(kinematic_result.failed + talus_result.failed),
              "cases");
  summary.set("time_ratio_median", median_or_nan(time_ratios), "1",
              "kinematic path at its own profile ÷ Talus's plan");
  summary.set(
      "time_ratio_min",
      time_ratios.empty() ? kInf : *std::min_element(time_ratios.begin(), time_ratios.end()), "1");
  summary.set(
      "time_ratio_max",
      time_ratios.empty() ? kInf : *std::max_element(time_ratios.begin(), time_ratios.end()), "1");
  summary.set("planning_ratio_median", median_or_nan(planning_ratios), "1",
              "kinematic planner's seconds ÷ Talus planner's seconds (one machine, one run)");
  summary.set("kinematic_length_spread_across_friction_m", invariants.length_spread, "m",
              "0: the kinematic planner never sees the vehicle");
  summary.set("kinematic_friction_pairs", static_cast<double>(invariants.pairs), "pairs");
  summary.set("kinematic_friction_monotonicity_violations",
              static_cast<double>(invariants.violations), "pairs",
              "0: more friction never slows the profile along one path");
  summary.set("kinematic_time_over_length_at_max_speed_min", hait_over_top_speed, "1",
              ">= 1: no profile beats its own length at the top speed");
  summary.set("talus_time_over_length_at_max_speed_min", talus_over_top_speed, "1",
              ">= 1: no profile beats its own length at the top speed");
}

void run_sweep_baselines(const ExperimentContext& context) {
  if (!context.run_command) throw Error("sweep-baselines needs the CLI's command runner");
  require_gnuplot();
  const SweepConfig talus = load_experiment_sweep(context, "sweep-dynamic-vs-kinematic-talus");
  const std::filesystem::path talus_dir = context.output_dir / "talus";
  const SweepResult talus_result = run_experiment_sweep(context, talus, talus_dir);
  const double max_speed = matched_max_speed(context);
  // Every registered baseline with a sweep of its own on the same terrains and frictions.
  const std::vector<std::pair<std::string, std::string>> baselines = {
      {"hait", "sweep-dynamic-vs-kinematic"},
      {"dacre-wright", "sweep-baselines-dacre-wright"},
      {"eldershaw-yim", "sweep-baselines-eldershaw-yim"},
      {"iagnemma", "sweep-baselines-iagnemma"}};

  Report report("Sweep: Talus against every kinematic baseline");
  report.paragraph(
      "Each registered kinematic baseline plans on the terrains and frictions of "
      "`sweep-dynamic-vs-kinematic` (seeded fractal terrains of 10 m × 10 m, roughness × μ) and "
      "its path is driven at its time-optimal profile by the point mass matched to the chassis "
      "(`talus baseline NAME --vehicle`): along its own segments and arcs when it has a driving "
      "direction (Haït–Siméon–Taïx), along a clamped cubic fitted to its positions when it "
      "moves sideways or steps through CGspace (Dacre-Wright–Siméon; Eldershaw–Yim's walker, "
      "whose CG route is what is compared: `profile_method` fitted_cubic) or is a simulated "
      "vehicle's driven path (Iagnemma–Shimoda–Shiller's navigator). Talus plans the "
      "same queries once (`talus/`). Time ratio = the baseline path's time ÷ Talus's; "
      "planning-time ratio = the baseline's planning seconds ÷ Talus's whole planner (one "
      "machine, one run)" +
      std::string(context.quick ? "; quick mode: the configurations' `quick:` values" : "") + ".");
  report.bullet("Talus: " + talus_result.brief_report());
  Table overview({"baseline", "cases", "paths found", "compared", "median time ratio",
                  "median planning-time ratio", "failed cases"});
  ExperimentSummary& summary = *context.summary;
  summary.set("cases", static_cast<double>(talus.cases.size()), "cases");
  summary.set("talus_failed_cases", static_cast<double>(talus_result.failed), "cases");
  for (const auto& [name, config_name] : baselines) {
    const SweepConfig config = load_experiment_sweep(context, config_name);
    const std::filesystem::path dir = context.output_dir / name;
    const SweepResult result = run_experiment_sweep(context, config, dir);
    const std::vector<Comparison> all = comparisons(config, talus, dir, talus_dir);
    const FamilyStats stats = family_stats(all, max_speed);
    const KinematicInvariants invariants = kinematic_invariants(all);
    overview.row({name, std::to_string(all.size()), std::to_string(stats.found),
                  std::to_string(stats.time_ratios.size()),
                  ratio_text(median_or_nan(stats.time_ratios)),
                  ratio_text(median_or_nan(stats.planning_ratios)), std::to_string(result.failed)});
    report.heading("`" + name + "`")
        .bullet(result.brief_report())
        .bullet("its path does not change with μ (largest length spread " +
                fmt("%.3g", invariants.length_spread) +
                " m) and its profile never slows with more friction: " +
                std::to_string(invariants.violations) + " violations over " +
                std::to_string(invariants.pairs) + " pairs")
        .table(ratio_table(all, "height scale [m]", &Comparison::roughness));
    std::string key = name;
    std::replace(key.begin(), key.end(), '-', '_');
    if (!stats.time_ratios.empty()) {  // gnuplot refuses a figure with no point at all
      const FigureLink figure =
          ratio_figure(all, context.output_dir, "time_ratio_" + key, &Comparison::time_ratio,
                       "time ratio (" + name + " / Talus)");
      report.figure(figure.caption, figure.file);
    }
    summary.set(key + "_paths_found", static_cast<double>(stats.found), "cases");
    summary.set(key + "_compared_cases", static_cast<double>(stats.time_ratios.size()), "cases");
    summary.set(key + "_failed_cases", static_cast<double>(result.failed), "cases");
    summary.set(key + "_time_ratio_median", median_or_nan(stats.time_ratios), "1",
                "the baseline's path at its profile ÷ Talus's plan");
    summary.set(key + "_planning_ratio_median", median_or_nan(stats.planning_ratios), "1");
    summary.set(key + "_length_spread_across_friction_m", invariants.length_spread, "m",
                "0: the baseline never sees the vehicle");
    summary.set(key + "_friction_monotonicity_violations",
                static_cast<double>(invariants.violations), "pairs",
                "0: more friction never slows the profile along one path");
    summary.set(key + "_time_over_length_at_max_speed_min", stats.kinematic_over_top_speed, "1");
  }
  report.heading("Overview").table(overview);
  report.write(context.output_dir);
}

}  // namespace talus::experiments
