#include "global_search_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/relief.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/grid_window.hpp"
#include "talus/core/terrain_statistics.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/candidate_metrics.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/map_frame.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/relief_raster.hpp"
#include "talus/report/report.hpp"
#include "talus/scenarios/bundled_dem.hpp"

namespace talus::experiments {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------
// Fixed settings, named so the report can quote them.

constexpr const char* kDemStem = "mount_st_helens_usgs30m";

/// The crop, in DEM node indices (column from the west, row from the south):
/// the DEM's full width and rows 60–389, which hold the whole cone, the
/// crater with its northern breach and, to the south, the lowland apron that
/// the route round the mountain needs at low friction (the northern debris
/// plain beyond row 389 plays no part and is left out). True 30 m posting:
/// the slopes (crater walls up to ~69°, flanks 20–35°) are what a car-like
/// vehicle feels, so no rescaling.
constexpr GridWindow kCrop{0, 60, 317, 330};

/// Start and goal in DEM node indices: west and east of the cone, on gentle
/// ground (slope < 12° around both), so that the straight line crosses the
/// crater and a route must go over the flanks north or south of it, or round
/// the mountain. Both lie in the one region that stays connected at μ = 0.35
/// (the apron south of the cone, which reaches up its west and east sides);
/// the northern plain and the crater floor are cut off from it at that
/// friction, so a start there would make the μ = 0.35 run unreachable.
constexpr GridIndex kStart{14.0, 275.0};
constexpr GridIndex kGoal{289.0, 303.0};

/// The search runs on the smoothing fit. The 1980 USGS DEM carries an
/// east–west striping artefact: going north along a column on the flanks,
/// one-cell steps of 15–25 m (tan 0.5–0.8) alternate with flat or reversed
/// cells (over the whole DEM the mean |second difference| is 4.3 m along y
/// against 2.9 m along x; the report gives the crop's values). The
/// interpolating fit honours every step exactly, and each step steeper than
/// atan μ becomes a one-row untraversable bar that the search must detour
/// around, although the real flank is passable. λ = 1 (dimensionless,
/// grid-index units) smooths over about one cell, which removes the terraces
/// but keeps the crater walls and gullies. The interpolating fit is kept as a
/// control run so that the report can show the effect.
constexpr double kSmoothingLambda = 1.0;

constexpr double kFrictions[] = {0.7, 0.35};
constexpr int kConnectivity = 16;
constexpr std::size_t kCandidates = 3;
/// Quick mode: the same crop on a lattice three cells apart (9× fewer nodes).
constexpr double kQuickLatticeCells = 3.0;

constexpr std::size_t kRasterMaxSamples = 480;  // relief raster, longer side
constexpr std::size_t kQuickRasterMaxSamples = 240;
constexpr int kContourTargetLevels = 12;
constexpr double kExcessShare = 0.2;  // colour range of the excess panel, × J*
/// A candidate's vertex "shares" the best route's corridor if it lies within
/// this fraction of the separation of it (about 200 m here, 7 cells).
constexpr double kSharedFraction = 0.25;

/// Candidate colours (ColorBrewer Set1 red, blue, purple; then orange, brown):
/// saturated enough to read over the washed relief tint.
constexpr const char* kCandidateColours[] = {"#e41a1c", "#377eb8", "#984ea3", "#ff7f00", "#a65628"};
/// The best route at each friction in the comparison figure.
constexpr const char* kFrictionColours[] = {"#e41a1c", "#377eb8"};

// ---------------------------------------------------------------------------
// Formatting.

/// A data-file number: "NaN" for NaN and ±inf (gnuplot leaves such pixels
/// transparent and skips them when tracing contours), else 7 significant digits.
std::string num(double value) {
  if (!std::isfinite(value)) return "NaN";
  return fmt("%.7g", value);
}

/// "mu0.7": the file-name tag of one friction.
std::string friction_tag(double mu) {
  return "mu" + fmt("%g", mu);
}

double degrees(double radians) {
  return radians * 180.0 / std::numbers::pi;
}

// ---------------------------------------------------------------------------
// Terrain.

struct Setup {
  Setup(ElevationGrid grid, BPatch surface, BPatch control)
      : dem_crop(std::move(grid)), patch(std::move(surface)), interpolating(std::move(control)) {}
  ElevationGrid dem_crop;
  BPatch patch;          ///< smoothing fit: what the search runs on
  BPatch interpolating;  ///< exact at the nodes: the control run
  double zmin = 0.0, zmax = 0.0;
  Vec2 start = Vec2::Zero(), goal = Vec2::Zero();
  Vec2 summit = Vec2::Zero();  ///< highest node of the crop
  double summit_z = 0.0;
  double spacing = 0.0;  ///< lattice spacing [m]
  double fit_seconds = 0.0;
  /// Mean |second difference| of the crop's nodes along x and along y [m]:
  /// the row terracing shows as a larger value along y.
  double roughness_x = 0.0, roughness_y = 0.0;
  Vec2 origin() const { return {patch.x_min(), patch.y_min()}; }
  MapFrame frame() const { return MapFrame::of(patch, MapUnit::kKilometre); }
  double width() const { return patch.x_max() - patch.x_min(); }
  double height() const { return patch.y_max() - patch.y_min(); }
};

// ---------------------------------------------------------------------------
// One search and what the figures and the report need from it.

/// What the figures and the report use of one candidate.
struct CandidateInfo {
  CandidateMetrics metrics;  ///< along the route (measure_candidate)
  LandmarkPassage passage;   ///< where it passes the summit
  /// Relation to the best candidate: symmetric Hausdorff distance and the
  /// share of this route's vertices within kSharedFraction × the separation
  /// of it (the same corridor); the defaults for the best one itself.
  CorridorOverlap vs_best;
};

struct FrictionRun {
  double friction = 0.0;
  Vehicle vehicle;
  GlobalSearchResult result;
  std::vector<CandidateInfo> info;
  std::size_t steep_nodes = 0;  ///< lattice nodes whose terrain slope exceeds atan(μ)
  std::size_t unreachable = 0;  ///< lattice nodes with cost_from_start = +inf
};

Vehicle make_vehicle(double friction) {
  Vehicle v;
  v.model = VehicleModel::kPointMass;
  v.friction = friction;
  v.cg_height = 0.8;
  v.half_track = 0.8;
  v.max_speed = 20.0;  // J needs a finite top speed (global_search.hpp)
  v.validate();
  return v;
}

FrictionRun run_search(const Setup& setup, double friction, const GlobalSearchOptions& options) {
  FrictionRun run;
  run.friction = friction;
  run.vehicle = make_vehicle(friction);
  run.result = global_search(setup.patch, run.vehicle, setup.start, setup.goal, options);
  const GlobalSearchResult& r = run.result;
  if (r.status != GlobalSearchStatus::kOk || r.candidates.empty()) {
    // The start and goal are fixed; an unreachable goal here means the search
    // or the limits changed, which the figures could not show meaningfully.
    throw InfeasibleError("global-search: μ = " + fmt("%g", friction) + ": " + r.message);
  }
  const LatticeCensus census = lattice_census(setup.patch, r, friction);
  run.steep_nodes = census.steep_nodes;
  run.unreachable = census.unreachable_nodes;
  for (const CandidatePath& c : r.candidates) {
    run.info.push_back({measure_candidate(setup.patch, run.vehicle, c, r.spacing),
                        landmark_passage(c.vertices, setup.start, setup.goal, setup.summit),
                        {}});
  }
  // How distinct the candidates really are: the search's Hausdorff rule is
  // met by one far-off vertex, so also count how much of each route runs in
  // the best one's corridor.
  const std::vector<Vec2>& best = r.candidates.front().vertices;
  const double separation = default_separation(r);
  for (std::size_t c = 1; c < r.candidates.size(); ++c) {
    run.info[c].vs_best =
        corridor_overlap(r.candidates[c].vertices, best, kSharedFraction * separation);
  }
  return run;
}

/// The same search on the interpolating fit: best cost and reachability only.
struct ControlRun {
  double friction = 0.0;
  bool ok = false;
  double cost = kNaN, length = kNaN;
  std::size_t unreachable = 0, steep_nodes = 0, nodes = 0;
};

ControlRun run_control(const Setup& setup, double friction, GlobalSearchOptions options) {
  ControlRun control;
  control.friction = friction;
  options.candidates = 1;  // the fields are still computed: cost_fields stays true
  const GlobalSearchResult r =
      global_search(setup.interpolating, make_vehicle(friction), setup.start, setup.goal, options);
  control.ok = r.status == GlobalSearchStatus::kOk && !r.candidates.empty();
  if (control.ok) {
    control.cost = r.candidates.front().cost_seconds;
    control.length = r.candidates.front().length_m;
  }
  control.nodes = r.nodes;
  const LatticeCensus census = lattice_census(setup.interpolating, r, friction);
  control.steep_nodes = census.steep_nodes;
  control.unreachable = census.unreachable_nodes;
  return control;
}

// ---------------------------------------------------------------------------
// Data files.

/// Shaded relief raster (washed towards white so that routes and overlays
/// read on top of it) and the elevation raster gnuplot traces contours on.
/// Shared by every map; returns the contour levels.
ContourLevels write_relief(const Setup& setup, std::size_t max_samples, const fs::path& out_dir) {
  const ReliefImage image = write_relief_image(
      setup.patch, setup.frame(), std::string(kDemStem) + " crop, smoothing B-patch",
      out_dir / "relief.rgb", max_samples, std::pair{setup.zmin, setup.zmax});
  std::ostringstream elevation_header;
  elevation_header << "# " << kDemStem << " crop: smoothing B-patch (lambda " << kSmoothingLambda
                   << ") on a " << image.raster.size.nx << " x " << image.raster.size.ny
                   << " raster\n# x - x_min [m], y - y_min [m], z [m]\n";
  write_elevation_raster(image.raster, elevation_header.str(), out_dir / "elevation.dat");
  return ContourLevels::within(setup.zmin, setup.zmax,
                               contour_interval(setup.zmax - setup.zmin, kContourTargetLevels));
}

/// Lattice nodes of `r` as offsets from the crop's south-west node.
Vec2 node_offset(const Setup& setup, const GlobalSearchResult& r, std::size_t n) {
  return r.origin - setup.origin() +
         r.spacing * Vec2(static_cast<double>(n % r.nx), static_cast<double>(n / r.nx));
}

/// Translucent overlay of the lattice nodes unreachable from the start:
/// x y r g b alpha, alpha 0 where reachable. `other` (optional) adds a second,
/// lighter shade for nodes unreachable only in `r` but reachable in `other`.
void write_unreachable(const Setup& setup, const GlobalSearchResult& r,
                       const GlobalSearchResult* other, const fs::path& file) {
  std::ofstream out = open_output_file(file);
  out << "# lattice nodes unreachable from the start (alpha > 0)\n"
      << "# x - x_min [m], y - y_min [m], red, green, blue, alpha [0-255]\n";
  for (std::size_t j = 0; j < r.ny; ++j) {
    for (std::size_t i = 0; i < r.nx; ++i) {
      const std::size_t n = j * r.nx + i;
      const Vec2 p = node_offset(setup, r, n);
      const bool here = !(r.cost_from_start[n] < kInf);
      const bool there = other != nullptr && !(other->cost_from_start[n] < kInf);
      int alpha = 0;
      if (here) alpha = (other == nullptr || there) ? 150 : 70;
      out << fmt("%.7g", p.x()) << ' ' << fmt("%.7g", p.y()) << " 25 25 25 " << alpha << '\n';
    }
    out << '\n';
  }
  close_output_file(out, file);
}

/// One block per candidate (separated by two blank lines, for gnuplot's
/// `index`): x - x_min, y - y_min, s, z, slope, and the speed of the edge
/// that ends at the vertex.
void write_route_blocks(const Setup& setup, const FrictionRun& run, const fs::path& file) {
  std::ofstream out = open_output_file(file);
  out << "# μ = " << run.friction << ": one block per candidate, best first\n"
      << "# x - x_min [m], y - y_min [m], s [m], z [m], terrain slope [deg], "
         "length/J of the edge ending here [m/s]\n";
  for (std::size_t c = 0; c < run.result.candidates.size(); ++c) {
    const CandidatePath& path = run.result.candidates[c];
    const CandidateInfo& info = run.info[c];
    out << "# candidate " << c + 1 << "\n";
    for (std::size_t k = 0; k < path.vertices.size(); ++k) {
      const Vec2 p = path.vertices[k] - setup.origin();
      out << fmt("%.7g", p.x()) << ' ' << fmt("%.7g", p.y()) << ' '
          << fmt("%.7g", info.metrics.s[k]) << ' ' << fmt("%.7g", info.metrics.z[k]) << ' '
          << fmt("%.4g", info.metrics.slope[k]) << ' '
          << (k == 0 ? "NaN" : fmt("%.5g", info.metrics.edge_speed[k - 1])) << '\n';
    }
    out << "\n\n";
  }
  close_output_file(out, file);
}

void write_candidates_csv(const Setup& setup, const FrictionRun& run, const fs::path& file) {
  std::ostringstream csv;
  csv << "candidate,x,y,z\n";
  for (std::size_t c = 0; c < run.result.candidates.size(); ++c)
    for (const Vec2& p : run.result.candidates[c].vertices)
      csv << c + 1 << ',' << fmt("%.3f", p.x()) << ',' << fmt("%.3f", p.y()) << ','
          << fmt("%.3f", setup.patch.elevation(p)) << '\n';
  write_text_file(file, csv.str());
}

/// The two cost-to-go fields on the lattice: x, y, T_start [s], and the
/// excess T_start + T_goal − J* [s] of the best route through each node.
void write_fields(const Setup& setup, const FrictionRun& run, const fs::path& file) {
  const GlobalSearchResult& r = run.result;
  const double best = r.candidates.front().cost_seconds;
  std::ofstream out = open_output_file(file);
  out << "# μ = " << run.friction << ": lattice cost-to-go fields (NaN = unreachable)\n"
      << "# x - x_min [m], y - y_min [m], T_start [s], T_start + T_goal - J* [s] (J* = "
      << fmt("%.6g", best) << " s)\n";
  for (std::size_t j = 0; j < r.ny; ++j) {
    for (std::size_t i = 0; i < r.nx; ++i) {
      const std::size_t n = j * r.nx + i;
      const Vec2 p = node_offset(setup, r, n);
      const double through = r.cost_from_start[n] + r.cost_to_goal[n];
      out << fmt("%.7g", p.x()) << ' ' << fmt("%.7g", p.y()) << ' ' << num(r.cost_from_start[n])
          << ' ' << num(through - best) << '\n';
    }
    out << '\n';
  }
  close_output_file(out, file);
}

// ---------------------------------------------------------------------------
// Figures.

/// Start and goal labels, boxed in white: they must read over dark field
/// colours too.
std::string endpoint_labels(const Setup& setup) {
  const MapFrame frame = setup.frame();
  return "set style textbox opaque noborder fillcolor rgb 'white' margins 1,1\n"
         "set label 101 'start' at " +
         frame.at(setup.start) +
         " offset char -1.5,1.3 front boxed font ',12' tc rgb 'black'\n"
         "set label 102 'goal' at " +
         frame.at(setup.goal) + " offset char 0.9,0.9 front boxed font ',12' tc rgb 'black'\n";
}

void write_endpoints(const Setup& setup, const fs::path& out_dir) {
  write_text_file(out_dir / "endpoints.dat", "# start, then goal: x - x_min [m], y - y_min [m]\n" +
                                                 offset_row(setup.start, setup.origin()) + "\n" +
                                                 offset_row(setup.goal, setup.origin()) + "\n");
}

std::string candidate_title(std::size_t c, const CandidatePath& path) {
  return "candidate " + std::to_string(c + 1) + ": J = " + fmt("%.1f", path.cost_seconds) + " s, " +
         fmt("%.2f", path.length_m * 1e-3) + " km, mean " +
         fmt("%.1f", path.length_m / path.cost_seconds) + " m/s";
}

std::string vehicle_text(const Vehicle& v) {
  return "point mass, μ = " + fmt("%g", v.friction) + ", h = " + fmt("%g", v.cg_height) +
         " m, b = " + fmt("%g", v.half_track) + " m, v_{max} ≤ " + fmt("%g", v.max_speed) + " m/s";
}

const char* candidate_colour(std::size_t c) {
  return kCandidateColours[c % std::size(kCandidateColours)];
}

/// Plot items of the candidates of `routes_file` in a white casing, drawn
/// worst first so the best lies on top where routes share a corridor.
void add_routes(PlotItems& items, const MapFrame& frame, const std::string& routes_file,
                std::size_t count, const std::string& width, const std::string& casing) {
  for (std::size_t c = count; c-- > 0;) {
    const std::string block = "'" + routes_file + "' index " + std::to_string(c) + " using " +
                              frame.xy() + " with lines lw ";
    items.push_back(block + casing + " lc rgb 'white' notitle");
    items.push_back(block + width + " lc rgb '" + candidate_colour(c) + "' notitle");
  }
}

/// Figure 1: the candidates of one friction over shaded relief.
void draw_routes(const Setup& setup, const FrictionRun& run, const ContourLevels& contours,
                 const fs::path& out_dir) {
  const std::string tag = friction_tag(run.friction);
  write_unreachable(setup, run.result, nullptr, out_dir / ("unreachable_" + tag + ".rgba"));
  const GlobalSearchResult& r = run.result;
  const MapFrame frame = setup.frame();
  std::ostringstream title;
  title << "Global search on Mount St. Helens (30 m DEM): " << r.candidates.size()
        << " distinct candidates, " << vehicle_text(run.vehicle) << "\n"
        << kConnectivity << "-connected lattice, spacing " << fmt("%g", r.spacing)
        << " m; shaded: unreachable from the start; contours every " << fmt("%g", contours.step)
        << " m";
  PlotItems items{
      "'relief.rgb' using " + frame.xy() + ":3:4:5 with rgbimage notitle",
      "'unreachable_" + tag + ".rgba' using " + frame.xy() + ":3:4:5:6 with rgbalpha notitle",
      "keyentry with boxes fs solid 0.6 noborder fc rgb '#191919' "
      "title 'unreachable from the start'",
      frame.contour_item("contours.dat", "lc rgb '#606060' lw 0.5 notitle")};
  // Legend best first.
  for (std::size_t c = 0; c < r.candidates.size(); ++c) {
    items.push_back("keyentry with lines lw 3 lc rgb '" + std::string(candidate_colour(c)) +
                    "' title " + gnuplot_string(candidate_title(c, r.candidates[c])));
  }
  add_routes(items, frame, "routes_" + tag + ".dat", r.candidates.size(), "3", "5.5");
  items.push_back(frame.endpoint_items("endpoints.dat", 0));
  GnuplotFigure figure(out_dir, "routes_" + tag);
  figure.describe("Candidate routes at μ = " + fmt("%g", run.friction) +
                      ", from `talus experiment global-search`.",
                  "relief.rgb, elevation.dat, unreachable_" + tag + ".rgba, routes_" + tag +
                      ".dat (one block per candidate), endpoints.dat.")
          .canvas(1100, frame.canvas_height(1100, 60))
      << trace_contours("elevation.dat", 3, contours, "contours.dat") << frame.axes();
  figure.title(title.str(), ",10", true)
      << endpoint_labels(setup) << "set key outside bottom center vertical maxrows 3 samplen 2\n";
  figure.plot(items).render();
}

/// Figure 2: the cost-to-go field from the start and the excess of the best
/// route through each node over the optimum, side by side.
void draw_fields(const Setup& setup, const FrictionRun& run, const fs::path& out_dir) {
  const std::string tag = friction_tag(run.friction);
  write_fields(setup, run, out_dir / ("fields_" + tag + ".dat"));
  const GlobalSearchResult& r = run.result;
  const MapFrame frame = setup.frame();
  const double best = r.candidates.front().cost_seconds;
  double t_max = 0.0;
  for (const double t : r.cost_from_start)
    if (t < kInf) t_max = std::max(t_max, t);
  const double t_step = contour_interval(t_max, 10);
  // The excess panel saturates at 20 % of J*: the candidates may cost up to
  // max_cost_ratio = 2 times J*, but the valleys they follow lie within a
  // few per cent of it and would all look alike on a [0, J*] scale.
  const double excess_max = kExcessShare * best;
  const double excess_step = contour_interval(excess_max, 6);
  const std::string fields = "fields_" + tag + ".dat";
  const std::string relief = "'relief.rgb' using " + frame.xy() + ":3:4:5 with rgbimage notitle";
  const std::string best_route = "'routes_" + tag + ".dat' index 0 using " + frame.xy();

  std::ostringstream title;
  title << "Cost-to-go fields on Mount St. Helens, " << vehicle_text(run.vehicle) << ", "
        << kConnectivity << "-connected lattice, spacing " << fmt("%g", r.spacing)
        << " m; bare relief: unreachable from the start";
  GnuplotFigure figure(out_dir, "fields_" + tag);
  figure.describe(
            "Cost-to-go fields at μ = " + fmt("%g", run.friction) +
                ", from `talus experiment global-search`.",
            fields + " (x y T_start excess), relief.rgb, routes_" + tag + ".dat, endpoints.dat.")
          .canvas(1800, frame.canvas_height(920))
      << trace_contours(fields, 3, {0.0, t_step, t_max}, "fields_" + tag + "_isochrones.dat")
      << trace_contours(fields, 4, {excess_step, excess_step, excess_max},
                        "fields_" + tag + "_excess.dat")
      << "set multiplot layout 1,2 title " << gnuplot_string(title.str()) << " font ',12'\n"
      << frame.axes() << endpoint_labels(setup)
      << "set key outside bottom center vertical maxrows 2 samplen 2\n"
      << "set cblabel 'T_{start} [s]'\n"
      << "# Viridis-like: dark = reached early. Unreachable nodes are NaN, drawn\n"
      << "# transparent, so the bare relief marks them.\n"
      << "set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21918c', 0.75 '#5ec962', 1 "
         "'#fde725')\n"
      << "set cbrange [0:" << fmt("%.10g", t_max) << "]\n";
  figure.title(
      "(a) minimum time from the start, T_{start}; isochrones every " + fmt("%g", t_step) + " s",
      "", true);
  figure.plot(
      {relief, "'" + fields + "' using " + frame.xy() + ":3 with image notitle",
       frame.contour_item("fields_" + tag + "_isochrones.dat", "lc rgb 'white' lw 0.7 notitle"),
       best_route + " with lines lw 5.5 lc rgb 'white' notitle",
       best_route + " with lines lw 3 lc rgb '#e41a1c' title 'best route'",
       frame.endpoint_items("endpoints.dat", 0)});
  figure << "set cblabel 'T_{start} + T_{goal} − J* [s]'\n"
         << "# Magma-like, reversed: dark valleys = nodes on near-optimal routes.\n"
         << "set palette defined (0 '#000004', 0.25 '#51127c', 0.5 '#b73779', 0.75 '#fc8961', 1 "
            "'#fcfdbf')\n"
         << "set cbrange [0:" << fmt("%.10g", excess_max) << "]\n";
  figure.title("(b) excess time of the best route through each node over J* = " +
                   fmt("%.1f", best) + " s; lines every " + fmt("%g", excess_step) +
                   " s, colours saturate at " + fmt("%.0f", excess_max) + " s",
               "", true);
  const std::string cap = fmt("%.10g", excess_max);
  PlotItems items{
      relief,
      "'" + fields + "' using " + frame.xy() + ":($4 < " + cap + " ? $4 : " + cap +
          ") with image notitle",
      frame.contour_item("fields_" + tag + "_excess.dat", "lc rgb 'white' lw 0.7 notitle")};
  for (std::size_t c = 0; c < r.candidates.size(); ++c) {
    items.push_back("keyentry with lines lw 2.5 lc rgb '" + std::string(candidate_colour(c)) +
                    "' title 'candidate " + std::to_string(c + 1) + "'");
  }
  add_routes(items, frame, "routes_" + tag + ".dat", r.candidates.size(), "2.5", "5");
  items.push_back(frame.endpoint_items("endpoints.dat", 0));
  figure.plot(items) << "unset multiplot\n";
  figure.render();
}

/// Figure 3: the best route at each friction on one map, with their
/// elevation and terrain slope against distance.
void draw_comparison(const Setup& setup, const std::vector<FrictionRun>& runs,
                     const ContourLevels& contours, const fs::path& out_dir) {
  // Shade where the lowest friction cannot reach: light where only it
  // fails, dark where every friction fails.
  const FrictionRun& high = runs.front();
  const FrictionRun& low = runs.back();
  write_unreachable(setup, low.result, &high.result, out_dir / "unreachable_compare.rgba");
  const MapFrame frame = setup.frame();
  GnuplotFigure figure(out_dir, "compare");
  figure.describe("Best route at each friction, from `talus experiment global-search`.",
                  "relief.rgb, elevation.dat, unreachable_compare.rgba, routes_mu*.dat, "
                  "endpoints.dat.")
          .canvas(1900, frame.canvas_height(1060, 40))
      << trace_contours("elevation.dat", 3, contours, "contours.dat") << "set multiplot title "
      << gnuplot_string("Best route at μ = " + fmt("%g", high.friction) +
                        " and μ = " + fmt("%g", low.friction) +
                        ", Mount St. Helens (30 m DEM), point mass h = b = 0.8 m, v ≤ 20 m/s")
      << " font ',13'\n"
      << "# Left: the map (52 % of the width).\n"
      << "set origin 0,0\nset size 0.52,0.96\n"
      << frame.axes() << endpoint_labels(setup)
      << "set key outside bottom center vertical maxrows 3 samplen 2\n";
  figure.title("routes; shaded: unreachable at μ = " + fmt("%g", low.friction) +
                   " (light: reachable at μ = " + fmt("%g", high.friction) + ", dark: at neither)",
               "", true);
  PlotItems items{
      "'relief.rgb' using " + frame.xy() + ":3:4:5 with rgbimage notitle",
      "'unreachable_compare.rgba' using " + frame.xy() + ":3:4:5:6 with rgbalpha notitle",
      frame.contour_item("contours.dat", "lc rgb '#606060' lw 0.5 notitle")};
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const FrictionRun& run = runs[k];
    const CandidatePath& best = run.result.candidates.front();
    const std::string block =
        "'routes_" + friction_tag(run.friction) + ".dat' index 0 using " + frame.xy();
    items.push_back(block + " with lines lw 6 lc rgb 'white' notitle");
    items.push_back(block + " with lines lw 3.5 lc rgb '" +
                    kFrictionColours[k % std::size(kFrictionColours)] + "' title " +
                    gnuplot_string("μ = " + fmt("%g", run.friction) +
                                   ": J = " + fmt("%.1f", best.cost_seconds) + " s, " +
                                   fmt("%.2f", best.length_m * 1e-3) + " km"));
  }
  items.push_back(frame.endpoint_items("endpoints.dat", 0));
  figure.plot(items);
  // Slowest edge of either best route: when it is the top speed, J is just
  // length / v_max and panel (b) says so instead of plotting a flat line.
  double slowest = kInf;
  for (const FrictionRun& run : runs)
    slowest = std::min(slowest, run.info.front().metrics.min_edge_speed);
  const double top = high.vehicle.max_speed;
  figure << "unset label\nset size noratio\nset autoscale\n"
         << "set xlabel 'distance along the route s [km]'\nset grid lc rgb '#d0d0d0'\n"
         << "set key inside top right opaque samplen 2\n";
  // Right column: two stacked panels.
  const std::string slope_title =
      slowest >= top * (1.0 - 1e-9)
          ? "(b) terrain slope at the vertices; dashed: atan μ\nevery edge of both routes is "
            "driven at the top speed " +
                fmt("%g", top) + " m/s, so J = length / " + fmt("%g", top) + " m/s"
          : "(b) terrain slope at the vertices; dashed: atan μ\nslowest edge of either route "
            "(length / J): " +
                fmt("%.1f", slowest) + " m/s";
  const std::string panels[][3] = {
      {"elevation z [m]", "4", "(a) elevation along the best route"},
      {"terrain slope [°]", "5", slope_title},
  };
  for (int p = 0; p < 2; ++p) {
    figure << "set origin 0.55," << fmt("%.4g", 0.49 - 0.46 * p) << "\nset size 0.44,0.46\n"
           << "set ylabel '" << panels[p][0] << "'\n";
    figure.title(panels[p][2], "", true)
        << (p == 1 ? "set yrange [0:" +
                         fmt("%.0f",
                             10.0 * std::ceil(degrees(std::atan(high.friction)) / 10.0) + 10.0) +
                         "]\nset key horizontal maxrows 2\n"
                   : std::string("set yrange [*:*]\n"));
    PlotItems profile;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const FrictionRun& run = runs[k];
      const std::string colour = kFrictionColours[k % std::size(kFrictionColours)];
      profile.push_back("'routes_" + friction_tag(run.friction) + ".dat' index 0 using ($3/1000):" +
                        panels[p][1] + " with lines lw 2 lc rgb '" + colour +
                        "' title 'μ = " + fmt("%g", run.friction) + "'");
      if (p == 1) {
        const double steep = degrees(std::atan(run.friction));
        profile.push_back(fmt("%.6g", steep) + " with lines dt (6,4) lw 1.5 lc rgb '" + colour +
                          "' title 'atan " + fmt("%g", run.friction) + " = " + fmt("%.1f", steep) +
                          "°'");
      }
    }
    figure.plot(profile);
  }
  figure << "unset multiplot\n";
  figure.render();
}

