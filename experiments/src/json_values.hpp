#pragma once
/// @file
/// The JSON form of numbers in the commands' summaries: a non-finite value
/// (NaN for "not computed", ±inf for "unbounded") becomes null in the
/// document itself, since JSON has no literal for it; readers and tests then
/// see is_null() rather than a number that only dump() turns into null.
#include <cmath>

#include <nlohmann/json.hpp>

namespace talus::experiments {

/// `value`, or null when it is not finite.
inline nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace talus::experiments
