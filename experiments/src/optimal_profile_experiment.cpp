#include "optimal_profile_experiment.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/relief.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"
#include "talus/optimal/profile_analysis.hpp"
#include "talus/optimal/profile_convergence.hpp"
#include "talus/optimal/time_optimal_profile.hpp"
#include "talus/optimal/trajectory.hpp"
#include "talus/optimal/verify_profile.hpp"
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
using Clock = std::chrono::steady_clock;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------
// Fixed settings, named so the report can quote them.

/// The DEM, its rover scale and the path (west_bijou_path.hpp) are those of
/// the velocity-limits experiment, so the two experiments' figures can be
/// read together (the path is about 170 m long at rover scale).
/// The DEM stores whole metres; at rover scale those steps are 4 cm per 1 m
/// cell, and the interpolating fit turns each into a curvature spike that
/// sets v_max at cell spacing (see the velocity-limits experiment). λ = 1
/// (dimensionless, grid-index units) smooths over about one cell and keeps
/// the landforms.
constexpr double kSmoothingLambda = 1.0;

/// Stations of the profile figure: about 5 cm spacing (full) or 21 cm
/// (quick), fine enough that the figure shows the converged profile (see the
/// convergence study) rather than discretisation effects.
constexpr std::size_t kProfileStations = 3201;
constexpr std::size_t kQuickProfileStations = 801;

/// Convergence levels: the count doubles, so the spacing roughly halves and
/// consecutive errors give the observed order directly. The finest level is
/// the reference.
constexpr std::size_t kLevels[] = {25,   50,   100,  200,   400,   800,
                                   1600, 3200, 6400, 12800, 25600, 51200};
constexpr std::size_t kQuickMaxLevel = 3200;
/// Solve timings repeat a solve until this much time has passed (and at least
/// kMinRepeats times) and keep the fastest call: a single 10 µs solve is
/// dominated by timer and cache noise.
constexpr double kTimingBudgetSeconds = 0.02;
constexpr int kMinRepeats = 3;
/// Relative error the recommendation of a station spacing aims at (0.1 %).
constexpr double kTargetError = 1e-3;

/// A station counts as "on the limit curve" if v >= (1 − this) v_max
/// (ProfileAnalysisOptions::touch_tolerance).
constexpr double kTouchTolerance = 1e-3;

constexpr std::size_t kRasterMaxSamples = 400;  // relief raster of the map, longer side

/// Rigid-body half wheelbase. The brief asked for l = 0.6 m "so that l/h < μ",
/// but with h = 0.5 m that is l/h = 1.2 > μ = 0.7: the friction ellipse then
/// always caps |f_t| below (l/h) R and pitch-over can never bind. l = 0.3 m
/// gives l/h = 0.6 < μ (the l/h of velocity-limits' tall rigid body), so
/// pitch-over caps braking at 0.6 g R ≈ 5.9 m/s² on level ground, just below
/// the 6 m/s² brake. l = 0.6 m is kept as a third, table-only vehicle to show
/// that, with pitch-over out of reach, it differs from the point mass only by
/// its chassis' view of the terrain (wheel_contact.hpp).
constexpr double kRigidHalfWheelbase = 0.3;
constexpr double kBriefHalfWheelbase = 0.6;

// ---------------------------------------------------------------------------
// Formatting.

/// A relative error as a signed percentage with three significant digits.
std::string percent_error(double relative) {
  if (!std::isfinite(relative)) return "–";
  if (relative == 0.0) return "0 (reference)";
  return fmt("%+.3g", 100.0 * relative) + " %";
}

std::string share(double part, double whole) {
  return whole > 0.0 ? fmt("%.1f", 100.0 * part / whole) + " %" : "–";
}

// ---------------------------------------------------------------------------
// Vehicles.

struct VehicleSpec {
  std::string name;   ///< file-name part
  std::string label;  ///< for titles and the report
  Vehicle vehicle;
};

/// The point mass is the bundled rover (data/vehicles/rover.yaml: μ = 0.7,
/// h = 0.5 m, b = 0.6 m, 15 m/s). Its drive and brake bound the traction
/// force per unit mass f_t = s̈ + g k_t (vehicle.hpp): 3 m/s² is below
/// μg = 6.9 m/s², so on level ground the motor, not friction, limits
/// acceleration; the 6 m/s² brake is just below μg, so friction limits braking
/// only where the ground load drops (crests) or the turn uses up friction.
std::vector<VehicleSpec> make_vehicles(const fs::path& data_dir) {
  const Vehicle point = load_vehicle((data_dir / "vehicles" / "rover.yaml").string());
  if (point.model != VehicleModel::kPointMass) {
    throw InputError("optimal-profile: data/vehicles/rover.yaml is not a point mass");
  }

  Vehicle rigid = point;
  rigid.model = VehicleModel::kRigidBody;
  rigid.half_wheelbase = kRigidHalfWheelbase;

  Vehicle brief = rigid;
  brief.half_wheelbase = kBriefHalfWheelbase;

  std::vector<VehicleSpec> specs = {
      {"point_mass", "point mass", point},
      {"rigid_body", "rigid body", rigid},
      {"rigid_body_l06", "rigid body, l = 0.6 m", brief},
  };
  for (const VehicleSpec& spec : specs) spec.vehicle.validate();
  return specs;
}

std::string vehicle_parameters(const Vehicle& v) {
  std::ostringstream text;
  text << "μ = " << fmt("%g", v.friction) << ", h = " << fmt("%g", v.cg_height)
       << " m, b = " << fmt("%g", v.half_track) << " m";
  if (v.model == VehicleModel::kRigidBody) {
    text << ", l = " << fmt("%g", v.half_wheelbase)
         << " m (l/h = " << fmt("%g", v.half_wheelbase / v.cg_height) << ")";
  }
  text << ", max speed " << fmt("%g", v.max_speed) << " m/s, drive " << fmt("%g", v.max_accel)
       << " m/s², brake " << fmt("%g", v.max_decel) << " m/s²";
  return text.str();
}

/// Colour and legend text of each constraint that can set v_max or bound s̈.
/// One table so that every figure's colours and the gnuplot colour function
/// cannot drift apart.
constexpr ConstraintStyle kStyles[] = {
    {Constraint::kContact, "#d62728", "contact"},
    {Constraint::kSliding, "#1f77b4", "sliding (friction)"},
    {Constraint::kTipover, "#ff7f0e", "lateral tip-over"},
    {Constraint::kMaxSpeed, "#7f7f7f", "max speed"},
    {Constraint::kPitchover, "#9467bd", "pitch-over"},
    {Constraint::kDrive, "#2ca02c", "drive limit"},
    {Constraint::kBrake, "#8c564b", "brake limit"},
    {Constraint::kNone, "#000000", "none"},
};

// ---------------------------------------------------------------------------
// One profile and its checks.

/// One vehicle's profile along the path, verified (verify_profile) and
/// analysed (analyze_profile: step classes, switching points, limiting lengths).
struct ProfileRun {
  explicit ProfileRun(const VehicleSpec& s) : spec(&s), limits(s.vehicle) {}
  const VehicleSpec* spec;
  VelocityLimits limits;
  TimeOptimalProfile profile;
  ProfileVerification verification;
  /// Its switches are those of the both-ends classification; the solver's
  /// own are in profile.switching_points.
  ProfileAnalysis analysis;
  double limits_seconds = 0.0, solve_seconds = 0.0;
  double max_gap = 0.0;  ///< largest v_point_mass − v at any station [m/s] (rigid body only)
};

