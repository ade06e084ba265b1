#include "talus/optimal/local_stage_summary.hpp"

#include <cmath>

namespace talus {

LocalStageSummary summarise_local_stage(const PlannerResult& result) {
  LocalStageSummary sum;
  for (const CandidateOutcome& c : result.candidates) {
    if (!c.optimization) continue;
    const OptimizedPath& o = *c.optimization;
    ++sum.optimised;
    sum.evaluations += o.evaluations;
    sum.iterations += o.iterations;
    sum.gradient_evaluations += o.gradient_evaluations;
    sum.finite_difference_fallbacks += o.finite_difference_fallbacks;
    if (std::isfinite(o.optimality) && !(o.optimality <= sum.worst_optimality))
      sum.worst_optimality = o.optimality;
  }
  return sum;
}

}  // namespace talus
