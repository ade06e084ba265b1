#pragma once
/// @file
/// Every planner Talus implements behind BaselinePlanner: the kinematic
/// baselines (BaselineRegistry::builtin(): hait, dacre-wright,
/// eldershaw-yim), Iagnemma–Shimoda–Shiller's navigation ("iagnemma",
/// navigation/iagnemma_baseline.hpp) and Talus's own two-stage planner
/// ("talus", talus_planner.hpp). The CLI's `talus baseline NAME` and the conformance
/// suite reach each of them through it.
#include "talus/kinematic/baseline_registry.hpp"

namespace talus {

/// BaselineRegistry::builtin()'s entries, then "iagnemma" and "talus".
const BaselineRegistry& planner_registry();

}  // namespace talus
