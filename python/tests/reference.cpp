/// @file
/// The C++ side of the Python bindings' bit-for-bit tests: runs a case through
/// the library directly and prints every number with %.17g (which round-trips
/// a double exactly), for python/tests to compare with == against the same
/// case run through `import talus`.
///
///   talus_python_reference profile TERRAIN.asc VEHICLE.yaml X0 Y0 X1 Y1 V0 V1
///     the straight line (X0, Y0) -> (X1, Y1) on the interpolating fit, limits at
///     station_count(length) stations, the time-optimal profile from V0 to V1;
///     then evaluate_trajectory() of the same line.
///   talus_python_reference plan TERRAIN.asc VEHICLE.yaml X0 Y0 X1 Y1 CANDIDATES
///     talus::plan with default options but `CANDIDATES` global candidates.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/time_optimal_profile.hpp"
#include "talus/optimal/trajectory.hpp"

namespace {

using namespace talus;

void print_array(const char* name, const std::vector<double>& values) {
  std::printf("%s", name);
  for (const double v : values) std::printf(" %.17g", v);
  std::printf("\n");
}

void print_profile(const char* prefix, const TimeOptimalProfile& p) {
  std::printf("%s.status %s\n", prefix, p.status == ProfileStatus::kOk ? "ok" : "infeasible");
  std::printf("%s.travel_time %.17g\n", prefix, p.travel_time);
  for (const auto& [name, values] :
       {std::pair{"s", &p.s}, std::pair{"v", &p.v}, std::pair{"a", &p.a}, std::pair{"t", &p.t},
        std::pair{"v_max", &p.v_max}}) {
    print_array((std::string(prefix) + "." + name).c_str(), *values);
  }
}

int profile(char** argv) {
  const BPatch surface = BPatch::interpolate(read_esri_ascii(argv[0]));
  const Vehicle vehicle = load_vehicle(argv[1]);
  const Vec2 a(std::strtod(argv[2], nullptr), std::strtod(argv[3], nullptr));
  const Vec2 b(std::strtod(argv[4], nullptr), std::strtod(argv[5], nullptr));
  const ProfileOptions speeds{std::strtod(argv[6], nullptr), std::strtod(argv[7], nullptr)};
  const Curve2 line = Curve2::interpolate({a, b});
  const SurfacePath path(surface, line);
  const VelocityLimits limits(vehicle, path, station_count(path.length()));
  TimeOptimalProfileSolver solver;
  print_profile("profile", solver.solve(limits, speeds));
  TrajectoryOptions options;
  options.speeds = speeds;
  const Trajectory trajectory = evaluate_trajectory(surface, vehicle, line, options);
  print_profile("trajectory", trajectory.profile);
  std::printf("trajectory.length %.17g\n", trajectory.length());
  return 0;
}

int plan_case(char** argv) {
  const BPatch surface = BPatch::interpolate(read_esri_ascii(argv[0]));
  const PlanningProblem problem(surface, load_vehicle(argv[1]),
                                {std::strtod(argv[2], nullptr), std::strtod(argv[3], nullptr)},
                                {std::strtod(argv[4], nullptr), std::strtod(argv[5], nullptr)});
  PlannerOptions options;
  options.global.candidates = static_cast<std::size_t>(std::strtoul(argv[6], nullptr, 10));
  const PlannerResult result = plan(problem, options);
  std::printf("plan.status %s\n", std::string(to_string(result.status)).c_str());
  std::printf("plan.travel_time %.17g\n", result.travel_time());
  std::printf("plan.global_travel_time %.17g\n", result.global_travel_time());
  const Trajectory* best = result.best();
  if (best == nullptr) return 0;
  std::vector<double> control;
  for (const Vec2& p : best->path->curve().control_points()) {
    control.push_back(p.x());
    control.push_back(p.y());
  }
  print_array("plan.control_points", control);
  print_profile("plan.best", best->profile);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string command = argc > 1 ? argv[1] : "";
    if (command == "profile" && argc == 10) return profile(argv + 2);
    if (command == "plan" && argc == 9) return plan_case(argv + 2);
    std::fprintf(stderr, "usage: see python/tests/reference.cpp\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "talus_python_reference: %s\n", e.what());
    return 1;
  }
}
