// Walkthrough 01 — from an elevation grid to the path geometry that the
// dynamics layer consumes. Run it and read its output next to this file.
//
//   build/notebooks_cpp/01_terrain_and_bpatch [path/to/data]
#include <cmath>
#include <cstdio>
#include <string>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"

int main(int argc, char** argv) {
  using namespace talus;
  const std::string data = argc > 1 ? argv[1] : TALUS_DATA_DIR;
  try {
    // 1. A real DEM: West Bijou Creek escarpment (NASADEM, 25 m cells). The
    //    reader is strict; nodes are cell centres, rows counted from the south.
    const ElevationGrid grid =
        read_esri_ascii(data + "/terrain/west_bijou_escarpment_nasadem25m.asc");
    const auto range = grid.elevation_range();
    std::printf("1. Grid: %zu x %zu nodes, %.0f m cells, elevation %.0f .. %.0f m\n", grid.ncols(),
                grid.nrows(), grid.cellsize(), range->first, range->second);

    // 2. The terrain model: a C2 bicubic B-patch. The interpolating fit is
    //    exact at every node; the smoothing fit trades node error for less
    //    curvature (lambda is dimensionless, ~1 cell of smoothing at 1).
    const BPatch exact = BPatch::interpolate(grid);
    const BPatch smooth = BPatch::fit_smoothing(grid, 1.0);
    const BPatchFitReport re = exact.residuals(grid), rs = smooth.residuals(grid);
    std::printf(
        "2. Interpolating fit: max node residual %.2e m; smoothing fit (lambda 1): max %.2f m, "
        "RMS %.2f m\n",
        re.max_node_residual, rs.max_node_residual, rs.rms_residual);

    // 3. A path is a planar B-spline lifted onto the surface. Here: a curve
    //    through four points across the escarpment.
    const double x0 = grid.x_min(), y0 = grid.y_min();
    const Curve2 curve =
        Curve2::interpolate({Vec2(x0 + 200, y0 + 300), Vec2(x0 + 1000, y0 + 900),
                             Vec2(x0 + 1900, y0 + 700), Vec2(x0 + 2800, y0 + 1500)});
    const SurfacePath path(smooth, curve);
    std::printf(
        "3. Path: 3-D length %.1f m (its planar chord sum is shorter: it climbs and turns)\n",
        path.length());

    // 4. At each station the Darboux frame (t, q, r), the normal and geodesic
    //    curvatures and the vertical's components k_t, k_q, k_r — the inputs of
    //    the velocity limits (see bspline/include/talus/bspline/surface_path.hpp
    //    for the sign conventions).
    std::printf("4. Stations:\n   %8s %8s %8s %10s %10s %7s %7s %7s\n", "s [m]", "z [m]", "slope",
                "kappa_n", "kappa_g", "k_t", "k_q", "k_r");
    for (const PathFrame& f : path.sample(9)) {
      std::printf("   %8.1f %8.1f %7.2f° %10.2e %10.2e %7.3f %7.3f %7.3f\n", f.s, f.point.z(),
                  std::acos(f.k_r) * 180.0 / 3.14159265358979, f.kappa_n, f.kappa_g, f.k_t, f.k_q,
                  f.k_r);
    }

    // 5. Asking for a point off the map is an error with a clear message, never garbage.
    try {
      smooth.elevation(Vec2(x0 - 100, y0));
    } catch (const InputError& e) {
      std::printf("5. Off the map: %s\n", e.what());
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "walkthrough failed: %s\n", e.what());
    return 1;
  }
  return 0;
}