// ---------------------------------------------------------------------------
// Summary and report.

void write_summary(const std::vector<FrictionRun>& runs, const fs::path& file) {
  std::ostringstream csv;
  csv << "friction,candidate,cost_seconds,length_m,mean_speed_mps,nodes,edges_evaluated,"
         "search_seconds,max_slope_deg,max_z_m,climb_m\n";
  for (const FrictionRun& run : runs) {
    const GlobalSearchResult& r = run.result;
    for (std::size_t c = 0; c < r.candidates.size(); ++c) {
      const CandidatePath& p = r.candidates[c];
      const CandidateInfo& info = run.info[c];
      csv << fmt("%g", run.friction) << ',' << c + 1 << ',' << fmt("%.6f", p.cost_seconds) << ','
          << fmt("%.3f", p.length_m) << ',' << fmt("%.4f", p.length_m / p.cost_seconds) << ','
          << r.nodes << ',' << r.edges_evaluated << ',' << fmt("%.4f", r.search_seconds) << ','
          << fmt("%.2f", info.metrics.max_slope) << ',' << fmt("%.1f", info.metrics.max_z) << ','
          << fmt("%.1f", info.metrics.climb) << '\n';
    }
  }
  write_text_file(file, csv.str());
}

std::string percent(std::size_t part, std::size_t whole) {
  return fmt("%.1f", 100.0 * static_cast<double>(part) / static_cast<double>(whole)) + " %";
}

