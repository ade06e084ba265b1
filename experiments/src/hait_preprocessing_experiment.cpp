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

#include "figure.hpp"
#include "hait_experiments.hpp"
#include "hait_scenarios.hpp"
#include "number_format.hpp"
#include "plot.hpp"
#include "report.hpp"
#include "stopwatch.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/core/sample_statistics.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"
#include "talus/kinematic/hait/hait_robot_validity.hpp"
#include "talus/kinematic/hait/potential_bitmap.hpp"

namespace talus::experiments {
namespace {

/// One measured terrain.
struct Sample {
  std::string sweep;
  std::size_t n = 0;  ///< nodes per side
  double spacing = 0.0;
  int slices = 72;
  double validity_seconds = 0.0;  ///< HaitRobotValidity: chassis table + quadtree
  double bitmap_seconds = 0.0;    ///< one PotentialBitmap (cost + wave)
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
    PotentialBitmapOptions bo;
    bo.robot_radius = validity.radius();
    const auto t0 = Clock::now();
    const PotentialBitmap bitmap(terrain, Vec2(0.5 * extent, 0.5 * extent), bo);
    s.bitmap_seconds = std::min(s.bitmap_seconds, seconds_since(t0));
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
  const Robot robot = load_hait_chassis(context.data_dir);
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
  std::vector<std::pair<int, double>> slices;
  {
    const RuledTerrain terrain(hait_rough_terrain(fixed_n, fixed_n, 0.25, 8, 3));
    for (const int k : quick ? std::vector<int>{18, 36} : std::vector<int>{18, 36, 72, 144}) {
      ChassisTableOptions o;
      o.theta_slices = k;
      double best = std::numeric_limits<double>::infinity();
      for (int r = 0; r < repeats; ++r) {
        best = std::min(best, ChassisPlacementTable(chassis, terrain, o).diagnostics().seconds);
      }
      slices.emplace_back(k, best);
    }
  }

  std::string csv =
      "sweep,ncols,nrows,nodes,spacing_m,theta_slices,validity_seconds,"
      "bitmap_seconds,total_seconds\n";
  for (const Sample& s : samples) {
    csv += s.sweep + "," + std::to_string(s.n) + "," + std::to_string(s.n) + "," +
           std::to_string(s.n * s.n) + "," + csv_number(s.spacing) + ",72," +
           csv_number(s.validity_seconds) + "," + csv_number(s.bitmap_seconds) + "," +
           csv_number(s.total()) + "\n";
  }
  for (const auto& [k, t] : slices) {
    csv += "slices," + std::to_string(fixed_n) + "," + std::to_string(fixed_n) + "," +
           std::to_string(fixed_n * fixed_n) + ",0.25," + std::to_string(k) + "," + csv_number(t) +
           ",nan,nan\n";
  }
  write_text_file(context.output_dir / "preprocessing.csv", csv);

  const auto slope = [&](const std::string& sweep, bool against_resolution) {
    std::vector<double> x, y;
    for (const Sample& s : samples) {
      if (s.sweep != sweep) continue;
      x.push_back(against_resolution ? 1.0 / s.spacing : s.nodes());
      y.push_back(s.total());
    }
    return power_law_exponent(x, y);
  };
  std::vector<double> sx, sy;
  for (const auto& [k, t] : slices) {
    sx.push_back(k);
    sy.push_back(t);
  }
  const double size_exponent = slope("size", false);
  const double area_exponent = slope("area", true);
  const double points_exponent = slope("points", true);
  const double slices_exponent = power_law_exponent(sx, sy);

  const std::filesystem::path dat = context.output_dir / "preprocessing.dat";
  std::ofstream out = open_output_file(dat);
  out << "# nodes, 1/spacing [1/m], total preprocessing [s], chassis table + quadtree [s];\n"
         "# blocks: fixed 0.25 m spacing, fixed area, fixed number of nodes\n";
  for (const char* sweep : {"size", "area", "points"}) write_series(out, samples, sweep);
  close_output_file(out, dat);
  GnuplotFigure figure(context.output_dir, "preprocessing");
  figure.canvas(1100, 500)
      << "set multiplot layout 1,2\nset logscale xy\nset grid\nset key top left\n"
      << "set ylabel 'preprocessing time [s]'\nset xlabel 'terrain nodes'\n";
  figure.title("against size (exponent: fixed 0.25 m " + fmt("%.2f", size_exponent) + ")", ",10",
               true)
          .plot(
              {"'preprocessing.dat' index 0 using 1:3 with linespoints pt 7 lw 2 title 'fixed 0.25 "
               "m spacing'",
               "'' index 1 using 1:3 with linespoints pt 5 lw 2 title 'fixed " + sig3(area_side) +
                   " m square'"})
      << "set xlabel 'resolution 1/h [nodes per metre]'\n";
  figure.title("against resolution (exponents: fixed area " + fmt("%.2f", area_exponent) +
                   ", fixed nodes " + fmt("%.2f", points_exponent) + ")",
               ",10", true)
          .plot({"'preprocessing.dat' index 1 using 2:3 with linespoints pt 5 lw 2 title 'fixed "
                 "area'",
                 "'' index 2 using 2:3 with linespoints pt 9 lw 2 title 'fixed " +
                     std::to_string(fixed_n * fixed_n) + " nodes'"})
      << "unset multiplot\n";
  figure.render();

