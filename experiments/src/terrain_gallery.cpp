#include "terrain_gallery.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/fit_residuals.hpp"
#include "talus/bspline/relief.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/map_frame.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/relief_raster.hpp"
#include "talus/report/report.hpp"

namespace talus::experiments {
namespace {

namespace fs = std::filesystem;

// Fixed settings of the gallery, named so the report can quote them.
constexpr double kSmoothingLambda = 1.0;        // "smooths over about one cell" (bpatch.hpp)
constexpr std::size_t kRasterMaxSamples = 400;  // relief raster, longer side
constexpr int kContourTargetLevels = 12;
constexpr double kCurvatureFraction = 0.10;       // "most curved" nodes for the residual statistic
constexpr double kResidualColourQuantile = 0.99;  // residual colours saturate beyond it
constexpr std::size_t kFullFractalSize = 257;
constexpr std::size_t kQuickFractalSize = 65;
constexpr std::size_t kQuickDemCount = 2;
// Above this extent the axes switch from m to km: 7-digit metre tick labels
// (the Mars grids span 1.4 million metres) are hard to read.
constexpr double kKilometreAxesAbove = 100e3;

/// One terrain to draw.
struct TerrainInput {
  std::string name;    ///< file stem, or a generated name; prefixes every output file
  std::string origin;  ///< where it came from, for the report
  ElevationGrid grid;
};

/// What the gallery measured on one terrain: the summary.csv row plus the
/// extra numbers the report's table and commentary use.
struct TerrainResult {
  std::string name, origin;
  std::size_t ncols = 0, nrows = 0, voids = 0;
  double cellsize = 0.0, zmin = 0.0, zmax = 0.0;
  double interpolate_seconds = 0.0, smoothing_seconds = 0.0;
  double max_residual = 0.0, rms_residual = 0.0;
  double max_interpolation_residual = 0.0;  ///< max |interpolating fit - data| at the nodes [m]
  double exaggeration = 1.0, contour_step = 1.0;
  /// Share of the summed squared residual carried by the kCurvatureFraction
  /// of nodes with the largest thin-plate curvature of the interpolating fit.
  double curvature_share = 0.0;
  std::size_t raster_nx = 0, raster_ny = 0;
  bool filled_voids = false;
};

/// Short place and source of the bundled DEMs, condensed from
/// data/terrain/README.md (the full provenance table lives there).
std::string describe_dem(const std::string& stem) {
  struct Entry {
    const char* stem;
    const char* text;
  };
  static constexpr Entry kEntries[] = {
      {"bigtujunga_srtm30m", "Big Tujunga catchment, San Gabriel Mountains, California; SRTM 1″"},
      {"mount_st_helens_usgs30m", "Mount St. Helens after the 1980 eruption; USGS 30 m DEM"},
      {"rub_al_khali_dunes_srtm90m", "Rub' al Khali mega-dunes, Saudi Arabia; SRTM GL3"},
      {"west_bijou_escarpment_nasadem25m", "West Bijou Creek escarpment, Colorado; NASADEM"},
      {"mars_gale_mola_megdr15km", "Mars, Gale crater and the dichotomy boundary; MOLA MEGDR"},
      {"mars_valles_marineris_mola_megdr15km", "Mars, Valles Marineris; MOLA MEGDR"},
  };
  for (const Entry& entry : kEntries)
    if (stem == entry.stem) return entry.text;
  return "bundled DEM (see data/terrain/README.md)";
}

/// The bundled DEMs (all terrain/*.asc, by name) plus the fractal terrain.
/// In quick mode only the two DEMs with the fewest nodes are kept.
std::vector<TerrainInput> gather_inputs(const ExperimentContext& context) {
  const fs::path folder = context.data_dir / "terrain";
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    throw InputError("terrain-gallery: no terrain folder at " + folder.string());
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".asc")
      files.push_back(entry.path());
  }
  if (ec) throw InputError("terrain-gallery: cannot list " + folder.string() + ": " + ec.message());
  if (files.empty()) throw InputError("terrain-gallery: no *.asc files in " + folder.string());
  std::sort(files.begin(), files.end());

