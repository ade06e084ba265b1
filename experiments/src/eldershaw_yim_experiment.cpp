// eldershaw-footmap: footmap and CGmap at theta = 0 of Eldershaw and Yim (ICRA
// 2001, §3.1, Fig. 3, 4 and 6) for the spider and the Ambler-like walker on the
// generated test terrain, the counts behind the figures and the paper's claims.
#include "eldershaw_yim_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "eldershaw_yim_outputs.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/eldershaw_yim/cg_space.hpp"
#include "talus/kinematic/eldershaw_yim/eldershaw_yim_planner.hpp"
#include "talus/kinematic/eldershaw_yim/legged_robot.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/report.hpp"
#include "talus/sweep/mpi_session.hpp"

namespace talus::experiments {
namespace {

/// What one robot's maps hold.
struct MapCounts {
  std::string name, file;
  std::size_t foot_nodes = 0, invalid_foot = 0;
  std::size_t cg_cells = 0, off_data = 0, no_support = 0, too_short = 0;
  std::size_t regions = 0;          ///< 4-connected regions of invalid foot nodes
  std::size_t straddled = 0;        ///< regions under which every CG cell is valid
  std::size_t border = 0;           ///< invalid CG cells (not off the data) over valid foot nodes
  std::size_t peaks_straddled = 0;  ///< of the nine peak apices, CG cells there valid
  bool cliff_crossable = false;     ///< some CG cell astride the east cliff is valid
  double seconds = 0.0;
  std::size_t invalid() const { return no_support + too_short; }
};

/// Labels of the 4-connected components of invalid foot nodes (-1 = valid node).
std::vector<int> invalid_regions(const Footmap& fm, std::size_t& count) {
  const std::size_t nc = fm.ncols(), nr = fm.nrows();
  std::vector<int> label(nc * nr, -1);
  count = 0;
  std::vector<std::size_t> stack;
  for (std::size_t start = 0; start < nc * nr; ++start) {
    if (label[start] >= 0 || fm.valid(start % nc, start / nc)) continue;
    const int id = static_cast<int>(count++);
    label[start] = id;
    stack.assign(1, start);
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      const std::size_t i = k % nc, j = k / nc;
      const std::size_t nb[4] = {i > 0 ? k - 1 : k, i + 1 < nc ? k + 1 : k, j > 0 ? k - nc : k,
                                 j + 1 < nr ? k + nc : k};
      for (std::size_t n : nb) {
        if (label[n] >= 0 || fm.valid(n % nc, n / nc)) continue;
        label[n] = id;
        stack.push_back(n);
      }
    }
  }
  return label;
}

/// The test terrain of both experiments: 24 m square (the generator lays it out in units of
/// half the side: plateau +-3.6 m at 1 m with a cliff to the east, peaks 1.5 m high of base
/// radius 0.96 m), seed 2001.
ElevationGrid test_terrain(bool quick) {
  EldershawYimOptions t;
  t.shape = quick ? GridShape{81, 81, 0.3, 0.0, 0.0} : GridShape{121, 121, 0.2, 0.0, 0.0};
  t.seed = 2001;
  return generate_eldershaw_yim(t);
}

}  // namespace

