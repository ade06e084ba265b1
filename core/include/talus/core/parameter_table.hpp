#pragma once
/// @file
/// A declared parameter table: every tunable option of an options struct
/// declared once — its name, kind, bounds and documentation, its default
/// being the struct's own — so that each front end is generated from the
/// declaration instead of spelling the option again: the CLI's options and
/// their checks, the echo of the options in summary.json, Python's keyword
/// arguments and the sweep's parameter names (OMPL's ParamSet plays the same
/// role for its planners).
///
/// Names are snake_case; the command line spells a name as --kebab-case
/// (cli_spelling), and a flag whose default is true as --no-kebab-case.
/// A parameter reads and writes its options through two functions, so it
/// may live in a nested struct, convert an enum to its name, or keep a
/// derived field consistent. Bounds are checked by the table (check(),
/// set()); a setter may also refuse a value (an enum name it does not know)
/// by throwing InputError, which the table prefixes with the parameter's
/// spelling.
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "talus/core/error.hpp"

namespace talus {

/// What a parameter holds.
enum class ParameterKind {
  kFlag,         ///< on or off
  kInteger,      ///< a whole number within [lower, upper], or one of `allowed`
  kReal,         ///< a finite number within [lower, upper] (upper may be +inf: "none")
  kChoice,       ///< one of `choices` (the name of an enum value)
  kIntegerList,  ///< whole numbers, each within [lower, upper]; empty = none
};
std::string_view to_string(ParameterKind kind);

/// A parameter's value: bool (kFlag), long long (kInteger), double (kReal),
/// std::string (kChoice) or std::vector<long long> (kIntegerList).
using ParameterValue = std::variant<bool, long long, double, std::string, std::vector<long long>>;

/// How messages name a parameter: as its field (lattice_spacing) or as the
/// command line spells it (--lattice-spacing; a default-true flag --no-...).
enum class ParameterSpelling { kField, kCli };

/// One declared parameter of an options struct `Options`.
template <class Options>
struct Parameter {
  std::string name;  ///< snake_case: JSON key, Python attribute; CLI --kebab-case
  ParameterKind kind = ParameterKind::kReal;
  std::string doc;  ///< what it is, its unit and what its special values mean
  /// Inclusive bounds of a number or of each list element; lower_open makes
  /// the lower one strict (> lower).
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool lower_open = false;
  bool allow_infinity = false;       ///< kReal: +inf accepted (meaning "none")
  std::vector<long long> allowed;    ///< kInteger: the only values (empty = any in bounds)
  std::vector<std::string> choices;  ///< kChoice: the names accepted
  std::function<ParameterValue(const Options&)> get;
  std::function<void(Options&, const ParameterValue&)> set;
};

/// `name` as the command line spells it: --kebab-case.
std::string cli_spelling(std::string_view name);
/// `value` as text: a flag true/false, numbers in their shortest round-trip
/// form (inf for an unbounded real), a list comma-separated ("" when empty).
std::string value_text(const ParameterValue& value);
/// Parses `text` as a value of `kind` (a list is comma-separated, a single 0
/// or an empty text being the empty list); std::nullopt when it is not one.
std::optional<ParameterValue> parse_parameter_text(ParameterKind kind, std::string_view text);

namespace detail {
/// The message naming what a parameter accepts: "an integer in [4, 64]",
/// "8, 16 or 32", "a number > 0 [s]"...
std::string accepted_text(ParameterKind kind, double lower, double upper, bool lower_open,
                          const std::vector<long long>& allowed,
                          const std::vector<std::string>& choices);
/// What `value` must do instead, after "NAME must " ("be in [4, 64], got 3"),
/// or empty when it keeps the bounds.
std::string bound_violation(ParameterKind kind, const ParameterValue& value, double lower,
                            double upper, bool lower_open, bool allow_infinity,
                            const std::vector<long long>& allowed);
}  // namespace detail

/// The declared parameters of `Options`, in the order the front ends list them.
template <class Options>
class ParameterTable {
 public:
  using Entry = Parameter<Options>;

