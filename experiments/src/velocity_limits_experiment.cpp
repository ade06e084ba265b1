#include "velocity_limits_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/relief.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/limit_summary.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"
#include "talus/report/constraint_style.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/path_map.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/relief_raster.hpp"
#include "talus/report/report.hpp"
#include "talus/scenarios/bundled_dem.hpp"
#include "west_bijou_path.hpp"

namespace talus::experiments {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------
// Fixed settings, named so the report can quote them.

constexpr std::size_t kFullStations = 2000;
constexpr std::size_t kQuickStations = 300;
/// Acceleration bounds are evaluated at this fraction of v_max(s): at v_max
/// itself the lateral force uses up the whole friction budget on sliding-bound
/// stations and the bounds collapse to a point, which says little.
constexpr double kAccelSpeedFraction = 0.8;
/// Constraint limit curves are clipped at this multiple of the max speed: a
/// crest limit of 300 m/s is as irrelevant as none, and would squash the plot.
constexpr double kClipFactor = 1.5;
constexpr std::size_t kRasterMaxSamples = 400;  // relief raster of the maps, longer side
constexpr double kSmoothingLambda = 1.0;  // control run: "smooths over about one cell" (bpatch.hpp)

// ---------------------------------------------------------------------------
// Formatting.

std::string percent(std::size_t part, std::size_t whole) {
  return whole == 0 ? "–" : fmt("%.1f", 100.0 * static_cast<double>(part) / whole) + " %";
}

// ---------------------------------------------------------------------------
// Vehicles and constraints.

struct VehicleSpec {
  std::string name;   ///< file-name part: point_mass, rigid_body, tall_rigid_body
  std::string label;  ///< for titles and the report
  Vehicle vehicle;
};

std::vector<VehicleSpec> make_vehicles() {
  Vehicle point;
  point.model = VehicleModel::kPointMass;
  point.friction = 0.7;
  point.cg_height = 0.5;
  point.half_track = 0.6;
  point.max_speed = 15.0;
  // gravity 9.81 m/s², max_accel and max_decel unlimited: the defaults, so
  // the acceleration bounds show the dynamic limits alone.

  Vehicle rigid = point;
  rigid.model = VehicleModel::kRigidBody;
  rigid.half_wheelbase = 1.0;

  // b/h = 0.45 < μ: it tips over sideways before it slides; l/h = 0.6 < μ:
  // pitch-over caps the tangential force before friction does. (The standard
  // rigid body has b/h = 1.2 and l/h = 2, both above μ = 0.7, so neither
  // tip-over limit can ever bind for it.)
  Vehicle tall = rigid;
  tall.cg_height = 1.0;
  tall.half_track = 0.45;
  tall.half_wheelbase = 0.6;

  std::vector<VehicleSpec> specs = {{"point_mass", "point mass", point},
                                    {"rigid_body", "rigid body", rigid},
                                    {"tall_rigid_body", "tall narrow rigid body", tall}};
  for (const VehicleSpec& spec : specs) spec.vehicle.validate();
  return specs;
}

std::string vehicle_parameters(const Vehicle& v) {
  std::ostringstream text;
  text << "μ = " << fmt("%g", v.friction) << ", h = " << fmt("%g", v.cg_height)
       << " m, b = " << fmt("%g", v.half_track) << " m";
  if (v.model == VehicleModel::kRigidBody) text << ", l = " << fmt("%g", v.half_wheelbase) << " m";
  text << ", max speed " << fmt("%g", v.max_speed) << " m/s";
  return text.str();
}

/// Colour and legend text of each constraint that can set v_max (or make a
/// station untraversable) or bound the acceleration. One table so the figures
/// and the gnuplot colour function cannot drift apart.
constexpr ConstraintStyle kStyles[] = {
    {Constraint::kContact, "#d62728", "contact (R ≥ 0)"},
    {Constraint::kSliding, "#1f77b4", "sliding (friction)"},
    {Constraint::kTipover, "#ff7f0e", "lateral tip-over"},
    {Constraint::kMaxSpeed, "#7f7f7f", "max speed"},
    {Constraint::kPitchover, "#9467bd", "pitch-over"},
    {Constraint::kNone, "#000000", "none"},
};

const ConstraintStyle& style(Constraint c) {
  for (const ConstraintStyle& s : kStyles)
    if (s.constraint == c) return s;
  return kStyles[std::size(kStyles) - 1];
}

// ---------------------------------------------------------------------------
// Per-vehicle results.

struct VehicleRun {
  VehicleSpec spec;
  LimitProfile profile;  ///< of spec.vehicle
  LimitSummary summary;
};

/// Speed limits of one vehicle along the path, and each constraint's own limits.
VehicleRun run_vehicle(const VehicleSpec& spec, const SurfacePath& path, std::size_t stations) {
  return {spec, limit_profile(spec.vehicle, path, stations), {}};
}

/// Acceleration bounds of every vehicle in `runs` (same path, same stations)
/// at one common speed per station (evaluate_common_accelerations).
void evaluate_accelerations(std::vector<VehicleRun>& runs) {
  std::vector<LimitProfile*> group;
  for (VehicleRun& run : runs) group.push_back(&run.profile);
  evaluate_common_accelerations(group, kAccelSpeedFraction);
}

// ---------------------------------------------------------------------------
// Terrain cases.

struct TerrainCase {
  std::string name;   ///< "dem" or "rover": prefixes every output file
  std::string label;  ///< for titles
  double scale = 1.0;
  ElevationGrid grid;
};

struct CaseResult {
  std::string name, label;
  double scale = 1.0, cellsize = 1.0, zmin = 0.0, zmax = 0.0, length = 0.0;
  double compute_seconds = 0.0, exaggeration = 1.0;
  std::size_t stations = 0;
  std::vector<Vec2> points;  ///< relative to the south-west node [m]
  std::vector<VehicleRun> runs;
  std::vector<VehicleRun> smoothed;  ///< point mass on the smoothing fit (one entry)
  double smoothed_seconds = 0.0;
};

// ---------------------------------------------------------------------------
// Output files.

void write_vehicle_csv(const VehicleRun& run, const fs::path& file) {
  std::ofstream out = open_output_file(file);
  out << "s,x,y,z,v_max,v_min,binding,v_sliding,v_tipover,v_contact,a_min,a_max,k_t,k_q,k_r,"
         "kappa_n,kappa_g\n";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const LimitStation& st : run.profile.stations) {
    const bool a_ok = st.accel.feasible;
    out << csv_number(st.s, 9) << ',' << csv_number(st.point.x(), 10) << ','
        << csv_number(st.point.y(), 10) << ',' << csv_number(st.point.z(), 9) << ','
        << csv_number(st.limits.v_max) << ',' << csv_number(st.limits.v_min) << ','
        << to_string(st.limits.upper_binding) << ',' << csv_number(st.v_sliding) << ','
        << csv_number(st.v_tipover) << ',' << csv_number(st.v_contact) << ','
        << csv_number(a_ok ? st.accel.a_min : nan) << ',' << csv_number(a_ok ? st.accel.a_max : nan)
        << ',' << csv_number(st.geometry.k_t) << ',' << csv_number(st.geometry.k_q) << ','
        << csv_number(st.geometry.k_r) << ',' << csv_number(st.geometry.kappa_n) << ','
        << csv_number(st.geometry.kappa_g) << '\n';
  }
  close_output_file(out, file);
}