ProfileRun solve_profile(const VehicleSpec& spec, const SurfacePath& path, std::size_t stations) {
  ProfileRun run(spec);
  const auto t0 = Clock::now();
  run.limits.compute(path, stations);
  const auto t1 = Clock::now();
  TimeOptimalProfileSolver solver;
  const ProfileOptions options;  // start and end at rest (the defaults)
  solver.solve(run.limits, options, run.profile);
  const auto t2 = Clock::now();
  run.limits_seconds = std::chrono::duration<double>(t1 - t0).count();
  run.solve_seconds = std::chrono::duration<double>(t2 - t1).count();
  if (run.profile.status != ProfileStatus::kOk) {
    throw InfeasibleError("optimal-profile: no admissible profile for the " + spec.label +
                          " along the path with " + std::to_string(stations) +
                          " stations: " + run.profile.message);
  }
  // v <= v_max, some s̈ admissible at every station and s̈ admissible at both
  // ends of every step (TOPP-RA's interpolation discretisation).
  run.verification = verify_profile(run.limits, run.profile);
  ProfileAnalysisOptions analysis;
  analysis.touch_tolerance = kTouchTolerance;
  run.analysis = analyze_profile(run.limits, run.profile, analysis);
  return run;
}

// ---------------------------------------------------------------------------
// Convergence study.

constexpr std::size_t kStudied = 2;  // the point mass and the rigid body
/// Convergence series: the two vehicles on the smoothing fit, and the point
/// mass on the interpolating fit as a control (its curvature spikes at cell
/// scale are the hardest case for a coarse station spacing).
constexpr std::size_t kSeries = 3;
constexpr std::size_t kInterpolatingSeries = 2;

/// The library's study (profile_convergence) for each series, over the same
/// station counts, so level i is the same station count in every series.
/// Spacings and the limits time are reported from series 0 (the point mass).
struct Convergence {
  std::array<ProfileConvergence, kSeries> series;
  std::size_t default_index = 0;  ///< the level of the count kDefaultStationSpacing gives

  std::size_t size() const { return series[0].levels.size(); }
  const ConvergenceLevel& at(std::size_t level, std::size_t v = 0) const {
    return series[v].levels[level];
  }
  const ConvergenceLevel& finest(std::size_t v = 0) const { return series[v].reference(); }
  const ConvergenceLevel& default_level(std::size_t v = 0) const { return at(default_index, v); }
  bool is_default(std::size_t level) const { return level == default_index; }
};

Convergence run_convergence(const std::vector<VehicleSpec>& vehicles, const SurfacePath& path,
                            const SurfacePath& interpolating_path, bool quick) {
  ProfileConvergenceOptions options;  // start and end at rest
  options.station_counts.clear();
  for (const std::size_t n : kLevels) {
    if (quick && n > kQuickMaxLevel) break;
    options.station_counts.push_back(n);
  }
  const std::size_t n_default = station_count(path.length());  // the library's rule
  options.extra_station_counts = {n_default};
  options.richardson_order = 1.0;  // e = C h, which the observed orders support
  options.timing_repeats = kMinRepeats;
  options.timing_budget_seconds = kTimingBudgetSeconds;
  const std::array<const VehicleSpec*, kSeries> series_vehicle = {&vehicles[0], &vehicles[1],
                                                                  &vehicles[0]};
  const std::array<const SurfacePath*, kSeries> series_path = {&path, &path, &interpolating_path};
  Convergence c;
  for (std::size_t v = 0; v < kSeries; ++v)
    c.series[v] = profile_convergence(series_vehicle[v]->vehicle, *series_path[v], options);
  c.default_index = c.series[0].find(n_default);
  return c;
}

/// The coarsest sequence level from which on every finer level (reference
/// excluded) is within kTargetError for both vehicles; nullptr if none.
const ConvergenceLevel* coarsest_within_target(const Convergence& c) {
  std::size_t found = 0;
  for (std::size_t v = 0; v < kStudied; ++v)
    found = std::max(found, c.series[v].coarsest_within(kTargetError));
  return found < c.size() ? &c.at(found) : nullptr;
}

// ---------------------------------------------------------------------------
// Output files.

std::string profile_csv_name(const ProfileRun& run) {
  return "profile_" + run.spec->name + ".csv";
}
/// The solver's own switching points (TimeOptimalProfile::switching_points).
std::string switching_csv_name(const ProfileRun& run) {
  return "switching_" + run.spec->name + ".csv";
}
/// The switching points of the both-ends classification (classify_steps).
std::string effective_csv_name(const ProfileRun& run) {
  return "switching_effective_" + run.spec->name + ".csv";
}

void write_profile_csv(const ProfileRun& run, const fs::path& file) {
  std::ofstream out = open_output_file(file);
  // The first eleven columns are the documented ones; the rest explain them.
  out << "s,x,y,z,v,a,t,v_max,binding,a_min,a_max,control,a_lower_binding,a_upper_binding,"
         "kappa_n,kappa_g,k_t\n";
  const TimeOptimalProfile& p = run.profile;
  for (std::size_t k = 0; k < p.s.size(); ++k) {
    const PathFrame& f = run.limits.frame(k);
    const AccelerationBounds& b = run.analysis.bounds[k];
    out << csv_number(p.s[k], 9) << ',' << csv_number(f.point.x(), 9) << ','
        << csv_number(f.point.y(), 9) << ',' << csv_number(f.point.z(), 9) << ','
        << csv_number(p.v[k], 9) << ',' << csv_number(p.a[k], 9) << ',' << csv_number(p.t[k], 9)
        << ',' << csv_number(p.v_max[k], 9) << ',' << to_string(p.binding[k]) << ','
        << csv_number(b.feasible ? b.a_min : kNaN) << ',' << csv_number(b.feasible ? b.a_max : kNaN)
        << ',' << to_string(p.control[k]) << ','
        << (b.feasible ? to_string(b.lower_binding) : "infeasible") << ','
        << (b.feasible ? to_string(b.upper_binding) : "infeasible") << ',' << csv_number(f.kappa_n)
        << ',' << csv_number(f.kappa_g) << ',' << csv_number(f.k_t) << '\n';
  }
  close_output_file(out, file);
}

void write_switching_csv(const ProfileRun& run, const std::vector<SwitchingPoint>& switches,
                         const fs::path& file) {
  std::ofstream out = open_output_file(file);
  out << "station,s,v,v_max,binding,from,to,x,y\n";
  const TimeOptimalProfile& p = run.profile;
  for (const SwitchingPoint& sw : switches) {
    const PathFrame& f = run.limits.frame(sw.station);
    out << sw.station << ',' << csv_number(sw.s, 9) << ',' << csv_number(p.v[sw.station], 9) << ','
        << csv_number(p.v_max[sw.station], 9) << ',' << to_string(p.binding[sw.station]) << ','
        << to_string(sw.from) << ',' << to_string(sw.to) << ',' << csv_number(f.point.x(), 9) << ','
        << csv_number(f.point.y(), 9) << '\n';
  }
  close_output_file(out, file);
}

void write_convergence_csv(const Convergence& c, const fs::path& file) {
  std::ofstream out = open_output_file(file);
  // The first five columns (point mass) are the documented ones.
  out << "stations,spacing_m,travel_time_s,relative_error,solve_seconds,max_spacing_m,"
         "limits_seconds,rigid_body_travel_time_s,rigid_body_relative_error,"
         "rigid_body_solve_seconds,default_spacing,interpolating_travel_time_s,"
         "interpolating_relative_error\n";
  for (std::size_t i = 0; i < c.size(); ++i) {
    const ConvergenceLevel &l = c.at(i), &rb = c.at(i, 1), &ip = c.at(i, kInterpolatingSeries);
    out << l.stations << ',' << csv_number(l.mean_spacing, 9) << ','
        << csv_number(l.travel_time, 12) << ',' << csv_number(l.error, 6) << ','
        << csv_number(l.solve_seconds, 4) << ',' << csv_number(l.max_spacing, 9) << ','
        << csv_number(l.limits_seconds, 4) << ',' << csv_number(rb.travel_time, 12) << ','
        << csv_number(rb.error, 6) << ',' << csv_number(rb.solve_seconds, 4) << ','
        << (c.is_default(i) ? 1 : 0) << ',' << csv_number(ip.travel_time, 12) << ','
        << csv_number(ip.error, 6) << '\n';
  }
  close_output_file(out, file);
}

// ---------------------------------------------------------------------------
// Figures.