  explicit ParameterTable(std::string owner, std::vector<Entry> entries = {})
      : owner_(std::move(owner)), entries_(std::move(entries)) {}

  /// The struct's name, for messages (PlannerOptions).
  const std::string& owner() const { return owner_; }
  const std::vector<Entry>& entries() const { return entries_; }

  /// The entry named `name`, or nullptr.
  const Entry* find(std::string_view name) const {
    for (const Entry& e : entries_)
      if (e.name == name) return &e;
    return nullptr;
  }
  /// The entry named `name`; InputError listing the names when there is none.
  const Entry& at(std::string_view name) const {
    if (const Entry* e = find(name)) return *e;
    std::string names;
    for (const Entry& e : entries_) names += (names.empty() ? "" : ", ") + e.name;
    throw InputError(owner_ + " has no parameter '" + std::string(name) +
                     "' (its parameters: " + names + ")");
  }

  /// How `entry` is named in messages.
  static std::string spelled(const Entry& entry, ParameterSpelling spelling) {
    if (spelling == ParameterSpelling::kField) return entry.name;
    return entry.kind == ParameterKind::kFlag && default_value(entry) == ParameterValue(true)
               ? "--no-" + cli_spelling(entry.name).substr(2)
               : cli_spelling(entry.name);
  }
  /// The entry's value in a default-constructed Options.
  static ParameterValue default_value(const Entry& entry) { return entry.get(Options{}); }
  /// What the entry accepts, as text for a help line or a message.
  static std::string accepted(const Entry& entry) {
    return detail::accepted_text(entry.kind, entry.lower, entry.upper, entry.lower_open,
                                 entry.allowed, entry.choices);
  }

  /// Sets parameter `name` of `options` to `value`, after checking its kind
  /// and bounds; InputError naming the parameter otherwise.
  void set(Options& options, std::string_view name, const ParameterValue& value,
           ParameterSpelling spelling = ParameterSpelling::kField) const {
    const Entry& e = at(name);
    if (value.index() != default_value(e).index()) {
      throw InputError(spelled(e, spelling) + " must be " + accepted(e) + ", got " +
                       value_text(value));
    }
    require_bounds(e, value, spelling);
    try {
      e.set(options, value);
    } catch (const InputError& error) {
      throw InputError(spelled(e, spelling) + ": " + error.what());
    }
  }
  /// set() from text (as the command line or a sweep gives it).
  void set_text(Options& options, std::string_view name, std::string_view text,
                ParameterSpelling spelling = ParameterSpelling::kCli) const {
    const Entry& e = at(name);
    const std::optional<ParameterValue> value = parse_parameter_text(e.kind, text);
    if (!value) {
      throw InputError(spelled(e, spelling) + " must be " + accepted(e) + ", got '" +
                       std::string(text) + "'");
    }
    set(options, name, *value, spelling);
  }
  /// Checks every parameter's value in `options` against its bounds.
  void check(const Options& options, ParameterSpelling spelling = ParameterSpelling::kField) const {
    for (const Entry& e : entries_) require_bounds(e, e.get(options), spelling);
  }
  /// Every parameter's value in `options`, in the table's order.
  std::vector<std::pair<std::string, ParameterValue>> values(const Options& options) const {
    std::vector<std::pair<std::string, ParameterValue>> out;
    out.reserve(entries_.size());
    for (const Entry& e : entries_) out.emplace_back(e.name, e.get(options));
    return out;
  }

 private:
  void require_bounds(const Entry& e, const ParameterValue& value,
                      ParameterSpelling spelling) const {
    const std::string why = detail::bound_violation(e.kind, value, e.lower, e.upper, e.lower_open,
                                                    e.allow_infinity, e.allowed);
    if (!why.empty()) throw InputError(spelled(e, spelling) + " must " + why);
  }