/// Speeds and bindings behind the acceleration figure: one row per station,
/// one group of columns per vehicle (the per-vehicle CSVs keep their fixed
/// column set).
void write_acceleration_csv(const CaseResult& c, const fs::path& file) {
  std::ofstream out = open_output_file(file);
  out << "s";
  for (const VehicleRun& run : c.runs) {
    const std::string& n = run.spec.name;
    out << ',' << n << "_speed," << n << "_a_min," << n << "_a_max," << n << "_lower_binding," << n
        << "_upper_binding";
  }
  out << '\n';
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < c.stations; ++k) {
    out << csv_number(c.runs.front().profile.stations[k].s, 9);
    for (const VehicleRun& run : c.runs) {
      const LimitStation& st = run.profile.stations[k];
      const bool ok = st.accel.feasible;
      out << ',' << csv_number(st.accel_speed) << ',' << csv_number(ok ? st.accel.a_min : nan)
          << ',' << csv_number(ok ? st.accel.a_max : nan) << ','
          << (ok ? to_string(st.accel.lower_binding) : "infeasible") << ','
          << (ok ? to_string(st.accel.upper_binding) : "infeasible");
    }
    out << '\n';
  }
  close_output_file(out, file);
}

std::string csv_name(const CaseResult& c, const VehicleRun& run) {
  return c.name + "_" + run.spec.name + ".csv";
}
std::string smoothed_csv_name(const CaseResult& c) {
  return c.name + "_smoothed_" + c.smoothed.front().spec.name + ".csv";
}

