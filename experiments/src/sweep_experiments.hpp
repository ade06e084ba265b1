#pragma once
/// @file
/// Experiments that are sweeps: each runs a configuration from the data
/// folder's sweeps/ with run_sweep (threads = the core count) and reports
/// on the family of results.
#include "experiment.hpp"

namespace talus::experiments {

/// `sweep-friction-stability` (data/sweeps/sweep-friction-stability.yaml):
/// the rover over friction μ × stability b/h × roughness — success, travel
/// time and what binds the plan, and the invariants the physics implies (the
/// lattice's minimum time cannot rise with μ nor fall with h).
void run_sweep_friction_stability(const ExperimentContext& context);

}  // namespace talus::experiments
