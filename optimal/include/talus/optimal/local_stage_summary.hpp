#pragma once
/// @file
/// Totals of the local stage of a plan (talus::plan): the solver work summed
/// over the optimised candidates and the worst first-order optimality, the
/// figures a solver comparison reports.
#include <cstddef>
#include <limits>

#include "talus/optimal/planner.hpp"

namespace talus {

/// Sums over the candidates of a PlannerResult that have an optimisation
/// (CandidateOutcome::optimization); candidates the optimiser refused add nothing.
struct LocalStageSummary {
  std::size_t optimised = 0;                    ///< candidates with an optimisation
  std::size_t evaluations = 0;                  ///< objective evaluations
  std::size_t iterations = 0;                   ///< Ipopt iterations; NLopt: evaluations
  std::size_t gradient_evaluations = 0;         ///< gradients asked for
  std::size_t finite_difference_fallbacks = 0;  ///< gradients taken by finite differences
  /// Largest finite per-candidate optimality (OptimizedPath::optimality)
  /// [s/m]; NaN when no candidate has one.
  double worst_optimality = std::numeric_limits<double>::quiet_NaN();
};

/// The local-stage totals of `result`.
LocalStageSummary summarise_local_stage(const PlannerResult& result);

}  // namespace talus
