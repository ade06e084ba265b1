#include "talus/core/termination.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "talus/core/error.hpp"

namespace talus {

std::string_view to_string(TerminationReason reason) {
  switch (reason) {
    case TerminationReason::kNone:
      return "none";
    case TerminationReason::kTimeLimit:
      return "time_limit";
    case TerminationReason::kStopRequested:
      return "stop_requested";
  }
  return "unknown";
}

double Termination::Condition::now() const {
  if (clock) return clock();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

Termination Termination::time_budget(double seconds, SecondsClock clock) {
  if (!(seconds > 0.0)) {
    throw InputError("Termination: a time budget must be > 0 [s] (+inf = none), got " +
                     std::to_string(seconds));
  }
  Termination t;
  if (std::isinf(seconds)) return t;
  Condition c;
  c.budget = seconds;
  c.clock = std::move(clock);
  t.conditions_.push_back(std::move(c));
  return t;
}

Termination Termination::when(std::function<bool()> should_stop) {
  Termination t;
  if (!should_stop) return t;
  Condition c;
  c.should_stop = std::move(should_stop);
  t.conditions_.push_back(std::move(c));
  return t;
}

Termination operator|(Termination a, const Termination& b) {
  a.conditions_.insert(a.conditions_.end(), b.conditions_.begin(), b.conditions_.end());
  return a;
}

Termination Termination::start() const {
  Termination armed = *this;
  for (Condition& c : armed.conditions_)
    if (!c.should_stop && std::isnan(c.deadline)) c.deadline = c.now() + c.budget;
  return armed;
}

TerminationReason Termination::check() const {
  for (const Condition& c : conditions_) {
    if (c.should_stop) {
      if (c.should_stop()) return TerminationReason::kStopRequested;
    } else if (!std::isnan(c.deadline) && c.now() >= c.deadline) {
      return TerminationReason::kTimeLimit;
    }
  }
  return TerminationReason::kNone;
}

double Termination::smallest_budget() const {
  double budget = std::numeric_limits<double>::infinity();
  for (const Condition& c : conditions_) budget = std::min(budget, c.budget);
  return budget;
}

double Termination::remaining() const {
  double left = std::numeric_limits<double>::infinity();
  for (const Condition& c : conditions_)
    if (!c.should_stop && !std::isnan(c.deadline)) left = std::min(left, c.deadline - c.now());
  return left;
}

}  // namespace talus
