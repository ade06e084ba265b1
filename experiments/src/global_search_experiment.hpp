#pragma once
#include "experiment.hpp"

namespace talus::experiments {

/// global-search: the global minimum-time search (J = ∫ ds / v_max on a
/// 16-connected lattice, with the tangential untraversability rules) across
/// Mount St. Helens at its true 30 m scale, for a car-like point mass at tyre
/// friction 0.7 and 0.35: the distinct candidate corridors over shaded relief,
/// the cost-to-go fields whose valleys they follow, and how the best route
/// changes when the friction halves (the analogue of the global-optimal-path
/// figure of Iagnemma–Shimoda–Shiller 2008).
void run_global_search_experiment(const ExperimentContext& context);

}  // namespace talus::experiments