/// The gnuplot lines of a switching-point series: one point style per new
/// control, so accelerate / brake / limit switches read at a glance.
std::string switching_series(const std::string& file, bool filled, const std::string& who) {
  struct Kind {
    const char* name;
    int filled_pt, open_pt;
    const char* colour;
  };
  constexpr Kind kinds[] = {{"accelerate", 9, 8, "#2ca02c"},
                            {"decelerate", 11, 10, "#d62728"},
                            {"limit", 7, 6, "#000000"}};
  std::ostringstream gp;
  for (const Kind& k : kinds) {
    gp << ", \\\n     " << gnuplot_string(file) << " skip 1 using 2:(strcol(7) eq '" << k.name
       << "' ? $3 : NaN) with points pt " << (filled ? k.filled_pt : k.open_pt)
       << " ps 1.3 lw 1.5 lc rgb '" << k.colour << "' title "
       << gnuplot_string(who + ": switch to " + k.name);
  }
  return gp.str();
}

/// The acceleration panel of one vehicle: the admissible band at the profile
/// speed, its edges coloured by the constraint setting them, and s̈(s).
std::string acceleration_panel(const ProfileRun& run) {
  const std::string file = gnuplot_string(profile_csv_name(run));
  const Vehicle& v = run.spec->vehicle;
  std::ostringstream gp;
  gp << "set title " << gnuplot_string(run.spec->label + ": " + vehicle_parameters(v)) << "\n"
     << "set ylabel 's̈ [m/s²]'\nset yrange [*:*]\n"
     << "plot " << file
     << " skip 1 using 1:10:11 with filledcurves lc rgb '#dde8f0' title 'admissible [a_{min}, "
        "a_{max}] at v(s)', \\\n"
     << "     '' skip 1 using 1:11:(binding_colour(strcol(14))) with lines lw 1.5 lc rgb "
        "variable notitle, \\\n"
     << "     '' skip 1 using 1:10:(binding_colour(strcol(13))) with lines lw 1.5 lc rgb "
        "variable notitle, \\\n"
     << "     '' skip 1 using 1:6 with steps lw 1.5 lc rgb 'black' title 's̈(s) of the profile'";
  for (const Constraint c :
       {Constraint::kDrive, Constraint::kBrake, Constraint::kSliding, Constraint::kPitchover}) {
    bool occurs = false;  // legend only for bindings that occur
    for (const AccelerationBounds& b : run.analysis.bounds)
      occurs |= b.feasible && (b.lower_binding == c || b.upper_binding == c);
    if (!occurs) continue;
    for (const ConstraintStyle& s : kStyles)
      if (s.constraint == c)
        gp << ", \\\n     " << key_entry(s.colour, std::string("bound set by ") + s.label);
  }
  gp << "\n";
  return gp.str();
}

/// The Fig. 8 analogue: v(s) of both vehicles under v_max(s) (coloured by
/// what sets it; identical for both, since pitch-over acts on s̈ only), the
/// switching points, and each vehicle's s̈(s) inside its admissible band.
/// [s0, s1] is the range of s shown (the whole path, or a zoom).
void draw_profile(const std::vector<ProfileRun>& runs, double length, const std::string& stem,
                  const std::string& title, double s0, double s1, const fs::path& out_dir) {
  const ProfileRun& pm = runs[0];
  const ProfileRun& rb = runs[1];
  const double max_speed = pm.spec->vehicle.max_speed;
  GnuplotFigure gp(out_dir, stem);
  gp.describe("Time-optimal velocity profile, from `talus experiment optimal-profile`.",
              "profile_<vehicle>.csv (1 s, 5 v, 6 a, 8 v_max, 9 binding, 10 a_min, 11 a_max, "
              "13/14 a bound bindings), switching_<vehicle>.csv (2 s, 3 v, 7 new control).")
          .canvas(1400, 1350)
      << "set datafile separator ','\n"
      << gnuplot_colour_function("binding_colour", kStyles) << "set multiplot layout 3,1 title "
      << gnuplot_string(title) << "\n"
      << "set xrange [" << fmt("%.10g", s0) << ":" << fmt("%.10g", std::min(s1, length)) << "]\n"
      << "set xlabel 'arc length s [m]'\n"
      << "set grid xtics ytics lc rgb '#d8d8d8'\nset tics out nomirror\n"
      << "set lmargin at screen 0.07\nset rmargin at screen 0.74\n"
      << "set key at graph 1.02, graph 1 left top vertical Left reverse samplen 2 spacing 1.05 "
         "font ',9'\n"
      << "set xzeroaxis lt 1 lc rgb '#808080'\n";
  // Panel 1: speeds.
  gp << "set title 'speed: v_{max}(s) coloured by the constraint that sets it (the same for both "
        "vehicles), and the optimal v(s)'\n"
     << "set ylabel 'speed [m/s]'\nset yrange [0:" << fmt("%g", 1.12 * max_speed) << "]\n"
     << "plot " << gnuplot_string(profile_csv_name(pm))
     << " skip 1 using 1:8:(binding_colour(strcol(9))) with lines lw 3 lc rgb variable notitle";
  for (const ConstraintStyle& s : kStyles) {
    bool occurs = false;
    for (const Constraint c : pm.profile.binding) occurs |= c == s.constraint;
    if (occurs)
      gp << ", \\\n     " << key_entry(s.colour, std::string("v_{max} set by ") + s.label);
  }
  gp << ", \\\n     " << gnuplot_string(profile_csv_name(pm))
     << " skip 1 using 1:5 with lines lw 2 lc rgb 'black' title 'point mass v(s)', \\\n"
     << "     " << gnuplot_string(profile_csv_name(rb))
     << " skip 1 using 1:5 with lines lw 2 dt (5,3) lc rgb '#e7298a' title 'rigid body v(s)'"
     << switching_series(effective_csv_name(pm), true, "point mass")
     << switching_series(effective_csv_name(rb), false, "rigid body") << ", \\\n     "
     << gnuplot_string(switching_csv_name(pm))
     << " skip 1 using 2:3 with points pt 1 ps 0.9 lw 1 lc rgb '#505050' title "
     << gnuplot_plain_text("point mass: the solver's switching_points (" +
                           std::to_string(pm.profile.switching_points.size()) + ")")
     << "\n";
  gp << acceleration_panel(pm) << acceleration_panel(rb) << "unset multiplot\n";
  gp.render();
}

/// The path over shaded relief of the smoothing fit, coloured by the point
/// mass's optimal speed, with the interpolation points.
void draw_map(const BPatch& patch, const ProfileRun& run, const std::vector<Vec2>& points,
              double zmin, double zmax, const fs::path& out_dir) {
  const MapFrame frame = MapFrame::of(patch);
  const Vec2& origin = frame.origin();
  GnuplotFigure figure(out_dir, "map");
  const double exaggeration =
      write_relief_image(patch, frame,
                         "smoothing B-patch (lambda " + fmt("%g", kSmoothingLambda) + ")",
                         figure.file("_relief.rgb"), kRasterMaxSamples, std::pair{zmin, zmax})
          .colouring.exaggeration;

  // About 300 segments are plenty at map scale; with every station the seams
  // between thousands of tiny segments show as stripes.
  const fs::path path_file = figure.file("_path.dat");
  std::ofstream path = open_output_file(path_file);
  path << "# " << run.spec->label << ": x - x_min [m], y - y_min [m], optimal speed v [m/s]\n";
  const std::size_t n = run.profile.s.size();
  const std::size_t stride = std::max<std::size_t>(1, n / 300);
  const auto write_station = [&](std::size_t k) {
    path << offset_row(run.limits.frame(k).point.head<2>(), origin) << ' '
         << csv_number(run.profile.v[k]) << '\n';
  };
  for (std::size_t k = 0; k < n; k += stride) write_station(k);
  write_station(n - 1);
  close_output_file(path, path_file);

  std::vector<Vec2> offsets;
  for (const Vec2& p : points) offsets.push_back(frame.offset(p));
  write_path_points(offsets, "# path interpolation points: x - x_min [m], y - y_min [m], label\n",
                    figure.file("_points.dat"));

  std::ostringstream title;
  title << "West Bijou at rover scale (1/25, 1 m cells): path coloured by the point mass's "
           "optimal speed\nover shaded relief of the smoothing fit (λ = "
        << fmt("%g", kSmoothingLambda) << "; elevation " << sig3(zmin) << " to " << sig3(zmax)
        << " m, hillshade × " << fmt("%g", exaggeration) << " vertical exaggeration)";
  figure.describe("Map of the optimal profile, from `talus experiment optimal-profile`.",
                  "map_relief.rgb (x y r g b), map_path.dat (x y v), map_points.dat (x y label).");
  figure.canvas(1100, frame.canvas_height(1100))
      << path_map_settings(frame, title.str(), run.spec->vehicle.max_speed, "v [m/s]")
      << path_map_plot("map_relief.rgb", "map_path.dat", "path, coloured by optimal v", "",
                       "map_points.dat");
  figure.render();
}

