// Plan under a time budget, and stop on request: one talus::Termination for the whole plan.
// Usage: plan_within_budget DEM.asc VEHICLE.yaml SECONDS
// Prints the status ("ok", or "time_limit" with the best trajectory found by then, if any)
// and the brief report; exits 0 when a trajectory exists, 2 when none, 1 on bad input.
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/termination.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/planner.hpp"

namespace {
std::atomic<bool> interrupted{false};
void on_interrupt(int) {
  interrupted = true;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: plan_within_budget DEM.asc VEHICLE.yaml SECONDS\n";
    return 1;
  }
  try {
    const talus::ElevationGrid grid = talus::read_esri_ascii(argv[1]);
    const talus::BPatch surface = talus::BPatch::fit_smoothing(grid, 1.0);
    const talus::Vehicle vehicle = talus::load_vehicle(argv[2]);
    const talus::Vec2 start(grid.x_min(), grid.y_min()), goal(grid.x_max(), grid.y_max());
    const talus::PlanningProblem problem(surface, vehicle, start, goal);

    // Ctrl-C stops the plan as soon as a stage looks (status "stopped"); the budget counts from
    // plan()'s start (status "time_limit"). Whichever comes first.
    std::signal(SIGINT, on_interrupt);
    talus::PlannerOptions options;
    options.termination = talus::Termination::time_budget(std::stod(argv[3])) |
                          talus::Termination::when([] { return interrupted.load(); });
    const talus::PlannerResult result = talus::plan(problem, options);

    std::cout << "status: " << talus::to_string(result.status) << "\n" << result.brief_report();
    return result.best() != nullptr ? 0 : 2;
  } catch (const talus::Error& error) {  // bad input: files, options, a budget <= 0
    std::cerr << "plan_within_budget: " << error.what() << "\n";
    return 1;
  } catch (const std::exception& error) {  // std::stod
    std::cerr << "plan_within_budget: bad SECONDS: " << error.what() << "\n";
    return 1;
  }
}