  std::vector<TerrainInput> inputs;
  for (const fs::path& file : files) {
    inputs.push_back({file.stem().string(), "data/terrain/" + file.filename().string(),
                      read_esri_ascii(file.string())});
  }
  if (context.quick && inputs.size() > kQuickDemCount) {
    // Stable sort keeps name order among equal sizes, so the choice is deterministic.
    std::stable_sort(inputs.begin(), inputs.end(), [](const auto& a, const auto& b) {
      return a.grid.ncols() * a.grid.nrows() < b.grid.ncols() * b.grid.nrows();
    });
    inputs.resize(kQuickDemCount);
    std::sort(inputs.begin(), inputs.end(),
              [](const auto& a, const auto& b) { return a.name < b.name; });
  }

  FractalTerrainOptions fractal;  // defaults: the Iagnemma–Shimoda–Shiller terrain
  const std::size_t n = context.quick ? kQuickFractalSize : kFullFractalSize;
  fractal.shape.ncols = n;
  fractal.shape.nrows = n;
  fractal.seed = 1;
  std::ostringstream origin;
  origin << "generate_fractal_terrain: default options (D = " << fractal.fractal_dimension
         << ", height scale " << fractal.height_scale << " m, cell " << fractal.shape.cellsize
         << " m), " << n << " × " << n << " nodes, seed " << fractal.seed;
  inputs.push_back({"fractal_seed1", origin.str(), generate_fractal_terrain(fractal)});
  return inputs;
}

/// The map frame of a grid: kilometre axes for continental-scale grids.
MapFrame map_frame(const ElevationGrid& grid) {
  const double extent = std::max(grid.x_max() - grid.x_min(), grid.y_max() - grid.y_min());
  return MapFrame::of(grid, extent > kKilometreAxesAbove ? MapUnit::kKilometre : MapUnit::kMetre);
}

/// "512 × 512 nodes, cell 30 m" style size text.
std::string size_text(const ElevationGrid& grid) {
  std::ostringstream text;
  text << grid.ncols() << " × " << grid.nrows() << " nodes, cell " << fmt("%g", grid.cellsize())
       << " m";
  return text.str();
}

std::string contours_title(const TerrainResult& result) {
  return gnuplot_string("contours every " + fmt("%g", result.contour_step) + " m");
}

/// Evaluates the interpolating patch on the relief raster, writes the
/// elevation and shaded-colour files, and writes and runs the relief script.
void draw_relief(const TerrainInput& input, const BPatch& patch, const SunPosition& sun,
                 const fs::path& out_dir, TerrainResult& result) {
  const ElevationGrid& grid = input.grid;
  const MapFrame frame = map_frame(grid);
  const std::string name = input.name;
  GnuplotFigure figure(out_dir, name + "_relief");
  const ReliefImage image =
      write_relief_image(patch, frame, name + ": interpolating B-patch", figure.file(".rgb"),
                         kRasterMaxSamples, std::pair{result.zmin, result.zmax}, false, sun);
  result.raster_nx = image.raster.size.nx;
  result.raster_ny = image.raster.size.ny;
  result.exaggeration = image.colouring.exaggeration;
  std::ostringstream elevation_header;
  elevation_header << "# " << name << ": interpolating B-patch on a " << image.raster.size.nx
                   << " x " << image.raster.size.ny
                   << " raster\n# x - x_min [m], y - y_min [m], z [m]; one block per raster row\n";
  write_elevation_raster(image.raster, elevation_header.str(), out_dir / (name + "_elevation.dat"));
  const double relief = result.zmax - result.zmin;
  result.contour_step = contour_interval(relief, kContourTargetLevels);

  std::ostringstream title;
  title << name << ": " << size_text(grid) << ", relief " << sig3(relief) << " m ("
        << sig3(result.zmin) << " to " << sig3(result.zmax) << " m)\n"
        << "interpolating B-patch, hillshade from azimuth " << fmt("%g", sun.azimuth_deg)
        << "°, altitude " << fmt("%g", sun.altitude_deg) << "°";
  if (result.exaggeration != 1.0) {
    title << ", vertical exaggeration × " << fmt("%g", result.exaggeration);
  }
  figure.describe(
            "Shaded relief with contours of " + name + ", from `talus experiment terrain-gallery`.",
            name + "_elevation.dat (x y z on the raster, for the contours) and " + name +
                "_relief.rgb (x y r g b: hypsometric tint x hillshade).")
          .canvas(1000, frame.canvas_height(1000))
      << trace_contours(name + "_elevation.dat", 3,
                        ContourLevels::within(result.zmin, result.zmax, result.contour_step),
                        name + "_contours.dat")
      << frame.axes();
  figure.title(title.str(), "")
      << "# The colour key shows the unshaded tint (same stops as the image).\n"
      << "set palette defined (";
  bool comma = false;
  for (const ColourStop& stop : hypsometric_stops()) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "%02x%02x%02x", to_byte(stop.colour.r), to_byte(stop.colour.g),
                  to_byte(stop.colour.b));
    figure << (comma ? ", " : "") << fmt("%g", stop.t) << " '#" << hex << "'";
    comma = true;
  }
  figure << ")\n"
         << "set cbrange [" << fmt("%.10g", result.zmin) << ":"
         << fmt("%.10g", relief > 0.0 ? result.zmax : result.zmin + 1.0) << "]\n"
         << "set cblabel 'elevation [m]'\nset colorbox\n"
         << "set key outside bottom center horizontal samplen 2\n";
  figure
      .plot({gnuplot_string(figure.name(".rgb")) + " using " + frame.xy() +
                 ":3:4:5 with rgbimage notitle",
             frame.contour_item(name + "_contours.dat",
                                "lc rgb '#303030' lw 0.6 title " + contours_title(result)),
             // Draws nothing; makes gnuplot show the colour key.
             "NaN with lines lc palette cb " + fmt("%.10g", result.zmin) + " notitle"})
      .render();
}

