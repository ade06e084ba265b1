#pragma once
/// @file
/// The JSON form of numbers in the commands' summaries: a non-finite value
/// (NaN for "not computed", ±inf for "unbounded") becomes null in the
/// document itself, since JSON has no literal for it; readers and tests then
/// see is_null() rather than a number that only dump() turns into null.
#include <cmath>
#include <variant>

#include <nlohmann/json.hpp>

#include "talus/core/parameter_table.hpp"

namespace talus::experiments {

/// `value`, or null when it is not finite.
inline nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

/// A declared parameter's value as JSON (an unbounded real as null).
inline nlohmann::json parameter_json(const ParameterValue& value) {
  if (const double* x = std::get_if<double>(&value)) return finite_or_null(*x);
  return std::visit([](const auto& v) { return nlohmann::json(v); }, value);
}

/// Every declared parameter of `options` by its name: a summary's echo of them.
template <class Options>
nlohmann::json parameters_json(const ParameterTable<Options>& table, const Options& options) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, value] : table.values(options)) out[name] = parameter_json(value);
  return out;
}

}  // namespace talus::experiments