/// The |error| series of the convergence panel: a line per series, filled
/// points where the coarse profile is too slow, open where too fast. Point
/// sets with no data are left out (gnuplot warns about empty sets).
std::string error_series(const Convergence& c) {
  struct Style {
    int column;
    const char* title;
    const char* colour;
    const char* dash;
    int filled_pt, open_pt;
    double size;  // the point mass's points are larger: the rigid body's nearly cover them
  };
  constexpr Style styles[kSeries] = {
      {4, "point mass", "black", "solid", 7, 6, 1.6},
      {9, "rigid body", "#e7298a", "(5,3)", 5, 4, 0.9},
      {13, "point mass, interpolating fit (control)", "#2ca02c", "solid", 9, 8, 1.2},
  };
  std::ostringstream gp;
  for (std::size_t v = 0; v < kSeries; ++v) {
    const Style& st = styles[v];
    bool positive = false, negative = false;
    for (const ConvergenceLevel& l : c.series[v].levels) {
      positive |= l.error > 0.0;
      negative |= l.error < 0.0;
    }
    std::string col =
        "$";  // (not "$" + to_string(): GCC 12 warns -Wrestrict, a known false positive)
    col += std::to_string(st.column);
    gp << "'convergence.csv' skip 1 using 2:(" << col << " != 0 ? abs(" << col
       << ") : NaN) with lines lw 1.5 dt " << st.dash << " lc rgb '" << st.colour << "' title "
       << gnuplot_string(st.title) << ", \\\n     ";
    if (positive)
      gp << "'' skip 1 using 2:(" << col << " > 0 ? " << col << " : NaN) with points pt "
         << st.filled_pt << " ps " << st.size << " lc rgb '" << st.colour << "' notitle, \\\n     ";
    if (negative)
      gp << "'' skip 1 using 2:(" << col << " < 0 ? -" << col << " : NaN) with points pt "
         << st.open_pt << " ps " << st.size << " lc rgb '" << st.colour << "' notitle, \\\n     ";
  }
  return gp.str();
}

/// Travel time vs station count, |relative error| vs spacing (log-log, with
/// slope-1 and slope-2 guides), and solve time vs station count.
void draw_convergence(const Convergence& c, const fs::path& out_dir) {
  // Guides anchored at the middle non-reference level of the point mass.
  std::size_t anchor = (c.size() - 1) / 2;
  while (anchor > 0 && !(std::abs(c.at(anchor).error) > 0.0)) --anchor;
  const double h0 = c.at(anchor).mean_spacing;
  const double e0 = std::max(std::abs(c.at(anchor).error), 1e-12);
  const double t_anchor = c.finest().solve_seconds / static_cast<double>(c.finest().stations);
  GnuplotFigure gp(out_dir, "convergence");
  gp.describe(
        "Convergence of the travel time in the station count, from `talus experiment "
        "optimal-profile`.",
        "convergence.csv (1 stations, 2 mean spacing, 3/8 travel time, 4/9 relative error, "
        "5/10 solve seconds, 7 limits seconds, 11 default-spacing row, 12/13 point mass on "
        "the interpolating fit; point mass, rigid body).")
          .canvas(1800, 650)
      << "set datafile separator ','\n"
      << "set multiplot layout 1,3 title "
      << gnuplot_string(
             "Convergence of the optimal travel time in the number of stations (same path; "
             "reference: the finest level, " +
             std::to_string(c.finest().stations) + " stations)")
      << "\n"
      << "set grid lc rgb '#d8d8d8'\nset tics out nomirror\nset key top right font ',10'\n"
      << "set logscale x\nset format x '10^{%T}'\n"
      // Panel (a).
      << "set title '(a) travel time'\nset xlabel 'stations N'\nset ylabel 'travel time [s]'\n"
      << "plot 'convergence.csv' skip 1 using 1:3 with linespoints pt 7 lw 1.5 lc rgb 'black' "
         "title 'point mass', \\\n"
      << "     '' skip 1 using 1:8 with linespoints pt 6 lw 1.5 dt (5,3) lc rgb '#e7298a' "
         "title 'rigid body', \\\n"
      << "     '' skip 1 using 1:($11 == 1 ? $3 : NaN) with points pt 4 ps 2.5 lw 2 lc rgb "
         "'#1f77b4' title "
      << gnuplot_string("default spacing " + fmt("%g", kDefaultStationSpacing) + " m") << ", \\\n"
      << "     '' skip 1 using 1:($11 == 1 ? $8 : NaN) with points pt 4 ps 2.5 lw 2 lc rgb "
         "'#1f77b4' notitle\n"
      // Panel (b).
      << "set title '(b) |relative error| (filled: too slow, open: too fast)'\n"
      << "set logscale y\nset format y '10^{%T}'\n"
      << "set xlabel 'mean station spacing [m]'\nset ylabel '|T_N / T_{ref} − 1|'\n"
      << "set key bottom right\n"
      << "set arrow 1 from " << fmt("%g", kDefaultStationSpacing) << ", graph 0 to "
      << fmt("%g", kDefaultStationSpacing) << ", graph 1 nohead dt 2 lc rgb '#1f77b4'\n"
      << "set label 1 'default " << fmt("%g", kDefaultStationSpacing) << " m' at "
      << fmt("%g", kDefaultStationSpacing) << ", graph 0.96 offset char 0.5,0 tc rgb '#1f77b4'\n"
      << "set arrow 2 from graph 0, first " << fmt("%g", kTargetError) << " to graph 1, first "
      << fmt("%g", kTargetError) << " nohead dt 3 lc rgb '#808080'\n"
      << "h0 = " << fmt("%.10g", h0) << "; e0 = " << fmt("%.10g", e0) << "\n"
      << "plot " << error_series(c)
      << "     e0 * (x / h0) with lines dt 2 lc rgb '#909090' title 'slope 1 (O(h))', \\\n"
      << "     e0 * (x / h0)**2 with lines dt 4 lc rgb '#909090' title 'slope 2 (O(h^2))'\n"
      << "unset arrow 1\nunset arrow 2\nunset label 1\n"
      // Panel (c).
      << "set title '(c) time per solve (fastest of repeats)'\nset key top left\n"
      << "set xlabel 'stations N'\nset ylabel 'seconds'\n"
      << "t1 = " << fmt("%.10g", t_anchor) << "\n"
      << "# Infeasible levels (travel time nan) are left out: their solve stops early.\n"
      << "plot 'convergence.csv' skip 1 using 1:($3 == $3 ? $5 : NaN) with linespoints pt 7 lw "
         "1.5 lc rgb 'black' title 'solver, point mass', \\\n"
      << "     '' skip 1 using 1:($8 == $8 ? $10 : NaN) with linespoints pt 6 lw 1.5 dt (5,3) lc "
         "rgb '#e7298a' "
         "title 'solver, rigid body', \\\n"
      << "     '' skip 1 using 1:7 with linespoints pt 2 lw 1 lc rgb '#2ca02c' "
         "title 'VelocityLimits::compute (path + limits)', \\\n"
      << "     t1 * x with lines dt 2 lc rgb '#909090' title 'O(N)'\n"
      << "unset multiplot\n";
  gp.render();
}

