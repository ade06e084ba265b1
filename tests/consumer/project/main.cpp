// Downstream use of the installed Talus package: build a small elevation grid
// with a void, round-trip it through the ESRI ASCII writer and reader, and
// check that nothing changed. Returns non-zero on any difference.
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/kinematic/hait/hait_baseline.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    std::cerr << "MISMATCH: " << what << '\n';
    ++failures;
  }
}

}  // namespace

int main() {
  // 5 x 4 nodes, 25 m cells; origin chosen so corner <-> centre is exact.
  talus::ElevationGrid grid(5, 4, 25.0, 512345.5, 4401012.5);
  for (std::size_t j = 0; j < grid.nrows(); ++j) {
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      grid.at(i, j) = 1612.37 + 0.1 * static_cast<double>(i) - 3.3 * static_cast<double>(j * j);
    }
  }
  grid.set_void(3, 2);

  std::stringstream stream;
  talus::write_esri_ascii(grid, stream);
  const talus::ElevationGrid back = talus::read_esri_ascii(stream, "<stringstream>");

  check(back.ncols() == grid.ncols(), "ncols");
  check(back.nrows() == grid.nrows(), "nrows");
  check(back.cellsize() == grid.cellsize(), "cellsize");
  check(back.x_min() == grid.x_min(), "x_min");
  check(back.y_min() == grid.y_min(), "y_min");
  check(back.void_count() == 1, "void count");
  if (back.ncols() == grid.ncols() && back.nrows() == grid.nrows()) {
    for (std::size_t j = 0; j < grid.nrows(); ++j) {
      for (std::size_t i = 0; i < grid.ncols(); ++i) {
        const std::string node = "node (" + std::to_string(i) + ", " + std::to_string(j) + ")";
        check(back.valid(i, j) == grid.valid(i, j), node + " validity");
        if (grid.valid(i, j)) check(back.at(i, j) == grid.at(i, j), node + " elevation");
      }
    }
  }
  check(back.elevation_range() == grid.elevation_range(), "elevation range");

  // Library code paths beyond I/O: interpolation and the error hierarchy.
  const talus::Vec2 mid = grid.node_position(0, 0) + talus::Vec2(12.5, 12.5);
  check(back.bilinear(mid) == grid.bilinear(mid), "bilinear interpolation");
  bool threw = false;
  try {
    std::istringstream bad("ncols 2\nnrows 2\n");
    (void)talus::read_esri_ascii(bad, "<bad>");
  } catch (const talus::InputError&) {
    threw = true;
  }
  check(threw, "malformed input must throw talus::InputError");

  // Every layer through the installed package: a smoothing B-patch (CHOLMOD),
  // a vehicle from YAML (yaml-cpp), and the time-optimal profile on a flat
  // straight line, whose time is 2 sqrt(L / (mu g)).
  talus::ElevationGrid flat(41, 11, 1.0, 0.0, 0.0, 3.0);
  const talus::BPatch patch = talus::BPatch::fit_smoothing(flat, 1.0);
  const talus::SurfacePath path(
      patch, talus::Curve2::interpolate({talus::Vec2(0, 5), talus::Vec2(40, 5)}));
  const talus::Vehicle vehicle = talus::parse_vehicle(
      "model: point_mass\nfriction: 0.5\ncg_height: 0.5\nhalf_track: 0.6\n", "<consumer>");
  const talus::VelocityLimits limits(vehicle, path, 401);
  talus::TimeOptimalProfileSolver solver;
  const talus::TimeOptimalProfile profile = solver.solve(limits, {});
  const double expected = 2.0 * std::sqrt(40.0 / (0.5 * 9.81));
  check(profile.status == talus::ProfileStatus::kOk &&
            std::abs(profile.travel_time - expected) < 0.005 * expected,
        "time-optimal profile on a flat line");

  // The kinematic layer: a robot from YAML (yaml-cpp) planned across flat
  // ground by the registered Hait-Simeon-Taix baseline, a straight 2 m line.
  const talus::Robot robot = talus::parse_robot(
      "type: wheeled\nwheels: [[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]]\n"
      "cg_height: 0.2\nmax_spring_extension: 0.05\nmax_roll: 0.3\nmax_pitch: 0.3\n"
      "body: {front: 0.4, rear: 0.4, half_width: 0.25, clearance: 0.1}\n",
      "<consumer>");
  talus::HaitOptions hait;
  hait.heuristic = talus::HaitHeuristic::kEuclidean;
  const talus::HaitBaseline baseline(robot, hait);
  const talus::BaselineResult route =
      baseline.plan(talus::RuledTerrain(talus::ElevationGrid(17, 9, 0.25, 0.0, 0.0, 1.0)),
                    {1.0, 1.0, 0.0}, {3.0, 1.0, 0.0});
  check(route.found() && std::abs(route.length_m - 2.0) < 1e-6, "hait baseline on flat ground");
  check(!talus::BaselineRegistry::builtin().names().empty(), "registered baselines");

  if (failures != 0) {
    std::cerr << failures << " check(s) failed\n";
    return EXIT_FAILURE;
  }
  std::cout << "talus_consumer: " << grid.ncols() << " x " << grid.nrows()
            << " grid round-tripped through ESRI ASCII\n";
  return EXIT_SUCCESS;
}
