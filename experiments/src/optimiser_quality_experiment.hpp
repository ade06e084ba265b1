#pragma once
/// @file
/// `talus experiment optimiser-quality` (issue #12, item 6): how good the
/// planner's local stage is. On the fractal battery (fractal_battery.hpp,
/// point-mass UGV) and on every bundled DEM (rover, 10 % -> 90 % of the
/// diagonal): the default plan's success, the fraction of local
/// optimisations that converge by the solver's own status, its travel time
/// against a multistart reference (the best plan over formulations × solvers
/// × 8-24 control points, with restarts and the polish; on the DEMs, the
/// default with the polish), its planning time, and a
/// verification of every best trajectory (verify_profile and a fresh
/// evaluation of its curve). Per configuration: the nested-against-
/// simultaneous table. Quick mode: two battery seeds, a reduced reference.
#include "experiment.hpp"

namespace talus::experiments {

void run_optimiser_quality(const ExperimentContext& context);

}  // namespace talus::experiments