/// Residuals of the smoothing fit at the nodes and the curvature statistic
/// (fit_residuals), and the residual map (data file, script, PNG).
void draw_residuals(const TerrainInput& input, const BPatch& interpolating, const BPatch& smoothing,
                    const fs::path& out_dir, TerrainResult& result) {
  const ElevationGrid& grid = input.grid;
  const std::string name = input.name;
  const fs::path data_file = out_dir / (name + "_residual.dat");
  std::ofstream data = open_output_file(data_file);
  data << "# " << name << ": smoothing B-patch (lambda = " << kSmoothingLambda
       << ") minus data at the nodes\n# x - x_min [m], y - y_min [m], residual [m] (NaN at "
          "NODATA nodes)\n";

  FitResidualOptions options;
  options.curvature_fraction = kCurvatureFraction;
  options.abs_quantile = kResidualColourQuantile;
  const FitResiduals residuals = fit_residuals(grid, smoothing, interpolating, options);
  for (std::size_t j = 0; j < grid.nrows(); ++j) {
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const Vec2 p = grid.node_position(i, j);
      const std::string xy =
          fmt("%.7g", p.x() - grid.x_min()) + ' ' + fmt("%.7g", p.y() - grid.y_min()) + ' ';
      if (!grid.valid(i, j)) {
        data << xy << "NaN\n";
        continue;
      }
      data << xy << fmt("%.6g", residuals.residual[j * grid.ncols() + i]) << '\n';
    }
    data << '\n';
  }
  close_output_file(data, data_file);
  result.max_residual = residuals.max_abs;
  result.rms_residual = residuals.rms;
  result.curvature_share = residuals.curvature_share;

  // Colour scale: symmetric so white is exactly zero; clipped at the 99th
  // percentile of |r| so a handful of extreme nodes do not wash out the rest.
  double limit = residuals.abs_quantile;
  if (!(limit > 0.0)) limit = residuals.max_abs > 0.0 ? residuals.max_abs : 1.0;
  const bool clipped = limit < residuals.max_abs;

  const MapFrame frame = map_frame(grid);
  std::ostringstream title;
  title << name << ": smoothing fit (λ = " << fmt("%g", kSmoothingLambda)
        << ") minus data at the nodes, " << size_text(grid) << "\n"
        << "max |residual| " << sig3(result.max_residual) << " m, RMS " << sig3(result.rms_residual)
        << " m";
  if (clipped) title << "; colours saturate beyond ±" << sig3(limit) << " m (99th pct.)";

  GnuplotFigure figure(out_dir, name + "_residual");
  figure.describe("Residual map of " + name + ", from `talus experiment terrain-gallery`.",
                  name +
                      "_residual.dat (x y residual at every node); the grey lines are the "
                      "contours traced by " +
                      name + "_relief.gp (run that one first).")
          .canvas(1000, frame.canvas_height(1000))
      << frame.axes();
  figure.title(title.str(), "")
      << "# Diverging palette (ColorBrewer RdBu): blue = fit below the data, red = above.\n"
      << "set palette defined (-1 '#2166ac', -0.5 '#92c5de', 0 '#f7f7f7', 0.5 '#f4a582', "
         "1 '#b2182b')\n"
      << "set cbrange [" << fmt("%.6g", -limit) << ":" << fmt("%.6g", limit) << "]\n"
      << "set cblabel 'smoothing fit − data [m]'\n"
      << "set key outside bottom center horizontal samplen 2\n";
  figure
      .plot({gnuplot_string(figure.name(".dat")) + " using " + frame.xy() + ":3 with image notitle",
             frame.contour_item(name + "_contours.dat",
                                "lc rgb '#a0000000' lw 0.5 title " + contours_title(result))})
      .render();
}