/// The 3–5 sentences on how the route changes with friction, built from the
/// measured numbers so that they stay true if the settings change.
std::string commentary(const Setup& setup, const std::vector<FrictionRun>& runs) {
  const FrictionRun& high = runs.front();
  const FrictionRun& low = runs.back();
  const CandidatePath& bh = high.result.candidates.front();
  const CandidatePath& bl = low.result.candidates.front();
  const CandidateInfo& ih = high.info.front();
  const CandidateInfo& il = low.info.front();
  const std::size_t nodes = high.result.nodes;
  const double top = high.vehicle.max_speed;
  std::ostringstream text;
  text << "Halving the friction from μ = " << fmt("%g", high.friction) << " to "
       << fmt("%g", low.friction) << " makes the best route "
       << fmt("%.0f", 100.0 * (bl.cost_seconds / bh.cost_seconds - 1.0))
       << " % slower (J = " << fmt("%.1f", bh.cost_seconds) << " s → "
       << fmt("%.1f", bl.cost_seconds) << " s) and "
       << fmt("%.0f", 100.0 * (bl.length_m / bh.length_m - 1.0)) << " % longer ("
       << fmt("%.2f", bh.length_m * 1e-3) << " → " << fmt("%.2f", bl.length_m * 1e-3)
       << " km): at μ = " << fmt("%g", high.friction) << " it crosses the cone "
       << fmt("%.1f", ih.passage.distance * 1e-3) << " km " << ih.passage.side << " of the "
       << fmt("%.0f", setup.summit_z) << " m summit and climbs to " << fmt("%.0f", ih.metrics.max_z)
       << " m, at μ = " << fmt("%g", low.friction) << " it swings round the mountain "
       << fmt("%.1f", il.passage.distance * 1e-3) << " km " << il.passage.side
       << " of the summit and never rises above " << fmt("%.0f", il.metrics.max_z) << " m. ";
  text << "The reason is the friction cone: on ground that is planar at the scale of an edge "
          "the three rules of the search coincide, and a slope θ is passable (in any direction, "
          "then at any speed) exactly when tan θ ≤ μ — heading across the slope, the sliding "
          "condition |k_q| ≤ μ k_r fails and v_max = 0 (rule a); heading along the fall line, "
          "the friction force μ g k_r can neither hold g sin θ uphill (rule b) nor brake it "
          "downhill (rule c); lateral tip-over (b/h = "
       << fmt("%g", high.vehicle.half_track / high.vehicle.cg_height)
       << ", 45°) never binds first because μ < b/h. ";
  text << "The threshold drops from atan " << fmt("%g", high.friction) << " = "
       << fmt("%.1f", degrees(std::atan(high.friction))) << "° to atan " << fmt("%g", low.friction)
       << " = " << fmt("%.1f", degrees(std::atan(low.friction)))
       << "°, so the share of lattice nodes steeper than it grows from "
       << percent(high.steep_nodes, nodes) << " (mostly the crater walls and gully sides) to "
       << percent(low.steep_nodes, nodes) << " (most of the cone above its apron), and with "
       << "the pockets cut off behind them " << percent(high.unreachable, nodes) << " and "
       << percent(low.unreachable, nodes) << " of the nodes are unreachable from the start. ";
  double slowest = kInf;
  for (const FrictionRun& run : runs)
    slowest = std::min(slowest, run.info.front().metrics.min_edge_speed);
  if (slowest >= top * (1.0 - 1e-9)) {
    text << "Speed itself does not change: every edge of both best routes is driven at the "
         << fmt("%g", top) << " m/s top speed (the 30 m DEM's curvatures are far too gentle for "
         << "sliding or tip-over to bind below it: contact on a crest, for one, is lost at "
         << fmt("%g", top) << " m/s only if its radius is under v²/g ≈ "
         << fmt("%.0f", top * top / high.vehicle.gravity) << " m), so J = length / "
         << fmt("%g", top) << " m/s and friction acts purely by removing terrain. ";
  } else {
    text << "The slowest edge of either best route is driven at " << fmt("%.1f", slowest)
         << " m/s against the " << fmt("%g", top) << " m/s top speed. ";
  }
  text << "The steepest terrain under the best routes, sampled at the search's own edge "
          "stations, is "
       << fmt("%.1f", ih.metrics.max_slope) << "° at μ = " << fmt("%g", high.friction) << " and "
       << fmt("%.1f", il.metrics.max_slope) << "° at μ = " << fmt("%g", low.friction);
  if (ih.metrics.speed_only_stations + il.metrics.speed_only_stations > 0) {
    text << " (" << ih.metrics.speed_only_stations << " and " << il.metrics.speed_only_stations
         << " stations steeper than atan μ, where the extra normal load κ_n v² of a concave "
            "stretch at speed lets the vehicle climb or brake although it could not stand "
            "there at rest; see the observations below).";
  } else {
    text << ", within the thresholds.";
  }
  return text.str();
}