void run_eldershaw_footmap(const ExperimentContext& context) {
  require_gnuplot();
  const ElevationGrid grid = test_terrain(context.quick);
  write_esri_ascii(grid, (context.output_dir / "terrain.asc").string());
  const RuledTerrain terrain(grid);
  const double side = grid.x_max() - grid.x_min();
  const Vec2 centre(grid.x_min() + side / 2, grid.y_min() + side / 2);
  const double unit = side / 2;
  // Peak apices: the nine local maxima of the ring (the highest node in each 40-degree sector).
  std::vector<Vec2> apices(9, centre);
  std::vector<double> apex_z(9, -1e300);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const Vec2 p = grid.node_position(i, j);
      const Vec2 d = p - centre;
      if (d.norm() < 0.65 * unit || d.norm() > 0.95 * unit) continue;
      double a = std::atan2(d.y(), d.x());
      if (a < 0) a += 2 * std::acos(-1.0);
      // Sectors centred on the generator's evenly spaced angles 2 pi k / 9.
      const auto k = static_cast<std::size_t>(std::lround(a / (2 * std::acos(-1.0) / 9))) % 9;
      if (grid.at(i, j) > apex_z[k]) apex_z[k] = grid.at(i, j), apices[k] = p;
    }

  std::vector<MapCounts> maps;
  std::vector<std::vector<CgState>> slices;
  std::vector<CgLattice> lattices;
  std::vector<LeggedRobot> robots;
  for (const auto& [name, file] : {std::pair{"spider", "eldershaw_spider.yaml"},
                                   std::pair{"ambler", "eldershaw_ambler.yaml"}}) {
    const auto t0 = std::chrono::steady_clock::now();
    const LeggedRobot robot = load_legged_robot(context.data_dir / "robots" / file);
    const Footmap fm(terrain, robot);
    const CgLattice L(grid, robot.foot_print, 16);
    std::vector<CgState> slice = evaluate_cg_slice(fm, robot, L, 0);
    MapCounts m;
    m.name = name;
    m.file = file;
    m.foot_nodes = fm.ncols() * fm.nrows();
    m.invalid_foot = fm.invalid_count();
    m.cg_cells = slice.size();
    const std::vector<int> label = invalid_regions(fm, m.regions);
    std::vector<std::size_t> under(m.regions, 0), invalid_under(m.regions, 0);
    for (int iy = 0; iy < L.ny(); ++iy)
      for (int ix = 0; ix < L.nx(); ++ix) {
        const CgState s = slice[static_cast<std::size_t>(iy) * static_cast<std::size_t>(L.nx()) +
                                static_cast<std::size_t>(ix)];
        m.off_data += s == CgState::kOffData ? 1 : 0;
        m.no_support += s == CgState::kNoSupport ? 1 : 0;
        m.too_short += s == CgState::kTooShort ? 1 : 0;
        const SE2Pose q = L.centre({ix, iy, 0});
        const auto i =
            static_cast<std::size_t>(std::lround((q.x - grid.x_min()) / grid.cellsize()));
        const auto j =
            static_cast<std::size_t>(std::lround((q.y - grid.y_min()) / grid.cellsize()));
        const int r = label[std::min(j, fm.nrows() - 1) * fm.ncols() + std::min(i, fm.ncols() - 1)];
        if (r >= 0) {
          ++under[static_cast<std::size_t>(r)];
          invalid_under[static_cast<std::size_t>(r)] += s == CgState::kValid ? 0 : 1;
        } else if ((s == CgState::kNoSupport || s == CgState::kTooShort) &&
                   std::min({q.x - grid.x_min(), q.y - grid.y_min(), grid.x_max() - q.x,
                             grid.y_max() - q.y}) >= robot.outer_radius()) {
          ++m.border;  // not counting the cells whose legs would reach off the map
        }
      }
    for (std::size_t r = 0; r < m.regions; ++r)
      m.straddled += under[r] > 0 && invalid_under[r] == 0 ? 1 : 0;
    for (const Vec2& a : apices)
      m.peaks_straddled += evaluate_cg_pose(fm, robot, {a.x(), a.y(), 0}) == CgState::kValid;
    // The cliff is the plateau's east edge (x = centre + 0.3 u), |y| < 0.25 u from the centre.
    for (double y = centre.y() - 0.25 * unit; y <= centre.y() + 0.25 * unit; y += robot.foot_print)
      m.cliff_crossable =
          m.cliff_crossable ||
          evaluate_cg_pose(fm, robot, {centre.x() + 0.3 * unit, y, 0}) == CgState::kValid;
    m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    CgMapFigure fig;
    fig.footmap = &fm;
    fig.lattice = &L;
    fig.slice = slice;
    fig.it = 0;
    fig.title = "eldershaw-footmap: " + robot.name + " (cf. Fig. " +
                (std::string(name) == "spider" ? "4" : "6") + ")";
    render_cg_map(context.output_dir, std::string("cgmap_") + name, fig);
    maps.push_back(m);
    slices.push_back(std::move(slice));
    lattices.push_back(L);
    robots.push_back(robot);
  }
  const MapCounts& sp = maps[0];
  const MapCounts& am = maps[1];

  std::string csv =
      "robot,foot_nodes,invalid_foot_nodes,cg_cells,off_data,no_support,too_short,"
      "invalid_foot_regions,straddled_regions,black_border_cells,peaks_straddled,cliff_crossable,"
      "seconds\n";
  Table table({"robot", "invalid foot nodes", "invalid CG cells (no support / too short)",
               "off the map", "invalid-foot regions", "straddled", "black border",
               "peaks straddled", "cliff crossable"});
  for (const MapCounts& m : maps) {
    csv += m.name + "," + std::to_string(m.foot_nodes) + "," + std::to_string(m.invalid_foot) +
           "," + std::to_string(m.cg_cells) + "," + std::to_string(m.off_data) + "," +
           std::to_string(m.no_support) + "," + std::to_string(m.too_short) + "," +
           std::to_string(m.regions) + "," + std::to_string(m.straddled) + "," +
           std::to_string(m.border) + "," + std::to_string(m.peaks_straddled) + "," +
           (m.cliff_crossable ? "1" : "0") + "," + csv_number(m.seconds) + "\n";
    table.row({m.name, std::to_string(m.invalid_foot) + " of " + std::to_string(m.foot_nodes),
               std::to_string(m.invalid()) + " of " + std::to_string(m.cg_cells) + " (" +
                   std::to_string(m.no_support) + " / " + std::to_string(m.too_short) + ")",
               std::to_string(m.off_data), std::to_string(m.regions), std::to_string(m.straddled),
               std::to_string(m.border), std::to_string(m.peaks_straddled) + " of 9",
               m.cliff_crossable ? "yes" : "no"});
  }
  write_text_file(context.output_dir / "counts.csv", csv);

  // The CGmaps differ between the vehicles: compare at the Ambler's cell centres (0.5 m is a
  // multiple of the spider's 0.25 m, both lattices start at the south-west node).
  std::size_t compared = 0, differ = 0;
  for (int iy = 0; iy < lattices[1].ny(); ++iy)
    for (int ix = 0; ix < lattices[1].nx(); ++ix) {
      const SE2Pose q = lattices[1].centre({ix, iy, 0});
      const CgCell c = lattices[0].cell_of(q);
      const CgState a = slices[1][static_cast<std::size_t>(iy) * lattices[1].nx() + ix];
      const CgState s = slices[0][static_cast<std::size_t>(c.iy) * lattices[0].nx() + c.ix];
      if (a == CgState::kOffData || s == CgState::kOffData) continue;
      ++compared;
      differ += (a == CgState::kValid) != (s == CgState::kValid) ? 1 : 0;
    }

  struct Claim {
    std::string text, evidence;
    bool holds;
  };
  const std::vector<Claim> claims{
      {"the sharp peaks are too steep for traction (invalid foot regions)",
       std::to_string(sp.regions) + " / " + std::to_string(am.regions) +
           " invalid-foot regions for spider / Ambler (nine peaks, the plateau's cliff)",
       sp.regions >= 9 && am.regions >= 9},
      {"CGmaps depend on the vehicle, not only on the environment",
       std::to_string(differ) + " of " + std::to_string(compared) +
           " compared cells valid for one vehicle only",
       differ > 0},
      {"invalid foot positions need not be invalid CG cells: a vehicle straddles them",
       std::to_string(am.straddled) + " regions straddled by the Ambler, " +
           std::to_string(sp.straddled) + " by the spider",
       am.straddled > 0},
      {"the Ambler's longer reach is clearly seen (fewer invalid CG cells)",
       std::to_string(am.invalid()) + " of " + std::to_string(am.cg_cells) + " vs " +
           std::to_string(sp.invalid()) + " of " + std::to_string(sp.cg_cells) + " (fractions " +
           sig3(double(am.invalid()) / am.cg_cells) + " vs " +
           sig3(double(sp.invalid()) / sp.cg_cells) + ")",
       double(am.invalid()) / am.cg_cells < double(sp.invalid()) / sp.cg_cells},
      {"a black border of invalid CG cells surrounds large invalid foot regions (no support on "
       "one side)",
       std::to_string(sp.border) + " spider cells, " + std::to_string(am.border) +
           " Ambler cells invalid over valid foot nodes",
       sp.border > 0},
      {"a cliff is impassable only because no leg reaches from its base to its top",
       std::string("spider (reach 0.3 m) ") + (sp.cliff_crossable ? "crosses" : "cannot cross") +
           " the 1 m cliff, Ambler (reach 1.8-2.2 m) " +
           (am.cliff_crossable ? "crosses" : "cannot cross"),
       !sp.cliff_crossable && am.cliff_crossable},
  };
  std::size_t holding = 0;
  Table claim_table({"paper's claim", "ours", "holds"});
  for (const Claim& c : claims) {
    holding += c.holds ? 1 : 0;
    claim_table.row({c.text, c.evidence, c.holds ? "yes" : "no"});
  }

  ExperimentSummary& sum = *context.summary;
  sum.set("claims_holding", static_cast<double>(holding), "1",
          std::to_string(claims.size()) + ": every claim of §3.1/§5 checked holds");
  sum.set("claims_checked", static_cast<double>(claims.size()), "1", "");
  for (const MapCounts& m : maps) {
    sum.set(m.name + "_invalid_foot_nodes", static_cast<double>(m.invalid_foot), "1", "");
    sum.set(m.name + "_invalid_cg_cells", static_cast<double>(m.invalid()), "1", "");
    sum.set(m.name + "_straddled_regions", static_cast<double>(m.straddled), "1", "");
    sum.set(m.name + "_black_border_cells", static_cast<double>(m.border), "1", "");
    sum.set(m.name + "_peaks_straddled", static_cast<double>(m.peaks_straddled), "1", "of 9");
    sum.set(m.name + "_seconds", m.seconds, "s", "footmap and one CG slice");
  }
  sum.set("cells_valid_for_one_vehicle_only", static_cast<double>(differ), "1", "> 0");

  Report report("eldershaw-footmap: footmap and CGmap (Eldershaw, Yim, ICRA 2001)");
  report.paragraph(
      "**Problem.** The `eldershaw-yim` test terrain (seed 2001, " + std::to_string(grid.ncols()) +
      " × " + std::to_string(grid.nrows()) + " nodes at " + sig3(grid.cellsize()) +
      " m: a 1 m plateau with ramps to the west, north and south and a sheer cliff to the east, "
      "nine 1.5 m peaks round it, 2 cm roughness; the paper prints no dimensions of its Fig. 3) "
      "for the spider (`eldershaw_spider.yaml`) and the Ambler-like walker "
      "(`eldershaw_ambler.yaml`), both invented. CGmaps at θ = 0; a region is a 4-connected set "
      "of invalid foot nodes, straddled when every CG cell centred on it is valid; black-border "
      "cells are invalid CG cells centred on valid foot nodes, at least the legs' outer radius "
      "from the map's edge (nearer, the legs' ranges leave the map).");
  if (context.quick) report.paragraph("**Quick mode**: 81 × 81 nodes at 0.3 m.");
  report.heading("Counts").table(table);
  report.heading("The paper's claims, one by one").table(claim_table);
  report.write(context.output_dir,
               "`counts.csv`, `terrain.asc`, `cgmap_spider.png`, `cgmap_ambler.png`",
               {{"footmap and CGmap at θ = 0, spider (cf. Fig. 4)", "cgmap_spider.png"},
                {"footmap and CGmap at θ = 0, Ambler-like (cf. Fig. 6)", "cgmap_ambler.png"}});
}