// ---------------------------------------------------------------------------
// Report.

struct Setup {
  const ElevationGrid* dem = nullptr;
  double zmin = 0.0, zmax = 0.0, length = 0.0, fit_seconds = 0.0;
  std::vector<Vec2> points;  ///< rover-scale metres, from the south-west node
  std::size_t stations = 0;
};

std::string control_name(ControlKind k) {
  return std::string(to_string(k));
}

std::string commentary(const std::vector<ProfileRun>& runs, const ProfileRun& check_run,
                       const Convergence& convergence, const Setup& setup) {
  const ProfileRun& pm = runs[0];
  const ProfileRun& rb = runs[1];
  const double t_pm = pm.profile.travel_time, t_rb = rb.profile.travel_time;
  const ProfileAnalysis& c = pm.analysis;
  const LimitingLengths& lp = pm.analysis.lengths;
  const LimitingLengths& lr = rb.analysis.lengths;
  const double brake_pm = lp.decelerating(), brake_rb = lr.decelerating();
  const double accel_pm = lp.accelerating();
  std::ostringstream text;
  // 1. The shape of the profile.
  text << "The point mass covers the " << sig3(setup.length) << " m path in " << fmt("%.2f", t_pm)
       << " s (mean " << sig3(setup.length / t_pm) << " m/s, peak " << sig3(c.max_speed)
       << " m/s) and rides v_max(s) over only " << share(c.touch_length, setup.length)
       << " of it: with a 3 m/s² drive the sliding dips of v_max (turns on the escarpment and "
          "the knoll) come faster than it can regain speed, so the profile is almost all "
          "bang-bang, accelerating over "
       << sig3(accel_pm) << " m (" << sig3(lp.accelerate_drive) << " m on the drive limit, "
       << sig3(lp.accelerate_sliding) << " m on friction) and braking over " << sig3(brake_pm)
       << " m (" << sig3(lp.decelerate_brake) << " m brake, " << sig3(lp.decelerate_sliding)
       << " m friction), and touching v_max at " << c.dips_touched << " of its " << c.dips
       << " local minima, among them the slowest, " << sig3(c.slowest_v_max)
       << " m/s at s = " << sig3(c.slowest_s) << " m (passed at " << sig3(c.slowest_v) << " m/s). ";
  // 2. Rigid body.
  text << "The rigid body (l/h = "
       << fmt("%g", rb.spec->vehicle.half_wheelbase / rb.spec->vehicle.cg_height)
       << ") judges its normal load at its wheels (the chassis spans crests shorter than its "
          "wheelbase), and pitch-over sets its braking bound over "
       << sig3(lr.decelerate_pitch) << " m of its " << sig3(brake_rb)
       << " m of braking, but 0.6 g R ≈ 5.9 m/s² is barely below the 6 m/s² brake: together "
          "they change its time by "
       << fmt("%+.3f", t_rb - t_pm) << " s (" << fmt("%+.2f", 100.0 * (t_rb / t_pm - 1.0))
       << " %, at most " << sig3(rb.max_gap)
       << " m/s slower at any station); with the l = " << fmt("%g", kBriefHalfWheelbase)
       << " m of the brief (l/h = "
       << fmt("%g", kBriefHalfWheelbase / check_run.spec->vehicle.cg_height)
       << " > μ) pitch-over never binds and the travel time is "
       << fmt("%+.3f", 100.0 * (check_run.profile.travel_time / t_pm - 1.0))
       << " % off the point mass's, the chassis' view of the terrain alone. ";
  // 3. Convergence.
  const ConvergenceLevel &def = convergence.default_level(), &def_rb = convergence.default_level(1);
  const ConvergenceLevel* good = coarsest_within_target(convergence);
  text << "The travel time converges at first order and from above (coarse profiles are slower, "
          "because each step's constant s̈ must be admissible at both of its ends): at the "
          "default spacing "
       << fmt("%g", kDefaultStationSpacing) << " m (" << def.stations << " stations) it is "
       << percent_error(def.error) << " (point mass) and " << percent_error(def_rb.error)
       << " (rigid body) off the " << convergence.finest().stations << "-station reference";
  if (good != nullptr) {
    text << ", and " << fmt("%g", 100.0 * kTargetError) << " % is first met for both at "
         << sig3(good->mean_spacing) << " m (" << good->stations << " stations)";
  }
  text << ". ";
  text << "On the interpolating fit (control) the error changes sign and is no longer monotone ("
       << percent_error(convergence.default_level(kInterpolatingSeries).error)
       << " at the default spacing): coarse "
          "stations step over the cell-scale curvature spikes, miss the dips of v_max between "
          "them and come out too fast.";
  return text.str();
}

std::string solver_observations(const std::vector<ProfileRun>& runs,
                                const Convergence& convergence) {
  std::ostringstream md;
  // 1. Spurious infeasibility.
  std::size_t failures = 0, spurious = 0;
  for (std::size_t i = 0; i < convergence.size(); ++i)
    for (std::size_t v = 0; v < kSeries; ++v)
      if (!convergence.at(i, v).feasible) {
        ++failures;
        if (convergence.at(i, v).failure.rest_admissible) ++spurious;
      }
  md << "1. **Infeasible verdicts.** ";
  if (failures == 0) {
    md << "The solver returned a profile at every level.\n";
  } else {
    md << "The solver reported `kInfeasible` in " << failures
       << " convergence runs (table above); in " << spurious
       << " of them the verdict is provably wrong, because standing still is admissible at every "
          "station from the failing one to the end (v_min = 0 and 0 ∈ [a_min, a_max] at v = 0), "
          "so x = 0 with s̈ = 0 reaches the end at rest:\n\n";
    for (std::size_t i = 0; i < convergence.size(); ++i)
      for (std::size_t v = 0; v < kSeries; ++v) {
        const ConvergenceLevel& l = convergence.at(i, v);
        const InfeasibilityDiagnosis& f = l.failure;
        if (l.feasible) continue;
        md << "   - "
           << (v == kInterpolatingSeries ? "point mass, interpolating fit" : runs[v].spec->label)
           << ", " << l.stations << " stations: station " << f.station << " (s = " << sig3(f.s)
           << " m) of " << l.stations
           << "; rest admissible from there: " << (f.rest_admissible ? "yes" : "no")
           << ". Message: \"" << f.message << "\"\n";
      }
    md << "\n   It only happens with long steps (a few metres), where braking to rest within the "
          "last step is friction-limited in a turn: the closed-form braking state of the "
          "backward pass then lies on the friction ellipse of the step's start station, and a "
          "rejection of it by rounding leaves the upper end of the controllable set undefined "
          "(found by replaying the backward pass outside this experiment: the rejected state needs "
          "an s̈ about 1e-11 m/s² beyond the start station's bound, more than the solver's 1e-12 "
          "relative widening, and both targets of the retry loop are the same point when the end "
          "state is fixed).\n";
  }
  // 2. Switching-point classification.
  const ProfileRun& pm = runs[0];
  std::size_t mislabelled = 0, limit_steps = 0;
  for (std::size_t k = 0; k < pm.analysis.steps.size(); ++k) {
    if (pm.profile.control[k] != ControlKind::kLimit) continue;
    ++limit_steps;
    if (pm.analysis.steps[k].kind != ControlKind::kLimit) ++mislabelled;
  }
  md << "2. **Switching points.** The solver's `switching_points` ("
     << pm.profile.switching_points.size() << " for the point mass, "
     << runs[1].profile.switching_points.size()
     << " for the rigid body) are mostly not switches of the control: " << mislabelled
     << " of the point mass's " << limit_steps
     << " steps labelled `limit` have s̈ exactly on a_max or a_min at the step's **end** station "
        "(whose bound is the tighter one there), i.e. they are full-drive or full-braking steps. "
        "The solver labels a step by comparing s̈ with the bounds at its start only, although it "
        "holds s̈ admissible at both ends, so a bang-bang arc whose bound tightens along the path "
        "alternates between `accelerate` (or `decelerate`) and `limit` every few stations. "
        "Classifying against both ends (this experiment's `switching_effective_<vehicle>.csv`, "
        "the markers of the profile figure and the tables above) leaves "
     << pm.analysis.switches.size() << " and " << runs[1].analysis.switches.size()
     << " switching points.\n";
  // 3. Limits timing (not the solver, but it sets the cost of a station).
  const std::vector<ConvergenceLevel>& levels = convergence.series[0].levels;
  const ConvergenceLevel* slow = &levels.front();
  const ConvergenceLevel* fast = &levels.front();
  const auto per_station = [](const ConvergenceLevel& l) {
    return l.limits_seconds / static_cast<double>(l.stations);
  };
  for (const ConvergenceLevel& l : levels) {
    if (per_station(l) > per_station(*slow)) slow = &l;
    if (per_station(l) < per_station(*fast)) fast = &l;
  }
  if (per_station(*slow) > 3.0 * per_station(*fast)) {
    md << "3. **Limits cost (outside the solver).** `VelocityLimits::compute` costs "
       << sig3(1e6 * per_station(*slow)) << " µs per station at " << slow->stations
       << " stations but " << sig3(1e6 * per_station(*fast)) << " µs at " << fast->stations
       << ": below the arc-length table's piece count `SurfacePath::sample_uniform_parameter` "
          "takes s from table look-ups instead of the Hermite-corrected trapezoid rule, by "
          "design (accuracy), so on this path the default spacing's "
       << convergence.default_level().stations << " stations ("
       << fmt("%.3g", 1e3 * convergence.default_level().limits_seconds)
       << " ms) cost more than 400 stations would. Harmless in absolute terms.\n";
  }
  return md.str();
}

