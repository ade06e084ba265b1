#pragma once
/// @file
/// The registry of kinematic baselines: name → factory from text options,
/// with each baseline's one-line summary and accepted options. The CLI
/// (`talus baseline NAME`), the experiments and the conformance suite reach
/// every baseline through it.
///
/// The built-in registry is an explicit list in baseline_registry.cpp (one
/// line per baseline), not self-registration from static objects, which a
/// static library's link would silently drop.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "talus/kinematic/baseline_options.hpp"
#include "talus/kinematic/baseline_planner.hpp"

namespace talus {

/// Builds a configured planner; throws InputError (BaselineOptionError for a
/// bad value, the file's error for an unreadable robot file) for bad options.
using BaselineFactory =
    std::function<std::unique_ptr<BaselinePlanner>(const BaselineOptions& options)>;

/// One registered baseline.
struct BaselineEntry {
  std::string name;                         ///< e.g. "hait"
  std::string summary;                      ///< one sentence: the paper and the method
  std::vector<BaselineOptionSpec> options;  ///< accepted keys, "budget" among them
  BaselineFactory make;
};

/// Name → entry, in registration order.
class BaselineRegistry {
 public:
  /// Every baseline Talus implements.
  static const BaselineRegistry& builtin();

  /// Adds `entry`; throws InputError for an empty name or factory, a name
  /// already taken, or options without a "budget" key.
  void add(BaselineEntry entry);
  /// The names, in registration order.
  std::vector<std::string> names() const;
  /// The entry called `name`; InputError listing the names if there is none.
  const BaselineEntry& entry(const std::string& name) const;
  /// entry(name).make(options).
  std::unique_ptr<BaselinePlanner> make(const std::string& name,
                                        const BaselineOptions& options = {}) const;

 private:
  std::vector<BaselineEntry> entries_;
};

}  // namespace talus
