#pragma once
/// @file
/// The JSON form of numbers in the commands' summaries: a non-finite value
/// (NaN for "not computed", ±inf for "unbounded") is written as null, since
/// JSON has no literal for it and nlohmann::json would write null silently
/// only for some of them.
#include <cmath>

#include <nlohmann/json.hpp>

namespace talus::experiments {

/// `value`, or null when it is not finite.
inline nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace talus::experiments
