#pragma once
/// @file
/// dynamic-vs-kinematic: the Haït–Siméon–Taïx kinematic path followed at its
/// own time-optimal velocity profile (path–velocity decomposition) against
/// Talus's time-optimal plan, on the terrains of the hait-* experiments.
#include "experiment.hpp"

namespace talus::experiments {

/// Writes `<out>/dynamic-vs-kinematic/`: comparison.csv, a map per terrain and report.md.
void run_dynamic_vs_kinematic(const ExperimentContext& context);

}  // namespace talus::experiments
