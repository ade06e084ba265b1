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

/// `sweep-dynamic-vs-kinematic` (data/sweeps/sweep-dynamic-vs-kinematic.yaml and
/// sweep-dynamic-vs-kinematic-talus.yaml, paired case by case on their terrain.* and vehicle.*
/// parameters): the Haït path at its own time-optimal profile (`talus baseline hait --vehicle`)
/// against Talus's plan over roughness × μ — the time ratio and the planning-time ratio — and
/// the invariants: the kinematic path does not depend on μ, and its profile is never slower
/// with more friction.
void run_sweep_dynamic_vs_kinematic(const ExperimentContext& context);

/// `sweep-baselines`: Talus's plans (the Talus half of sweep-dynamic-vs-kinematic) against
/// every registered kinematic baseline's path at its time-optimal profile (hait: the
/// sweep-dynamic-vs-kinematic configuration; dacre-wright: sweep-baselines-dacre-wright.yaml,
/// whose sideways-moving paths are driven along a fitted cubic), per baseline: paths found,
/// time ratio and planning-time ratio by roughness, and the same invariants.
void run_sweep_baselines(const ExperimentContext& context);

}  // namespace talus::experiments
