#pragma once
/// @file
/// Termination: when a long computation should give up. One rule for the
/// planner, its global search and its local solvers (in the spirit of OMPL's
/// PlannerTerminationCondition): a time budget on a clock, a caller's stop
/// predicate, or any combination of them (`a | b`: whichever holds first).
///
/// A time budget counts from start(): a computation arms its termination
/// once, when it begins, and hands the armed copy to its stages, whose own
/// start() keeps deadlines already armed. So a plan's 10 s are 10 s for the
/// whole plan, not 10 s per stage, and options built long before a call do
/// not age. Polling is cheap (a clock read per budget, one call per
/// predicate); the computations say how often they poll.
#include <functional>
#include <limits>
#include <string_view>
#include <vector>

namespace talus {

/// Why a termination holds.
enum class TerminationReason {
  kNone,           ///< it does not (yet)
  kTimeLimit,      ///< a time budget ran out
  kStopRequested,  ///< a stop predicate said so
};
/// "none", "time_limit", "stop_requested".
std::string_view to_string(TerminationReason reason);

class Termination {
 public:
  /// Seconds on any monotone scale (tests inject one to hit a limit
  /// deterministically). Empty: the steady clock.
  using SecondsClock = std::function<double()>;

  /// Never terminates.
  Termination() = default;
  /// Terminates `seconds` after start() on `clock`. seconds > 0; +inf gives
  /// a termination that never holds (as Termination()). InputError for
  /// seconds <= 0 or NaN.
  static Termination time_budget(double seconds, SecondsClock clock = {});
  /// Terminates once `should_stop` returns true (polled; it may be called
  /// from the computation's thread only). An empty function never does.
  static Termination when(std::function<bool()> should_stop);

  /// Whichever of `a` and `b` holds first (a's conditions are asked first).
  friend Termination operator|(Termination a, const Termination& b);

  /// A copy whose time budgets not yet armed become deadlines from now;
  /// budgets armed before keep their deadlines.
  Termination start() const;
  /// The first condition that holds now (kNone: carry on). A budget not yet
  /// armed by start() never holds.
  TerminationReason check() const;
  bool should_stop() const { return check() != TerminationReason::kNone; }
  /// The smallest time budget [s] (+inf when there is none): what a report
  /// or an echo of the options calls "the time limit".
  double smallest_budget() const;
  /// Seconds left to the earliest armed deadline (+inf when none is armed;
  /// may be negative once passed).
  double remaining() const;
  /// True when no condition can ever hold.
  bool never() const { return conditions_.empty(); }

 private:
  struct Condition {
    double budget = std::numeric_limits<double>::infinity();     ///< [s]; +inf: a predicate
    double deadline = std::numeric_limits<double>::quiet_NaN();  ///< on clock; NaN: unarmed
    SecondsClock clock;
    std::function<bool()> should_stop;
    double now() const;
  };
  std::vector<Condition> conditions_;
};

}  // namespace talus
