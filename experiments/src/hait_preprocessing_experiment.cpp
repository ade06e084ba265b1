// hait-preprocessing: preprocessing time against terrain size and resolution
// (Haït, Siméon, Taïx 2002 §4.3, Fig. 20: linear in size, quadratic in
// resolution).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "hait_experiments.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/core/sample_statistics.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"
#include "talus/kinematic/hait/hait_robot_validity.hpp"
#include "talus/kinematic/hait/potential_bitmap.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/report.hpp"
#include "talus/scenarios/hait_robots.hpp"

namespace talus::experiments {
namespace {

/// One measured terrain.
struct Sample {
  std::string sweep;
  std::size_t n = 0;  ///< nodes per side
  double spacing = 0.0;
  int slices = 72;
  double validity_seconds = 0.0;   ///< HaitRobotValidity: chassis table + quadtree
  double bitmap_seconds = 0.0;     ///< one PotentialBitmap (cost + wave)
  long long table_placements = 0;  ///< Place_axle runs of the chassis table (slices × nodes)
  std::size_t disc_nodes = 0;      ///< nodes of the cost bitmap's disc (work per node)
  double total() const { return validity_seconds + bitmap_seconds; }
  double nodes() const { return static_cast<double>(n * n); }
};

Sample measure(const std::string& sweep, const Robot& robot, std::size_t n, double spacing,
               int repeats) {
  const double extent = spacing * static_cast<double>(n - 1);
  const auto hills = static_cast<std::size_t>(std::lround(8.0 * extent * extent / (35.0 * 35.0)));
  const RuledTerrain terrain(hait_rough_terrain(n, n, spacing, hills, 3));
  Sample s{sweep, n, spacing};
  s.validity_seconds = s.bitmap_seconds = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeats; ++r) {  // the fastest run: the least disturbed by other load
    const HaitRobotValidity validity(terrain, robot);
    s.validity_seconds = std::min(s.validity_seconds, validity.preprocessing_seconds());
    s.table_placements = validity.diagnostics().table_placements;
    PotentialBitmapOptions bo;
    bo.robot_radius = validity.radius();
    const auto t0 = Clock::now();
    const PotentialBitmap bitmap(terrain, Vec2(0.5 * extent, 0.5 * extent), bo);
    s.bitmap_seconds = std::min(s.bitmap_seconds, seconds_since(t0));
    s.disc_nodes = bitmap.stats().disc_nodes;
  }
  return s;
}

void write_series(std::ofstream& out, const std::vector<Sample>& samples,
                  const std::string& sweep) {
  for (const Sample& s : samples) {
    if (s.sweep != sweep) continue;
    out << fmt("%.8g", s.nodes()) << ' ' << fmt("%.8g", 1.0 / s.spacing) << ' '
        << fmt("%.8g", s.total()) << ' ' << fmt("%.8g", s.validity_seconds) << '\n';
  }
  out << "\n\n";
}

}  // namespace

