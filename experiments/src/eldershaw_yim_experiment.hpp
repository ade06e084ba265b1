#pragma once
/// @file
/// `talus experiment eldershaw-footmap`: the footmap and CGmap (θ = 0) of
/// Eldershaw and Yim 2001 (figures 4 and 6) for the eight-legged spider and
/// the Ambler-like walker on the `eldershaw-yim` test terrain (nine sharp
/// peaks round a central plateau with a cliff), with the counts of invalid
/// foot nodes, invalid CG cells, straddled invalid-foot regions and "black
/// border" cells, and the paper's qualitative claims checked one by one.
#include "experiment.hpp"

namespace talus::experiments {

void run_eldershaw_footmap(const ExperimentContext& context);

}  // namespace talus::experiments

namespace talus::experiments {

/// `talus experiment eldershaw-plan`: the full route across the same terrain
/// for both vehicles, tree-PRM against direct A* (local-planner calls, CG
/// cells materialised, time, length), the foot plan along each route
/// (steps, §3.3 feedback events) and the routes with footprints.
void run_eldershaw_plan(const ExperimentContext& context);

}  // namespace talus::experiments