/// The smallest and largest observed order of the point mass's series, over the levels where the
/// reference's own error (about h_ref/h of the measured one for first order) is small enough not
/// to bias them.
std::pair<double, double> observed_order_range(const Convergence& convergence) {
  std::pair<double, double> range{kInf, -kInf};
  for (const ConvergenceLevel& l : convergence.series[0].levels)
    if (std::isfinite(l.order) && l.mean_spacing >= 16.0 * convergence.finest().mean_spacing) {
      range.first = std::min(range.first, l.order);
      range.second = std::max(range.second, l.order);
    }
  return range;
}

/// The headline numbers of summary.json.
void summarise(const std::vector<ProfileRun>& runs, const ProfileRun& check_run,
               const Convergence& convergence, ExperimentSummary& summary) {
  summary.set("travel_time_point_mass_s", runs[0].profile.travel_time, "s");
  summary.set("travel_time_rigid_body_s", runs[1].profile.travel_time, "s");
  summary.set("rigid_body_over_point_mass",
              runs[1].profile.travel_time / runs[0].profile.travel_time, "1",
              "pitch-over removes admissible states; the chassis, judged at its wheels, spans "
              "crests shorter than its wheelbase and adds a few (wheel_contact.hpp)");
  summary.set("rigid_body_long_over_point_mass",
              check_run.profile.travel_time / runs[0].profile.travel_time, "1",
              "with l/h > mu pitch-over never binds: the only difference from the point mass is "
              "the chassis' view of the terrain, at most as slow on crests long against 2 l");
  summary.set("default_spacing_error", convergence.default_level().error, "1");
  const auto [low, high] = observed_order_range(convergence);
  summary.set("observed_order_min", low, "1",
              "1: first order, the forward-backward scheme's step admissible at both ends");
  summary.set("observed_order_max", high, "1", "1 (as observed_order_min)");
}

