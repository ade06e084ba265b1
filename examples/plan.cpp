// Plan a time-optimal trajectory across a DEM, corner to corner.
// Usage: plan_example DEM.asc VEHICLE.yaml
#include <iostream>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/planner.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: plan_example DEM.asc VEHICLE.yaml\n";
    return 1;
  }
  try {
    const talus::ElevationGrid grid = talus::read_esri_ascii(argv[1]);
    const talus::BPatch surface = talus::BPatch::fit_smoothing(grid, 1.0);
    const talus::Vehicle vehicle = talus::load_vehicle(argv[2]);

    const talus::Vec2 start(grid.x_min(), grid.y_min()), goal(grid.x_max(), grid.y_max());
    const talus::PlanningProblem problem(surface, vehicle, start, goal);
    talus::PlannerOptions options;  // 3 candidates, Ipopt, 16 control points, 2 restarts
    const talus::PlannerResult result = talus::plan(problem, options);

    std::cout << result.brief_report();
    if (const talus::Trajectory* best = result.best()) {
      const talus::TimeOptimalProfile& profile = best->profile;
      std::cout << "arrives after " << profile.t.back() << " s at " << profile.v.back() << " m/s\n";
    }
    return result.status == talus::PlannerStatus::kOk ? 0 : 2;
  } catch (const talus::Error& error) {  // bad input: files, options
    std::cerr << "plan_example: " << error.what() << "\n";
    return 1;
  }
}
