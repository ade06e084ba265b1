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

/// `talus experiment eldershaw-parallel`: the spider's tree-PRM query of
/// eldershaw-plan (more heading slices and a wider connect radius, so the
/// local-planner calls dominate) on 1, 2 and 4 worker threads and on 2 MPI
/// ranks (this program under mpirun, when installed): the same plan
/// everywhere, the median search time of 3 runs, the speed-up and the peak
/// memory, beside the paper's "five modules roughly halved the planning time".
void run_eldershaw_parallel(const ExperimentContext& context);

}  // namespace talus::experiments
