// Notebook 09 — the third kinematic baseline: the legged-vehicle planner of
// Eldershaw and Yim (ICRA 2001). Leg range and reach, not a slope threshold,
// decide where a walker can stand: a footmap of the ground a foot grips, a
// CGspace of the body positions some foot supports in every quadrant, a
// tree-PRM of A* searches over it, and the footsteps along the route.
//
//   build/notebooks_cpp/09_eldershaw_yim_baseline [--quick] [--out DIR] [--data DIR]
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "notebook.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/eldershaw_yim/cg_space.hpp"
#include "talus/kinematic/eldershaw_yim/eldershaw_yim_planner.hpp"
#include "talus/kinematic/eldershaw_yim/foot_planner.hpp"
#include "talus/kinematic/eldershaw_yim/footmap.hpp"
#include "talus/kinematic/eldershaw_yim/legged_robot.hpp"

using namespace talus;
using namespace talus::notebooks;

namespace {

/// Whether consecutive cells differ by one step along exactly one axis (θ wraps).
bool six_connected(const std::vector<CgCell>& cells, int theta_slices) {
  for (std::size_t k = 1; k < cells.size(); ++k) {
    const int dx = std::abs(cells[k].ix - cells[k - 1].ix);
    const int dy = std::abs(cells[k].iy - cells[k - 1].iy);
    int dt = std::abs(cells[k].it - cells[k - 1].it);
    dt = std::min(dt, theta_slices - dt);
    if (dx + dy + dt != 1) return false;
  }
  return true;
}

/// Every foot in contact stands on ground it grips and inside its leg's
/// range, the range read in the body frame of the step's CG pose.
bool feet_where_the_robot_allows(const FootPlan& plan, const Footmap& footmap,
                                 const LeggedRobot& robot) {
  for (const FootStep& step : plan.steps) {
    const double c = std::cos(step.cg.theta), s = std::sin(step.cg.theta);
    for (std::size_t leg = 0; leg < step.feet.size(); ++leg) {
      const FootState& foot = step.feet[leg];
      if (!foot.contact) continue;
      if (!footmap.valid(foot.i, foot.j)) return false;
      const Vec3 p = foot_position(footmap, foot);
      const Vec2 d(p.x() - step.cg.x, p.y() - step.cg.y);
      if (!robot.legs[leg].in_range({c * d.x() + s * d.y(), -s * d.x() + c * d.y()})) return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  return run([&] {
    Notebook nb(argc, argv, "09_eldershaw_yim_baseline", "09 · The Eldershaw–Yim baseline");

    nb.section("The idea: legs decide where a walker can stand");
    nb.say(
        "A wheeled vehicle needs the ground under its wheels; a legged one needs ground its "
        "feet can reach. Eldershaw and Yim (ICRA 2001) describe a walker by its legs: each "
        "has a *range* (the polygon of the body's plane where its foot may go) and a *reach* "
        "(how far below the body's zero plane the foot can press), and the body has an "
        "under-carriage (how far its underside hangs). A cliff is impassable only when no "
        "leg reaches from its foot to its top; a patch of ground no foot grips can be "
        "straddled by legs long enough to step over it.");
    nb.say(
        "Three layers follow. The *footmap* marks the terrain nodes a foot grips (slope at "
        "most the robot's traction slope). *CGspace* is a lattice of body positions (x, y, θ) "
        "at the foot print's resolution: a cell is valid when each of the four quadrants "
        "around the CG holds some valid foot position inside some leg's range whose height "
        "plus the leg's reach clears the under-carriage's lowest point over the ground "
        "(MinHeight). The high-level planner is a tree-PRM over CGspace whose edges are A* "
        "searches on small blocks (or one A* over everything, the paper's 'large server' "
        "mode); the foot-level planner then walks the CG route move by move.");

    nb.section("The paper's test terrain and two robots");
    EldershawYimOptions t;
    t.shape = nb.quick() ? GridShape{81, 81, 0.3, 0.0, 0.0} : GridShape{121, 121, 0.2, 0.0, 0.0};
    t.seed = 2001;
    const ElevationGrid grid = generate_eldershaw_yim(t);
    const RuledTerrain terrain(grid);
    nb.say(
        "The `eldershaw-yim` generator (seed 2001): a 24 m square with a central plateau "
        "1 m high whose east side is a cliff, ringed by nine sharp peaks, on " +
        std::to_string(grid.ncols()) + " × " + std::to_string(grid.nrows()) +
        " nodes. The robots are `data/robots/eldershaw_spider.yaml` (eight legs, a 0.5 m "
        "body, ranges 0.3–0.9 m from the CG, reach 0.3 m) and "
        "`data/robots/eldershaw_ambler.yaml` (six long legs with large overlapping ranges); "
        "the paper gives no dimensions, so these are invented and documented in the files.");

    const SE2Pose start{4, 4, 0}, goal{20, 20, 0};
    struct Walker {
      std::string name;
      LeggedRobot robot;
      EldershawYimResult prm, direct;
    };
    std::vector<Walker> walkers;
    Table maps({"robot", "footmap: nodes no foot grips", "CGmap θ = 0: cells",
                "no support in a quadrant", "legs too short", "off the data"});
    for (const auto& [name, file] : {std::pair{"spider", "robots/eldershaw_spider.yaml"},
                                     std::pair{"ambler", "robots/eldershaw_ambler.yaml"}}) {
      Walker w{name, load_legged_robot(nb.data(file)), {}, {}};
      const Footmap footmap(terrain, w.robot);
      const CgLattice lattice(grid, w.robot.foot_print, 16);
      const std::vector<CgState> slice = evaluate_cg_slice(footmap, w.robot, lattice, 0);
      const auto count = [&slice](CgState state) {
        return std::to_string(std::count(slice.begin(), slice.end(), state));
      };
      maps.row({name, std::to_string(footmap.invalid_count()), std::to_string(slice.size()),
                count(CgState::kNoSupport), count(CgState::kTooShort), count(CgState::kOffData)});
      EldershawYimPlannerOptions o;
      o.prm_points = nb.quick() ? 100 : 200;
      o.feet.budget = nb.quick() ? 5000 : 20000;
      w.prm = plan_eldershaw_yim(terrain, w.robot, start, goal, o);
      o.direct = true;
      w.direct = plan_eldershaw_yim(terrain, w.robot, start, goal, o);
      walkers.push_back(std::move(w));
    }
    nb.table(maps);
    nb.say(
        "The footmaps differ only through the traction slopes. The CGmaps differ far more, "
        "and for the paper's reasons: a cell fails when some quadrant has no foothold in any "
        "leg's range (*no support*) or when every foothold there is out of reach of the "
        "ground under the body (*legs too short*, at the cliff and the peaks). The "
        "Ambler-like walker's long, overlapping legs straddle what stops the spider (the "
        "eldershaw-footmap experiment draws both maps and checks the paper's claims one by "
        "one).");

    nb.section("Routes: tree-PRM against one direct A*");
    Table runs({"robot", "mode", "status", "length [m]", "local-planner calls",
                "CG cells materialised", "foot plan"});
    std::vector<Route> routes;
    for (const Walker& w : walkers) {
      for (const auto* r : {&w.prm, &w.direct}) {
        const std::string mode = r == &w.prm ? "tree-PRM" : "direct A*";
        runs.row({w.name, mode, to_string(r->status), num("%.2f", r->length_m),
                  std::to_string(r->local_planner_calls),
                  std::to_string(r->cells_materialised) + " of " + std::to_string(r->cg_cells),
                  r->feet_planned ? std::string(to_string(r->foot_plan.status)) + ", " +
                                        std::to_string(r->foot_plan.steps.size()) + " steps"
                                  : "none"});
      }
      std::vector<Vec2> points;
      for (const SE2Pose& q : w.direct.path) points.push_back(q.position());
      routes.push_back(
          {w.name + " (direct A*): " + num("%.1f", w.direct.length_m) + " m", points,
           w.name == "spider" ? "lines lw 3 lc rgb '#e6550d'" : "lines lw 3 lc rgb '#2c7fb8'"});
    }
    nb.table(runs);
    nb.say(
        "The tree-PRM joins random valid CG cells with A* searches confined to a block a "
        "little larger than the two cells' bounding box, and keeps its trees as separate "
        "lists until the start's and the goal's merge; the direct mode spends more CGspace "
        "on one search but finds the route that is shortest in its metric. Only the blocks "
        "a search touched are materialised, a fraction of the whole lattice.");
    const BPatch surface = BPatch::interpolate(grid);
    nb.say(
        "Over the map, the difference is the paper's point: the Ambler-like walker's route "
        "runs straight over the peaks in its way, its legs straddling them, while the "
        "spider's threads between them. Both routes are staircases because CGspace is "
        "6-connected: their length is measured along the cells, which is why equal lengths "
        "can hide different routes.");
    nb.figure("The two walkers' direct routes over the test terrain",
              nb.map("routes", "Eldershaw–Yim: CG routes of the spider and the Ambler-like walker",
                     surface, routes));

    nb.section("Checking what it claims");
    const Walker& spider = walkers[0];
    const Walker& ambler = walkers[1];
    bool all_found = true;
    for (const Walker& w : walkers) all_found = all_found && w.prm.found() && w.direct.found();
    nb.check(all_found, "both robots find a route in both modes");
    if (!all_found) return nb.finish();
    bool connected = true;
    for (const Walker& w : walkers) {
      connected = connected && six_connected(w.prm.cells, 16) && six_connected(w.direct.cells, 16);
    }
    nb.check(connected, "every CG route steps one cell at a time along x, y or θ (6-adjacency)");
    nb.check(spider.prm.length_m >= spider.direct.length_m - 1e-9 &&
                 ambler.prm.length_m >= ambler.direct.length_m - 1e-9,
             "no tree-PRM route is shorter than the direct A*'s, which is optimal in its metric");
    nb.check(ambler.direct.length_m <= spider.direct.length_m + 1e-9,
             "the Ambler-like walker's route is no longer than the spider's: it can stand "
             "wherever the spider can and more");
    bool feet_ok = true;
    for (const Walker& w : walkers) {
      if (!w.direct.feet_planned || !w.direct.foot_plan.found()) continue;
      feet_ok = feet_ok &&
                feet_where_the_robot_allows(w.direct.foot_plan, Footmap(terrain, w.robot), w.robot);
    }
    nb.check(feet_ok,
             "along every found foot plan, each foot in contact grips its node and lies inside "
             "its leg's range (checked here from the robot file, not by the planner)");
    EldershawYimPlannerOptions o;
    o.prm_points = nb.quick() ? 100 : 200;
    o.feet.budget = nb.quick() ? 5000 : 20000;
    const EldershawYimResult again = plan_eldershaw_yim(terrain, spider.robot, start, goal, o);
    nb.check(again.cells == spider.prm.cells &&
                 again.local_planner_calls == spider.prm.local_planner_calls,
             "a rerun with the same seed gives the same tree-PRM route and counters");
    return nb.finish();
  });
}