/// Figure 1: per vehicle, each constraint's limit curve (thin) and v_max(s)
/// coloured by its binding constraint (thick), one panel per vehicle.
void draw_speed_limits(const CaseResult& c, const fs::path& out_dir) {
  const double max_speed = c.runs.front().spec.vehicle.max_speed;
  const double cap = kClipFactor * max_speed;
  const int panel_height = 400;
  GnuplotFigure gp(out_dir, c.name + "_speed_limits");
  gp.describe(
        "Speed limits along the path, " + c.label + ", from `talus experiment velocity-limits`.",
        c.name +
            "_<vehicle>.csv (columns: 1 s, 5 v_max, 6 v_min, 7 binding, 8 v_sliding, "
            "9 v_tipover, 10 v_contact).")
          .canvas(1250, 90 + panel_height * static_cast<int>(c.runs.size()))
      << "set datafile separator ','\n"
      << "CAP = " << fmt("%g", cap) << "\n"
      << "# Limits above CAP (and ∞) are drawn just above the plot so their lines leave it.\n"
      << "clip(v) = (v > CAP) ? 1.02 * CAP : v\n"
      << gnuplot_colour_function("binding_colour", kStyles) << "set multiplot layout "
      << c.runs.size() << ",1 title "
      << gnuplot_string(c.label +
                        ": speed limits along the path [m/s]\nthin: each constraint's own "
                        "limit, clipped at " +
                        fmt("%g", cap) + " m/s = " + fmt("%g", kClipFactor) +
                        " × max speed (∞ where it does not bound the speed); thick: v_{max}(s) "
                        "coloured by the constraint that sets it")
      << "\n"
      << "set xrange [0:" << fmt("%.10g", c.length) << "]\nset yrange [0:CAP]\n"
      << "set xlabel 'arc length s [m]'\nset ylabel 'speed [m/s]'\n"
      << "set grid ytics lc rgb '#d0d0d0'\nset tics out nomirror\n"
      << "set lmargin at screen 0.06\nset rmargin at screen 0.72\n"
      << "# The key sits right of each panel, at a fixed place so the panels line up.\n"
      << "set key at graph 1.03, graph 1 left top vertical Left reverse samplen 2 spacing 1.1 "
         "font ',10'\n";
  for (const VehicleRun& run : c.runs) {
    const LimitSummary& sum = run.summary;
    const std::string file = gnuplot_string(csv_name(c, run));
    const auto limit_title = [&](const char* name, double min_v) {
      std::string t = std::string(name) + " limit";
      if (!(min_v <= cap)) t += " (> " + fmt("%g", cap) + " m/s everywhere)";
      return gnuplot_string(t);
    };
    gp << "\nset title "
       << gnuplot_string(run.spec.label + ": " + vehicle_parameters(run.spec.vehicle)) << "\nplot "
       << file << " skip 1 using 1:(clip($8)) with lines lw 1.2 lc rgb '#601f77b4' "
       << "title " << limit_title("sliding", sum.min_v_sliding) << ", \\\n"
       << "     '' skip 1 using 1:(clip($9)) with lines lw 1.2 lc rgb '#60ff7f0e' title "
       << limit_title("tip-over", sum.min_v_tipover) << ", \\\n"
       << "     '' skip 1 using 1:(clip($10)) with lines lw 1.2 lc rgb '#60d62728' title "
       << limit_title("contact", sum.min_v_contact) << ", \\\n";
    if (sum.lower_bound_stations > 0) {
      gp << "     '' skip 1 using 1:($6 > 0 ? $6 : NaN) with lines lw 1.5 dt 2 lc rgb 'black' "
            "title 'v_{min} (lower bound)', \\\n";
    }
    // Each segment takes the colour of its end station's binding constraint.
    gp << "     '' skip 1 using 1:5:(binding_colour(strcol(7))) with lines lw 2.5 lc rgb "
          "variable notitle";
    for (const ConstraintStyle& s : kStyles) {
      const std::size_t count = sum.upper_count(s.constraint);
      if (count == 0) continue;  // legend only for constraints that occur
      gp << ", \\\n     "
         << key_entry(s.colour, std::string("v_{max} set by ") + s.label + " (" +
                                    percent(count, run.profile.stations.size()) + ")");
    }
    if (sum.untraversable > 0) {
      gp << ", \\\n     '' skip 1 using 1:($5 == 0 ? 0 : NaN) with points pt 2 ps 1.2 lc rgb "
            "'black' title "
         << gnuplot_string("untraversable (" + std::to_string(sum.untraversable) + " stations)");
    }
    if (&run == &c.runs.front() && !c.smoothed.empty()) {
      gp << ", \\\n     " << gnuplot_string(smoothed_csv_name(c))
         << " skip 1 using 1:5 with lines lw 1 lc rgb 'black' title "
         << gnuplot_string("v_{max}, smoothing fit (λ = " + fmt("%g", kSmoothingLambda) + ")");
    }
    gp << "\n";
  }
  gp << "unset multiplot\n";
  gp.render();
}

