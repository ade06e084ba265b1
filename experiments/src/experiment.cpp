#include "experiment.hpp"

#include <cstdlib>

#include "closed_loop_experiment.hpp"
#include "dacre_wright_experiment.hpp"
#include "dynamic_vs_kinematic_experiment.hpp"
#include "eldershaw_yim_experiment.hpp"
#include "global_search_experiment.hpp"
#include "hait_experiments.hpp"
#include "iagnemma_table1_experiment.hpp"
#include "model_agreement_experiment.hpp"
#include "optimal_profile_experiment.hpp"
#include "optimiser_quality_experiment.hpp"
#include "shiller_gwo_experiment.hpp"
#include "sweep_experiments.hpp"
#include "talus/core/error.hpp"
#include "terrain_gallery.hpp"
#include "velocity_limits_experiment.hpp"

namespace talus::experiments {

std::vector<Experiment> all_experiments() {
  return {
      {"terrain-gallery",
       "every bundled DEM and a fractal terrain as shaded relief with contours, and the "
       "smoothing B-patch fit's residual map",
       run_terrain_gallery},
      {"velocity-limits",
       "speed limits of each constraint, the binding one and the acceleration bounds along a "
       "path across the West Bijou escarpment, at DEM and at rover scale",
       run_velocity_limits},
      {"optimal-profile",
       "the time-optimal velocity profile under the limit curve, with switching points and "
       "acceleration bounds, along a curved path on the rover-scale West Bijou DEM, and its "
       "convergence in the number of stations",
       run_optimal_profile},
      {"global-search",
       "the global minimum-time search across Mount St. Helens at true scale for a car-like "
       "vehicle at friction 0.7 and 0.35: distinct candidate corridors over shaded relief, the "
       "cost-to-go fields and how the best route changes with friction",
       run_global_search_experiment},
      {"shiller-gwo",
       "the two-stage time-optimal planner (global candidates, B-spline local optima, best "
       "trajectory and profile) on the West Bijou DEM and a fractal terrain, Ipopt against "
       "NLopt LBFGS and BOBYQA, and the control-point study",
       run_shiller_gwo},
      {"hait-heuristics",
       "Hait-Simeon-Taix planner, the three search guidances on one problem (nodes created, "
       "developed, placements, search time) beside the paper's table",
       run_hait_heuristics},
      {"hait-preprocessing",
       "Hait-Simeon-Taix preprocessing time (chassis placement table, quadtree, potential "
       "bitmap) against terrain size and resolution, with fitted exponents",
       run_hait_preprocessing},
      {"hait-smoothing",
       "Hait-Simeon-Taix Reeds-Shepp smoothing: control changes before and after, path drawn "
       "before and after",
       run_hait_smoothing},
      {"hait-uncertainty",
       "Hait-Simeon-Taix planning with position and terrain uncertainty: the route avoids a "
       "gorge, and the preprocessing cost ratio",
       run_hait_uncertainty},
      {"dynamic-vs-kinematic",
       "the Hait-Simeon-Taix kinematic path at its own time-optimal profile against Talus's "
       "time-optimal plan: travel times, ratio and planning times on the hait terrains",
       run_dynamic_vs_kinematic},
      {"dacre-wright-octree",
       "Dacre-Wright-Simeon free-space structuring: the (x, y, theta) octree of admissible "
       "voxels on a 64 x 64 rough terrain (FREE voxels at four headings, voxels per level, the "
       "effect of p0), an incremental search against the whole octree, Proposition 1 sampled",
       run_dacre_wright_octree},
      {"eldershaw-footmap",
       "Eldershaw-Yim legged vehicles: footmap and CGmap at theta = 0 (Fig. 4 and 6) for the "
       "spider and the Ambler-like walker on the generated test terrain, counts of invalid "
       "foot nodes, invalid CG cells, straddled regions and black-border cells, and the "
       "paper's claims checked one by one",
       run_eldershaw_footmap},
      {"eldershaw-plan",
       "Eldershaw-Yim legged vehicles: the full route across the test terrain for the spider "
       "and the Ambler-like walker, tree-PRM against direct A* (local-planner calls, CG cells "
       "materialised, time, length), the foot plan and its section 3.3 feedback",
       run_eldershaw_plan},
      {"eldershaw-parallel",
       "Eldershaw-Yim legged vehicles: the tree-PRM's local-planner calls on 1, 2 and 4 threads "
       "and on 2 MPI ranks (mpirun, when installed): the same plan, search-time speed-up and "
       "peak memory beside the paper's five modules halving the planning time",
       run_eldershaw_parallel},
      {"sweep-friction-stability",
       "a sweep of the rover's plans over friction x stability (b/h) x roughness on a fractal "
       "terrain: success, travel time, binding-constraint shares, and the monotonicity the "
       "physics implies",
       run_sweep_friction_stability},
      {"sweep-dynamic-vs-kinematic",
       "a sweep of the Hait-Simeon-Taix path at its own time-optimal profile against Talus's "
       "plan over terrain roughness x friction: time ratio, planning-time ratio, invariants",
       run_sweep_dynamic_vs_kinematic},
      {"sweep-baselines",
       "a sweep of Talus's plans against every registered kinematic baseline's path at its "
       "time-optimal profile over roughness x friction: paths found, time and planning-time "
       "ratios, invariants",
       run_sweep_baselines},
      {"closed-loop-plans",
       "the planner's trajectories for the Iagnemma UGV on the fractal battery driven by the "
       "rigid-body simulation at 90, 100 and 110 % of their profile speed: failures, margins "
       "kept and travel time against the plan; each plan's largest drivable speed scale s*",
       run_closed_loop_plans},
      {"model-agreement",
       "canonical manoeuvres (flat and banked circle, crest, side slope, straight drive and "
       "brake) planned for the Iagnemma UGV and driven by the rigid-body simulation at several "
       "speed scales: planned limit against the closed form, the simulator's friction and "
       "contact utilisation against the scale, the largest scale still driven",
       run_model_agreement},
      {"iagnemma-table1",
       "Table I of Iagnemma-Shimoda-Shiller (IROS 2008): near-optimal (model-based lookahead) "
       "against standard potential-field navigation of the paper's UGV on 25 fractal terrains "
       "under the layered scheme: incidence of failure and increase over the optimal time, "
       "beside the paper's, per-terrain rows and figures 7-9",
       run_iagnemma_table1},
      {"optimiser-quality",
       "the planner's local stage on the fractal battery and every bundled DEM against a "
       "multistart reference (formulations x solvers x 8-16 control points x restarts x polish): "
       "success, convergence by solver status, travel time above the reference, planning time, the "
       "nested-against-simultaneous table",
       run_optimiser_quality},
  };
}

std::filesystem::path find_data_dir(const std::string& explicit_dir) {
  namespace fs = std::filesystem;
  const auto has_terrain = [](const fs::path& dir) { return fs::is_directory(dir / "terrain"); };
  if (!explicit_dir.empty()) {
    if (!has_terrain(explicit_dir)) {
      throw InputError("data folder '" + explicit_dir + "' has no terrain/ subfolder");
    }
    return explicit_dir;
  }
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("TALUS_DATA_DIR")) candidates.emplace_back(env);
  candidates.emplace_back(TALUS_SOURCE_DATA_DIR);
  candidates.emplace_back(TALUS_INSTALL_DATA_DIR);
  for (const fs::path& dir : candidates) {
    if (has_terrain(dir)) return dir;
  }
  throw InputError(
      "cannot find the bundled data (terrain/*.asc): pass --data DIR or set TALUS_DATA_DIR");
}

}  // namespace talus::experiments
