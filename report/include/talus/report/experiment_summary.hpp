#pragma once
/// @file
/// An experiment's headline numbers, written as `summary.json` beside its report so that tests
/// and sweeps read numbers, not prose.
#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace talus {

/// The numbers an experiment stands by, each with its unit ("s", "m", "1" for a ratio, "count").
/// Written as
///   {"experiment": NAME, "quick": BOOL, "numbers": {KEY: VALUE}, "units": {KEY: UNIT},
///    "references": {KEY: TEXT}}
/// where `references` says, for the numbers that have one, what they are to be compared with (a
/// closed form, the paper's figure). Non-finite values are written as null.
class ExperimentSummary {
 public:
  /// Records `value` under `key` (replacing an earlier one). `key` is a JSON-friendly identifier.
  void set(const std::string& key, double value, const std::string& unit);
  /// Records `value` and what it should be compared with, e.g. "sqrt(mu g r) = 14.35 m/s".
  void set(const std::string& key, double value, const std::string& unit,
           const std::string& reference);

  /// The recorded value; std::out_of_range if `key` was never set (a programming error).
  double number(const std::string& key) const;

  /// The JSON document above, for experiment `name`.
  nlohmann::json to_json(const std::string& name, bool quick) const;
  /// Writes to_json() to `file` (atomically).
  void write(const std::filesystem::path& file, const std::string& name, bool quick) const;

 private:
  struct Entry {
    double value = 0.0;
    std::string unit, reference;
  };
  std::map<std::string, Entry> numbers_;
};

}  // namespace talus