/// Figure 2: tangential-acceleration bounds. Top: point mass vs rigid body.
/// Bottom: the tall rigid body, segments coloured by what sets the bound.
void draw_acceleration(const CaseResult& c, const fs::path& out_dir) {
  const std::string data = gnuplot_string(c.name + "_acceleration.csv");
  // Column of vehicle v's quantity q (0 speed, 1 a_min, 2 a_max, 3 lower, 4 upper).
  const auto col = [](std::size_t v, int q) { return std::to_string(2 + 5 * v + q); };
  GnuplotFigure gp(out_dir, c.name + "_acceleration");
  gp.describe("Tangential-acceleration bounds along the path, " + c.label +
                  ", from `talus experiment velocity-limits`.",
              c.name +
                  "_acceleration.csv (per vehicle: speed, a_min, a_max, lower and upper "
                  "binding).")
          .canvas(1250, 900)
      << "set datafile separator ','\n"
      << gnuplot_colour_function("binding_colour", kStyles) << "set multiplot layout 2,1 title "
      << gnuplot_string(c.label +
                        ": admissible tangential acceleration s̈ ∈ [a_{min}, a_{max}] [m/s²]\n"
                        "all vehicles at one common speed per station, " +
                        fmt("%g", kAccelSpeedFraction) +
                        " × the smallest v_{max}(s) of the three; no drive or brake limit")
      << "\n"
      << "set xrange [0:" << fmt("%.10g", c.length) << "]\n"
      << "set xlabel 'arc length s [m]'\nset ylabel 'acceleration [m/s²]'\n"
      << "set grid ytics lc rgb '#d0d0d0'\nset tics out nomirror\n"
      << "set lmargin at screen 0.06\nset rmargin at screen 0.72\n"
      << "set key at graph 1.03, graph 1 left top vertical Left reverse samplen 3 spacing 1.1 "
         "font ',10'\n"
      << "set xzeroaxis lt 1 lc rgb '#808080'\n";
  // Top panel: vehicles 0 and 1 (point mass, rigid body).
  const Vehicle& rigid = c.runs[1].spec.vehicle;
  const std::size_t rigid_pitch = c.runs[1].summary.accel_bound_stations(Constraint::kPitchover);
  gp << "set title "
     << gnuplot_string(
            "point mass vs rigid body (l/h = " + fmt("%g", rigid.half_wheelbase / rigid.cg_height) +
            (rigid.half_wheelbase / rigid.cg_height > rigid.friction ? " > " : " ≤ ") +
            "μ = " + fmt("%g", rigid.friction) + "; pitch-over binds at " +
            std::to_string(rigid_pitch) + " stations" +
            (rigid_pitch == 0 ? ", so the dashed curves lie on the solid ones)" : ")"))
     << "\nplot " << data << " skip 1 using 1:" << col(0, 2)
     << " with lines lw 3 lc rgb '#1f77b4' title 'point mass a_{max}', \\\n"
     << "     '' skip 1 using 1:" << col(0, 1)
     << " with lines lw 3 lc rgb '#6baed6' title 'point mass a_{min}', \\\n"
     << "     '' skip 1 using 1:" << col(1, 2)
     << " with lines lw 1.5 dt (6,4) lc rgb '#d62728' title 'rigid body a_{max}', \\\n"
     << "     '' skip 1 using 1:" << col(1, 1)
     << " with lines lw 1.5 dt (6,4) lc rgb '#ff9896' title 'rigid body a_{min}'\n";
  // Bottom panel: the tall rigid body coloured by binding, point mass for reference.
  if (c.runs.size() > 2) {
    const VehicleRun& tall = c.runs[2];
    gp << "set title "
       << gnuplot_string(tall.spec.label + ": " + vehicle_parameters(tall.spec.vehicle) +
                         "; colour = constraint setting the bound")
       << "\nplot " << data << " skip 1 using 1:" << col(0, 2)
       << " with lines lw 1 lc rgb '#b0b0b0' title 'point mass (reference)', \\\n"
       << "     '' skip 1 using 1:" << col(0, 1)
       << " with lines lw 1 lc rgb '#b0b0b0' notitle, \\\n"
       << "     '' skip 1 using 1:" << col(2, 2) << ":(binding_colour(strcol(" << col(2, 4)
       << "))) with lines lw 2.5 lc rgb variable notitle, \\\n"
       << "     '' skip 1 using 1:" << col(2, 1) << ":(binding_colour(strcol(" << col(2, 3)
       << "))) with lines lw 2.5 lc rgb variable notitle";
    for (const Constraint cst : {Constraint::kSliding, Constraint::kPitchover}) {
      if (tall.summary.accel_bound_stations(cst) == 0) continue;  // legend only if it occurs
      gp << ", \\\n     "
         << key_entry(style(cst).colour, std::string("bound set by ") + style(cst).label);
    }
    gp << "\n";
  }
  gp << "unset multiplot\n";
  gp.render();
}

/// Figure 3: the path over shaded relief, coloured by v_max of the point mass
/// (identical to the rigid body's).
void draw_map(const CaseResult& c, const BPatch& patch, const fs::path& out_dir,
              double& exaggeration) {
  const MapFrame frame = MapFrame::of(patch);
  const Vec2& origin = frame.origin();
  GnuplotFigure figure(out_dir, c.name + "_map");
  exaggeration = write_relief_image(patch, frame, c.label + ": interpolating B-patch",
                                    out_dir / (c.name + "_relief.rgb"), kRasterMaxSamples,
                                    std::pair{c.zmin, c.zmax})
                     .colouring.exaggeration;

  const VehicleRun& run = c.runs.front();
  const fs::path path_file = out_dir / (c.name + "_path.dat");
  std::ofstream path = open_output_file(path_file);
  path << "# " << c.label << ": path stations; x - x_min [m], y - y_min [m], v_max of the "
       << run.spec.label << " [m/s], 1 if untraversable\n";
  for (const LimitStation& st : run.profile.stations) {
    path << offset_row(st.point.head<2>(), origin) << ' ' << csv_number(st.limits.v_max) << ' '
         << (st.limits.traversable ? 0 : 1) << '\n';
  }
  close_output_file(path, path_file);
  write_path_points(c.points,
                    "# interpolation points of the path: x - x_min [m], y - y_min [m], label\n",
                    out_dir / (c.name + "_path_points.dat"));

  std::ostringstream title;
  title << c.label << ": path coloured by v_{max} of the point mass (= rigid body)\n"
        << "over shaded relief of the interpolating fit (elevation " << sig3(c.zmin) << " to "
        << sig3(c.zmax) << " m, hillshade × " << fmt("%g", exaggeration)
        << " vertical exaggeration)";
  figure.describe("Map of the path, " + c.label + ", from `talus experiment velocity-limits`.",
                  c.name + "_relief.rgb (x y r g b), " + c.name +
                      "_path.dat (x y v_max untraversable), " + c.name +
                      "_path_points.dat (x y label).");
  figure.canvas(1100, frame.canvas_height(1100))
      << path_map_settings(frame, title.str(), run.spec.vehicle.max_speed, "v_{max} [m/s]")
      << path_map_plot(
             c.name + "_relief.rgb", c.name + "_path.dat", "path, coloured by v_{max}",
             run.summary.untraversable > 0
                 ? "     '' using 1:($4 > 0 ? $2 : NaN) with points pt 2 ps 1.5 lw 2 lc rgb "
                   "'black' title 'untraversable', \\\n"
                 : "",
             c.name + "_path_points.dat");
  figure.render();
}

