#pragma once
/// @file
/// The declared parameters of talus::plan (PlannerOptions): each option a
/// user tunes, declared here once with its bounds and documentation, its
/// default being PlannerOptions{}'s. `talus plan`'s options and their checks,
/// the `options` echo in its summary.json, Python's PlannerOptions(**kwargs)
/// and attributes, and a sweep's `plan` parameter names are all generated
/// from this table; PlannerOptions::validate() checks its bounds. Adding a
/// planner option to every front end is one entry in planner_parameters.cpp.
///
/// Problem data (start, goal, their speeds and headings) is in
/// PlanningProblem, not here; `optimize` is `talus plan --stage`.
#include "talus/core/parameter_table.hpp"
#include "talus/optimal/planner.hpp"

namespace talus {

/// Largest control-point count of a local-stage fit the front ends accept.
inline constexpr long long kMaxPlannerControlPoints = 64;

/// The table (built once; thread-safe to read).
const ParameterTable<PlannerOptions>& planner_parameters();

}  // namespace talus