TerrainResult process_terrain(const TerrainInput& input, const SunPosition& sun,
                              const fs::path& out_dir) {
  using Clock = std::chrono::steady_clock;
  const ElevationGrid& grid = input.grid;
  TerrainResult result;
  result.name = input.name;
  result.origin = input.origin;
  result.ncols = grid.ncols();
  result.nrows = grid.nrows();
  result.cellsize = grid.cellsize();
  result.voids = grid.void_count();
  const auto range = grid.elevation_range();
  if (!range) throw InputError("terrain-gallery: " + input.name + " has no valid node");
  result.zmin = range->first;
  result.zmax = range->second;

  // The interpolating fit refuses NODATA; none of the bundled grids has any,
  // but a user's data folder might, so fill with the nearest valid node (for
  // the picture only: the smoothing fit and the residuals use the true voids).
  result.filled_voids = result.voids > 0;
  const ElevationGrid filled = result.filled_voids ? fill_voids(grid, VoidFill::kNearest) : grid;

  const auto t0 = Clock::now();
  const BPatch interpolating = BPatch::interpolate(filled);
  const auto t1 = Clock::now();
  const BPatch smoothing = BPatch::fit_smoothing(grid, kSmoothingLambda);
  const auto t2 = Clock::now();
  result.interpolate_seconds = std::chrono::duration<double>(t1 - t0).count();
  result.smoothing_seconds = std::chrono::duration<double>(t2 - t1).count();

  result.max_interpolation_residual = fit_residuals(filled, interpolating, interpolating).max_abs;
  draw_relief(input, interpolating, sun, out_dir, result);
  draw_residuals(input, interpolating, smoothing, out_dir, result);
  return result;
}

void write_summary(const std::vector<TerrainResult>& results, const fs::path& path) {
  std::ostringstream csv;
  csv << "terrain,ncols,nrows,cellsize_m,zmin_m,zmax_m,voids,interpolate_seconds,"
         "smoothing_seconds,smoothing_lambda,max_residual_m,rms_residual_m\n";
  for (const TerrainResult& r : results) {
    csv << r.name << ',' << r.ncols << ',' << r.nrows << ',' << fmt("%.10g", r.cellsize) << ','
        << fmt("%.10g", r.zmin) << ',' << fmt("%.10g", r.zmax) << ',' << r.voids << ','
        << fmt("%.6f", r.interpolate_seconds) << ',' << fmt("%.6f", r.smoothing_seconds) << ','
        << fmt("%g", kSmoothingLambda) << ',' << fmt("%.6g", r.max_residual) << ','
        << fmt("%.6g", r.rms_residual) << '\n';
  }
  write_text_file(path, csv.str());
}