CaseResult process_case(const TerrainCase& tc, const std::vector<VehicleSpec>& vehicles,
                        std::size_t stations, const fs::path& out_dir) {
  using Clock = std::chrono::steady_clock;
  CaseResult c;
  c.name = tc.name;
  c.label = tc.label;
  c.scale = tc.scale;
  c.cellsize = tc.grid.cellsize();
  c.stations = stations;
  const auto range = tc.grid.elevation_range();
  if (!range) throw InputError("velocity-limits: " + tc.label + " has no valid node");
  c.zmin = range->first;
  c.zmax = range->second;

  const auto t0 = Clock::now();
  const BPatch patch = BPatch::interpolate(tc.grid);
  const std::vector<Vec2> points = west_bijou_path_points(tc.grid, "velocity-limits");
  for (const Vec2& p : points) c.points.emplace_back(p.x() - patch.x_min(), p.y() - patch.y_min());
  const Curve2 curve = Curve2::interpolate(points);
  const SurfacePath path(patch, curve);
  c.length = path.length();
  for (const VehicleSpec& spec : vehicles) c.runs.push_back(run_vehicle(spec, path, stations));
  evaluate_accelerations(c.runs);
  for (VehicleRun& run : c.runs) run.summary = summarise_limits(run.profile.stations);
  c.compute_seconds = std::chrono::duration<double>(Clock::now() - t0).count();

  // Control run: the same path on the smoothing fit, point mass only. The DEM
  // stores whole metres, so the interpolating fit turns the 1 m steps into
  // curvature; the smoothing fit (about one cell of smoothing, and λ is
  // dimensionless, so the same at both scales) shows how much of v_max(s)
  // comes from that quantisation rather than from the landforms.
  const auto t1 = Clock::now();
  const BPatch smooth_patch = BPatch::fit_smoothing(tc.grid, kSmoothingLambda);
  const SurfacePath smooth_path(smooth_patch, curve);
  c.smoothed.push_back(run_vehicle(vehicles.front(), smooth_path, stations));
  evaluate_accelerations(c.smoothed);
  c.smoothed.front().summary = summarise_limits(c.smoothed.front().profile.stations);
  c.smoothed_seconds = std::chrono::duration<double>(Clock::now() - t1).count();

  for (const VehicleRun& run : c.runs) write_vehicle_csv(run, out_dir / csv_name(c, run));
  write_vehicle_csv(c.smoothed.front(), out_dir / smoothed_csv_name(c));
  write_acceleration_csv(c, out_dir / (c.name + "_acceleration.csv"));
  draw_speed_limits(c, out_dir);
  draw_acceleration(c, out_dir);
  draw_map(c, patch, out_dir, c.exaggeration);
  return c;
}

// ---------------------------------------------------------------------------
// Report.

void write_summary_csv(const std::vector<CaseResult>& cases, const fs::path& file) {
  std::ostringstream csv;
  csv << "case,vehicle,stations,length_m,min_v_max,median_v_max,share_contact,share_sliding,"
         "share_tipover,share_max_speed,untraversable,lower_bound_stations,max_v_min,"
         "pitchover_accel_stations,median_a_min,median_a_max\n";
  for (const CaseResult& c : cases)
    for (const VehicleRun& run : c.runs) {
      const LimitSummary& s = run.summary;
      const auto share = [&](Constraint cst) { return csv_number(s.upper_share(cst), 5); };
      csv << c.name << ',' << run.spec.name << ',' << run.profile.stations.size() << ','
          << csv_number(c.length, 8) << ',' << csv_number(s.min_v_max, 5) << ','
          << csv_number(s.median_v_max, 5) << ',' << share(Constraint::kContact) << ','
          << share(Constraint::kSliding) << ',' << share(Constraint::kTipover) << ','
          << share(Constraint::kMaxSpeed) << ',' << s.untraversable << ',' << s.lower_bound_stations
          << ',' << csv_number(s.max_v_min, 5) << ','
          << s.accel_bound_stations(Constraint::kPitchover) << ',' << csv_number(s.median_a_min, 5)
          << ',' << csv_number(s.median_a_max, 5) << '\n';
    }
  write_text_file(file, csv.str());
}

