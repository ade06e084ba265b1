// Walkthrough 02 — from a path on the terrain to its time-optimal velocity
// profile: speed limits, acceleration bounds, the profile and its switching
// points, then the global search that proposes the path in the first place.
//
//   build/notebooks_cpp/02_limits_and_profile [path/to/data]
#include <cmath>
#include <cstdio>
#include <string>

#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/time_optimal_profile.hpp"
#include "talus/optimal/trajectory.hpp"

int main(int argc, char** argv) {
  using namespace talus;
  const std::string data = argc > 1 ? argv[1] : TALUS_DATA_DIR;
  try {
    // 1. Terrain and vehicle. The West Bijou DEM (25 m cells) is scaled by
    //    1/25 in x, y and z: 1 m cells with unchanged slopes, so that a rover's
    //    limits bind (data/terrain/README.md, "Rover-scale use").
    const ElevationGrid dem =
        read_esri_ascii(data + "/terrain/west_bijou_escarpment_nasadem25m.asc");
    ElevationGrid grid(dem.ncols(), dem.nrows(), 1.0, 0.0, 0.0);
    for (std::size_t j = 0; j < dem.nrows(); ++j)
      for (std::size_t i = 0; i < dem.ncols(); ++i) grid.at(i, j) = dem.at(i, j) / 25.0;
    const BPatch terrain = BPatch::fit_smoothing(grid, 1.0);
    const Vehicle rover = load_vehicle(data + "/vehicles/rover.yaml");
    std::printf("1. Terrain %zu x %zu m; rover: mu %.2f, h %.2f m, b %.2f m, v <= %.0f m/s\n",
                grid.ncols() - 1, grid.nrows() - 1, rover.friction, rover.cg_height,
                rover.half_track, rover.max_speed);

    // 2. The global stage proposes a path: minimum J = integral of ds / v_max
    //    over a 16-connected lattice, with untraversable edges removed.
    GlobalSearchOptions search;
    search.candidates = 2;
    const GlobalSearchResult global = global_search(terrain, rover, {5, 5}, {115, 75}, search);
    if (global.status != GlobalSearchStatus::kOk) throw Error(global.message);
    for (std::size_t k = 0; k < global.candidates.size(); ++k) {
      std::printf("2. Candidate %zu: J = %.2f s over %.1f m (%zu lattice vertices)\n", k,
                  global.candidates[k].cost_seconds, global.candidates[k].length_m,
                  global.candidates[k].vertices.size());
    }

    // 3. The best candidate as a smooth path: the interpolating cubic
    //    B-spline through every fourth vertex, lifted onto the surface.
    std::vector<Vec2> through;
    const std::vector<Vec2>& vertices = global.candidates[0].vertices;
    for (std::size_t k = 0; k < vertices.size(); k += 4) through.push_back(vertices[k]);
    if (through.back() != vertices.back()) through.push_back(vertices.back());
    const SurfacePath path(terrain, Curve2::interpolate(through));
    const auto stations = station_count(path.length());
    const VelocityLimits limits(rover, path, stations);
    std::printf("3. Path: %.1f m, %zu stations (%.2f m apart)\n", path.length(), stations,
                kDefaultStationSpacing);

    // 4. Speed limits: each station's v_max and the constraint that sets it.
    double slowest = INFINITY;
    std::size_t at = 0;
    for (std::size_t k = 0; k < limits.size(); ++k) {
      if (limits.limits(k).v_max < slowest) slowest = limits.limits(k).v_max, at = k;
    }
    std::printf("4. Tightest limit: %.2f m/s at s = %.1f m, set by %s (kappa_g = %.3f 1/m)\n",
                slowest, limits.frame(at).s,
                std::string(to_string(limits.limits(at).upper_binding)).c_str(),
                limits.frame(at).kappa_g);
    const AccelerationBounds a = limits.acceleration_bounds(at, 0.5 * slowest);
    std::printf("   At half that speed there, s'' may range over [%.2f, %.2f] m/s^2 (%s / %s)\n",
                a.a_min, a.a_max, std::string(to_string(a.lower_binding)).c_str(),
                std::string(to_string(a.upper_binding)).c_str());

    // 5. The exact time-optimal profile from rest to rest.
    TimeOptimalProfileSolver solver;
    const TimeOptimalProfile profile = solver.solve(limits, {});
    if (profile.status != ProfileStatus::kOk) throw Error(profile.message);
    double peak = 0.0;
    for (double v : profile.v) peak = std::max(peak, v);
    std::printf(
        "5. Travel time %.2f s (J of the lattice path: %.2f s), peak %.2f m/s, %zu "
        "switching points:\n",
        profile.travel_time, global.candidates[0].cost_seconds, peak,
        profile.switching_points.size());
    for (std::size_t k = 0; k < std::min<std::size_t>(profile.switching_points.size(), 6); ++k) {
      const SwitchingPoint& sp = profile.switching_points[k];
      std::printf("   s = %7.2f m: %s -> %s\n", sp.s, std::string(to_string(sp.from)).c_str(),
                  std::string(to_string(sp.to)).c_str());
    }
    // The profile is longer than J: J drives at v_max everywhere, the profile
    // must also accelerate from rest, brake before tight spots and stop.
  } catch (const Error& e) {
    std::fprintf(stderr, "walkthrough failed: %s\n", e.what());
    return 1;
  }
  return 0;
}