/// The two-to-four sentences of commentary, built from the measured numbers
/// so they stay true whatever the data folder holds.
std::string commentary(const std::vector<TerrainResult>& results) {
  const auto relative_rms = [](const TerrainResult& r) {
    const double relief = r.zmax - r.zmin;
    return relief > 0.0 ? r.rms_residual / relief : 0.0;
  };
  const auto by_relative_rms = [&](const TerrainResult& a, const TerrainResult& b) {
    return relative_rms(a) < relative_rms(b);
  };
  const auto by_share = [](const TerrainResult& a, const TerrainResult& b) {
    return a.curvature_share < b.curvature_share;
  };
  const auto by_nodes = [](const TerrainResult& a, const TerrainResult& b) {
    return a.ncols * a.nrows < b.ncols * b.nrows;
  };
  const TerrainResult& smoothest =
      *std::min_element(results.begin(), results.end(), by_relative_rms);
  const TerrainResult& roughest =
      *std::max_element(results.begin(), results.end(), by_relative_rms);
  const TerrainResult& low_share = *std::min_element(results.begin(), results.end(), by_share);
  const TerrainResult& high_share = *std::max_element(results.begin(), results.end(), by_share);
  const TerrainResult& largest = *std::max_element(results.begin(), results.end(), by_nodes);
  const int percent = static_cast<int>(std::lround(100.0 * kCurvatureFraction));

  std::ostringstream text;
  text << "The smoothing fit's (λ = " << fmt("%g", kSmoothingLambda)
       << ") RMS residual ranges from " << fmt("%.2g", 100.0 * relative_rms(smoothest))
       << " % of the relief on `" << smoothest.name << "` (" << sig3(smoothest.rms_residual)
       << " m) to " << fmt("%.2g", 100.0 * relative_rms(roughest)) << " % on `" << roughest.name
       << "` (" << sig3(roughest.rms_residual) << " m RMS, " << sig3(roughest.max_residual)
       << " m at worst): a fixed λ smooths over about one cell, so it costs most where landforms "
          "are only a few cells wide. ";
  // The concentration claim is made only if the data support it on every
  // terrain: at least twice the share a curvature-blind residual would have.
  if (low_share.curvature_share >= 2.0 * kCurvatureFraction) {
    text << "The residuals concentrate where the terrain is most curved: on every terrain the "
         << percent << " % of nodes with the largest thin-plate curvature carry between "
         << fmt("%.0f", 100.0 * low_share.curvature_share) << " % (`" << low_share.name << "`) and "
         << fmt("%.0f", 100.0 * high_share.curvature_share) << " % (`" << high_share.name
         << "`) of the squared residual (" << percent
         << " % if residuals ignored curvature), which is why the residual maps light up along "
            "ridge crests and rims (fit below the data, blue) and valley, canyon and crater "
            "floors (fit above, red) and stay pale on planar slopes and flats. ";
  } else {
    text << "The " << percent << " % of nodes with the largest thin-plate curvature carry between "
         << fmt("%.0f", 100.0 * low_share.curvature_share) << " % (`" << low_share.name << "`) and "
         << fmt("%.0f", 100.0 * high_share.curvature_share) << " % (`" << high_share.name
         << "`) of the squared residual (" << percent
         << " % would mean no relation to curvature). ";
  }
  text << "On the largest grid, `" << largest.name << "` (" << largest.ncols << " × "
       << largest.nrows << " nodes), the interpolating fit (two 1-D tensor-product solves) took "
       << sig3(largest.interpolate_seconds) << " s and the smoothing fit (one sparse CHOLMOD "
       << "solve over all control points) " << sig3(largest.smoothing_seconds) << " s. ";
  bool any_exaggerated = false;
  for (const TerrainResult& r : results) any_exaggerated |= r.exaggeration != 1.0;
  if (any_exaggerated) {
    text << "The gentle terrains (see the VE column) are hillshaded with a vertical exaggeration, "
            "otherwise their shading would be almost uniform; contours and colours use the true "
            "elevations.";
  }
  return text.str();
}