void write_report(const Setup& setup, const std::vector<FrictionRun>& runs,
                  const std::vector<ControlRun>& controls, const ExperimentContext& context,
                  double total_seconds, double contour_step) {
  const GlobalSearchResult& r0 = runs.front().result;
  const double distance = (setup.goal - setup.start).norm();
  const double separation = default_separation(r0);
  const Vec2 o = setup.origin();
  const auto km = [&](const Vec2& p) {
    return fmt("%.3f", (p.x() - o.x()) * 1e-3) + ", " + fmt("%.3f", (p.y() - o.y()) * 1e-3);
  };
  Report report("Global search: distinct minimum-time corridors across Mount St. Helens");
  report.paragraph(
      "The global stage of the planner (`talus::global_search`) on a real DEM at its true scale, "
      "for a car-like vehicle at two tyre frictions — the analogue of the global-optimal-path "
      "figure of Iagnemma, Shimoda and Shiller (IROS 2008).");
  report.heading("What was run")
      .bullet("Terrain: `data/terrain/" + std::string(kDemStem) +
              ".asc` (USGS 30 m DEM of Mount St. Helens after the 1980 eruption, NAD27 / UTM 10N; "
              "provenance in `data/terrain/README.md`), cropped to " +
              std::to_string(kCrop.ncols) + " × " + std::to_string(kCrop.nrows) +
              " nodes (DEM columns " + std::to_string(kCrop.col) + "–" +
              std::to_string(kCrop.col + kCrop.ncols - 1) + " from the west, rows " +
              std::to_string(kCrop.row) + "–" + std::to_string(kCrop.row + kCrop.nrows - 1) +
              " from the south): " + fmt("%.2f", setup.width() * 1e-3) + " × " +
              fmt("%.2f", setup.height() * 1e-3) + " km, elevation " + fmt("%.0f", setup.zmin) +
              "–" + fmt("%.0f", setup.zmax) + " m, summit " + fmt("%.0f", setup.summit_z) +
              " m at (" + fmt("%.2f", (setup.summit.x() - o.x()) * 1e-3) + ", " +
              fmt("%.2f", (setup.summit.y() - o.y()) * 1e-3) +
              ") km on the crater's south rim. True scale: slopes and curvatures are those of the "
              "mountain.")
      .bullet(
          "Surface: `BPatch::fit_smoothing` with λ = " + fmt("%g", kSmoothingLambda) +
          " (about one cell of smoothing), fitted in " + sig3(setup.fit_seconds) +
          " s. Why not the interpolating fit: this early DEM carries an east–west striping "
          "artefact (going north along a column on the flanks, one-cell steps of 15–25 m "
          "alternate with flat or reversed cells; over the crop the mean |second difference| of "
          "the nodes is " +
          fmt("%.1f", setup.roughness_y) + " m along y against " + fmt("%.1f", setup.roughness_x) +
          " m along x). The interpolating fit reproduces every step, and each step steeper than "
          "atan μ becomes a one-row untraversable bar across a passable flank. The control run "
          "below shows the effect.")
      .bullet(
          "Vehicle: point mass, μ = 0.7 and μ = 0.35, centre-of-mass height h = 0.8 m, half track "
          "b = 0.8 m, max speed 20 m/s, g = 9.81 m/s², no drive or brake limit (friction alone "
          "bounds the tangential force).")
      .bullet(
          "Start (" + km(setup.start) + ") km and goal (" + km(setup.goal) +
          ") km from the crop's south-west node (DEM nodes (" + fmt("%g", kStart.i) + ", " +
          fmt("%g", kStart.j) + ") and (" + fmt("%g", kGoal.i) + ", " + fmt("%g", kGoal.j) +
          ")): gentle ground west and east of the cone, " + fmt("%.2f", distance * 1e-3) +
          " km apart, the straight line between them crossing the crater. They were chosen in the "
          "one region of the crop that stays connected at μ = 0.35 (the lowland apron south of "
          "the cone, which reaches up its west and east sides), so both runs succeed.")
      .bullet(
          "Search: `global_search` with candidates = " + std::to_string(kCandidates) +
          ", connectivity " + std::to_string(kConnectivity) + ", lattice spacing " +
          fmt("%g", r0.spacing) + " m" +
          (context.quick ? " (quick mode: 3 cells)" : " (= the cell size)") + ", " +
          std::to_string(r0.nx) + " × " + std::to_string(r0.ny) +
          " nodes, cost_fields = true, max_cost_ratio 2 (default). Cost J = ∫ ds / v_max along "
          "straight lattice edges lifted onto the surface (Simpson's rule, stations at most half "
          "a spacing apart); an edge is untraversable in a direction if at some station no speed "
          "satisfies the speed limits (a), or the vehicle can neither climb nor hold its speed at "
          "any admissible speed (b), or cannot brake at any admissible speed (c).")
      .bullet(
          "Distinctness (as documented in `global_search.hpp`): lattice nodes are taken in "
          "increasing order of T_start + T_goal, the cost of the best route through them, up to "
          "2 J*; a node's route (start tree + goal tree) is accepted if the node is at least the "
          "separation away from every accepted candidate and the route's symmetric Hausdorff "
          "distance to each of them is at least the separation — here the default max(10 % of "
          "the start–goal distance, 3 spacings) = " +
          fmt("%.0f", separation) + " m.")
      .bullet(
          "Relief: the smoothing patch on a raster, hypsometric tint × hillshade (sun azimuth "
          "315°, altitude 45°), washed towards white; contours every " +
          fmt("%g", contour_step) +
          " m traced by gnuplot. Every figure's gnuplot script and data sit beside it "
          "(`gnuplot <name>.gp` in this folder re-renders it).")
      .bullet("Total run time " + fmt("%.1f", total_seconds) +
              " s on this machine (searches, fits, data files and gnuplot).");
  report.heading("Candidates")
      .paragraph(
          "Numbers also in `summary.csv`; vertices in `candidates_mu<μ>.csv` (absolute UTM "
          "coordinates, z on the smoothing patch). Mean speed = length / J. Max slope: steepest "
          "terrain slope at the search's edge stations along the route. Passes summit: distance "
          "and compass direction from the summit of the point where the route crosses the line "
          "through the summit perpendicular to the start→goal axis. Hausdorff / shared: "
          "symmetric Hausdorff distance to candidate 1 (the quantity the distinctness rule tests) "
          "and the share of the route's vertices within " +
          fmt("%.0f", kSharedFraction * separation) +
          " m (a quarter of the separation) of candidate 1, i.e. in its corridor.");
  Table candidates({"μ", "candidate", "J [s]", "length [km]", "mean speed [m/s]", "max slope [°]",
                    "highest point [m]", "total climb [m]", "passes summit", "Hausdorff to 1 [m]",
                    "shared with 1"});
  Table lattice({"μ", "lattice nodes", "edges evaluated", "reachable from start",
                 "steeper than atan μ", "search [s]"});
  for (const FrictionRun& run : runs) {
    const GlobalSearchResult& r = run.result;
    for (std::size_t c = 0; c < r.candidates.size(); ++c) {
      const CandidatePath& p = r.candidates[c];
      const CandidateInfo& info = run.info[c];
      candidates.row({fmt("%g", run.friction), std::to_string(c + 1), fmt("%.1f", p.cost_seconds),
                      fmt("%.2f", p.length_m * 1e-3), fmt("%.2f", p.length_m / p.cost_seconds),
                      fmt("%.1f", info.metrics.max_slope), fmt("%.0f", info.metrics.max_z),
                      fmt("%.0f", info.metrics.climb),
                      fmt("%.1f", info.passage.distance * 1e-3) + " km " + info.passage.side,
                      c == 0 ? "–" : fmt("%.0f", info.vs_best.hausdorff),
                      c == 0 ? "–" : fmt("%.0f", 100.0 * info.vs_best.shared) + " %"});
    }
    lattice.row(
        {fmt("%g", run.friction), std::to_string(r.nodes), std::to_string(r.edges_evaluated),
         std::to_string(r.reachable_nodes) + " (" + percent(r.reachable_nodes, r.nodes) + ")",
         std::to_string(run.steep_nodes) + " (" + percent(run.steep_nodes, r.nodes) + ")",
         fmt("%.2f", r.search_seconds)});
  }
  Table control({"μ", "best J [s]", "length [km]", "steeper than atan μ", "unreachable",
                 "J vs smoothing fit"});
  for (std::size_t k = 0; k < controls.size(); ++k) {
    const ControlRun& c = controls[k];
    const CandidatePath& best = runs[k].result.candidates.front();
    control.row({fmt("%g", c.friction), c.ok ? fmt("%.1f", c.cost) : "unreachable",
                 c.ok ? fmt("%.2f", c.length * 1e-3) : "–", percent(c.steep_nodes, c.nodes),
                 percent(c.unreachable, c.nodes),
                 c.ok ? fmt("%+.0f", 100.0 * (c.cost / best.cost_seconds - 1.0)) + " %" : "–"});
  }
  report.table(candidates)
      .table(lattice)
      .paragraph(
          "Control run on the interpolating fit (same lattice, start and goal; best route only):")
      .table(control)
      .heading("What the figures show")
      .paragraph(commentary(setup, runs));

  // Observations on the search's behaviour, measured rather than asserted.
  report.heading("Observations on the search");
  for (const FrictionRun& run : runs) {
    const std::string mu = fmt("%g", run.friction);
    const GlobalSearchResult& r = run.result;
    double worst_check = 0.0;
    bool any_reversal = false;
    for (std::size_t c = 0; c < r.candidates.size(); ++c) {
      worst_check = std::max(worst_check, std::abs(run.info[c].metrics.recomputed_cost -
                                                   r.candidates[c].cost_seconds) /
                                              r.candidates[c].cost_seconds);
      any_reversal = any_reversal || run.info[c].metrics.revisits;
    }
    std::string text =
        "μ = " + mu + ": J recomputed edge by edge with the public `edge_cost` agrees with " +
        "`cost_seconds` to " + fmt("%.1e", worst_check) + " (relative); " +
        (any_reversal ? "**a candidate revisits a lattice node** (its route goes out and back)"
                      : "no candidate revisits a lattice node") +
        ".";
    for (std::size_t c = 1; c < r.candidates.size(); ++c) {
      const CandidateInfo& info = run.info[c];
      if (info.vs_best.shared >= 0.5) {
        text += " Candidate " + std::to_string(c + 1) + " passes the Hausdorff rule (" +
                fmt("%.0f", info.vs_best.hausdorff) + " m against " + fmt("%.0f", separation) +
                " m) but " + fmt("%.0f", 100.0 * info.vs_best.shared) +
                " % of its vertices lie within " + fmt("%.0f", kSharedFraction * separation) +
                " m of candidate 1: a variant of the same corridor with one bulge, not a "
                "different way round.";
      }
    }
    std::size_t steep = 0, speed_only = 0, concave = 0;
    for (const CandidateInfo& info : run.info) {
      steep += info.metrics.steep_stations;
      speed_only += info.metrics.speed_only_stations;
      concave += info.metrics.concave_speed_only;
    }
    if (steep > 0) {
      text += " Of the candidates' edge stations, " + std::to_string(steep) +
              " are steeper than atan " + mu + " = " +
              fmt("%.1f", degrees(std::atan(run.friction))) + "°; at " +
              std::to_string(speed_only) +
              " of them the vehicle could not stand still (at v = 0, a_max < 0 uphill or "
              "a_min > 0 downhill), and " +
              std::to_string(concave) +
              " of those lie on a concave stretch of the edge (κ_n > 0). The edges pass rules (b) "
              "and (c) because these ask for *some* admissible speed at which the vehicle can "
              "climb or brake, and at the top speed κ_n v² adds normal load. The search's cost "
              "assumes the top speed there, so the local stage must carry speed through these "
              "spots; a profile that has to slow down or start there will find them infeasible.";
    }
    report.bullet(text);
  }
  report.heading("Figures");
  for (const FrictionRun& run : runs) {
    const std::string mu = fmt("%g", run.friction), tag = friction_tag(run.friction);
    report.figures("μ = " + mu, {{"candidate routes at μ = " + mu, "routes_" + tag + ".png"},
                                 {"cost-to-go fields at μ = " + mu, "fields_" + tag + ".png"}});
  }
  report.figures("Friction comparison", {{"best route at each friction", "compare.png"}})
      .write(context.output_dir);
}

}  // namespace