void write_report(const std::vector<ProfileRun>& runs, const ProfileRun& check_run,
                  const Convergence& convergence, const Setup& setup,
                  const ExperimentContext& context, double total_seconds) {
  const ElevationGrid& dem = *setup.dem;
  Table points({"point", "cells (u, v)", "x, y from the south-west node [m]"});
  for (std::size_t i = 0; i < std::size(kWestBijouPathCells); ++i) {
    points.row({fmt("P%g", static_cast<double>(i)),
                fmt("%g", kWestBijouPathCells[i].u) + ", " + fmt("%g", kWestBijouPathCells[i].v),
                sig3(setup.points[i].x()) + ", " + sig3(setup.points[i].y())});
  }
  Report report("Time-optimal velocity profile on a real DEM");
  report
      .paragraph(
          "The time-optimal velocity profile v(s) under the limit curve v_max(s) along a fixed "
          "curved path on the West Bijou escarpment at rover scale, with its switching points "
          "and the tangential acceleration s̈(s) inside the admissible [a_min, a_max]: the "
          "analogue of the velocity-profile figure (Fig. 8) of Iagnemma, Shimoda and Shiller "
          "(IROS 2008). Then a convergence study of the travel time in the number of stations, "
          "which is the evidence for the library's default station spacing.")
      .heading("What was run")
      .bullet("Terrain: " + west_bijou_terrain_text(dem) +
              ", scaled to rover size by multiplying x, y **and** "
              "z by 1/25 (README \"Rover-scale use\"): 1 m cells, elevations " +
              sig3(setup.zmin) + " to " + sig3(setup.zmax) +
              " m, slopes unchanged, curvatures 25 × larger.")
      .bullet("Surface: the smoothing B-patch fit (`BPatch::fit_smoothing`, λ = " +
              fmt("%g", kSmoothingLambda) + ", fitted in " + sig3(1e3 * setup.fit_seconds) +
              " ms). Not the interpolating fit: the DEM stores whole metres, which at rover scale "
              "are 4 cm steps per 1 m cell, and the interpolating fit reproduces each step as a "
              "curvature spike; v_max(s) then has a narrow dip at nearly every cell (see the "
              "velocity-limits experiment), which is quantisation, not terrain. The "
              "interpolating fit appears here only as a control series of the convergence study.")
      .bullet("Path: `Curve2::interpolate` (cubic, chord-length parameters) through " +
              std::to_string(std::size(kWestBijouPathCells)) +
              " fixed points (the path of the velocity-limits experiment), 3-D length " +
              sig3(setup.length) + " m:\n\n" + points.markdown("  ") + "\n  " +
              kWestBijouPathRoute);
  std::string vehicles =
      "Vehicles (g = 9.81 m/s²; drive and brake limits bound the traction force per unit mass "
      "f_t = s̈ + g k_t, so downhill a_max exceeds 3 m/s² and uphill it is less):\n";
  for (const ProfileRun* run : {&runs[0], &runs[1], &check_run}) {
    const Vehicle& v = run->spec->vehicle;
    vehicles +=
        "  - `" + run->spec->name +
        "`: " + (v.model == VehicleModel::kPointMass ? "point-mass model" : "rigid-body model") +
        ", " + vehicle_parameters(v) + (run == &check_run ? " — table only, see below" : "") + "\n";
  }
  report
      .bullet(vehicles +
              "\n  **Deviation from the brief:** the brief asked for the rigid body with l = " +
              fmt("%g", kBriefHalfWheelbase) +
              " m \"so that l/h < μ and pitch-over limits braking\", but with h = 0.5 m that is "
              "l/h = 1.2 > μ = 0.7: the friction ellipse then caps |f_t| ≤ μR < (l/h)R everywhere "
              "and pitch-over can never bind, so that vehicle is the point mass (its row below "
              "shows it). The figures therefore use l = " +
              fmt("%g", kRigidHalfWheelbase) +
              " m (l/h = 0.6 < μ), which caps braking at 0.6 g ≈ 5.9 m/s² on level ground, just "
              "below the 6 m/s² brake, and lower where the ground load drops.")
      .bullet(
          "Profile: `TimeOptimalProfileSolver` (reachability analysis in ṡ², constraints "
          "enforced at both ends of every step), start and end at rest, " +
          std::to_string(setup.stations) + " stations" + (context.quick ? " (quick mode)" : "") +
          " equally spaced in the curve parameter (mean spacing " +
          sig3(setup.length / static_cast<double>(setup.stations - 1)) +
          " m). a_min, a_max are `VelocityLimits::acceleration_bounds` at each station's "
          "profile speed.")
      .bullet("Convergence: the same path at " + std::to_string(convergence.size()) +
              " station counts from " + std::to_string(convergence.at(0).stations) + " to " +
              std::to_string(convergence.finest().stations) +
              (context.quick ? fmt(" (quick mode: up to %g)", kQuickMaxLevel) : "") +
              ", including the count the default spacing gives (" +
              std::to_string(convergence.default_level().stations) + " = ⌈L / " +
              fmt("%g", kDefaultStationSpacing) +
              " m⌉ + 1), for both vehicles and, as a control, the point mass on the "
              "interpolating fit; relative error against the finest level. Times are the fastest "
              "of repeated calls (at least " +
              std::to_string(kMinRepeats) + ", for at least " +
              fmt("%g", 1e3 * kTimingBudgetSeconds) +
              " ms); the solve time excludes `VelocityLimits::compute` (path sampling and "
              "limits), which is timed separately.")
      .bullet(
          "Files: `profile_<vehicle>.csv` (s, x, y, z, v, a, t, v_max, binding, a_min, a_max, "
          "then the solver's control label, what sets a_min and a_max, kappa_n, kappa_g, k_t; "
          "a is the s̈ of the step starting at the station), `switching_<vehicle>.csv` (the "
          "solver's `switching_points`), `switching_effective_<vehicle>.csv` (see \"Solver "
          "observations\"), `convergence.csv` (stations, spacing_m (mean), travel_time_s, "
          "relative_error, solve_seconds for the point mass, then max spacing, limits time, "
          "the rigid body's columns, the default-spacing flag and the interpolating-fit "
          "control), and every figure's gnuplot script beside its PNG.")
      .bullet("Whole run: " + sig3(total_seconds) + " s.")
      .heading("Travel times");
  Table times({"vehicle", "l/h", "travel time [s]", "mean speed [m/s]", "peak speed [m/s]",
               "on v_max", "switching points (solver's)",
               "accelerating: drive / friction / pitch [m]",
               "braking: brake / friction / pitch [m]", "limits + solve [ms]"});
  for (const ProfileRun* run : {&runs[0], &runs[1], &check_run}) {
    const Vehicle& v = run->spec->vehicle;
    const ProfileAnalysis& c = run->analysis;
    const LimitingLengths& l = c.lengths;
    times.row(
        {"`" + run->spec->name + "`",
         v.model == VehicleModel::kRigidBody ? fmt("%g", v.half_wheelbase / v.cg_height) : "–",
         fmt("%.3f", run->profile.travel_time), sig3(setup.length / run->profile.travel_time),
         sig3(c.max_speed), share(c.touch_length, setup.length),
         std::to_string(c.switches.size()) + " (" +
             std::to_string(run->profile.switching_points.size()) + ")",
         sig3(l.accelerate_drive) + " / " + sig3(l.accelerate_sliding) + " / " +
             sig3(l.accelerate_pitch),
         sig3(l.decelerate_brake) + " / " + sig3(l.decelerate_sliding) + " / " +
             sig3(l.decelerate_pitch),
         sig3(1e3 * run->limits_seconds) + " + " + sig3(1e3 * run->solve_seconds)});
  }
  const double max_dv = profile_difference(check_run.profile, runs[0].profile).largest_difference;
  report.table(times)
      .paragraph("\"On v_max\": share of the path length where v ≥ (1 − " +
                 fmt("%g", kTouchTolerance) +
                 ") v_max. Accelerating/braking: path length of the steps whose s̈ sits on a_max "
                 "(a_min) at the tighter of the step's two ends, by the constraint that sets that "
                 "bound; the rest rides v_max(s) or is a switching step. `" +
                 check_run.spec->name + "` differs from the point mass by at most " +
                 fmt("%.3g", max_dv) + " m/s at any station.")
      .heading("Switching points")
      .paragraph(
          "Where the control changes between accelerate (s̈ on a_max), decelerate (s̈ on a_min) "
          "and limit (riding v_max(s)), judged against the bounds at both ends of each step; a "
          "single step strictly inside the bounds between two arcs is the switch itself. v and "
          "v_max are at the switching station. The solver's own list is in "
          "`switching_<vehicle>.csv` (see \"Solver observations\").");
  constexpr std::size_t kMaxRows = 60;
  for (const ProfileRun* run : {&runs[0], &runs[1]}) {
    const TimeOptimalProfile& p = run->profile;
    const std::vector<SwitchingPoint>& effective = run->analysis.switches;
    Table switches(
        {"#", "station", "s [m]", "v [m/s]", "v_max [m/s]", "v_max set by", "from → to"});
    for (std::size_t i = 0; i < effective.size() && i < kMaxRows; ++i) {
      const SwitchingPoint& sw = effective[i];
      switches.row({std::to_string(i + 1), std::to_string(sw.station), fmt("%.2f", sw.s),
                    fmt("%.3f", p.v[sw.station]), fmt("%.3f", p.v_max[sw.station]),
                    std::string(to_string(p.binding[sw.station])),
                    std::string(control_name(sw.from)) + " → " + std::string(control_name(sw.to))});
    }
    report
        .heading(
            "`" + run->spec->name + "`: " + std::to_string(effective.size()) + " switching points",
            3)
        .table(switches);
    if (effective.size() > kMaxRows) {
      report.paragraph(fmt("(%g more in `", static_cast<double>(effective.size() - kMaxRows)) +
                       effective_csv_name(*run) + "`.)");
    }
  }
  Table table({"stations", "mean / max spacing [m]", "point mass T [s]", "rel. error", "order",
               "rigid body T [s]", "rel. error", "order", "interpolating fit: rel. error",
               "solve PM / RB [ms]", "limits [ms]"});
  const auto order = [](double p) { return std::isfinite(p) ? fmt("%.2f", p) : "–"; };
  const auto time = [](double t) { return std::isfinite(t) ? fmt("%.5f", t) : "infeasible"; };
  for (std::size_t i = 0; i < convergence.size(); ++i) {
    const ConvergenceLevel &l = convergence.at(i), &rb = convergence.at(i, 1),
                           &ip = convergence.at(i, kInterpolatingSeries);
    table.row({std::to_string(l.stations) + (convergence.is_default(i) ? " (default spacing)" : ""),
               sig3(l.mean_spacing) + " / " + sig3(l.max_spacing), time(l.travel_time),
               percent_error(l.error), order(l.order), time(rb.travel_time),
               percent_error(rb.error), order(rb.order),
               std::isfinite(ip.travel_time) ? percent_error(ip.error) : "infeasible",
               fmt("%.3g", 1e3 * l.solve_seconds) + " / " + fmt("%.3g", 1e3 * rb.solve_seconds),
               fmt("%.3g", 1e3 * l.limits_seconds)});
  }
  const ConvergenceLevel& def = convergence.default_level();
  const double t_star = convergence.series[0].extrapolated_time;
  const double t_star_rb = convergence.series[1].extrapolated_time;
  const std::pair<double, double> order_range = observed_order_range(convergence);
  report.heading("Convergence in the number of stations")
      .table(table)
      .paragraph(
          "\"order\": log(|e_N| / |e_2N|) / log(h_N / h_2N) between this level and the next "
          "doubling level (not computed against the reference itself). A positive error means "
          "the coarse profile is slower than the reference. Solve times of infeasible levels are "
          "of a solve that stopped early.")
      .paragraph(
          "The observed order (point mass) lies between " + fmt("%.2f", order_range.first) +
          " and " + fmt("%.2f", order_range.second) +
          " at the levels at least 16 times coarser than the reference; its rise towards the "
          "finest levels is the reference's own error, not faster convergence: with e = C h, "
          "measuring against a reference at h_ref gives log₂((4 − 1)/(2 − 1)) = 1.58 at h = "
          "4 h_ref and log₂(7/3) = 1.22 at 8 h_ref, which is what the table shows. A first-order "
          "Richardson estimate of the limit from the two finest levels, T* = T_ref + (T_ref − "
          "T_2h) / (h_2h / h_ref − 1) ≈ 2 T_ref − T_2h, gives " +
          fmt("%.5f", t_star) + " s (point mass) and " + fmt("%.5f", t_star_rb) +
          " s (rigid body), so the reference itself is " +
          fmt("%+.4f", 100.0 * (convergence.finest().travel_time / t_star - 1.0)) +
          " % off and the default spacing's error against the limit is " +
          fmt("%+.3f", 100.0 * (def.travel_time / t_star - 1.0)) + " %.");
  if (std::isfinite(def.error) && def.error > 0.0) {
    const double c = def.error / def.mean_spacing;
    report.paragraph(
        "**Default station spacing.** At kDefaultStationSpacing = " +
        fmt("%g", kDefaultStationSpacing) + " m the travel time is " + percent_error(def.error) +
        " too slow on the smoothing fit; e ≈ C h with C = " + fmt("%.3g", c) +
        " /m puts 0.1 % at h ≈ " + sig3(kTargetError / c) +
        " m. On the interpolating fit of the same 1 m-cell terrain the error at " +
        fmt("%g", kDefaultStationSpacing) + " m is " +
        percent_error(convergence.default_level(kInterpolatingSeries).error) +
        " and irregular in h (stations a fraction of a cell apart alias the cell-scale "
        "curvature). The solve is cheap at any of these spacings (see the solve-time column).");
  }
  report.heading("Sanity checks");
  for (const ProfileRun* run : {&runs[0], &runs[1]}) {
    const ProfileVerification& check = run->verification;
    const ProfileAnalysis& c = run->analysis;
    report.bullet("`" + run->spec->name + "`: v > v_max at " +
                  std::to_string(check.speed_violations) + " stations (largest v − v_max " +
                  fmt("%.3g", check.worst_speed.amount) +
                  " m/s); s̈ needing a contact force outside the admissible set at " +
                  std::to_string(check.acceleration_violations) + " step ends (largest distance " +
                  fmt("%.3g", check.worst_acceleration.amount) +
                  " m/s² in force per unit mass, checked at both ends of every step at their "
                  "profile speeds); stations with no "
                  "admissible s̈ at their profile speed (on the limit curve up to rounding): " +
                  std::to_string(check.inadmissible_states) + "; on v_max in " +
                  std::to_string(c.touch_segments) + " stretches (" + std::to_string(c.touching) +
                  " stations), including " + std::to_string(c.dips_touched) + " of the " +
                  std::to_string(c.dips) + " local minima of v_max.");
  }
  report.heading("What the figures show")
      .paragraph(commentary(runs, check_run, convergence, setup))
      .heading("Solver observations")
      .paragraph(solver_observations(runs, convergence))
      .heading("Figures")
      .paragraph(
          "`profile.png`: top, v_max(s) coloured by the constraint that sets it, the two optimal "
          "profiles and the switching points (filled: point mass, open: rigid body; grey +: the "
          "solver's own switching_points of the point mass); middle and bottom, each vehicle's "
          "s̈(s) (black) inside its admissible band at the profile speed, the band's edges "
          "coloured by what sets them.")
      .figure("optimal velocity profile", "profile.png")
      .paragraph(
          "`profile_zoom.png`: the same around the largest speed gap between the two "
          "vehicles.")
      .figure("optimal velocity profile, zoom", "profile_zoom.png")
      .figure("path coloured by speed", "map.png")
      .figure("convergence", "convergence.png")
      .write(context.output_dir);
}

