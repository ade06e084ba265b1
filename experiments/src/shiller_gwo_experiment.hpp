#pragma once
/// @file
/// `talus experiment shiller-gwo`: the two-stage planner of Shiller & Gwo
/// (1991) reproduced end to end on a bundled real DEM and on a fractal
/// terrain — global candidates, local optima, the best trajectory and its
/// profile — with a comparison of the local solvers (Ipopt against NLopt
/// LBFGS and BOBYQA: time to solution and final travel time on the same
/// cases) and the control-point study behind PathOptimizerOptions'
/// default.
#include "experiment.hpp"

namespace talus::experiments {

void run_shiller_gwo(const ExperimentContext& context);

}  // namespace talus::experiments