/// The headline numbers of summary.json: each friction's best cost, against two bounds that
/// hold whatever the terrain: no route is faster than the straight line at the top speed, and
/// less friction never makes the best route faster.
void summarise(const Setup& setup, const std::vector<FrictionRun>& runs,
               ExperimentSummary& summary) {
  const double straight = (setup.goal - setup.start).norm();
  for (const FrictionRun& run : runs) {
    const std::string tag = friction_tag(run.friction);
    const double best = run.result.candidates.front().cost_seconds;
    summary.set("best_cost_" + tag + "_s", best, "s");
    summary.set("candidates_" + tag, static_cast<double>(run.result.candidates.size()), "count");
    summary.set("best_cost_over_straight_line_" + tag, best / (straight / run.vehicle.max_speed),
                "1", ">= 1: the straight line at the top speed is a lower bound");
  }
  summary.set("best_cost_low_over_high_friction",
              runs.back().result.candidates.front().cost_seconds /
                  runs.front().result.candidates.front().cost_seconds,
              "1", ">= 1: less friction only removes edges");
}

void run_global_search_experiment(const ExperimentContext& context) {
  const auto t_start = Clock::now();
  require_gnuplot();
  const fs::path out_dir = context.output_dir;

  const fs::path dem_file = scenarios::bundled_dem_file(context.data_dir, kDemStem);
  const ElevationGrid dem = read_esri_ascii(dem_file.string());
  ElevationGrid cropped = crop_grid(dem, kCrop);
  const auto fit_start = Clock::now();
  BPatch patch = BPatch::fit_smoothing(cropped, kSmoothingLambda);
  const double fit_seconds = std::chrono::duration<double>(Clock::now() - fit_start).count();
  BPatch control = BPatch::interpolate(cropped);
  Setup setup(std::move(cropped), std::move(patch), std::move(control));
  setup.fit_seconds = fit_seconds;
  const auto range = setup.dem_crop.elevation_range();
  if (!range) throw InputError("global-search: the crop of " + dem_file.string() + " is empty");
  setup.zmin = range->first;
  setup.zmax = range->second;
  const SecondDifferences roughness = second_differences(setup.dem_crop);
  setup.roughness_x = roughness.mean_abs_x;
  setup.roughness_y = roughness.mean_abs_y;
  setup.start = grid_position(dem, kStart);
  setup.goal = grid_position(dem, kGoal);
  const GridNode summit = *highest_node(setup.dem_crop);  // the range above has a valid node
  setup.summit_z = summit.z;
  setup.summit = summit.position;
  setup.spacing = dem.cellsize() * (context.quick ? kQuickLatticeCells : 1.0);

  GlobalSearchOptions options;
  options.lattice_spacing = setup.spacing;
  options.connectivity = kConnectivity;
  options.candidates = kCandidates;
  options.cost_fields = true;

  std::vector<FrictionRun> runs;
  for (const double mu : kFrictions) {
    runs.push_back(run_search(setup, mu, options));
    const FrictionRun& run = runs.back();
    std::cout << "global-search: μ = " << mu << ": " << run.result.candidates.size()
              << " candidates, best J = " << fmt("%.2f", run.result.candidates.front().cost_seconds)
              << " s, search " << fmt("%.2f", run.result.search_seconds) << " s ("
              << run.result.nodes << " nodes, " << run.result.edges_evaluated << " edges)\n";
  }

  std::vector<ControlRun> controls;
  for (const double mu : kFrictions) controls.push_back(run_control(setup, mu, options));

  const ContourLevels contours =
      write_relief(setup, context.quick ? kQuickRasterMaxSamples : kRasterMaxSamples, out_dir);
  write_endpoints(setup, out_dir);
  for (const FrictionRun& run : runs) {
    const std::string tag = friction_tag(run.friction);
    write_candidates_csv(setup, run, out_dir / ("candidates_" + tag + ".csv"));
    write_route_blocks(setup, run, out_dir / ("routes_" + tag + ".dat"));
    draw_routes(setup, run, contours, out_dir);
    draw_fields(setup, run, out_dir);
  }
  draw_comparison(setup, runs, contours, out_dir);
  write_summary(runs, out_dir / "summary.csv");
  summarise(setup, runs, *context.summary);
  const double total = std::chrono::duration<double>(Clock::now() - t_start).count();
  write_report(setup, runs, controls, context, total, contours.step);
  std::cout << "global-search: wrote " << out_dir.string() << " in " << fmt("%.1f", total)
            << " s\n";
}

}  // namespace talus::experiments