void run_hait_preprocessing(const ExperimentContext& context) {
  require_gnuplot();
  const Robot robot = scenarios::load_hait_chassis(context.data_dir);
  const ArticulatedChassis& chassis = std::get<ArticulatedChassis>(robot);
  const bool quick = context.quick;
  const int repeats = quick ? 1 : 2;

  std::vector<Sample> samples;
  // (a) size at the paper's fixed 0.25 m resolution.
  for (const std::size_t n : quick ? std::vector<std::size_t>{31, 45, 63}
                                   : std::vector<std::size_t>{71, 100, 141, 200, 283}) {
    samples.push_back(measure("size", robot, n, 0.25, repeats));
  }
  // (b) resolution over a fixed area (35 m x 35 m; quick 10 m): more nodes per metre.
  const double area_side = quick ? 10.0 : 35.0;
  for (const double h : quick ? std::vector<double>{0.5, 0.35, 0.25}
                              : std::vector<double>{0.5, 0.35, 0.25, 0.175, 0.125}) {
    const auto n = static_cast<std::size_t>(std::lround(area_side / h)) + 1;
    samples.push_back(measure("area", robot, n, area_side / static_cast<double>(n - 1), repeats));
  }
  // (c) resolution at a fixed number of nodes (141 x 141 = 19881, the paper's 20000).
  const std::size_t fixed_n = quick ? 45 : 141;
  for (const double h :
       quick ? std::vector<double>{0.125, 0.5} : std::vector<double>{0.125, 0.25, 0.5, 1.0}) {
    samples.push_back(measure("points", robot, fixed_n, h, repeats));
  }
  // (d) theta slices of the chassis table at 141 x 141, 0.25 m.
  struct SliceSample {
    int slices = 0;
    double seconds = 0.0;
    long long placements = 0;
  };
  std::vector<SliceSample> slices;
  {
    const RuledTerrain terrain(hait_rough_terrain(fixed_n, fixed_n, 0.25, 8, 3));
    for (const int k : quick ? std::vector<int>{18, 36} : std::vector<int>{18, 36, 72, 144}) {
      ChassisTableOptions o;
      o.theta_slices = k;
      SliceSample ss{k, std::numeric_limits<double>::infinity(), 0};
      for (int r = 0; r < repeats; ++r) {
        const ChassisPlacementTable table(chassis, terrain, o);
        ss.seconds = std::min(ss.seconds, table.diagnostics().seconds);
        ss.placements = table.diagnostics().placements;
      }
      slices.push_back(ss);
    }
  }

  std::string csv =
      "sweep,ncols,nrows,nodes,spacing_m,theta_slices,validity_seconds,"
      "bitmap_seconds,total_seconds,table_placements,bitmap_disc_nodes\n";
  for (const Sample& s : samples) {
    csv += s.sweep + "," + std::to_string(s.n) + "," + std::to_string(s.n) + "," +
           std::to_string(s.n * s.n) + "," + csv_number(s.spacing) + ",72," +
           csv_number(s.validity_seconds) + "," + csv_number(s.bitmap_seconds) + "," +
           csv_number(s.total()) + "," + std::to_string(s.table_placements) + "," +
           std::to_string(s.disc_nodes) + "\n";
  }
  for (const SliceSample& ss : slices) {
    csv += "slices," + std::to_string(fixed_n) + "," + std::to_string(fixed_n) + "," +
           std::to_string(fixed_n * fixed_n) + ",0.25," + std::to_string(ss.slices) + "," +
           csv_number(ss.seconds) + ",nan,nan," + std::to_string(ss.placements) + ",nan\n";
  }
  write_text_file(context.output_dir / "preprocessing.csv", csv);

  // Exponent of one component of one sweep, against nodes or against the resolution 1/h.
  const auto exponent = [&](const std::string& sweep, bool against_resolution,
                            double (*value)(const Sample&)) {
    std::vector<double> x, y;
    for (const Sample& s : samples) {
      if (s.sweep != sweep) continue;
      x.push_back(against_resolution ? 1.0 / s.spacing : s.nodes());
      y.push_back(value(s));
    }
    return power_law_exponent(x, y);
  };
  const auto total = [](const Sample& s) { return s.total(); };
  const auto table_part = [](const Sample& s) { return s.validity_seconds; };
  const auto bitmap_part = [](const Sample& s) { return s.bitmap_seconds; };
  const auto table_count = [](const Sample& s) { return static_cast<double>(s.table_placements); };
  const auto bitmap_work = [](const Sample& s) {
    return s.nodes() * static_cast<double>(s.disc_nodes);
  };
  struct Exponents {
    double total, table, bitmap, table_placements, bitmap_work;
  };
  const auto exponents = [&](const std::string& sweep, bool against_resolution) {
    return Exponents{exponent(sweep, against_resolution, total),
                     exponent(sweep, against_resolution, table_part),
                     exponent(sweep, against_resolution, bitmap_part),
                     exponent(sweep, against_resolution, table_count),
                     exponent(sweep, against_resolution, bitmap_work)};
  };
  const Exponents size_e = exponents("size", false);
  const Exponents area_e = exponents("area", true);
  const Exponents points_e = exponents("points", true);
  std::vector<double> sx, sy, sp;
  for (const SliceSample& ss : slices) {
    sx.push_back(ss.slices);
    sy.push_back(ss.seconds);
    sp.push_back(static_cast<double>(ss.placements));
  }
  const double slices_exponent = power_law_exponent(sx, sy);
  const double slices_placements_exponent = power_law_exponent(sx, sp);

  const std::filesystem::path dat = context.output_dir / "preprocessing.dat";
  std::ofstream out = open_output_file(dat);
  out << "# nodes, 1/spacing [1/m], total preprocessing [s], chassis table + quadtree [s];\n"
         "# blocks: fixed 0.25 m spacing, fixed area, fixed number of nodes\n";
  for (const char* sweep : {"size", "area", "points"}) write_series(out, samples, sweep);
  close_output_file(out, dat);
  const std::string nodes = std::to_string(fixed_n * fixed_n);
  GnuplotFigure figure(context.output_dir, "preprocessing");
  figure.canvas(1100, 500)
      << "set multiplot layout 1,2\nset logscale xy\nset grid\nset key top left\n"
      << "set ylabel 'preprocessing time [s]'\nset xlabel 'terrain nodes'\n";
  figure.title("the paper's size claim: fixed 0.25 m (exponent " + fmt("%.2f", size_e.total) + ")",
               ",10", true)
          .plot({"'preprocessing.dat' index 0 using 1:3 with linespoints pt 7 lw 2 title 'total'",
                 "'' index 0 using 1:4 with linespoints pt 6 lw 1 title 'table + quadtree'"})
      << "set xlabel 'resolution 1/h [nodes per metre]'\n";
  figure.title("the paper's resolution claim: fixed " + nodes + " nodes (exponent " +
                   fmt("%.2f", points_e.total) + ")",
               ",10", true)
          .plot({"'preprocessing.dat' index 2 using 2:3 with linespoints pt 9 lw 2 title 'total'",
                 "'' index 2 using 2:4 with linespoints pt 8 lw 1 title 'table + quadtree'",
                 "'' index 1 using 2:3 with linespoints pt 5 lw 1 dt 2 title 'fixed " +
                     sig3(area_side) + " m square (not the paper''s sweep)'"})
      << "unset multiplot\n";
  figure.render();

  const auto verdict = [](double e, double lo, double hi) {
    return std::string(e >= lo && e <= hi ? "reproduced" : "**not reproduced**");
  };
  Report report("hait-preprocessing: preprocessing time (Haït, Siméon, Taïx 2002, §4.3, Fig. 20)");
  report.paragraph(
      std::string("**What is timed.** The preprocessing of `plan_hait` for the articulated chassis "
                  "(`marsokhod_chassis.yaml`): `HaitRobotValidity` (the θ-sliced chassis placement "
                  "table, 72 slices × every node, and the collision quadtree) plus one "
                  "`PotentialBitmap` (cost bitmap over a disc of the robot's radius around every "
                  "node, and the wave propagation; `plan_hait` builds two, one per control "
                  "point). Terrains: `hait_rough_terrain` (fractal D = 2.2 plus steep hills, seed "
                  "3). Each time is the ") +
      (repeats > 1 ? "fastest of 2 runs" : "single run") + ", one core.");
  if (quick)
    report.paragraph("**Quick mode**: small terrains; the exponents are not the reproduction.");
  report.paragraph(
      "**The paper's claims** (§4.3): \"Computation time is linear with the size (number of "
      "points) and quadratic with the resolution of the terrain. Tests have been performed first "
      "for a given resolution (25cm between two consecutive points), and then for a given size "
      "of terrain (20000 points).\" Sweep (a) tests the first claim, sweep (c) the second. "
      "A claim counts as reproduced when the total time's fitted exponent is within ±0.25 of "
      "the paper's (1, resp. 2).");
  Table claims({"sweep", "tests", "paper", "total", "table + quadtree", "bitmap", "verdict"});
  claims
      .row({"(a) size at 0.25 m spacing (" + std::to_string(samples.front().n * samples.front().n) +
                "–" + std::to_string(samples[quick ? 2 : 4].n * samples[quick ? 2 : 4].n) +
                " nodes)",
            "time ∝ nodes^p", "p = 1", fmt("%.2f", size_e.total), fmt("%.2f", size_e.table),
            fmt("%.2f", size_e.bitmap), verdict(size_e.total, 0.75, 1.25)})
      .row({"(c) resolution at a fixed " + nodes +
                " nodes (h = " + (quick ? "0.125–0.5" : "0.125–1") + " m)",
            "time ∝ (1/h)^p", "p = 2", fmt("%.2f", points_e.total), fmt("%.2f", points_e.table),
            fmt("%.2f", points_e.bitmap), verdict(points_e.total, 1.75, 2.25)});
  report.table(claims);
  report.paragraph(
      "**Why (c) is not reproduced.** The chassis table places an axle at every node for every "
      "θ slice: " +
      fmt("%.2f", points_e.table_placements) +
      " is the exponent of its Place_axle count against 1/h at a fixed number of nodes (72 × " +
      nodes +
      " at every spacing), so the table's time cannot grow with the resolution, and the table is "
      "most of the preprocessing. The one component whose work per node grows with resolution is "
      "the cost bitmap: its disc of the robot's radius R holds ≈ π (R/h)² nodes (nodes × disc "
      "nodes: exponent " +
      fmt("%.2f", points_e.bitmap_work) + "; its time: " + fmt("%.2f", points_e.bitmap) +
      "; by the same ±0.25 band the bitmap alone is " + verdict(points_e.bitmap, 1.75, 2.25) +
      "). A preprocessing dominated by such a neighbourhood operation would be quadratic in "
      "resolution at a fixed number of points; the paper does not say which of its steps grows, "
      "and ours is dominated by the table. We do not relabel the claim: at a fixed number of "
      "points our total time is not quadratic in resolution.");
  report.paragraph(
      "**Other sweeps, not the paper's claims.** (b) resolution over a fixed " + sig3(area_side) +
      " m × " + sig3(area_side) +
      " m area: the node count grows as (1/h)², so this is claim (a) in disguise (exponent 2 × "
      "(a)'s if linear in nodes): total " +
      fmt("%.2f", area_e.total) + ", table + quadtree " + fmt("%.2f", area_e.table) + ", bitmap " +
      fmt("%.2f", area_e.bitmap) + ". (d) θ slices of the chassis table alone at " + nodes +
      " nodes: time exponent " + fmt("%.2f", slices_exponent) + ", Place_axle count exponent " +
      fmt("%.2f", slices_placements_exponent) + " (one run per node per slice).");
  Table timings({"sweep", "nodes", "spacing [m]", "table + quadtree [s]", "bitmap [s]", "total [s]",
                 "Place_axle runs", "disc nodes"});
  for (const Sample& s : samples) {
    timings.row({s.sweep, std::to_string(s.n * s.n), fmt("%.4g", s.spacing),
                 fmt("%.3g", s.validity_seconds), fmt("%.3g", s.bitmap_seconds),
                 fmt("%.3g", s.total()), std::to_string(s.table_placements),
                 std::to_string(s.disc_nodes)});
  }
  std::string slice_times = "θ slices (table alone, " + nodes + " nodes):";
  for (const SliceSample& ss : slices) {
    slice_times += ' ';  // not `" " + std::to_string(k)`: GCC 12 warns falsely (-Wrestrict)
    slice_times += std::to_string(ss.slices) + " → " + fmt("%.3g", ss.seconds) + " s;";
  }
  report.table(timings)
      .paragraph(slice_times)
      .paragraph(
          "Timing noise: the same terrain (" + nodes +
          " nodes at 0.25 m) appears in sweeps (a), (b) and (c); their times differ by the load "
          "of the machine, which bounds how far the fitted time exponents can be trusted. The "
          "Place_axle counts are exact.")
      .paragraph(
          "The paper's absolute times (Fig. 20, a 2002 workstation) are not given in the text; "
          "its 12 s for one terrain without uncertainty (§5.4) compares with our total at about "
          "20000 nodes above.")
      .write(context.output_dir,
             "`preprocessing.csv`, `preprocessing.png` (`preprocessing.gp`, `preprocessing.dat`).",
             {{"preprocessing", "preprocessing.png"}});

  // summary.json. The Place_axle counts are deterministic: one per node per slice, so their
  // exponents are 1 against nodes (sweep a) and slices (d), 0 against 1/h at fixed nodes (c).
  ExperimentSummary& summary = *context.summary;
  summary.set("size_table_placements_exponent", size_e.table_placements, "1",
              "1 exactly: slices x nodes Place_axle runs");
  summary.set("points_table_placements_exponent", points_e.table_placements, "1",
              "0 exactly: a fixed number of nodes at every spacing");
  summary.set("slices_table_placements_exponent", slices_placements_exponent, "1",
              "1 exactly: one run per node per slice");
  summary.set("size_time_exponent", size_e.total, "1", "paper: 1 (linear in the number of points)");
  summary.set("size_table_time_exponent", size_e.table, "1", "paper: 1");
  summary.set("size_bitmap_time_exponent", size_e.bitmap, "1", "paper: 1");
  summary.set("points_time_exponent", points_e.total, "1",
              "paper: 2 (quadratic in resolution at 20000 points); not reproduced");
  summary.set("points_table_time_exponent", points_e.table, "1", "paper: 2");
  summary.set("points_bitmap_time_exponent", points_e.bitmap, "1", "paper: 2");
  summary.set("points_bitmap_work_exponent", points_e.bitmap_work, "1",
              "nodes x disc nodes, about 2 while the disc holds many nodes");
  summary.set("area_time_exponent", area_e.total, "1", "not a claim of the paper");
  summary.set("slices_time_exponent", slices_exponent, "1", "not a claim of the paper");
}

}  // namespace talus::experiments
