// Notebook 01 — from an elevation grid to the path geometry the dynamics
// layer consumes: the DEM, the B-patch surface fitted to it, and a path
// lifted onto that surface with its Darboux frame.
//
//   build/notebooks_cpp/01_terrain_and_bpatch [--quick] [--out DIR] [--data DIR]
#include <algorithm>
#include <cmath>
#include <numbers>

#include "notebook.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"

using namespace talus;
using namespace talus::notebooks;

int main(int argc, char** argv) {
  return run([&] {
    Notebook nb(argc, argv, "01_terrain_and_bpatch", "01 · Terrain and B-patch");

    nb.section("The elevation grid");
    // A real DEM: the West Bijou Creek escarpment (NASADEM, 25 m cells). The
    // reader is strict; nodes are cell centres, rows counted from the south.
    const ElevationGrid grid =
        read_esri_ascii(nb.data("terrain/west_bijou_escarpment_nasadem25m.asc"));
    const auto range = grid.elevation_range();
    nb.say("The West Bijou Creek escarpment (Colorado, NASADEM): " + std::to_string(grid.ncols()) +
           " × " + std::to_string(grid.nrows()) + " nodes " + num("%.0f", grid.cellsize()) +
           " m apart, elevations " + num("%.0f", range->first) + " to " +
           num("%.0f", range->second) +
           " m. Talus reads a value as sitting at a cell centre (a node) and counts rows from "
           "the south, so node (i, j) lies at (x_min + i h, y_min + j h).");

    nb.section("The B-patch: a C² surface through the nodes");
    nb.say(
        "Planning needs curvatures, so the grid becomes a uniform bicubic B-spline surface "
        "(a *B-patch*) with knots at the nodes. The **interpolating** fit passes through "
        "every node; the **smoothing** fit minimises the node residuals plus λ times the "
        "surface's bending energy (λ dimensionless, about one cell of smoothing at λ = 1). "
        "A DEM that stores whole metres has steps the interpolant turns into curvature "
        "spikes; smoothing removes them at the price of node error.");
    const BPatch exact = BPatch::interpolate(grid);
    Table fits({"fit", "max node residual [m]", "RMS residual [m]"});
    const BPatchFitReport re = exact.residuals(grid);
    fits.row({"interpolating", num("%.1e", re.max_node_residual), num("%.1e", re.rms_residual)});
    double previous_rms = re.rms_residual;
    bool rms_grows = true;
    for (const double lambda : {1.0, 10.0}) {
      const BPatchFitReport r = BPatch::fit_smoothing(grid, lambda).residuals(grid);
      fits.row({"smoothing λ = " + num("%g", lambda), num("%.2f", r.max_node_residual),
                num("%.2f", r.rms_residual)});
      rms_grows = rms_grows && r.rms_residual > previous_rms;
      previous_rms = r.rms_residual;
    }
    nb.table(fits);
    nb.check(re.max_node_residual < 1e-6 * (range->second - range->first),
             "the interpolating fit is exact at the nodes (max residual " +
                 num("%.1e", re.max_node_residual) + " m)");
    nb.check(rms_grows, "more smoothing (larger λ) moves the surface further from the nodes");

    // The interpolating fit uses not-a-knot end conditions, so it reproduces
    // any bicubic polynomial exactly, between the nodes too.
    ElevationGrid cubic(9, 7, 2.0, 0.0, 0.0);
    const auto poly = [](double x, double y) {
      return 0.01 * x * x * x - 0.02 * x * y * y + 0.3 * x * y + 0.05 * y * y - 2.0;
    };
    for (std::size_t j = 0; j < cubic.nrows(); ++j)
      for (std::size_t i = 0; i < cubic.ncols(); ++i) cubic.at(i, j) = poly(2.0 * i, 2.0 * j);
    const BPatch cubic_fit = BPatch::interpolate(cubic);
    double worst = 0.0;
    for (double x = 0.0; x <= 16.0; x += 0.37)
      for (double y = 0.0; y <= 12.0; y += 0.41)
        worst = std::max(worst, std::abs(cubic_fit.elevation({x, y}) - poly(x, y)));
    nb.check(worst < 1e-9,
             "a bicubic polynomial sampled on a 9 × 7 grid is reproduced between "
             "the nodes too (max error " +
                 num("%.1e", worst) + " m)");

    nb.section("A path on the surface");
    // A path is a planar B-spline lifted onto the surface: here the
    // interpolating cubic through four points across the escarpment.
    const BPatch smooth = BPatch::fit_smoothing(grid, 1.0);
    const double x0 = grid.x_min(), y0 = grid.y_min();
    const std::vector<Vec2> through = {Vec2(x0 + 200, y0 + 300), Vec2(x0 + 1000, y0 + 900),
                                       Vec2(x0 + 1900, y0 + 700), Vec2(x0 + 2800, y0 + 1500)};
    const SurfacePath path(smooth, Curve2::interpolate(through));
    const std::vector<PathFrame> frames = path.sample(nb.quick() ? 200 : 1000);
    Route route{"path (cubic through 4 points)", {}, "lines lw 3 lc rgb '#e6550d'"};
    Series z{"z(s)", {}, {}, "lines lw 2 lc rgb '#2c7fb8'"};
    Series slope{"slope along the path [°]", {}, {}, "lines lw 2 lc rgb '#d73027'"};
    double planar = 0.0, unit_error = 0.0;
    bool upward = true;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const PathFrame& f = frames[k];
      route.points.push_back(f.point.head<2>());
      z.x.push_back(f.s);
      z.y.push_back(f.point.z());
      slope.x.push_back(f.s);
      slope.y.push_back(std::asin(std::clamp(f.k_t, -1.0, 1.0)) * 180.0 / std::numbers::pi);
      if (k > 0) planar += (f.point.head<2>() - frames[k - 1].point.head<2>()).norm();
      unit_error =
          std::max(unit_error, std::abs(f.k_t * f.k_t + f.k_q * f.k_q + f.k_r * f.k_r - 1));
      upward = upward && f.k_r > 0.0;
    }
    nb.figure("The smoothing fit as shaded relief, with the path",
              nb.map("map", "West Bijou escarpment, smoothing fit λ = 1", smooth, {route}));
    nb.say(
        "At each station the path has a Darboux frame: t the unit tangent, r the upward "
        "surface normal and q = r × t to the left. The curvature splits into the normal "
        "curvature κ_n (< 0 on a crest) and the geodesic curvature κ_g (> 0 turning left); "
        "the vertical's components (k_t, k_q, k_r) in that frame say how much of gravity "
        "pulls along, across and into the path. These six numbers per station are all the "
        "dynamics layer needs.");
    nb.figure("Elevation along the path",
              nb.plot("elevation", "Elevation along the path", "s [m]", "z [m]", {z}));
    nb.figure("Slope along the path (k_t = sin of the slope; > 0 uphill)",
              nb.plot("slope", "Slope along the path", "s [m]", "slope [°]", {slope}));
    nb.say("The path is " + num("%.1f", path.length()) + " m long on the surface, " +
           num("%.1f", planar) + " m in plan.");
    nb.check(path.length() >= planar, "the 3-D length is at least the planar length");
    nb.check(unit_error < 1e-12, "(k_t, k_q, k_r) is a unit vector at every station (error " +
                                     num("%.0e", unit_error) + ")");
    nb.check(upward, "k_r > 0 everywhere: the frame's r points up, out of the ground");

    nb.section("Off the map");
    bool refused = false;
    try {
      smooth.elevation(Vec2(x0 - 100, y0));
    } catch (const InputError& e) {
      refused = true;
      nb.say(std::string("Asking for a point off the map is an error with a clear message: `") +
             e.what() + "`");
    }
    nb.check(refused, "a point off the map is an InputError, never an extrapolated number");
    return nb.finish();
  });
}
