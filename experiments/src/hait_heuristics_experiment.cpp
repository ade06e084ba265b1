// hait-heuristics: the table of Haït, Siméon, Taïx 2002 §4.3 (nodes created,
// nodes developed, placements, time for three search guidances) on seeded
// problems of the paper's size, in the paper's configuration (the search ends
// in the goal's cell) and in ours (a Reeds–Shepp curve to the exact goal).
#include <algorithm>
#include <array>
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
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/report.hpp"
#include "talus/scenarios/hait_robots.hpp"

namespace talus::experiments {
namespace {

/// The paper's table (§4.3): euclidean, potential, potential + Reeds–Shepp.
struct PaperRow {
  double created, developed, placements, seconds;
};
constexpr std::array<PaperRow, 3> kPaper{
    {{33004, 30579, 80885, 125.1}, {2278, 1583, 5425, 4.47}, {775, 413, 1757, 1.83}}};

constexpr std::array<HaitHeuristic, 3> kHeuristics{
    HaitHeuristic::kEuclidean, HaitHeuristic::kPotential, HaitHeuristic::kPotentialRs};

/// Seeds of the fractal base; 7 is hait_heuristics_scenario's own terrain, the
/// one the potential-rs blend was tuned on.
const std::vector<std::uint64_t> kSeeds{7, 17, 27, 37, 47};
constexpr std::size_t kQuickSeeds = 2;

/// One query: a seed, the goal connection, a heuristic.
struct Run {
  std::uint64_t seed = 0;
  bool connect = false;
  HaitHeuristic heuristic = HaitHeuristic::kEuclidean;
  HaitResult result;
  double straight_m = 0.0;  ///< start–goal distance [m]
  bool found() const { return result.status == HaitStatus::kFound; }
};

/// The hait_heuristics_scenario problem with its fractal base drawn from
/// `seed` (the same crescent of hills, start and goal; the base's relief as
/// in hait_scenarios.cpp: 1.2 m, quick 0.5 m). Seed 7 is the scenario itself.
HaitScenario seeded_scenario(bool quick, std::uint64_t seed) {
  HaitScenario s = hait_heuristics_scenario(quick);
  if (seed == 7) return s;
  s.grid =
      hait_fractal_base(s.grid.ncols(), s.grid.nrows(), s.grid.cellsize(), quick ? 0.5 : 1.2, seed);
  add_hills(s.grid, s.hills);
  return s;
}

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

const Run* find_run(const std::vector<Run>& runs, std::uint64_t seed, bool connect,
                    HaitHeuristic h) {
  for (const Run& r : runs) {
    if (r.seed == seed && r.connect == connect && r.heuristic == h) return &r;
  }
  return nullptr;
}

std::string count_cell(const Run* r, double (*value)(const HaitResult&)) {
  if (r == nullptr || !r->found()) return r ? status_name(r->result.status) : "–";
  return fmt("%.0f", value(r->result));
}

double created(const HaitResult& r) {
  return static_cast<double>(r.nodes_created);
}
double developed(const HaitResult& r) {
  return static_cast<double>(r.nodes_developed);
}
double placements(const HaitResult& r) {
  return static_cast<double>(r.placements);
}
double seconds(const HaitResult& r) {
  return r.search_seconds;
}

}  // namespace

void run_hait_heuristics(const ExperimentContext& context) {
  require_gnuplot();
  const Robot robot = scenarios::load_hait_chassis(context.data_dir);
  const std::vector<std::uint64_t> seeds(
      kSeeds.begin(),
      kSeeds.begin() + static_cast<std::ptrdiff_t>(context.quick ? kQuickSeeds : kSeeds.size()));
  std::vector<Run> runs;
  const HaitScenario first = seeded_scenario(context.quick, seeds.front());
  std::string csv =
      "seed,goal_connection,heuristic,status,nodes_created,nodes_developed,placements,"
      "search_seconds,preprocessing_seconds,length_m,start_goal_distance_m\n";
  for (const std::uint64_t seed : seeds) {
    const HaitScenario scenario = seeded_scenario(context.quick, seed);
    const RuledTerrain terrain(scenario.grid);
    for (const bool connect : {false, true}) {
      for (const HaitHeuristic h : kHeuristics) {
        HaitOptions options;
        options.heuristic = h;
        options.connect_goal = connect;
        Run run{seed, connect, h, plan_hait(terrain, robot, scenario.start, scenario.goal, options),
                std::hypot(scenario.goal.x - scenario.start.x, scenario.goal.y - scenario.start.y)};
        const HaitResult& r = run.result;
        csv += std::to_string(seed) + "," + (connect ? "on" : "off") + "," + heuristic_name(h) +
               "," + status_name(r.status) + "," + std::to_string(r.nodes_created) + "," +
               std::to_string(r.nodes_developed) + "," + std::to_string(r.placements) + "," +
               csv_number(r.search_seconds) + "," + csv_number(r.preprocessing_seconds) + "," +
               csv_number(run.found() ? r.length_m : std::nan("")) + "," +
               csv_number(run.straight_m) + "\n";
        runs.push_back(std::move(run));
      }
    }
  }
  write_text_file(context.output_dir / "results.csv", csv);

  // The paths of the first seed in the paper's configuration.
  const std::array<const char*, 3> colours{"#2c7fb8", "#31a354", "#e6550d"};
  std::vector<HaitRoute> routes;
  for (std::size_t k = 0; k < 3; ++k) {
    const Run* r = find_run(runs, seeds.front(), false, kHeuristics[k]);
    if (r == nullptr || !r->found()) continue;
    routes.push_back({r->result.path,
                      heuristic_name(kHeuristics[k]) + ": " +
                          std::to_string(r->result.nodes_created) + " nodes, " +
                          sig3(r->result.length_m) + " m",
                      colours[k]});
  }
  render_hait_map(context.output_dir, "paths", first, routes,
                  "hait-heuristics: the three search guidances, seed " +
                      std::to_string(seeds.front()) + ", no goal connection (the paper's)");

  // Medians over the seeds, per configuration and heuristic.
  struct Medians {
    double created, developed, placements, seconds;
    std::size_t found;
  };
  const auto medians = [&](bool connect, HaitHeuristic h) {
    std::vector<double> c, d, p, s;
    for (const Run& r : runs) {
      if (r.connect != connect || r.heuristic != h || !r.found()) continue;
      c.push_back(created(r.result));
      d.push_back(developed(r.result));
      p.push_back(placements(r.result));
      s.push_back(seconds(r.result));
    }
    return Medians{median(c), median(d), median(p), median(s), c.size()};
  };
  // Per seed, the ratio a / b of nodes created (both found), and how many seeds have a < b.
  struct Comparison {
    double min_ratio = std::numeric_limits<double>::infinity(), max_ratio = 0.0;
    std::size_t seeds = 0, fewer = 0;
  };
  const auto compare = [&](bool connect, HaitHeuristic num, HaitHeuristic den) {
    Comparison out;
    for (const std::uint64_t seed : seeds) {
      const Run* a = find_run(runs, seed, connect, num);
      const Run* b = find_run(runs, seed, connect, den);
      if (!a || !b || !a->found() || !b->found()) continue;
      const double ratio = created(a->result) / created(b->result);
      out.min_ratio = std::min(out.min_ratio, ratio);
      out.max_ratio = std::max(out.max_ratio, ratio);
      ++out.seeds;
      if (b->result.nodes_created < a->result.nodes_created) ++out.fewer;
    }
    return out;
  };

  const auto config_table = [&](bool connect) {
    Table t({"median over " + std::to_string(seeds.size()) + " seeds", "euclidean (ours)", "paper",
             "potential (ours)", "paper", "potential-rs (ours)", "paper"});
    struct Measure {
      const char* name;
      double Medians::*ours;
      double PaperRow::*paper;
      bool count;
    };
    const Measure measures[] = {
        {"nodes created", &Medians::created, &PaperRow::created, true},
        {"nodes developed", &Medians::developed, &PaperRow::developed, true},
        {"placements", &Medians::placements, &PaperRow::placements, true},
        {"search time [s]", &Medians::seconds, &PaperRow::seconds, false}};
    for (const Measure& m : measures) {
      std::vector<std::string> cells{m.name};
      for (std::size_t k = 0; k < 3; ++k) {
        const double ours = medians(connect, kHeuristics[k]).*m.ours;
        cells.push_back(m.count ? fmt("%.0f", ours) : fmt("%.3g", ours));
        cells.push_back(m.count ? sig3(kPaper[k].*m.paper) : fmt("%.3g", kPaper[k].*m.paper));
      }
      t.row(cells);
    }
    std::vector<std::string> found{"paths found"};
    for (std::size_t k = 0; k < 3; ++k) {
      found.push_back(std::to_string(medians(connect, kHeuristics[k]).found) + " / " +
                      std::to_string(seeds.size()));
      found.push_back("–");
    }
    t.row(found);
    return t;
  };
  const auto seed_table = [&](bool connect) {
    Table t({"seed", "euclidean", "potential", "potential-rs", "potential ÷ potential-rs"});
    for (const std::uint64_t seed : seeds) {
      const Run* e = find_run(runs, seed, connect, HaitHeuristic::kEuclidean);
      const Run* p = find_run(runs, seed, connect, HaitHeuristic::kPotential);
      const Run* q = find_run(runs, seed, connect, HaitHeuristic::kPotentialRs);
      const bool both = p && q && p->found() && q->found();
      t.row({std::to_string(seed) + (seed == 7 ? " (tuned on)" : ""), count_cell(e, created),
             count_cell(p, created), count_cell(q, created),
             both ? fmt("%.2f", created(p->result) / created(q->result)) : "–"});
    }
    return t;
  };

  const Comparison e_over_p = compare(false, HaitHeuristic::kEuclidean, HaitHeuristic::kPotential);
  const Comparison e_over_q =
      compare(false, HaitHeuristic::kEuclidean, HaitHeuristic::kPotentialRs);
  const Comparison p_over_q =
      compare(false, HaitHeuristic::kPotential, HaitHeuristic::kPotentialRs);
  const Comparison p_over_q_on =
      compare(true, HaitHeuristic::kPotential, HaitHeuristic::kPotentialRs);
  const Medians off_e = medians(false, HaitHeuristic::kEuclidean);
  const Medians off_p = medians(false, HaitHeuristic::kPotential);
  const Medians off_q = medians(false, HaitHeuristic::kPotentialRs);
  const auto holds = [](bool ok) { return std::string(ok ? "**holds**" : "**does not hold**"); };
  const auto seeds_of = [](const Comparison& c) {
    return std::to_string(c.fewer) + " of " + std::to_string(c.seeds) + " seeds";
  };

  Report report("hait-heuristics: search guidance (Haït, Siméon, Taïx 2002, §4.3)");
  report.paragraph(
      "**Problem.** " + first.description +
      " The other seeds draw the fractal base from another seed, with the same crescent, start "
      "and goal. Robot: `data/robots/marsokhod_chassis.yaml` (three-axle articulated chassis, as "
      "the paper's Lama), placed through the θ-sliced placement table; default `HaitOptions` "
      "(0.25 m × 0.25 m × 2π/32 cells, 0.4 m control steps, 1 m turning radius, checks every "
      "0.1 m). The paper's terrain and robot dimensions are not published, so the absolute "
      "counts cannot match; the ordering and the reductions are what compare.");
  if (context.quick) {
    report.paragraph("**Quick mode**: a 61 × 61 map and " + std::to_string(seeds.size()) +
                     " seeds; the numbers below are not the reproduction.");
  }
  report
      .paragraph(
          "**The paper's configuration** (`connect_goal = false`): the search ends when a node "
          "reaches the goal's cell (within 0.25 m and one heading cell). The paper mentions no "
          "final curve to the exact goal; its Reeds–Shepp curves enter only the heuristic "
          "(\"close to the goal the Reeds and Shepp curves are used to take into account the "
          "goal orientation\").")
      .table(config_table(false))
      .paragraph("Nodes created per seed (no goal connection):")
      .table(seed_table(false))
      .paragraph(
          "**Ours** (`connect_goal = true`, the library's default): from every developed node "
          "within 3 m of the goal a valid Reeds–Shepp curve to the exact goal ends the search.")
      .table(config_table(true))
      .paragraph("Nodes created per seed (goal connection on):")
      .table(seed_table(true));

  report.heading("The paper's claims, one by one");
  report.bullet(
      "*The potential bitmap creates far fewer nodes than the straight-line distance* (33,004 → "
      "2,278, 14.5×): " +
      holds(e_over_p.seeds > 0 && e_over_p.fewer == e_over_p.seeds) + " on " + seeds_of(e_over_p) +
      " (euclidean ÷ potential " + fmt("%.0f", e_over_p.min_ratio) + "–" +
      fmt("%.0f", e_over_p.max_ratio) + "×, paper 14.5×; euclidean ÷ potential-rs " +
      fmt("%.0f", e_over_q.min_ratio) + "–" + fmt("%.0f", e_over_q.max_ratio) +
      "×, paper 42.6×). The size of the factor depends on the trap: our crescent cups the "
      "straight line, and the euclidean search fills (x, y, θ) cells in front of it; the "
      "paper's terrain is not published, so only the direction compares.");
  report.bullet(
      "*Adding the Reeds–Shepp guidance near the goal creates fewer nodes again* (2,278 → 775, "
      "2.9×, the paper's bottom row against its middle row): " +
      holds(p_over_q.seeds > 0 && p_over_q.fewer == p_over_q.seeds) + " in the paper's " +
      "configuration: potential-rs creates fewer nodes than the potential on " +
      seeds_of(p_over_q) + " (potential ÷ potential-rs " + fmt("%.2f", p_over_q.min_ratio) + "–" +
      fmt("%.2f", p_over_q.max_ratio) + "; medians " + fmt("%.0f", off_p.created) + " vs " +
      fmt("%.0f", off_q.created) +
      "). Why: the paper gives no rule for \"close\" nor for the combination; ours adds, within "
      "3 m of the goal, (1 − d/3 m) × the Reeds–Shepp distance's excess over the straight line. "
      "Our potential is already nearly exact near the goal (the wave started at each control "
      "point's goal position), so any term added there raises f above that of nodes far behind "
      "and A* develops those first. With our goal connection the order is the paper's on " +
      seeds_of(p_over_q_on) + " (ratio " + fmt("%.2f", p_over_q_on.min_ratio) + "–" +
      fmt("%.2f", p_over_q_on.max_ratio) +
      "): the gain there comes from the final curve, which the paper does not describe. The "
      "blend (weight, 3 m region, continuity at its edge) was tuned on seed 7 of this very "
      "problem, with the goal connection on; seeds 17–47 were not used to tune it.");
  report.bullet(
      "*Both potential guidances are much faster than the straight line* (125.1 s → 4.47 s and "
      "1.83 s): " +
      holds(off_p.seconds < off_e.seconds && off_q.seconds < off_e.seconds) + " for the medians (" +
      fmt("%.3g", off_e.seconds) + " s, " + fmt("%.3g", off_p.seconds) + " s, " +
      fmt("%.3g", off_q.seconds) +
      " s); the time follows the nodes created, and the potential's bitmaps are built in the "
      "preprocessing, outside the search time, as in the paper's table.");
  report.bullet(
      "*Placements per created node* (paper 2.45, 2.38, 2.27): ours " +
      fmt("%.2f", off_e.placements / off_e.created) + ", " +
      fmt("%.2f", off_p.placements / off_p.created) + ", " +
      fmt("%.2f", off_q.placements / off_q.created) +
      " (medians' ratio). Not comparable as counted: we check every arc at 4 configurations "
      "(0.4 m steps every 0.1 m), one placement each; the paper does not say how often it "
      "checks.");
  report.bullet(
      "*Nodes developed ÷ created* (paper 0.93, 0.69, 0.53): ours " +
      fmt("%.2f", off_e.developed / off_e.created) + ", " +
      fmt("%.2f", off_p.developed / off_p.created) + ", " +
      fmt("%.2f", off_q.developed / off_q.created) +
      ". The paper's euclidean search develops almost every node it creates, as ours does; the "
      "guided searches develop a smaller share in both.");
  report.write(context.output_dir,
               "`results.csv` (every run: seed, `goal_connection` off/on, heuristic, counts, "
               "times, path length), `paths.png` (the three paths of seed " +
                   std::to_string(seeds.front()) +
                   " without goal connection over shaded relief, `paths.gp`).",
               {{"paths", "paths.png"}});

  // summary.json: numbers with bounds that do not come from this code.
  ExperimentSummary& summary = *context.summary;
  std::size_t found = 0;
  double min_length_ratio = std::numeric_limits<double>::infinity();
  double min_placement_ratio = std::numeric_limits<double>::infinity();
  for (const Run& r : runs) {
    if (!r.found()) continue;
    ++found;
    // Without the connection the path ends within goal_position_tolerance (one cell) of the goal.
    const double lower = r.straight_m - (r.connect ? 0.0 : HaitOptions{}.cell_size);
    min_length_ratio = std::min(min_length_ratio, r.result.length_m / lower);
    if (!r.connect) {
      // Every created node but the start ends an arc checked at step / check_spacing = 4
      // configurations, one placement each at least.
      const double arcs = static_cast<double>(r.result.nodes_created - 1);
      min_placement_ratio = std::min(min_placement_ratio, placements(r.result) / (4.0 * arcs));
    }
  }
  summary.set("runs_without_path", static_cast<double>(runs.size() - found), "count",
              "0: every seeded problem has a path (the crescent opens towards the start)");
  summary.set("min_path_length_over_start_goal_distance", min_length_ratio, "1",
              ">= 1: no path is shorter than the straight line (less the goal cell without the "
              "connection)");
  summary.set("min_placements_over_4_per_created_node", min_placement_ratio, "1",
              ">= 1: each created node's arc was checked at 4 configurations");
  summary.set("euclidean_over_potential_nodes_min", e_over_p.min_ratio, "1",
              "paper 33004 / 2278 = 14.5; the claim (fewer nodes) holds when > 1");
  summary.set("potential_over_potential_rs_nodes_min_no_connection", p_over_q.min_ratio, "1",
              "paper 2278 / 775 = 2.9 (does not reproduce: < 1 means potential-rs creates more)");
  summary.set("potential_over_potential_rs_nodes_max_no_connection", p_over_q.max_ratio, "1",
              "paper 2278 / 775 = 2.9");
  summary.set("potential_over_potential_rs_nodes_min_connection", p_over_q_on.min_ratio, "1",
              "ours, with the Reeds-Shepp goal connection");
  summary.set("median_nodes_created_euclidean_no_connection", off_e.created, "count",
              "paper 33004");
  summary.set("median_nodes_created_potential_no_connection", off_p.created, "count", "paper 2278");
  summary.set("median_nodes_created_potential_rs_no_connection", off_q.created, "count",
              "paper 775");
}

}  // namespace talus::experiments