  Report report("hait-preprocessing: preprocessing time (Haït, Siméon, Taïx 2002, §4.3, Fig. 20)");
  report.paragraph(
      std::string("**What is timed.** The preprocessing of `plan_hait` for the articulated chassis "
                  "(`marsokhod_chassis.yaml`): `HaitRobotValidity` (the θ-sliced chassis placement "
                  "table, 72 slices × every node, and the collision quadtree) plus one "
                  "`PotentialBitmap` (cost bitmap and wave propagation; `plan_hait` builds two, "
                  "one per control point). Terrains: `hait_rough_terrain` (fractal D = 2.2 plus "
                  "steep hills, seed 3). Each time is the ") +
      (repeats > 1 ? "fastest of 2 runs" : "single run") + ", one core.");
  if (quick)
    report.paragraph("**Quick mode**: small terrains; the exponents are not the reproduction.");
  report.paragraph(
      "**Reading the paper's \"resolution\".** The paper times terrains \"for a given "
      "resolution (25 cm between two consecutive points), and then for a given size of terrain "
      "(20000 points)\". The preprocessing places an axle at every node for every θ slice, so its "
      "cost is (nodes) × (slices): linear in the number of nodes whatever the spacing. At a fixed "
      "number of nodes the spacing alone changes nothing (our sweep (c)); the quadratic law "
      "appears when the resolution 1/h grows over a fixed area, because the node count grows as "
      "(1/h)² (sweep (b)). We therefore read \"quadratic in resolution\" as at a fixed terrain "
      "area; the θ-slice count is a second resolution, and it is linear (sweep (d)).");
  const std::string nodes = std::to_string(fixed_n * fixed_n);
  report.table(
      Table({"sweep", "variable", "fitted exponent (ours)", "paper"})
          .row({"(a) size at 0.25 m spacing", "nodes", fmt("%.2f", size_exponent), "linear (1)"})
          .row({"(b) resolution, fixed " + sig3(area_side) + " m × " + sig3(area_side) + " m area",
                "1/h", fmt("%.2f", area_exponent), "quadratic (2)"})
          .row({"(c) resolution, fixed " + nodes + " nodes", "1/h", fmt("%.2f", points_exponent),
                "(the paper's wording; see above)"})
          .row({"(d) θ slices of the chassis table", "n_θ", fmt("%.2f", slices_exponent), "–"}));
  Table timings(
      {"sweep", "nodes", "spacing [m]", "table + quadtree [s]", "bitmap [s]", "total [s]"});
  for (const Sample& s : samples) {
    timings.row({s.sweep, std::to_string(s.n * s.n), fmt("%.4g", s.spacing),
                 fmt("%.3g", s.validity_seconds), fmt("%.3g", s.bitmap_seconds),
                 fmt("%.3g", s.total())});
  }
  std::string slice_times = "θ slices (table alone, " + nodes + " nodes):";
  for (const auto& [k, t] : slices) {
    slice_times += ' ';  // not `" " + std::to_string(k)`: GCC 12 warns falsely (-Wrestrict)
    slice_times += std::to_string(k) + " → " + fmt("%.3g", t) + " s;";
  }
  report.table(timings)
      .paragraph(slice_times)
      .paragraph(
          "The paper's absolute times (Fig. 20, a 2002 workstation) are not given in the text; "
          "its 12 s for one terrain without uncertainty (§5.4) compares with our total at about "
          "20000 nodes above.")
      .write(context.output_dir,
             "`preprocessing.csv`, `preprocessing.png` (`preprocessing.gp`, `preprocessing.dat`).",
             {{"preprocessing", "preprocessing.png"}});
}

}  // namespace talus::experiments