void write_report(const std::vector<TerrainResult>& results, const SunPosition& sun,
                  const ExperimentContext& context) {
  const double ambient = ReliefColouring{}.ambient;
  Report report("Terrain gallery");
  report
      .paragraph(
          "Every bundled DEM and one fractal terrain, drawn as shaded relief with contours from "
          "the interpolating B-patch, with the residual map of the smoothing B-patch.")
      .heading("What was run")
      .bullet(std::string("Inputs: ") + (context.quick ? "quick mode: the two smallest " : "all ") +
              "`data/terrain/*.asc` DEMs (provenance in `data/terrain/README.md`), and one fractal "
              "terrain.");
  for (const TerrainResult& r : results) {
    report.bullet(
        "`" + r.name + "`: " +
            (r.origin.starts_with("data/") ? describe_dem(r.name) + " (`" + r.origin + "`)"
                                           : r.origin) +
            (r.filled_voids ? "; NODATA nodes filled with the nearest valid value for "
                              "the relief image only"
                            : ""),
        1);
  }
  report
      .bullet(
          "Fits: `BPatch::interpolate` (exact at the nodes) and `BPatch::fit_smoothing` with "
          "λ = " +
          fmt("%g", kSmoothingLambda) +
          " (thin-plate weight in grid-index units, about one cell of smoothing), each timed "
          "once with `std::chrono::steady_clock` on this machine.")
      .bullet("Relief images: the interpolating patch evaluated on a raster of " +
              std::to_string(kRasterMaxSamples) +
              " samples along the longer side (square pixels); colour = hypsometric tint of the "
              "elevation × (" +
              fmt("%g", ambient) + " + " + fmt("%g", 1.0 - ambient) +
              " × hillshade). Hillshade = max(0, n · s), the Lambertian cosine between the "
              "surface normal n = (−k z_x, −k z_y, 1)/|…| and the unit vector s towards a sun at "
              "azimuth " +
              fmt("%g", sun.azimuth_deg) + "° (clockwise from north) and altitude " +
              fmt("%g", sun.altitude_deg) +
              "°; k is a vertical exaggeration, 1 unless the 95th-percentile slope is below 20° "
              "(then the largest of 1, 2, 5, 10, … not exceeding tan 20° / that slope). Contours "
              "are traced by gnuplot on the same raster at a {1, 2, 5} × 10^k interval giving "
              "12–30 levels. Axes are relative to the grid's south-west node.")
      .bullet(
          "Residual maps: smoothing fit minus data at every valid node (`BPatch::elevation` "
          "at the node positions); diverging colours, symmetric about zero, saturating at the "
          "99th percentile of |residual|. The curvature share is the fraction of the summed "
          "squared residual on the " +
          fmt("%.0f", 100.0 * kCurvatureFraction) +
          " % of nodes with the largest thin-plate energy z_uu² + 2 z_uv² + z_vv² of the "
          "interpolating patch.")
      .bullet(
          "Every figure has its gnuplot script (`<name>_relief.gp`, `<name>_residual.gp`) and "
          "data files next to it; `gnuplot <script>` in this folder re-renders it.")
      .heading("Results")
      .paragraph("Numbers also in `summary.csv`.");
  Table table({"terrain", "nodes", "cell [m]", "z min … max [m]", "voids", "interpolate [s]",
               "smoothing [s]", "max residual [m]", "RMS residual [m]", "RMS / relief",
               "curvature share", "VE", "contour step [m]"});
  for (const TerrainResult& r : results) {
    const double relief = r.zmax - r.zmin;
    table.row({"`" + r.name + "`", std::to_string(r.ncols) + " × " + std::to_string(r.nrows),
               fmt("%g", r.cellsize), fmt("%.6g", r.zmin) + " … " + fmt("%.6g", r.zmax),
               std::to_string(r.voids), sig3(r.interpolate_seconds), sig3(r.smoothing_seconds),
               sig3(r.max_residual), sig3(r.rms_residual),
               relief > 0.0 ? fmt("%.2g", 100.0 * r.rms_residual / relief) + " %" : "–",
               fmt("%.0f", 100.0 * r.curvature_share) + " %", fmt("%g", r.exaggeration),
               fmt("%g", r.contour_step)});
  }
  report.table(table)
      .heading("What the figures show")
      .paragraph(commentary(results))
      .heading("Figures");
  for (const TerrainResult& r : results) {
    report.figures(r.name, {{r.name + " shaded relief", r.name + "_relief.png"},
                            {r.name + " smoothing residuals", r.name + "_residual.png"}});
  }
  report.write(context.output_dir);
}

}  // namespace

void run_terrain_gallery(const ExperimentContext& context) {
  // Fail before minutes of fitting, not after, if the figures cannot be drawn.
  require_gnuplot();
  const SunPosition sun{315.0, 45.0};
  const std::vector<TerrainInput> inputs = gather_inputs(context);
  std::vector<TerrainResult> results;
  results.reserve(inputs.size());
  for (const TerrainInput& input : inputs) {
    results.push_back(process_terrain(input, sun, context.output_dir));
    const TerrainResult& r = results.back();
    std::cout << "terrain-gallery: " << r.name << " (" << r.ncols << " x " << r.nrows
              << "): interpolate " << fmt("%.3f", r.interpolate_seconds) << " s, smoothing "
              << fmt("%.3f", r.smoothing_seconds) << " s, RMS residual " << sig3(r.rms_residual)
              << " m\n";
  }
  write_summary(results, context.output_dir / "summary.csv");
  double worst_interpolation = 0.0, worst_relative = 0.0;
  for (const TerrainResult& r : results) {
    worst_interpolation = std::max(worst_interpolation, r.max_interpolation_residual);
    worst_relative = std::max(worst_relative, r.max_interpolation_residual / (r.zmax - r.zmin));
  }
  ExperimentSummary& summary = *context.summary;
  summary.set("terrains", static_cast<double>(results.size()), "count");
  summary.set("max_interpolation_residual_m", worst_interpolation, "m",
              "0: the interpolating B-patch passes through every node (rounding only)");
  summary.set("max_interpolation_residual_relative", worst_relative, "1",
              "0 relative to each grid's elevation range");
  write_report(results, sun, context);
}

}  // namespace talus::experiments