/// A window of the path worth a closer look: centred where the rigid body is
/// slowest relative to the point mass (its pitch-limited braking), ±`half`.
std::pair<double, double> zoom_window(const std::vector<ProfileRun>& runs, double length,
                                      double half) {
  const TimeOptimalProfile& a = runs[0].profile;
  const std::size_t worst = profile_difference(a, runs[1].profile).largest_gap_station;
  const double centre = std::clamp(a.s[worst], half, std::max(half, length - half));
  return {std::max(0.0, centre - half), std::min(length, centre + half)};
}

}  // namespace

void run_optimal_profile(const ExperimentContext& context) {
  const auto start = Clock::now();
  // Fail in a second, not after the computation, if the figures cannot be drawn.
  require_gnuplot();
  const fs::path dem_file = scenarios::bundled_dem_file(context.data_dir, kWestBijouStem);
  const ElevationGrid dem =
      scenarios::load_bundled_dem(context.data_dir, kWestBijouStem, "optimal-profile");
  const ElevationGrid rover = scenarios::scaled_grid(dem, kRoverScale);
  const auto range = rover.elevation_range();
  if (!range) throw InputError("optimal-profile: " + dem_file.string() + " has no valid node");

  Setup setup;
  setup.dem = &dem;
  setup.zmin = range->first;
  setup.zmax = range->second;
  const auto fit_start = Clock::now();
  const BPatch patch = BPatch::fit_smoothing(rover, kSmoothingLambda);
  setup.fit_seconds = std::chrono::duration<double>(Clock::now() - fit_start).count();
  const std::vector<Vec2> points = west_bijou_path_points(rover, "optimal-profile");
  for (const Vec2& p : points)
    setup.points.emplace_back(p.x() - patch.x_min(), p.y() - patch.y_min());
  const SurfacePath path(patch, Curve2::interpolate(points));
  setup.length = path.length();
  setup.stations = context.quick ? kQuickProfileStations : kProfileStations;

  const std::vector<VehicleSpec> vehicles = make_vehicles(context.data_dir);
  std::vector<ProfileRun> runs;
  for (std::size_t v = 0; v < kStudied; ++v)
    runs.push_back(solve_profile(vehicles[v], path, setup.stations));
  const ProfileRun check_run = solve_profile(vehicles[2], path, setup.stations);
  runs[1].max_gap = std::max(0.0, profile_difference(runs[0].profile, runs[1].profile).largest_gap);
  for (const ProfileRun& run : runs) {
    write_profile_csv(run, context.output_dir / profile_csv_name(run));
    write_switching_csv(run, run.profile.switching_points,
                        context.output_dir / switching_csv_name(run));
    write_switching_csv(run, run.analysis.switches, context.output_dir / effective_csv_name(run));
    std::cout << "optimal-profile: " << run.spec->name << ": travel time "
              << fmt("%.4f", run.profile.travel_time) << " s over " << sig3(setup.length) << " m, "
              << run.analysis.switches.size()
              << " switching points (solver: " << run.profile.switching_points.size() << ")\n";
  }

  // The control series: the same path on the interpolating fit.
  const BPatch interpolating_patch = BPatch::interpolate(rover);
  const SurfacePath interpolating_path(interpolating_patch, Curve2::interpolate(points));
  const Convergence convergence =
      run_convergence(vehicles, path, interpolating_path, context.quick);
  write_convergence_csv(convergence, context.output_dir / "convergence.csv");
  const ConvergenceLevel& def = convergence.default_level();
  std::cout << "optimal-profile: convergence over " << convergence.size()
            << " levels; default spacing (" << def.stations << " stations): error "
            << percent_error(def.error) << " (point mass)\n";

  draw_profile(runs, setup.length, "profile",
               "Time-optimal velocity profile, West Bijou at rover scale (1/25), smoothing fit "
               "λ = " +
                   fmt("%g", kSmoothingLambda) + ", " + std::to_string(setup.stations) +
                   " stations, start and end at rest",
               0.0, setup.length, context.output_dir);
  const auto [z0, z1] = zoom_window(runs, setup.length, 15.0);
  draw_profile(runs, setup.length, "profile_zoom",
               "Zoom on s = " + sig3(z0) + " … " + sig3(z1) +
                   " m, around the largest speed gap between the point mass and the "
                   "pitch-limited rigid body",
               z0, z1, context.output_dir);
  draw_map(patch, runs[0], points, setup.zmin, setup.zmax, context.output_dir);
  draw_convergence(convergence, context.output_dir);
  const double total = std::chrono::duration<double>(Clock::now() - start).count();
  summarise(runs, check_run, convergence, *context.summary);
  write_report(runs, check_run, convergence, setup, context, total);
}

}  // namespace talus::experiments
