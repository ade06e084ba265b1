// talus/optimal/local_stage_summary.hpp: totals over a plan's optimised candidates.
#include <gtest/gtest.h>

#include <cmath>

#include "talus/optimal/local_stage_summary.hpp"

namespace talus {
namespace {

CandidateOutcome optimised(std::size_t evaluations, std::size_t iterations, std::size_t gradients,
                           std::size_t fallbacks, double optimality) {
  OptimizedPath o(Curve2::interpolate({Vec2(0, 0), Vec2(1, 0)}));
  o.evaluations = evaluations;
  o.iterations = iterations;
  o.gradient_evaluations = gradients;
  o.finite_difference_fallbacks = fallbacks;
  o.optimality = optimality;
  CandidateOutcome c;
  c.optimization = o;
  return c;
}

TEST(LocalStageSummary, SumsTheOptimisedCandidates) {
  PlannerResult r;
  r.candidates.push_back(optimised(10, 4, 8, 1, 2e-3));
  r.candidates.push_back(CandidateOutcome{});  // refused by the optimiser: adds nothing
  r.candidates.push_back(optimised(7, 3, 5, 0, std::nan("")));
  r.candidates.push_back(optimised(1, 1, 1, 2, 5e-4));
  const LocalStageSummary s = summarise_local_stage(r);
  EXPECT_EQ(s.optimised, 3u);
  EXPECT_EQ(s.evaluations, 18u);
  EXPECT_EQ(s.iterations, 8u);
  EXPECT_EQ(s.gradient_evaluations, 14u);
  EXPECT_EQ(s.finite_difference_fallbacks, 3u);
  EXPECT_EQ(s.worst_optimality, 2e-3);  // the NaN one is skipped
}

TEST(LocalStageSummary, NothingOptimised) {
  PlannerResult r;
  r.candidates.push_back(CandidateOutcome{});
  const LocalStageSummary s = summarise_local_stage(r);
  EXPECT_EQ(s.optimised, 0u);
  EXPECT_EQ(s.evaluations, 0u);
  EXPECT_TRUE(std::isnan(s.worst_optimality));
  PlannerResult nan_only;
  nan_only.candidates.push_back(optimised(1, 1, 1, 0, std::nan("")));
  EXPECT_TRUE(std::isnan(summarise_local_stage(nan_only).worst_optimality));
}

}  // namespace
}  // namespace talus
