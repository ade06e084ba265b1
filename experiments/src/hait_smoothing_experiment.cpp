// hait-smoothing: controls (segments) before and after the Reeds–Shepp
// smoothing of Haït, Siméon, Taïx 2002 §4.4 (Fig. 21: 40 -> 13 controls).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "hait_experiments.hpp"
#include "hait_figures.hpp"
#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"
#include "talus/kinematic/hait/hait_robot_validity.hpp"
#include "talus/kinematic/hait/hait_smoothing.hpp"
#include "talus/kinematic/reeds_shepp.hpp"
#include "talus/report/experiment_summary.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/report.hpp"
#include "talus/scenarios/hait_robots.hpp"

namespace talus::experiments {

namespace {

/// One smoothing configuration of the study.
struct SmoothingVariant {
  const char* name;         ///< CSV / report label
  const char* description;  ///< report text
  HaitSmoothingMethod method;
  std::size_t iterations;
  double max_span;
  std::size_t max_span_controls;
  bool draw_within_span;
  bool paper_limit;  ///< the pair limit is the paper's hint (number of controls)
};

constexpr SmoothingVariant kVariants[] = {
    {"pairs-5m-rejection", "2000 pairs drawn over the whole path, those > 5 m apart skipped",
     HaitSmoothingMethod::kRandomPairs, 2000, 5.0, 0, false, false},
    {"pairs-5m", "2000 pairs, the second within 5 m of the first (default draw)",
     HaitSmoothingMethod::kRandomPairs, 2000, 5.0, 0, true, false},
    {"pairs-10m", "2000 pairs within 10 m", HaitSmoothingMethod::kRandomPairs, 2000, 10.0, 0, true,
     false},
    {"pairs-3c", "2000 pairs covering at most 3 controls (the paper's hint)",
     HaitSmoothingMethod::kRandomPairs, 2000, 0.0, 3, true, true},
    {"pairs-5c", "2000 pairs covering at most 5 controls (the paper's hint)",
     HaitSmoothingMethod::kRandomPairs, 2000, 0.0, 5, true, true},
    {"pairs-10c", "2000 pairs covering at most 10 controls (the paper's hint)",
     HaitSmoothingMethod::kRandomPairs, 2000, 0.0, 10, true, true},
    {"pairs-unlimited", "2000 pairs, no span limit", HaitSmoothingMethod::kRandomPairs, 2000, 0.0,
     0, false, false},
    {"greedy", "greedy shortcut passes only (ours)", HaitSmoothingMethod::kRandomPairsThenGreedy, 0,
     5.0, 0, true, false},
    {"pairs-5m+greedy", "2000 pairs within 5 m, then greedy passes (ours)",
     HaitSmoothingMethod::kRandomPairsThenGreedy, 2000, 5.0, 0, true, false},
};

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The paper's Fig. 21: 40 controls before smoothing, 13 after.
constexpr double kPaperBefore = 40.0, kPaperAfter = 13.0;

}  // namespace

void run_hait_smoothing(const ExperimentContext& context) {
  require_gnuplot();
  const HaitScenario scenario = hait_heuristics_scenario(context.quick);
  const Robot robot = scenarios::load_hait_chassis(context.data_dir);
  const RuledTerrain terrain(scenario.grid);
  const double radius = HaitOptions{}.turning_radius;

  // The search is deterministic; only the smoothing varies, so search once and
  // smooth the same path with every variant and seed.
  HaitOptions options;
  options.heuristic = HaitHeuristic::kPotentialRs;
  const HaitResult searched = plan_hait(terrain, robot, scenario.start, scenario.goal, options);
  if (searched.status != HaitStatus::kFound) {
    throw SolverError("hait-smoothing: no path: " + searched.message);
  }
  HaitValidityOptions vo;
  vo.sample_spacing = options.check_spacing;
  const HaitRobotValidity model(terrain, robot, vo);
  const ValidityFunction validity = model.function();
  const ReedsShepp curves(radius);

  // The random pairs depend on the seed: the seed sweep shows their spread.
  const std::vector<std::uint64_t> seeds = context.quick
                                               ? std::vector<std::uint64_t>{1, 2}
                                               : std::vector<std::uint64_t>{1, 2, 3, 4, 5, 6, 7, 8};
  const std::size_t before = searched.control_changes + 1;  // controls, the paper's count
  const double length_before = path_length(searched.path, radius);
  std::string csv =
      "variant,seed,controls_before,controls_after,control_changes_before,control_changes_after,"
      "length_before_m,length_after_m,replacements,placements\n";
  Table table({"variant", "controls after (seed 1)", "control changes after (seed 1)",
               "controls after, all seeds: min–max (median)", "median ratio to before",
               "length after, seed 1 [m]", "placements, seed 1"});
  std::vector<PathPoint> default_path, hint_path, greedy_path;
  std::size_t default_after = 0, hint_after = 0, greedy_after = 0;
  // Invariants over every run: a valid Reeds–Shepp curve is the shortest path of bounded
  // curvature between its ends, and the searched portions are such paths, so no replacement
  // lengthens the path; and no replacement is accepted that adds control changes.
  double max_length_increase = -kInf;
  double max_controls_added = -kInf;
  double min_controls_after = kInf;
  // The best median ratio of the paper's method with its own pair limit (number of controls) and
  // with our metric limit.
  double best_hint_ratio = kInf, best_metric_ratio = kInf;
  std::string best_hint_name, best_metric_name;
  // Each variant with the paper's pair limit, its median ratio and verdict; and the one closest
  // to the paper's ratio (the paper gives no number of controls, so N is a free parameter).
  std::string hint_ratios;
  double closest_hint_ratio = kInf;
  for (const SmoothingVariant& v : kVariants) {
    std::vector<std::size_t> after;
    HaitSmoothingReport first;
    std::vector<PathPoint> first_path;
    for (const std::uint64_t seed : seeds) {
      HaitSmoothingOptions so;
      so.method = v.method;
      so.iterations = v.iterations;
      so.max_span = v.max_span;
      so.max_span_controls = v.max_span_controls;
      so.draw_within_span = v.draw_within_span;
      so.check_spacing = options.check_spacing;
      so.seed = seed;
      HaitSmoothingReport rep;
      std::vector<PathPoint> smoothed = smooth_path(searched.path, validity, curves, so, &rep);
      after.push_back(rep.controls_after());
      max_length_increase = std::max(max_length_increase, rep.length_after - rep.length_before);
      max_controls_added =
          std::max(max_controls_added, static_cast<double>(rep.controls_after()) -
                                           static_cast<double>(rep.controls_before()));
      min_controls_after = std::min(min_controls_after, static_cast<double>(rep.controls_after()));
      csv += std::string(v.name) + "," + std::to_string(seed) + "," +
             std::to_string(rep.controls_before()) + "," + std::to_string(rep.controls_after()) +
             "," + std::to_string(rep.control_changes_before) + "," +
             std::to_string(rep.control_changes_after) + "," + csv_number(rep.length_before) + "," +
             csv_number(rep.length_after) + "," + std::to_string(rep.replacements) + "," +
             std::to_string(rep.placements) + "\n";
      if (seed == seeds.front()) {
        first = rep;
        first_path = std::move(smoothed);
      }
      // Without random pairs the variant is deterministic: one seed says it all.
      if (v.iterations == 0) break;
    }
    std::vector<std::size_t> sorted = after;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t median = sorted[sorted.size() / 2];
    const double ratio = static_cast<double>(median) / static_cast<double>(before);
    const std::string name = v.name;
    if (name == "pairs-5m") {
      default_path = first_path;
      default_after = first.controls_after();
    }
    if (name == "greedy") {
      greedy_path = first_path;
      greedy_after = first.controls_after();
    }
    if (v.paper_limit) {
      if (!hint_ratios.empty()) hint_ratios += ", ";
      hint_ratios += "`" + name + "` " + fmt("%.2f", ratio);
      if (std::abs(ratio - kPaperAfter / kPaperBefore) <
          std::abs(closest_hint_ratio - kPaperAfter / kPaperBefore)) {
        closest_hint_ratio = ratio;
      }
    }
    if (v.method == HaitSmoothingMethod::kRandomPairs) {
      if (v.paper_limit && ratio < best_hint_ratio) {
        best_hint_ratio = ratio;
        best_hint_name = name;
        hint_path = first_path;
        hint_after = first.controls_after();
      }
      if (!v.paper_limit && v.max_span > 0.0 && ratio < best_metric_ratio) {
        best_metric_ratio = ratio;
        best_metric_name = name;
      }
    }
    std::string key = name;
    std::replace(key.begin(), key.end(), '-', '_');
    std::replace(key.begin(), key.end(), '+', '_');
    context.summary->set("controls_ratio_" + key, ratio, "1",
                         "median over seeds of controls after / before; paper (Fig. 21): 13 / 40 "
                         "= 0.325");
    table.row({std::string("`").append(v.name).append("`: ").append(v.description),
               std::to_string(first.controls_after()), std::to_string(first.control_changes_after),
               std::to_string(sorted.front()) + "–" + std::to_string(sorted.back()) + " (" +
                   std::to_string(median) + ")",
               fmt("%.2f", ratio), sig3(first.length_after), std::to_string(first.placements)});
  }
  write_text_file(context.output_dir / "smoothing.csv", csv);

  ExperimentSummary& summary = *context.summary;
  summary.set("controls_before", static_cast<double>(before), "count",
              "the searched path's controls (segments); paper (Fig. 21): 40");
  summary.set("max_length_increase_m", max_length_increase, "m",
              "<= 0: the shortest Reeds–Shepp curve is never longer than the bounded-curvature "
              "portion it replaces");
  summary.set("max_controls_added", max_controls_added, "count",
              "<= 0: a replacement that adds control changes is never accepted");
  summary.set("min_controls_after", min_controls_after, "count", ">= 1: a path has one control");
  summary.set("best_paper_hint_controls_ratio", best_hint_ratio, "1",
              "best median ratio with pairs limited by controls; paper: 0.325");
  summary.set("closest_paper_hint_controls_ratio", closest_hint_ratio, "1",
              "the median ratio closest to the paper's among the pair limits 3, 5, 10 controls; "
              "paper: 0.325");
  summary.set("best_metric_span_controls_ratio", best_metric_ratio, "1",
              "best median ratio with pairs limited by a length (ours); paper: 0.325");

  std::vector<HaitRoute> routes;
  routes.push_back(
      {searched.path,
       "searched: " + std::to_string(before) + " controls, " + sig3(length_before) + " m",
       "#2c7fb8"});
  routes.push_back({default_path,
                    "pairs within 5 m (seed 1): " + std::to_string(default_after) + " controls, " +
                        sig3(path_length(default_path, radius)) + " m",
                    "#e6550d"});
  routes.push_back({hint_path,
                    "`" + best_hint_name + "` (seed 1): " + std::to_string(hint_after) +
                        " controls, " + sig3(path_length(hint_path, radius)) + " m",
                    "#756bb1"});
  routes.push_back({greedy_path,
                    "greedy (ours): " + std::to_string(greedy_after) + " controls, " +
                        sig3(path_length(greedy_path, radius)) + " m",
                    "#31a354"});
  render_hait_map(context.output_dir, "smoothing", scenario, routes,
                  "hait-smoothing: the potential-rs path before and after Reeds–Shepp smoothing");

  const double paper_ratio = kPaperAfter / kPaperBefore;
  const auto verdict = [&](double ratio) {
    // Within a third of the paper's ratio either way counts as reproduced: the paper shows one
    // path of one terrain, so its ratio is one sample of a spread the seeds show to be wide.
    return ratio <= paper_ratio * 4.0 / 3.0 && ratio >= paper_ratio * 2.0 / 3.0
               ? "reproduced"
               : (ratio < paper_ratio ? "more reduction than the paper's"
                                      : "not reproduced: less reduction than the paper's");
  };
  Report report("hait-smoothing: Reeds–Shepp smoothing (Haït, Siméon, Taïx 2002, §4.4)");
  report.paragraph(
      "**Problem.** The hait-heuristics problem (" + scenario.description +
      ") with the potential-rs guidance and the articulated chassis; the found path (" +
      std::to_string(before) + " controls, i.e. segments of constant control, " +
      std::to_string(before - 1) + " control changes, " + sig3(length_before) +
      " m) is smoothed by `smooth_path` with each variant below. A Reeds–Shepp replacement is "
      "kept only if every configuration on it is valid (checked every " +
      fmt("%g", options.check_spacing) +
      " m) and it removes control changes or keeps them and shortens the path; the controls of "
      "the replacement's own segments and of its two junctions count. The paper counts controls "
      "(Fig. 21: \"the number of controls decreases from 40 to 13\", ratio " +
      fmt("%.3f", paper_ratio) +
      "); so does the table (controls = control changes + 1), with control changes beside.");
  if (context.quick) report.paragraph("**Quick mode**: smaller map, two seeds.");
  report.paragraph("Controls after smoothing, from " + std::to_string(before) + ":")
      .table(table)
      .paragraph("**Claim by claim** (paper §4.4, Fig. 21):")
      .bullet(
          "*A valid Reeds–Shepp curve replaces a portion and decreases the number of control "
          "changes*: holds. Over every variant and seed, controls added at most " +
          fmt("%g", max_controls_added) +
          " (none is accepted that adds any) and the length "
          "grew by at most " +
          fmt("%.2g", max_length_increase) +
          " m, i.e. every run shortened the path (the shortest Reeds–Shepp curve is never "
          "longer than the arcs and segments it replaces, themselves a path of bounded "
          "curvature with cusps allowed).")
      .bullet(
          "*Pairs of random close configurations, the number of control changes between them "
          "limited* (the limit is not given): median ratios with pairs limited by the number "
          "of controls: " +
          hint_ratios + "; the closest to the paper's is " + fmt("%.2f", closest_hint_ratio) +
          ": " + verdict(closest_hint_ratio) +
          " for some limit (the paper's own limit is unknown, so this fits one free "
          "number; it is not a prediction). The best, " +
          fmt("%.2f", best_hint_ratio) + " (`" + best_hint_name + "`), is " +
          verdict(best_hint_ratio) + ". With our metric limit (5 m, 10 m) the best is " +
          fmt("%.2f", best_metric_ratio) + " (`" + best_metric_name +
          "`): " + verdict(best_metric_ratio) + ".")
      .bullet("*40 → 13 controls*: our searched path has " + std::to_string(before) +
              " controls, so only the ratio compares; 'reproduced' above means within a third of "
              "the paper's " +
              fmt("%.3f", paper_ratio) +
              " either way (the paper reports one path; our seeds show the spread).")
      .paragraph(
          "**Reading.** Short pairs (5 m, or 3 controls) stall in a local minimum: every short "
          "portion is already as good as one Reeds–Shepp curve makes it (a Reeds–Shepp curve has "
          "up to five pieces, so it rarely beats three controls), and ten times more pairs give "
          "the same count in our trials: the span limit, not the number of pairs, sets the result. "
          "Longer "
          "spans, by length or by controls, come close to the paper's ratio or below it. Medians "
          "over an even number of seeds are the upper middle value. The greedy shortcut is our "
          "addition "
          "(`HaitSmoothingMethod::kRandomPairsThenGreedy`): from each control switch, the "
          "farthest later switch reachable by a valid Reeds–Shepp curve; it is deterministic.")
      .write(context.output_dir,
             "`smoothing.csv` (every variant and seed, controls and control changes), "
             "`smoothing.png` (`smoothing.gp`), `summary.json`.",
             {{"smoothing", "smoothing.png"}});
}

}  // namespace talus::experiments