void run_eldershaw_plan(const ExperimentContext& context) {
  require_gnuplot();
  const ElevationGrid grid = test_terrain(context.quick);
  write_esri_ascii(grid, (context.output_dir / "terrain.asc").string());
  const RuledTerrain terrain(grid);
  const SE2Pose start{4, 4, 0}, goal{20, 20, 0};
  struct Run {
    std::string robot, mode;
    EldershawYimResult r;
  };
  std::vector<Run> runs;
  std::string csv =
      "robot,mode,status,length_m,prm_points,local_planner_calls,cg_cells_materialised,cg_cells,"
      "search_seconds,foot_plan_status,foot_plan_steps,foot_planner_nodes,feedback_events\n";
  Table table({"robot", "mode", "status", "length [m]", "PRM points", "local-planner calls",
               "CG cells materialised", "search [s]", "foot plan", "feedback events"});
  std::vector<FigureLink> figures;
  for (const auto& [name, file] : {std::pair{"spider", "eldershaw_spider.yaml"},
                                   std::pair{"ambler", "eldershaw_ambler.yaml"}}) {
    const LeggedRobot robot = load_legged_robot(context.data_dir / "robots" / file);
    for (const bool direct : {false, true}) {
      EldershawYimPlannerOptions o;
      o.direct = direct;
      o.prm_points = context.quick ? 100 : 200;
      o.feet.budget = context.quick ? 5000 : 20000;
      EldershawYimResult r = plan_eldershaw_yim(terrain, robot, start, goal, o);
      const std::string mode = direct ? "direct" : "tree-prm";
      csv += std::string(name) + "," + mode + "," + to_string(r.status) + "," +
             csv_number(r.length_m) + "," + std::to_string(r.prm_points.size()) + "," +
             std::to_string(r.local_planner_calls) + "," + std::to_string(r.cells_materialised) +
             "," + std::to_string(r.cg_cells) + "," + csv_number(r.search_seconds) + "," +
             (r.feet_planned ? to_string(r.foot_plan.status) : "none") + "," +
             std::to_string(r.feet_planned ? r.foot_plan.steps.size() : 0) + "," +
             std::to_string(r.foot_planner_nodes) + "," + std::to_string(r.feedback_events) + "\n";
      table.row({name, mode, to_string(r.status), sig3(r.length_m),
                 std::to_string(r.prm_points.size()), std::to_string(r.local_planner_calls),
                 std::to_string(r.cells_materialised) + " of " + std::to_string(r.cg_cells),
                 fmt("%.3g", r.search_seconds),
                 r.feet_planned ? std::string(to_string(r.foot_plan.status)) + ", " +
                                      std::to_string(r.foot_plan.steps.size()) + " steps"
                                : "none",
                 std::to_string(r.feedback_events)});
      if (direct) {
        const Footmap fm(terrain, robot);
        const CgLattice L(grid, robot.foot_print, o.theta_slices);
        CgMapFigure fig;
        fig.footmap = &fm;
        fig.lattice = &L;
        fig.slice = evaluate_cg_slice(fm, robot, L, 0);
        fig.path = r.path;
        if (r.feet_planned)
          for (const FootStep& st : r.foot_plan.steps)
            for (const FootState& f : st.feet)
              if (f.contact) fig.footprints.push_back(foot_position(fm, f).head<2>());
        fig.title = "eldershaw-plan: " + robot.name + ", direct A* route and footprints";
        render_cg_map(context.output_dir, std::string("route_") + name, fig);
        figures.push_back({std::string(name) + ": CGmap at θ = 0, the direct route and its "
                                               "footprints (cf. Fig. 6)",
                           std::string("route_") + name + ".png"});
      }
      runs.push_back({name, mode, std::move(r)});
    }
  }
  write_text_file(context.output_dir / "runs.csv", csv);
  const EldershawYimResult &sp_prm = runs[0].r, &sp_dir = runs[1].r, &am_prm = runs[2].r,
                           &am_dir = runs[3].r;
  ExperimentSummary& sum = *context.summary;
  std::size_t found = 0;
  for (const Run& run : runs) found += run.r.found() ? 1 : 0;
  sum.set("routes_found", static_cast<double>(found), "1", "4: both vehicles, both modes");
  for (const Run& run : runs) {
    const std::string k = run.robot + "_" + (run.mode == "direct" ? "direct" : "prm");
    sum.set(k + "_length_m", run.r.length_m, "m", "");
    sum.set(k + "_local_planner_calls", static_cast<double>(run.r.local_planner_calls), "1",
            run.mode == "direct" ? "1 per round (plus one per feedback event)" : "");
    sum.set(k + "_search_seconds", run.r.search_seconds, "s", "");
    sum.set(k + "_feedback_events", static_cast<double>(run.r.feedback_events), "1", "");
  }
  const double min_prm_over_direct =
      std::min(sp_prm.length_m / sp_dir.length_m, am_prm.length_m / am_dir.length_m);
  sum.set("min_prm_over_direct_length", min_prm_over_direct, "1",
          ">= 1: the trees' routes are less direct (§3.1); the direct A* is optimal in its metric "
          "on the final CGspace");
  sum.set("ambler_over_spider_direct_length", am_dir.length_m / sp_dir.length_m, "1",
          "<= 1: the Ambler straddles what the spider goes round");
  sum.set("ambler_foot_plan_found", am_dir.feet_planned && am_dir.foot_plan.found() ? 1.0 : 0.0,
          "1", "1: the foot planner follows the Ambler's route (Fig. 6's footprints)");

  Report report("eldershaw-plan: the full route (Eldershaw, Yim, ICRA 2001)");
  report.paragraph(
      "**Problem.** The `eldershaw-footmap` terrain, from (4, 4) to (20, 20) at θ = 0, for the "
      "spider and the Ambler-like walker; tree-PRM (" +
      std::to_string(context.quick ? 100 : 200) +
      " random points, seed 1, connect radius 40 foot prints) against one direct A* over "
      "CGspace (16 heading slices), then the foot-level planner along the route with §3.3 "
      "feedback (at most 3 rounds). Times are wall clock on a shared machine.");
  if (context.quick) report.paragraph("**Quick mode**: 81 × 81 nodes, 100 PRM points.");
  report.heading("Runs").table(table);
  report.heading("Paper beside ours")
      .table(Table({"statement", "paper", "ours"})
                 .row({"tree-PRM routes", "may take a considerably less direct route",
                       "PRM / direct length: spider " + sig3(sp_prm.length_m / sp_dir.length_m) +
                           ", Ambler " + sig3(am_prm.length_m / am_dir.length_m)})
                 .row({"direct A* on a server", "quite cheap; could replace the PRM",
                       "spider " + fmt("%.3g", sp_dir.search_seconds) + " s direct vs " +
                           fmt("%.3g", sp_prm.search_seconds) + " s PRM; Ambler " +
                           fmt("%.3g", am_dir.search_seconds) + " s vs " +
                           fmt("%.3g", am_prm.search_seconds) + " s"})
                 .row({"§3.3 situations", "not frequent in the authors' experience",
                       "feedback events: spider " + std::to_string(sp_dir.feedback_events) +
                           " (direct), " + std::to_string(sp_prm.feedback_events) +
                           " (PRM); Ambler " + std::to_string(am_dir.feedback_events) + ", " +
                           std::to_string(am_prm.feedback_events)})
                 .row({"Ambler footprints along the route (Fig. 6)", "shown",
                       am_dir.feet_planned
                           ? std::string(to_string(am_dir.foot_plan.status)) + ", " +
                                 std::to_string(am_dir.foot_plan.steps.size()) + " steps"
                           : "not planned"}));
  report.write(context.output_dir,
               "`runs.csv`, `terrain.asc`, `route_spider.png`, `route_ambler.png`", figures);
}

