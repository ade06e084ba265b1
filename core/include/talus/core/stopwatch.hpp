#pragma once
/// @file
/// Wall-clock timing of the commands' and experiments' stages.
#include <chrono>

namespace talus {

using Clock = std::chrono::steady_clock;

/// Seconds elapsed since `start`.
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace talus