  std::string owner_;
  std::vector<Entry> entries_;
};

namespace detail {
/// An entry with its name, kind, documentation and bounds set (the rest is the builder's).
template <class Options>
Parameter<Options> entry(std::string name, ParameterKind kind, std::string doc,
                         double lower = -std::numeric_limits<double>::infinity(),
                         double upper = std::numeric_limits<double>::infinity()) {
  Parameter<Options> p;
  p.name = std::move(name);
  p.kind = kind;
  p.doc = std::move(doc);
  p.lower = lower;
  p.upper = upper;
  return p;
}
}  // namespace detail

/// Builders of the common entries, reading and writing one member through
/// `field` (a generic function returning a reference to it, for const and
/// mutable options alike: [](auto& o) -> auto& {
/// return o.global.connectivity; }).
template <class Options, class Field>
Parameter<Options> flag_parameter(std::string name, Field field, std::string doc) {
  Parameter<Options> p =
      detail::entry<Options>(std::move(name), ParameterKind::kFlag, std::move(doc));
  p.get = [field](const Options& o) { return ParameterValue(static_cast<bool>(field(o))); };
  p.set = [field](Options& o, const ParameterValue& v) { field(o) = std::get<bool>(v); };
  return p;
}

/// A whole-number member (any integer type) within [lower, upper], or one of `allowed`.
template <class Options, class Field>
Parameter<Options> integer_parameter(std::string name, Field field, double lower, double upper,
                                     std::string doc, std::vector<long long> allowed = {}) {
  Parameter<Options> p = detail::entry<Options>(std::move(name), ParameterKind::kInteger,
                                                std::move(doc), lower, upper);
  p.allowed = std::move(allowed);
  p.get = [field](const Options& o) { return ParameterValue(static_cast<long long>(field(o))); };
  p.set = [field](Options& o, const ParameterValue& v) {
    using T = std::decay_t<decltype(field(o))>;
    field(o) = static_cast<T>(std::get<long long>(v));
  };
  return p;
}

/// A finite real member within [lower, upper]; lower_open: > lower;
/// allow_infinity: +inf is accepted too (an unbounded budget: "none").
template <class Options, class Field>
Parameter<Options> real_parameter(std::string name, Field field, double lower, double upper,
                                  std::string doc, bool lower_open = false,
                                  bool allow_infinity = false) {
  Parameter<Options> p =
      detail::entry<Options>(std::move(name), ParameterKind::kReal, std::move(doc), lower, upper);
  p.lower_open = lower_open;
  p.allow_infinity = allow_infinity;
  p.get = [field](const Options& o) { return ParameterValue(field(o)); };
  p.set = [field](Options& o, const ParameterValue& v) { field(o) = std::get<double>(v); };
  return p;
}

/// An enum member, by name: `to_name(value)` and `from_name(text)` (which
/// throws InputError for a name it does not know).
template <class Options, class Field, class ToName, class FromName>
Parameter<Options> choice_parameter(std::string name, Field field, std::vector<std::string> choices,
                                    ToName to_name, FromName from_name, std::string doc) {
  Parameter<Options> p =
      detail::entry<Options>(std::move(name), ParameterKind::kChoice, std::move(doc));
  p.choices = std::move(choices);
  p.get = [field, to_name](const Options& o) {
    return ParameterValue(std::string(to_name(field(o))));
  };
  p.set = [field, from_name](Options& o, const ParameterValue& v) {
    field(o) = from_name(std::get<std::string>(v));
  };
  return p;
}

/// A list of whole numbers (a std::vector of any integer type), each within [lower, upper].
template <class Options, class Field>
Parameter<Options> integer_list_parameter(std::string name, Field field, double lower, double upper,
                                          std::string doc) {
  Parameter<Options> p = detail::entry<Options>(std::move(name), ParameterKind::kIntegerList,
                                                std::move(doc), lower, upper);
  p.get = [field](const Options& o) {
    std::vector<long long> out;
    for (const auto m : field(o)) out.push_back(static_cast<long long>(m));
    return ParameterValue(std::move(out));
  };
  p.set = [field](Options& o, const ParameterValue& v) {
    auto& list = field(o);
    using T = typename std::decay_t<decltype(list)>::value_type;
    list.clear();
    for (const long long m : std::get<std::vector<long long>>(v)) list.push_back(static_cast<T>(m));
  };
  return p;
}

}  // namespace talus