namespace {

/// This process's peak resident memory so far [MiB] (Linux reports KiB).
double process_peak_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

double median3(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

void run_eldershaw_parallel(const ExperimentContext& context) {
  require_gnuplot();
  const ElevationGrid grid = test_terrain(context.quick);
  const std::string terrain_file = (context.output_dir / "terrain.asc").string();
  write_esri_ascii(grid, terrain_file);
  const RuledTerrain terrain(grid);
  const std::string robot_file = (context.data_dir / "robots" / "eldershaw_spider.yaml").string();
  const LeggedRobot robot = load_legged_robot(robot_file);
  const SE2Pose start{4, 4, 0}, goal{20, 20, 0};
  const int slices = context.quick ? 32 : 64;
  EldershawYimPlannerOptions o;
  o.theta_slices = slices;
  o.connect_radius = 8.0;
  o.local.margin = 12;
  o.local.heading_weight = 0.0;  // the robot's outer radius, as the CLI
  o.prm_points = 300;
  o.plan_feet = false;
  constexpr int kRuns = 3;

  struct Row {
    std::string mode;
    double search_s = 0, connect_s = 0, peak_mib = 0;
    bool same = true;
  };
  std::vector<Row> rows;
  EldershawYimResult serial;
  for (const int workers : {1, 2, 4}) {
    o.workers = workers;
    std::vector<double> search, connect;
    Row row{std::to_string(workers) + (workers == 1 ? " thread" : " threads")};
    for (int k = 0; k < kRuns; ++k) {
      const EldershawYimResult r = plan_eldershaw_yim(terrain, robot, start, goal, o);
      if (workers == 1 && k == 0) serial = r;
      row.same = row.same && r.cells == serial.cells && r.prm_points == serial.prm_points &&
                 r.local_planner_calls == serial.local_planner_calls &&
                 r.expansions == serial.expansions &&
                 r.cells_materialised == serial.cells_materialised;
      search.push_back(r.search_seconds);
      connect.push_back(r.connect_seconds + r.recreate_seconds);
    }
    row.search_s = median3(search);
    row.connect_s = median3(connect);
    row.peak_mib = process_peak_mib();
    rows.push_back(row);
  }

  // Two ranks: this program under mpirun, its summary.json read back.
  const bool mpi = MpiSession::mpirun_available();
  if (mpi) {
    std::vector<double> search, connect, peak;
    Row row{"2 MPI ranks"};
    for (int k = 0; k < kRuns; ++k) {
      const std::filesystem::path out = context.output_dir / ("mpi_run_" + std::to_string(k));
      const std::string cmd =
          "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe "
          "-n 2 /proc/" +
          std::to_string(getpid()) + "/exe baseline eldershaw-yim --terrain '" + terrain_file +
          "' --robot '" + robot_file + "' --start 4,4,0 --goal 20,20,0 --theta-slices " +
          std::to_string(slices) +
          " --connect-radius 8 --local-margin 12 --prm-points 300 --foot-budget 0 --out '" +
          out.string() + "' >/dev/null 2>&1";
      if (std::system(cmd.c_str()) != 0) throw SolverError("eldershaw-parallel: failed: " + cmd);
      std::ifstream in(out / "summary.json");
      const nlohmann::json s = nlohmann::json::parse(in);
      row.same = row.same && s["local_planner_calls"] == serial.local_planner_calls &&
                 s["expansions"] == serial.expansions &&
                 s["cg_cells_materialised"] == serial.cells_materialised &&
                 s["length_m"].get<double>() == serial.length_m;
      search.push_back(s["search_seconds"].get<double>());
      connect.push_back(s["connect_seconds"].get<double>() + s["recreate_seconds"].get<double>());
      peak.push_back(s["peak_rss_mib_max"].get<double>());
    }
    row.search_s = median3(search);
    row.connect_s = median3(connect);
    row.peak_mib = median3(peak);
    rows.push_back(row);
  }

  std::string csv =
      "mode,same_plan,search_seconds_median,local_planning_seconds_median,"
      "speed_up,peak_rss_mib\n";
  Table table(
      {"mode", "same plan", "search [s]", "local planning [s]", "speed-up", "peak memory [MiB]"});
  std::size_t same = 0;
  for (const Row& r : rows) {
    const double speed_up = rows[0].search_s / r.search_s;
    same += r.same ? 1 : 0;
    csv += r.mode + "," + (r.same ? "1" : "0") + "," + csv_number(r.search_s) + "," +
           csv_number(r.connect_s) + "," + csv_number(speed_up) + "," + csv_number(r.peak_mib) +
           "\n";
    table.row({r.mode, r.same ? "yes" : "NO", fmt("%.3g", r.search_s), fmt("%.3g", r.connect_s),
               fmt("%.3g", speed_up), fmt("%.4g", r.peak_mib)});
  }
  write_text_file(context.output_dir / "runs.csv", csv);
  // The median times per mode as bars (speedup.png).
  std::string dat;
  for (const Row& r : rows)
    dat += "\"" + r.mode + "\" " + csv_number(r.search_s) + " " + csv_number(r.connect_s) + "\n";
  write_text_file(context.output_dir / "speedup.dat", dat);
  write_text_file(context.output_dir / "speedup.gp",
                  png_terminal(900, 600) + "\nset output 'speedup.png'\n" + "set title " +
                      gnuplot_plain_text("eldershaw-parallel: median search time of " +
                                         std::to_string(kRuns) + " runs") +
                      "\nset style data histograms\nset style fill solid 0.7 border -1\n"
                      "set ylabel 'time [s]'\nset yrange [0:*]\nset key top left\n"
                      "plot 'speedup.dat' using 2:xtic(1) title 'search', '' using 3 title "
                      "'local-planner calls'\n");
  run_gnuplot(context.output_dir / "speedup.gp");
  ExperimentSummary& sum = *context.summary;
  sum.set("modes_run", static_cast<double>(rows.size()), "1", "3 thread counts, plus 2 ranks");
  sum.set("modes_differing", static_cast<double>(rows.size() - same), "1",
          "0: the plan and its counters do not depend on threads or ranks");
  sum.set("mpi_run", mpi ? 1.0 : 0.0, "1", "1 when mpirun is installed");
  sum.set("local_planner_calls", static_cast<double>(serial.local_planner_calls), "1", "");
  sum.set("speed_up_2_threads", rows[0].search_s / rows[1].search_s, "1", "search time");
  sum.set("speed_up_4_threads", rows[0].search_s / rows[2].search_s, "1", "search time");
  if (mpi) sum.set("speed_up_2_ranks", rows[0].search_s / rows[3].search_s, "1", "search time");

  Report report("eldershaw-parallel: distributed local planning (Eldershaw, Yim, ICRA 2001)");
  report.paragraph(
      "**Problem.** The spider's tree-PRM query of `eldershaw-plan` ((4, 4) to (20, 20)) with " +
      std::to_string(slices) +
      " heading slices, connect radius 8 m and local-planner margin 12 cells (300 points at "
      "most, no foot plan), " +
      std::to_string(serial.local_planner_calls) + " local-planner calls, " +
      std::to_string(serial.cells_materialised) +
      " CG cells evaluated. Threads run in this process (its peak memory only grows, so the "
      "column is the peak so far); ranks are this program under mpirun on the same machine "
      "(the column: the larger rank's peak). Search times are medians of 3 runs, wall clock "
      "on a shared 2-core machine.");
  if (!mpi) report.paragraph("mpirun is not installed here: the ranks were not run.");
  report.heading("Runs").table(table);
  report.heading("Paper beside ours")
      .table(Table({"statement", "paper", "ours"})
                 .row({"distributed local planning",
                       "five PolyBot modules roughly halved the "
                       "planning time",
                       "2 threads: speed-up " + fmt("%.3g", rows[0].search_s / rows[1].search_s) +
                           (mpi ? ", 2 ranks: " + fmt("%.3g", rows[0].search_s / rows[3].search_s)
                                : std::string())}));
  report.paragraph(
      "The calls of one new point are few (one per tree within reach, round by round) and each "
      "call's overlay evaluates the CGspace blocks the shared space lacks, so concurrent calls "
      "near each other evaluate some blocks twice, and the random points' validity is checked "
      "serially; under MPI every rank also evaluates those blocks itself.");
  report.write(context.output_dir,
               "`runs.csv`, `terrain.asc`, `speedup.png` (with `speedup.gp`, `speedup.dat`), "
               "`mpi_run_*/`",
               {{"Median search time and local-planner time per mode", "speedup.png"}});
}

}  // namespace talus::experiments
