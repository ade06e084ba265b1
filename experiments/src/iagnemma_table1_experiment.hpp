#pragma once
/// @file
/// `talus experiment iagnemma-table1` (issue #16): Table I of Iagnemma,
/// Shimoda & Shiller (IROS 2008, §V). On 25 seeded fractal terrains (the
/// battery of fractal_battery.hpp: D 2.05, 0.24 m = two wheel diameters,
/// height scale 4.2 m = 35 wheel diameters, undulation and peaks) the
/// paper's UGV (data/vehicles/iagnemma_ugv.yaml) runs the layered scheme
/// (navigate_layered: Talus's plan on the terrain decimated 4×, its
/// trajectory as waypoints, potential-field navigation on the fine terrain
/// with hazards detected from it) twice: with the model-based lookahead
/// ("near-optimal") and without ("standard"). Written: results.csv
/// (terrain,method,status,failure,navigation_time,optimal_time), the table
/// beside the paper's (incidence of failure, mean increase over the optimal
/// time), the per-terrain rows, and figures 7–9 of a representative run.
#include "experiment.hpp"

namespace talus::experiments {

void run_iagnemma_table1(const ExperimentContext& context);

}  // namespace talus::experiments
