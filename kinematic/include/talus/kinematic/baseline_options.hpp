#pragma once
/// @file
/// Options of a registered baseline as text key/value pairs, each baseline
/// declaring the keys it accepts (BaselineOptionSpec) and validating the
/// values through BaselineOptionReader.
///
/// Why text and not one options struct per baseline: the `talus baseline NAME`
/// command and the experiments reach every baseline through the registry, so
/// the CLI builds each subcommand's flags from the declared specs and stays
/// the same when a baseline lands; the typed options struct (e.g. HaitOptions)
/// remains the C++ API of each baseline, and its registry factory is the one
/// place that turns the text into it.
///
/// Shared keys: every baseline accepts `budget`, the most work units (the
/// baseline's own unit: search nodes, voxels, samples, steps) a query may
/// spend before returning BaselineStatus::kBudgetExceeded. A count, not a
/// time, so that results stay deterministic.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "talus/core/error.hpp"

namespace talus {

/// Text options given to a baseline's factory: key → value. Flags are "true"
/// or "false"; an absent key takes its documented default.
using BaselineOptions = std::map<std::string, std::string>;

/// One option a baseline accepts.
struct BaselineOptionSpec {
  std::string key;            ///< kebab-case, e.g. "terrain-uncertainty" (the CLI adds "--")
  std::string default_value;  ///< as text; "" = none (the option is then required or unset)
  std::string help;           ///< one sentence with the unit and the accepted range
  bool flag = false;          ///< a boolean that defaults to false ("true" / "false")
  bool required = false;      ///< the factory refuses options without it
};

/// A bad value for one option: InputError whose what() is
/// "option KEY: REASON"; key() and reason() let a CLI name its own flag.
class BaselineOptionError : public InputError {
 public:
  BaselineOptionError(const std::string& key, const std::string& reason);
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string key_;
  std::string reason_;
};

/// Typed, checked access to BaselineOptions against a baseline's specs. The
/// constructor rejects unknown keys (listing the accepted ones) and missing
/// required ones; each getter throws BaselineOptionError naming the key when
/// the text is not of the asked type or range.
class BaselineOptionReader {
 public:
  BaselineOptionReader(std::vector<BaselineOptionSpec> specs, const BaselineOptions& options);

  /// The value given, else the default ("" when neither).
  const std::string& text(const std::string& key) const;
  /// A finite number; throws unless it is in [min, max].
  double number(const std::string& key, double min, double max) const;
  /// A whole number >= min written in decimal digits.
  std::size_t count(const std::string& key, std::size_t min) const;
  /// "true" or "false".
  bool flag(const std::string& key) const;
  /// `n` finite numbers separated by commas ("" gives an empty vector).
  std::vector<double> numbers(const std::string& key, std::size_t n) const;

 private:
  const BaselineOptionSpec& spec(const std::string& key) const;
  std::vector<BaselineOptionSpec> specs_;
  BaselineOptions values_;
};

}  // namespace talus