std::string commentary(const CaseResult& dem, const CaseResult& rover) {
  const VehicleRun& dem_pm = dem.runs[0];
  const VehicleRun& pm = rover.runs[0];
  const VehicleRun& rb = rover.runs[1];
  const VehicleRun& tall = rover.runs[2];
  const VehicleRun& smooth = rover.smoothed.front();
  const Vehicle& v = pm.spec.vehicle;
  const auto count = [](const VehicleRun& run, Constraint c) { return run.summary.upper_count(c); };
  const auto share = [&](const VehicleRun& run, Constraint c) {
    return percent(count(run, c), run.profile.stations.size());
  };
  std::ostringstream text;

  // 1. The DEM's own scale.
  text << "At the DEM's own 25 m scale the dynamics hardly matter: the max speed sets v_max at "
       << share(dem_pm, Constraint::kMaxSpeed) << " of the stations of the " << sig3(dem.length)
       << " m path, and the tightest dynamic limits anywhere are "
       << sig3(dem_pm.summary.min_v_sliding) << " m/s (sliding) and "
       << sig3(dem_pm.summary.min_v_contact)
       << " m/s (contact), because turns and landform curvatures there have radii of hundreds "
          "of metres. ";

  // 2. Rover scale: what binds, and why contact never shows.
  const LimitStation& worst = pm.profile.stations[pm.summary.min_index];
  const double g = v.gravity;
  const double crest_only = worst.geometry.kappa_n < 0.0
                                ? std::sqrt(g * worst.geometry.k_r / -worst.geometry.kappa_n)
                                : std::numeric_limits<double>::infinity();
  const double turn_only =
      std::sqrt(v.friction * g / std::max(std::abs(worst.geometry.kappa_g), 1e-300));
  text << "At rover scale (1 m cells, curvatures × 25) the point mass's v_max is set by sliding at "
       << share(pm, Constraint::kSliding) << " of the stations and by the max speed at "
       << share(pm, Constraint::kMaxSpeed) << ", and by contact at only "
       << share(pm, Constraint::kContact)
       << ": the sliding interval always lies inside the contact interval and meets its end only "
          "where the lateral force vanishes, so a crest appears as sliding with the contact limit "
          "just above it ("
       << percent(pm.summary.sliding_on_crest, count(pm, Constraint::kSliding))
       << " of the sliding-bound stations have κ_n < 0); the slowest station, "
       << sig3(pm.summary.min_v_max) << " m/s at s = " << sig3(worst.s)
       << " m, is a crest (κ_n = " << sig3(worst.geometry.kappa_n) << " 1/m, contact alone "
       << sig3(crest_only) << " m/s) in a turn (κ_g = " << sig3(worst.geometry.kappa_g)
       << " 1/m, √(μg/|κ_g|) = " << sig3(turn_only)
       << " m/s on flat ground), and the two together give the lower value. ";

  // 3. How much of it is the DEM's vertical quantisation.
  text << "The many narrow dips are largely the DEM's whole-metre quantisation (4 cm steps per "
          "1 m cell after scaling), which the interpolating fit turns into curvature: v_max(s) "
          "has "
       << pm.summary.dips << " local minima along " << sig3(rover.length) << " m (one every "
       << sig3(rover.length / static_cast<double>(std::max<std::size_t>(pm.summary.dips, 1)))
       << " m, the cell scale) against " << smooth.summary.dips
       << " on the smoothing fit (λ = " << fmt("%g", kSmoothingLambda)
       << "), which lifts min/median v_max from " << sig3(pm.summary.min_v_max) << "/"
       << sig3(pm.summary.median_v_max) << " to " << sig3(smooth.summary.min_v_max) << "/"
       << sig3(smooth.summary.median_v_max)
       << " m/s; the broad pattern, sliding binding through the turns, survives the smoothing ("
       << share(smooth, Constraint::kSliding) << " of the stations there vs "
       << share(pm, Constraint::kSliding) << "). ";

  // 4. Rigid body vs point mass, and the tall vehicle.
  const bool same_limits = same_speed_limits(pm.profile, rb.profile);
  const bool same_accel = same_acceleration_bounds(pm.profile, rb.profile);
  const Vehicle& rv = rb.spec.vehicle;
  text << "The rigid body's speed limits are "
       << (same_limits ? "identical to the point mass's at every station" : "NOT identical")
       << " (its only extra constraint, pitch-over |f_t| ≤ (l/h) R, acts on the acceleration), "
          "and since l/h = "
       << fmt("%g", rv.half_wheelbase / rv.cg_height) << " exceeds μ = " << fmt("%g", rv.friction)
       << " the friction ellipse is always the tighter bound, so its acceleration bounds are "
       << (same_accel ? "identical" : "NOT identical") << " too (pitch-over binds at "
       << rb.summary.accel_bound_stations(Constraint::kPitchover) << " stations). ";
  const Vehicle& tv = tall.spec.vehicle;
  text << "The tall narrow rigid body (b/h = " << fmt("%g", tv.half_track / tv.cg_height)
       << ", l/h = " << fmt("%g", tv.half_wheelbase / tv.cg_height)
       << ", both below μ) shows both tip-over limits: lateral tip-over has the same form as "
          "the sliding condition with b/h in place of μ, so it replaces sliding everywhere ("
       << share(tall, Constraint::kTipover) << " tip-over, " << share(tall, Constraint::kSliding)
       << " sliding; median v_max " << sig3(tall.summary.median_v_max) << " vs "
       << sig3(pm.summary.median_v_max)
       << " m/s), and at the common evaluation speed pitch-over sets its acceleration bound at "
       << percent(tall.summary.accel_bound_stations(Constraint::kPitchover),
                  tall.profile.stations.size())
       << " of the stations (median a_max " << sig3(tall.summary.median_a_max) << " vs "
       << sig3(pm.summary.median_a_max) << " m/s² for the point mass).";
  return text.str();
}

