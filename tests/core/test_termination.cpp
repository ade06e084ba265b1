// Termination (core/termination.hpp): time budgets armed once, stop predicates,
// their combination, and bad budgets.
#include "talus/core/termination.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "talus/core/error.hpp"

namespace talus {
namespace {

TEST(Termination, TheDefaultNeverHolds) {
  const Termination never;
  EXPECT_TRUE(never.never());
  EXPECT_EQ(never.start().check(), TerminationReason::kNone);
  EXPECT_EQ(never.smallest_budget(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(never.remaining(), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(Termination::time_budget(std::numeric_limits<double>::infinity()).never());
  EXPECT_TRUE(Termination::when({}).never());
}

TEST(Termination, ABudgetHoldsFromItsDeadlineOnAndOnlyOnceArmed) {
  double now = 100.0;
  const Termination budget = Termination::time_budget(2.0, [&now] { return now; });
  EXPECT_EQ(budget.smallest_budget(), 2.0);
  now = 1e9;
  EXPECT_EQ(budget.check(), TerminationReason::kNone);  // not armed: options do not age
  now = 100.0;
  const Termination armed = budget.start();
  EXPECT_EQ(armed.remaining(), 2.0);
  now = 101.999;
  EXPECT_FALSE(armed.should_stop());
  now = 102.0;
  EXPECT_EQ(armed.check(), TerminationReason::kTimeLimit);
  EXPECT_EQ(to_string(armed.check()), "time_limit");
  // A stage that starts it again keeps the deadline armed before.
  now = 101.0;
  const Termination again = armed.start();
  now = 102.0;
  EXPECT_TRUE(again.should_stop());
}

TEST(Termination, CombinedConditionsHoldWhenEitherDoesAndNameTheFirst) {
  double now = 0.0;
  bool requested = false;
  const Termination both = Termination::time_budget(5.0, [&now] { return now; }) |
                           Termination::when([&requested] { return requested; });
  const Termination armed = both.start();
  EXPECT_EQ(armed.check(), TerminationReason::kNone);
  requested = true;
  EXPECT_EQ(armed.check(), TerminationReason::kStopRequested);
  EXPECT_EQ(to_string(armed.check()), "stop_requested");
  now = 10.0;  // both hold: the budget was given first
  EXPECT_EQ(armed.check(), TerminationReason::kTimeLimit);
  requested = false;
  EXPECT_EQ(armed.check(), TerminationReason::kTimeLimit);
  // Two budgets: the smaller is "the time limit" and the earlier deadline.
  const Termination two = Termination::time_budget(7.0, [&now] { return now; }) |
                          Termination::time_budget(3.0, [&now] { return now; });
  EXPECT_EQ(two.smallest_budget(), 3.0);
  now = 0.0;
  EXPECT_EQ(two.start().remaining(), 3.0);
}

TEST(Termination, ANonPositiveOrNanBudgetIsAnInputError) {
  for (const double seconds : {0.0, -1.0, std::nan(""), -std::numeric_limits<double>::infinity()})
    EXPECT_THROW(Termination::time_budget(seconds), InputError) << seconds;
}

TEST(Termination, TheSteadyClockRuns) {
  const Termination armed = Termination::time_budget(1e-9).start();
  while (!armed.should_stop()) {
  }
  EXPECT_EQ(armed.check(), TerminationReason::kTimeLimit);
  EXPECT_LE(armed.remaining(), 0.0);
}

}  // namespace
}  // namespace talus
