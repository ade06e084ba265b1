// Notebook 04 — the global stage: a minimum-time search over a lattice on the
// terrain, whose edge cost is the time at the speed limit, J = ∫ ds / v_max,
// and the extraction of several distinct candidate corridors.
//
//   build/notebooks_cpp/04_global_search [--quick] [--out DIR] [--data DIR]
#include <cmath>

#include "notebook.hpp"
#include "talus/core/error.hpp"
#include "talus/core/polyline.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/global_search.hpp"

using namespace talus;
using namespace talus::notebooks;

int main(int argc, char** argv) {
  return run([&] {
    Notebook nb(argc, argv, "04_global_search", "04 · Global search");
    const Vehicle rover = load_vehicle(nb.data("vehicles/rover.yaml"));
    const ElevationGrid grid = west_bijou_at_rover_scale(nb);
    const BPatch terrain = BPatch::fit_smoothing(grid, 1.0);
    const Vec2 start(5, 5), goal(115, 75);

    nb.section("Why a global stage");
    nb.say(
        "The local optimiser of notebook 05 improves a path it is given, and finds the "
        "best path *near* it. Which side of a hill to pass is a global question, so Talus "
        "first searches a lattice: nodes every h metres, each joined to its 16 neighbours "
        "by straight edges lifted onto the surface. An edge costs J = ∫ ds / v_max, the "
        "time to drive it at the speed limit, and is removed if the rover could not climb, "
        "hold or brake on it. J ignores acceleration, so it is a cheap, optimistic estimate "
        "of the travel time; the candidates it finds are starting points, not answers.");

    GlobalSearchOptions options;
    options.lattice_spacing = nb.quick() ? 2.0 : 1.0;
    options.candidates = 3;
    const GlobalSearchResult result = global_search(terrain, rover, start, goal, options);
    if (result.status != GlobalSearchStatus::kOk) throw Error(result.message);
    nb.say("From (" + num("%.0f", start.x()) + ", " + num("%.0f", start.y()) + ") to (" +
           num("%.0f", goal.x()) + ", " + num("%.0f", goal.y()) +
           ") m on the rover-scale West "
           "Bijou terrain, lattice spacing " +
           num("%.0f", options.lattice_spacing) + " m: " + std::to_string(result.nodes) +
           " nodes, " + std::to_string(result.edges_evaluated) + " edges evaluated, " +
           num("%.2f", result.search_seconds) + " s.");

    Table table({"candidate", "J [s]", "length [m]", "lattice vertices"});
    std::vector<Route> routes;
    const char* colours[] = {"#e6550d", "#2c7fb8", "#31a354", "#756bb1"};
    bool ordered = true, within_ratio = true, optimistic = true;
    const double straight = (result.goal_node - result.start_node).norm() / rover.max_speed;
    for (std::size_t k = 0; k < result.candidates.size(); ++k) {
      const CandidatePath& c = result.candidates[k];
      table.row({std::to_string(k), num("%.2f", c.cost_seconds), num("%.1f", c.length_m),
                 std::to_string(c.vertices.size())});
      routes.push_back(
          {"candidate " + std::to_string(k) + ": J = " + num("%.2f", c.cost_seconds) + " s",
           c.vertices, std::string("lines lw 3 lc rgb '") + colours[k % 4] + "'"});
      if (k > 0) ordered = ordered && c.cost_seconds >= result.candidates[k - 1].cost_seconds;
      within_ratio = within_ratio &&
                     c.cost_seconds <= options.max_cost_ratio * result.candidates[0].cost_seconds;
      optimistic = optimistic && c.cost_seconds >= straight;
    }
    nb.table(table);
    nb.say("The escarpment is gentle for the rover at this scale: the best J is only " +
           num("%.1f", 100.0 * (result.candidates[0].cost_seconds / straight - 1.0)) +
           " % above the straight line at top speed, and the alternatives cost little more. "
           "They differ in where they cross the slope, which the local stage will judge with "
           "the real profile.");
    nb.figure("Distinct candidate corridors over the shaded relief",
              nb.map("candidates", "Global candidates (cost J = ∫ ds / v_max)", terrain, routes));
    nb.check(ordered, "the candidates come best first");
    nb.check(within_ratio, "every candidate costs at most max_cost_ratio = " +
                               num("%g", options.max_cost_ratio) + " times the best");
    nb.check(optimistic, "no candidate beats the straight line at top speed (" +
                             num("%.2f", straight) + " s): J is a time, not a score");
    if (result.candidates.size() > 1) {
      const double d =
          hausdorff_distance(result.candidates[0].vertices, result.candidates[1].vertices);
      nb.say("Candidates 0 and 1 are " + num("%.1f", d) +
             " m apart (Hausdorff distance): distinct routes, not one corridor twice.");
      nb.check(d >= default_candidate_separation(result.start_node, result.goal_node,
                                                 options.lattice_spacing) /
                        1.1,
               "they are at least the separation d apart (within the lattice's 8 % chamfer "
               "approximation)");
    }

    nb.section("The same best route, cheaper");
    nb.say(
        "Several candidates need both cost-to-go fields over the whole lattice (Dijkstra "
        "from the start and from the goal). For one candidate A* suffices: its heuristic, "
        "the straight-line distance at top speed, never overestimates, so it finds the "
        "same optimum while evaluating fewer edges. Coarse-to-fine search (`kMulti`) "
        "restricts the fine lattice to a corridor around a coarse search's routes.");
    GlobalSearchOptions astar = options;
    astar.candidates = 1;
    astar.cost_fields = false;
    const GlobalSearchResult one = global_search(terrain, rover, start, goal, astar);
    GlobalSearchOptions multi = options;
    multi.candidates = 1;
    multi.resolution = GlobalSearchResolution::kMulti;
    const GlobalSearchResult coarse = global_search(terrain, rover, start, goal, multi);
    Table modes({"search", "best J [s]", "edges evaluated", "seconds"});
    modes.row({"Dijkstra, both fields", num("%.4f", result.candidates[0].cost_seconds),
               std::to_string(result.edges_evaluated), num("%.3f", result.search_seconds)});
    modes.row({"A*, one candidate", num("%.4f", one.candidates.at(0).cost_seconds),
               std::to_string(one.edges_evaluated), num("%.3f", one.search_seconds)});
    modes.row({"coarse to fine", num("%.4f", coarse.candidates.at(0).cost_seconds),
               std::to_string(coarse.edges_evaluated), num("%.3f", coarse.search_seconds)});
    nb.table(modes);
    const double best = result.candidates[0].cost_seconds;
    nb.check(std::abs(one.candidates[0].cost_seconds - best) <= 1e-9 * best,
             "A* finds the same minimum J as Dijkstra");
    nb.check(one.edges_evaluated < result.edges_evaluated, "and evaluates fewer edges");
    nb.check(coarse.candidates[0].cost_seconds >= best * (1 - 1e-12),
             "coarse to fine is never better than the full lattice's optimum (it searches a "
             "corridor of the same lattice)");
    return nb.finish();
  });
}