void write_report(const std::vector<CaseResult>& cases, const std::vector<VehicleSpec>& vehicles,
                  const ElevationGrid& dem, const ExperimentContext& context) {
  Table points({"point", "cells (u, v)", "`dem` x, y [m]", "`rover` x, y [m]"});
  for (std::size_t i = 0; i < std::size(kWestBijouPathCells); ++i) {
    points.row({fmt("P%g", static_cast<double>(i)),
                fmt("%g", kWestBijouPathCells[i].u) + ", " + fmt("%g", kWestBijouPathCells[i].v),
                sig3(cases[0].points[i].x()) + ", " + sig3(cases[0].points[i].y()),
                sig3(cases[1].points[i].x()) + ", " + sig3(cases[1].points[i].y())});
  }
  Report report("Velocity limits along a path on a real DEM");
  report
      .paragraph(
          "The speed limits v_min(s) ≤ ṡ ≤ v_max(s) of each dynamic constraint (sliding, lateral "
          "tip-over, loss of contact) and the binding one, and the admissible tangential "
          "acceleration, along one fixed curved path across the West Bijou escarpment, for three "
          "vehicles, at the DEM's own scale and at rover scale.")
      .heading("What was run")
      .bullet("Terrain: " + west_bijou_terrain_text(dem) +
              ", fitted with the interpolating B-patch "
              "(`BPatch::interpolate`, exact at every node).")
      .bullet("Two cases:")
      .bullet("`dem`: the DEM as it is (25 m cells, elevations " + sig3(cases[0].zmin) + " to " +
                  sig3(cases[0].zmax) + " m).",
              1)
      .bullet(
          "`rover`: the same DEM with x, y **and** z multiplied by k = 1/25 (README "
          "\"Rover-scale use\"), built in code: 1 m cells, elevations " +
              sig3(cases[1].zmin) + " to " + sig3(cases[1].zmax) +
              " m, slopes unchanged, curvatures 25 × larger. At 25 m cells the terrain's "
              "curvatures and the path's turns are too gentle for any limit to bind at "
              "vehicle speeds; at 1 m they are rover-sized. Note that the DEM stores whole "
              "metres, so at rover scale its 1 m quantisation steps become 4 cm steps per 1 m "
              "cell, which the interpolating fit reproduces as small-scale curvature.",
          1)
      .bullet("Path: `Curve2::interpolate` (cubic, chord-length parameters) through " +
              std::to_string(std::size(kWestBijouPathCells)) +
              " fixed points given in cells from the south-west node (the same for both cases); "
              "in metres from that node:\n\n" +
              points.markdown("  ") + "\n  " + kWestBijouPathRoute)
      .bullet("Stations: " + std::to_string(cases[0].stations) +
              (context.quick ? " (quick mode)" : "") +
              ", equally spaced in the curve parameter (`VelocityLimits`, "
              "`SurfacePath::sample_uniform_parameter`).")
      .bullet("Vehicles (g = 9.81 m/s², no drive or brake limit):");
  for (const VehicleSpec& v : vehicles) {
    const bool rigid = v.vehicle.model == VehicleModel::kRigidBody;
    report.bullet(
        "`" + v.name + "`: " + (rigid ? "rigid-body model" : "point-mass model") +
            ", friction μ = " + fmt("%g", v.vehicle.friction) +
            ", cg_height h = " + fmt("%g", v.vehicle.cg_height) +
            " m, half_track b = " + fmt("%g", v.vehicle.half_track) + " m" +
            (rigid ? ", half_wheelbase l = " + fmt("%g", v.vehicle.half_wheelbase) + " m" : "") +
            ", max_speed " + fmt("%g", v.vehicle.max_speed) +
            " m/s (b/h = " + fmt("%.3g", v.vehicle.half_track / v.vehicle.cg_height) + ")",
        1);
  }
  report
      .bullet(
          "Per station: `SpeedLimits` (v_max, v_min, the binding constraint) and each "
          "constraint's own interval of ṡ², plotted as √upper (∞ where unbounded, 0 where no "
          "speed satisfies it). Acceleration bounds (`acceleration_bounds`) of all three "
          "vehicles at one common speed per station, " +
          fmt("%g", kAccelSpeedFraction) +
          " × the smallest of their v_max(s) (raised to the largest v_min; v_max ≤ max "
          "speed, so the speed is capped there already): the lateral load is then the same "
          "for all three, and the curves differ only through the acceleration constraints.")
      .bullet("Control run: the same path on the smoothing fit (`BPatch::fit_smoothing`, λ = " +
              fmt("%g", kSmoothingLambda) +
              ", dimensionless, so the same smoothing at both scales), point mass only (its "
              "acceleration bounds at 0.8 × its own v_max), to separate the landforms from the "
              "DEM's vertical quantisation (whole metres).")
      .bullet(
          "Files: `<case>_<vehicle>.csv` (columns s, x, y, z, v_max, v_min, binding, "
          "v_sliding, v_tipover, v_contact, a_min, a_max, k_t, k_q, k_r, kappa_n, kappa_g; SI "
          "units, `inf`/`nan` spelled out), `<case>_smoothed_point_mass.csv` (the control "
          "run, same columns), `<case>_acceleration.csv` (per vehicle: evaluation speed, "
          "a_min, a_max and what sets each), `summary.csv`, and every figure's gnuplot script "
          "(`<case>_*.gp`) beside its PNG.")
      .heading("Results");
  for (const CaseResult& c : cases) {
    Table table({"vehicle", "min v_max [m/s]", "median v_max [m/s]", "contact", "sliding",
                 "tip-over", "max speed", "untraversable", "stations with v_min > 0",
                 "accel. bound by pitch-over", "median a_min … a_max [m/s²]"});
    std::vector<const VehicleRun*> rows;
    for (const VehicleRun& run : c.runs) rows.push_back(&run);
    rows.push_back(&c.smoothed.front());
    for (const VehicleRun* row : rows) {
      const LimitSummary& s = row->summary;
      const std::size_t n = row->profile.stations.size();
      const auto share = [&](Constraint constraint) {
        return percent(s.upper_count(constraint), n);
      };
      table.row({"`" + row->spec.name + "`" +
                     (row == rows.back() ? " on the smoothing fit (control)" : ""),
                 sig3(s.min_v_max), sig3(s.median_v_max), share(Constraint::kContact),
                 share(Constraint::kSliding), share(Constraint::kTipover),
                 share(Constraint::kMaxSpeed), std::to_string(s.untraversable),
                 std::to_string(s.lower_bound_stations) +
                     (s.lower_bound_stations > 0 ? " (max " + sig3(s.max_v_min) + " m/s)" : ""),
                 percent(s.accel_bound_stations(Constraint::kPitchover), n),
                 sig3(s.median_a_min) + " … " + sig3(s.median_a_max)});
    }
    report.heading("`" + c.name + "`: " + c.label, 3)
        .paragraph("Path length " + sig3(c.length) + " m (3-D), " + std::to_string(c.stations) +
                   " stations, limits computed in " + sig3(1e3 * c.compute_seconds) +
                   " ms (interpolating fit, path and all vehicles; the smoothing-fit control run " +
                   sig3(1e3 * c.smoothed_seconds) + " ms).")
        .table(table)
        .paragraph(
            "Shares are of all stations, by the constraint that sets v_max (an untraversable "
            "station counts under the constraint that fails).");
  }
  report.heading("What the figures show")
      .paragraph(commentary(cases[0], cases[1]))
      .heading("Figures");
  for (const CaseResult& c : cases) {
    report.figures("`" + c.name + "`",
                   {{c.name + " speed limits", c.name + "_speed_limits.png"},
                    {c.name + " acceleration bounds", c.name + "_acceleration.png"},
                    {c.name + " map", c.name + "_map.png"}});
  }
  report.write(context.output_dir);
}

}  // namespace

