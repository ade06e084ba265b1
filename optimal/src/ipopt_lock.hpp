#pragma once
// Internal to talus::optimal. Debian's Ipopt factorises with MUMPS, whose
// Fortran modules keep process-wide state (DMUMPS_LOAD_INIT and friends):
// two Ipopt solves on different threads at once corrupt each other and crash
// the process (two Python threads calling talus.plan did, segfault or
// "Fortran runtime error"). So every Ipopt application in Talus is made, run
// and destroyed under this one lock; the rest of a plan (global search,
// profiles, NLopt) runs concurrently. The result of a solve does not depend
// on the lock, so threads give the serial answer.
#include <mutex>

namespace talus::detail {

/// Holds the process-wide Ipopt lock until destroyed. Declare it before the
/// Ipopt::SmartPtrs of a solve so that they are released first. Recursive:
/// a solve's callbacks may start another solve on the same thread.
[[nodiscard]] inline std::unique_lock<std::recursive_mutex> lock_ipopt() {
  static std::recursive_mutex mutex;
  return std::unique_lock<std::recursive_mutex>(mutex);
}

}  // namespace talus::detail
