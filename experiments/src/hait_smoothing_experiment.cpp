// hait-smoothing: control changes before and after the Reeds–Shepp smoothing
// of Haït, Siméon, Taïx 2002 §4.4 (Fig. 21: 40 -> 13).
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "hait_experiments.hpp"
#include "hait_figures.hpp"
#include "hait_scenarios.hpp"
#include "number_format.hpp"
#include "plot.hpp"
#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/hait_planner.hpp"

namespace talus::experiments {

void run_hait_smoothing(const ExperimentContext& context) {
  require_gnuplot();
  const HaitScenario scenario = hait_heuristics_scenario(context.quick);
  const Robot robot = load_hait_chassis(context.data_dir);
  const RuledTerrain terrain(scenario.grid);

  // The smoothing draws random pairs: the seed sweep shows its spread.
  const std::vector<std::uint64_t> seeds = context.quick
                                               ? std::vector<std::uint64_t>{1, 2}
                                               : std::vector<std::uint64_t>{1, 2, 3, 4, 5, 6, 7, 8};
  std::vector<HaitResult> results;
  std::string csv =
      "seed,control_changes_before,control_changes_after,length_before_m,length_after_m,"
      "placements,smoothing_seconds\n";
  for (const std::uint64_t seed : seeds) {
    HaitOptions options;
    options.heuristic = HaitHeuristic::kPotentialRs;
    options.smooth = true;
    options.smoothing.seed = seed;
    options.smoothing.iterations = 2000;
    results.push_back(plan_hait(terrain, robot, scenario.start, scenario.goal, options));
    const HaitResult& r = results.back();
    if (r.status != HaitStatus::kFound) {
      throw SolverError("hait-smoothing: no path: " + r.message);
    }
    csv += std::to_string(seed) + "," + std::to_string(r.control_changes_unsmoothed) + "," +
           std::to_string(r.control_changes) + "," +
           csv_number(path_length(r.unsmoothed_path, options.turning_radius)) + "," +
           csv_number(r.length_m) + "," + std::to_string(r.placements) + "," +
           csv_number(r.smoothing_seconds) + "\n";
  }
  write_text_file(context.output_dir / "smoothing.csv", csv);

  const HaitResult& first = results.front();
  const double radius = HaitOptions{}.turning_radius;
  HaitMapData map;
  map.grid = &scenario.grid;
  map.routes.push_back({first.unsmoothed_path,
                        "searched: " + std::to_string(first.control_changes_unsmoothed) +
                            " control changes, " +
                            sig3(path_length(first.unsmoothed_path, radius)) + " m",
                        "#2c7fb8"});
  map.routes.push_back({first.path,
                        "smoothed (seed 1): " + std::to_string(first.control_changes) +
                            " control changes, " + sig3(first.length_m) + " m",
                        "#e6550d"});
  map.start = scenario.start;
  map.goal = scenario.goal;
  map.title = "hait-smoothing: the potential-rs path before and after Reeds–Shepp smoothing";
  render_hait_map(context.output_dir, "smoothing", map);

  std::vector<std::size_t> after;
  for (const HaitResult& r : results) after.push_back(r.control_changes);
  std::sort(after.begin(), after.end());
  std::ostringstream md;
  md << "# hait-smoothing: Reeds–Shepp smoothing (Haït, Siméon, Taïx 2002, §4.4)\n\n"
     << "**Problem.** The hait-heuristics problem (" << scenario.description
     << ") with the potential-rs guidance and the articulated chassis; the found path is "
        "smoothed by `smooth_path` (default `HaitSmoothingOptions` but 2000 "
        "random pairs at most 5 m apart; a Reeds–Shepp replacement is kept only if every "
        "configuration on it is valid and it removes control changes or shortens the path).\n\n"
     << (context.quick ? "**Quick mode**: smaller map, two seeds.\n\n" : "")
     << "| | ours (seed 1) | paper (Fig. 21) |\n|---|---|---|\n"
     << "| control changes before | " << first.control_changes_unsmoothed << " | 40 |\n"
     << "| control changes after | " << first.control_changes << " | 13 |\n"
     << "| ratio after / before | "
     << fmt("%.2f",
            static_cast<double>(first.control_changes) /
                std::max<double>(1.0, static_cast<double>(first.control_changes_unsmoothed)))
     << " | " << fmt("%.2f", 13.0 / 40.0) << " |\n"
     << "| length before → after [m] | " << sig3(path_length(first.unsmoothed_path, radius))
     << " → " << sig3(first.length_m) << " | – |\n\n"
     << "Over " << seeds.size() << " smoothing seeds the control changes after smoothing range "
     << after.front() << "–" << after.back() << " (median " << after[after.size() / 2] << "), from "
     << first.control_changes_unsmoothed << " (`smoothing.csv`).\n\n"
     << "Files: `smoothing.csv`, `smoothing.png` (`smoothing.gp`).\n\n"
        "![smoothing](smoothing.png)\n";
  write_text_file(context.output_dir / "report.md", md.str());
}

}  // namespace talus::experiments
