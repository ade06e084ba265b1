#include "sweep_experiments.hpp"

#include "sweep_command.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "talus/core/error.hpp"
#include "talus/core/report/figure.hpp"
#include "talus/core/report/number_format.hpp"
#include "talus/core/report/plot.hpp"
#include "talus/core/report/report.hpp"
#include "talus/core/sweep/sweep_config.hpp"
#include "talus/core/sweep/sweep_runner.hpp"

namespace talus::experiments {
namespace {

using Json = nlohmann::ordered_json;
constexpr double kInf = std::numeric_limits<double>::infinity();

double number_or(const Json& figures, const char* key, double fallback) {
  return figures.contains(key) && figures.at(key).is_number() ? figures.at(key).get<double>()
                                                              : fallback;
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
  const std::filesystem::path config_file =
      context.data_dir / "sweeps/sweep-friction-stability.yaml";
  SweepConfig config = load_sweep_config(config_file, context.quick);
  config.base_dir = context.data_dir.parent_path();
  SweepOptions options;
  options.output_dir = context.output_dir / "sweep";
  options.run_command = context.run_command;
  options.check_command = context.check_command;
  options.check_vehicle = check_sweep_vehicle;
  const SweepResult result = run_sweep(config, options);
  write_sweep_report(config, options.output_dir);
  const std::vector<Outcome> all = outcomes(config, options.output_dir);
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
      "fractal's height scale). Configuration: `" +
      config_file.filename().string() + "`" + (context.quick ? " with its `quick:` values" : "") +
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

}  // namespace talus::experiments
