// Notebook 05 — local optimisation and the whole planner in one call:
// talus::plan runs the global search, fits a B-spline to each candidate,
// optimises it for the travel time of its exact time-optimal profile and
// keeps the fastest.
//
//   build/notebooks_cpp/05_plan [--quick] [--out DIR] [--data DIR]
#include <cmath>

#include "notebook.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/verify_profile.hpp"

using namespace talus;
using namespace talus::notebooks;

namespace {

/// The planar points of a trajectory's path, for the map.
std::vector<Vec2> planar(const Trajectory& t) {
  std::vector<Vec2> points;
  if (t.path)
    for (const PathFrame& f : t.path->sample(300)) points.push_back(f.point.head<2>());
  return points;
}

}  // namespace

int main(int argc, char** argv) {
  return run([&] {
    Notebook nb(argc, argv, "05_plan", "05 · Local optimisation and the full plan");
    const Vehicle rover = load_vehicle(nb.data("vehicles/rover.yaml"));
    const ElevationGrid grid = west_bijou_at_rover_scale(nb);
    const BPatch terrain = BPatch::fit_smoothing(grid, 1.0);

    nb.section("One call");
    nb.say(
        "`talus::plan` (`optimal/include/talus/optimal/planner.hpp`) is the whole "
        "two-stage planner of Shiller and Gwo: the global search of notebook 04 proposes "
        "candidate corridors; each is replaced by a clamped cubic B-spline fitted to it, "
        "with the start and goal fixed; the spline's control points are then moved to "
        "minimise the travel time of its exact time-optimal profile (notebook 03), with "
        "Ipopt and the adjoint gradient of that time. Every result is re-evaluated at the "
        "final station spacing, and an optimum slower there than its own initial fit is "
        "replaced by the fit.");
    PlanningProblem problem(terrain, rover, {8, 12}, {112, 60});
    PlannerOptions options;
    options.global.lattice_spacing = nb.quick() ? 2.0 : 1.0;
    options.global.candidates = nb.quick() ? 2 : 3;
    if (nb.quick()) {
      options.local.max_iterations = 15;
      options.station_spacing = 0.25;
    }
    const PlannerResult result = plan(problem, options);
    std::string report = result.brief_report();
    while (!report.empty() && report.back() == '\n') report.pop_back();
    nb.say("```\n" + report + "\n```");
    if (!result.best()) throw Error("no trajectory: " + result.message);
    const Trajectory& best = *result.best();

    nb.section("Candidates before and after");
    Table table(
        {"candidate", "J [s]", "initial fit [s]", "optimised [s]", "solver", "kept the fit"});
    std::vector<Route> routes;
    bool never_slower = true;
    double fastest = INFINITY;
    for (const CandidateOutcome& c : result.candidates) {
      const CandidatePath& global = result.global.candidates[c.candidate];
      table.row({std::to_string(c.candidate), num("%.2f", global.cost_seconds),
                 num("%.2f", c.initial.travel_time()), num("%.2f", c.trajectory.travel_time()),
                 c.optimization ? c.optimization->solver_status : c.optimizer_message,
                 c.kept_initial ? "yes" : "no"});
      routes.push_back({c.candidate == 0 ? "global candidates" : "", global.vertices,
                        "lines lw 1.5 dt 2 lc rgb '#404040'"});
      routes.push_back({c.candidate == 0 ? "optimised paths" : "", planar(c.trajectory),
                        "lines lw 2.5 lc rgb '#2c7fb8'"});
      never_slower = never_slower && c.trajectory.travel_time() <= c.initial.travel_time();
      if (c.feasible()) fastest = std::min(fastest, c.trajectory.travel_time());
    }
    routes.push_back({"best: " + num("%.2f", best.travel_time()) + " s", planar(best),
                      "lines lw 5 lc rgb '#e6550d'"});  // drawn last, on top
    nb.table(table);
    nb.figure("Global candidates (dashed), optimised paths and the best",
              nb.map("plan", "talus::plan on the rover-scale West Bijou terrain", terrain, routes));
    nb.say("The best trajectory takes " + num("%.2f", result.travel_time()) +
           " s; the fastest initial fit took " + num("%.2f", result.global_travel_time()) +
           " s, an improvement of " + num("%.1f", result.improvement_percent()) +
           " %. Its J (time at the limit along the lattice path) is lower still, because J "
           "ignores acceleration and braking.");
    if (*result.best_candidate != 0) {
      nb.say("The winner is candidate " + std::to_string(*result.best_candidate) +
             ", not the one with the lowest J: J cannot see how much braking a corridor "
             "will need, which is why the planner optimises several candidates, not one.");
    }

    Series v{"v(s), time-optimal", {}, {}, "lines lw 2.5 lc rgb '#2c7fb8'"};
    Series v_max{"v_{max}(s)", {}, {}, "lines lw 1.5 lc rgb '#d73027'"};
    for (std::size_t k = 0; k < best.profile.s.size(); ++k) {
      v.x.push_back(best.profile.s[k]), v.y.push_back(best.profile.v[k]);
      v_max.x.push_back(best.profile.s[k]);
      v_max.y.push_back(std::min(best.profile.v_max[k], rover.max_speed));
    }
    nb.figure("The best trajectory's profile",
              nb.plot("profile", "Best trajectory: speed and its limit", "s [m]", "speed [m/s]",
                      {v_max, v}));

    nb.check(result.status == PlannerStatus::kOk,
             "the plan succeeded (status " + std::string(to_string(result.status)) + ")");
    nb.check(never_slower, "no candidate's result is slower than its own initial fit");
    nb.check(result.travel_time() == fastest, "the best is the fastest feasible candidate");
    nb.check(result.travel_time() <= result.global_travel_time(),
             "the plan is no slower than the fastest initial fit");
    nb.check(verify_profile(*best.limits, best.profile).status == VerificationStatus::kPass,
             "the best profile passes the independent admissibility check");
    TrajectoryOptions again;
    again.station_spacing = options.station_spacing;
    const Trajectory redo = evaluate_trajectory(terrain, rover, best.path->curve(), again);
    nb.check(redo.travel_time() == best.travel_time(),
             "re-evaluating the best curve with evaluate_trajectory gives the same travel time, "
             "to the bit (" +
                 num("%.6f", redo.travel_time()) + " s)");
    return nb.finish();
  });
}
