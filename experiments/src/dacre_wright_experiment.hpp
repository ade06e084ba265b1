#pragma once
/// @file
/// `talus experiment dacre-wright-octree`: the free-space structuring of
/// Dacre-Wright and Siméon 1993 on a seeded 64 × 64 rough terrain with the
/// six-wheel robot (figures 4 and 5, the per-level table, the effect of p0,
/// incremental search against the whole octree).
#include "experiment.hpp"

namespace talus::experiments {

void run_dacre_wright_octree(const ExperimentContext& context);

}  // namespace talus::experiments
