// Notebook 06 — a kinematic baseline: the planner of Haït, Siméon and Taïx
// (2002) through the baseline registry, its path then given a time-optimal
// velocity profile (path–velocity decomposition), against Talus's plan on
// the same terrain.
//
//   build/notebooks_cpp/06_hait_baseline [--quick] [--out DIR] [--data DIR]
#include <cmath>

#include "notebook.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/kinematic/driving_pieces.hpp"
#include "talus/kinematic/hait/hait_scenarios.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/polyline_travel_time.hpp"

using namespace talus;
using namespace talus::notebooks;

int main(int argc, char** argv) {
  return run([&] {
    Notebook nb(argc, argv, "06_hait_baseline", "06 · The Haït–Siméon–Taïx baseline");
    const BaselineRegistry& registry = BaselineRegistry::builtin();

    nb.section("Baselines through one registry");
    nb.say(
        "Talus implements the kinematic planners of the literature as baselines. Each is "
        "a `BaselinePlanner` configured from text options and queried with plan(terrain, "
        "start, goal); the registry finds them by name, as `talus baseline NAME` does.");
    Table names({"name", "what it is"});
    for (const std::string& name : registry.names())
      names.row({name, registry.entry(name).summary});
    nb.table(names);

    nb.section("A kinematic path");
    // The hait-heuristics problem: a crescent of steep hills that cups the
    // straight line from start to goal (quick: 61 × 61 nodes, 15 m).
    const HaitScenario scenario = hait_heuristics_scenario(nb.quick());
    const auto planner =
        registry.make("hait", {{"robot", nb.data("robots/marsokhod_chassis.yaml")}});
    const RuledTerrain ruled(scenario.grid);
    const BaselineResult kinematic = planner->plan(ruled, scenario.start, scenario.goal);
    nb.say(scenario.description);
    nb.say(
        "Haït et al. model the terrain as bilinear patches and the robot as a real chassis "
        "(here the three-axle Marsokhod, `data/robots/marsokhod_chassis.yaml`): a "
        "configuration (x, y, θ) is valid if the placed chassis keeps its roll, pitch and "
        "clearance limits. A* searches (x, y, θ) with arcs of fixed length and turning "
        "radius, guided by a potential bitmap. It knows nothing of speed.");
    nb.say("Its result: `" + kinematic.brief_report() + "`");
    if (!kinematic.found()) throw Error("the Haït planner found no path: " + kinematic.message);

    const ValidityFunction valid = planner->validity(ruled);
    bool all_valid = true;
    for (const SE2Pose& q : kinematic.path) all_valid = all_valid && valid(q).valid;
    nb.check(all_valid, "every one of the path's " + std::to_string(kinematic.path.size()) +
                            " configurations passes the planner's own validity check");
    const SE2Pose& first = kinematic.path.front();
    const SE2Pose& last = kinematic.path.back();
    nb.check(first.position() == scenario.start.position() &&
                 (last.position() - scenario.goal.position()).norm() <= 0.25,
             "it starts at the start and ends within one cell (0.25 m) of the goal");

    nb.section("Driving it as fast as possible");
    // Path–velocity decomposition: split the path at its cusps and give every
    // piece its time-optimal profile from rest to rest. The vehicle is the
    // point mass matched to the chassis (half track = its axle half width).
    Vehicle vehicle = load_vehicle(nb.data("vehicles/rover.yaml"));
    vehicle.friction = 0.7, vehicle.cg_height = 0.35, vehicle.half_track = 0.45;
    vehicle.max_speed = 2.0, vehicle.max_accel = 1.0, vehicle.max_decel = 1.0;
    const BPatch surface = BPatch::interpolate(scenario.grid);
    const std::vector<DrivingPiece> pieces = split_at_cusps(kinematic.path);
    double kinematic_time = 0.0;
    for (const DrivingPiece& piece : pieces)
      kinematic_time += polyline_travel_time(surface, vehicle, piece.points);
    nb.say("The kinematic path has " + std::to_string(pieces.size()) +
           " driving piece(s) "
           "between cusps; driven time-optimally, each from rest to rest, it takes " +
           num("%.2f", kinematic_time) + " s over " + num("%.1f", kinematic.length_m) +
           " m, for a point mass with μ = 0.7, h = 0.35 m, b = 0.45 m, top speed 2 m/s and "
           "±1 m/s² (the chassis' matched dynamics).");
    nb.check(std::isfinite(kinematic_time), "every piece has an admissible profile");

    nb.section("Talus on the same query");
    PlannerOptions options;
    options.global.candidates = nb.quick() ? 1 : 2;
    const PlannerResult talus_plan =
        plan(PlanningProblem(surface, vehicle, scenario.start.position(), scenario.goal.position()),
             options);
    if (!talus_plan.best()) throw Error("Talus found no trajectory: " + talus_plan.message);
    const Trajectory& best = *talus_plan.best();
    std::size_t chassis_valid = 0, stations = 0;
    std::vector<Vec2> talus_points;
    for (const PathFrame& f : best.path->sample(200)) {
      talus_points.push_back(f.point.head<2>());
      const SE2Pose q{f.point.x(), f.point.y(), std::atan2(f.tangent.y(), f.tangent.x())};
      chassis_valid += valid(q).valid ? 1 : 0;
      ++stations;
    }
    std::vector<Vec2> kinematic_points;
    for (const SE2Pose& q : kinematic.path) kinematic_points.push_back(q.position());
    nb.figure("The kinematic path and Talus's plan",
              nb.map("paths", "Haït–Siméon–Taïx (kinematic) and Talus (time-optimal)", surface,
                     {{"Haït et al.: " + num("%.1f", kinematic_time) + " s", kinematic_points,
                       "lines lw 3 lc rgb '#2c7fb8'"},
                      {"Talus: " + num("%.1f", best.travel_time()) + " s", talus_points,
                       "lines lw 3 lc rgb '#e6550d'"}}));
    Table compare({"planner", "length [m]", "travel time [s]", "planning [s]"});
    compare.row({"Haït et al., then its profile", num("%.1f", kinematic.length_m),
                 num("%.2f", kinematic_time),
                 num("%.2f", kinematic.preprocessing_seconds + kinematic.search_seconds)});
    compare.row({"Talus plan", num("%.1f", best.length()), num("%.2f", best.travel_time()),
                 num("%.2f", talus_plan.seconds.total)});
    nb.table(compare);
    nb.say(
        "Talus plans for time, so it takes wide, smooth lines where the kinematic path "
        "turns on its minimum radius (and it has no goal heading to meet, where the "
        "kinematic query must arrive heading north); the kinematic planner plans for validity of a "
        "real "
        "chassis, which Talus's point mass does not model: " +
        std::to_string(chassis_valid) + " of " + std::to_string(stations) +
        " stations of Talus's path are valid chassis configurations (heading along the "
        "path). The dynamic-vs-kinematic experiment and the sweep-dynamic-vs-kinematic "
        "sweep measure this over many terrains.");
    nb.check(best.travel_time() < kinematic_time,
             "on this query Talus's trajectory is faster than the kinematic path driven "
             "time-optimally (ratio " +
                 num("%.2f", kinematic_time / best.travel_time()) + ")");
    return nb.finish();
  });
}