/// The headline numbers of summary.json, with a similarity check: the rover case is the DEM case
/// with every length divided by 25, and the limits depend on the vehicle only through mu, b/h
/// and l/h, so at every station each constraint's own limit (uncapped by the top speed) on the DEM
/// is exactly sqrt(25) = 5 times the rover's (the interpolating fit is scale-free).
void summarise(const std::vector<CaseResult>& cases, ExperimentSummary& summary) {
  const CaseResult &dem = cases[0], &rover = cases[1];
  summary.set("path_length_dem_m", dem.length, "m");
  summary.set("path_length_rover_m", rover.length, "m");
  for (const CaseResult* c : {&dem, &rover}) {
    summary.set("min_v_max_point_mass_" + c->name + "_m_per_s", c->runs.front().summary.min_v_max,
                "m/s");
  }
  double low = INFINITY, high = -INFINITY;
  const auto& a = dem.runs.front().profile.stations;
  const auto& b = rover.runs.front().profile.stations;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    for (const auto& [va, vb] :
         {std::pair(a[k].v_sliding, b[k].v_sliding), std::pair(a[k].v_tipover, b[k].v_tipover),
          std::pair(a[k].v_contact, b[k].v_contact)}) {
      if (!std::isfinite(va) || !std::isfinite(vb) || !(vb > 0.0)) continue;
      low = std::min(low, va / vb);
      high = std::max(high, va / vb);
    }
  }
  const std::string why = "5 = sqrt(25): lengths scale by 25, speed limits by its square root";
  summary.set("dem_over_rover_v_max_min", low, "1", why);
  summary.set("dem_over_rover_v_max_max", high, "1", why);
  summary.set("dem_over_rover_length", dem.length / rover.length, "1", "25");
}

void run_velocity_limits(const ExperimentContext& context) {
  // Fail in a second, not after the computation, if the figures cannot be drawn.
  require_gnuplot();
  const ElevationGrid dem =
      scenarios::load_bundled_dem(context.data_dir, kWestBijouStem, "velocity-limits");
  const std::vector<VehicleSpec> vehicles = make_vehicles();
  const std::size_t stations = context.quick ? kQuickStations : kFullStations;

  const std::vector<TerrainCase> terrains = {
      {"dem", "West Bijou DEM, 25 m cells", 1.0, dem},
      {"rover", "West Bijou scaled by 1/25 (1 m cells)", kRoverScale,
       scenarios::scaled_grid(dem, kRoverScale)},
  };
  std::vector<CaseResult> cases;
  for (const TerrainCase& terrain : terrains) {
    cases.push_back(process_case(terrain, vehicles, stations, context.output_dir));
    const CaseResult& c = cases.back();
    std::cout << "velocity-limits: " << c.name << ": path " << sig3(c.length) << " m, "
              << c.stations << " stations, limits in " << fmt("%.3f", c.compute_seconds)
              << " s; point mass min v_max " << sig3(c.runs.front().summary.min_v_max) << " m/s\n";
  }
  write_summary_csv(cases, context.output_dir / "summary.csv");
  summarise(cases, *context.summary);
  write_report(cases, vehicles, dem, context);
}

}  // namespace talus::experiments
