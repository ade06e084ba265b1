#include "talus/core/parameter_table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace talus {
namespace {

/// Shortest text that reads back as `x` ("inf" for +infinity).
std::string number_text(double x) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

/// The whole of `text` (blanks round it and a leading '+' allowed) as a T; NaN is refused.
template <class T>
std::optional<T> parse_number(std::string_view text) {
  text = trimmed(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || value != value)
    return std::nullopt;
  return value;
}

/// "a, b or c".
template <class T, class Text>
std::string listed(const std::vector<T>& items, Text text) {
  std::string out;
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (k > 0) out += k + 1 == items.size() ? " or " : ", ";
    out += text(items[k]);
  }
  return out;
}

std::string interval_text(double lower, double upper, bool lower_open) {
  const bool low = std::isfinite(lower), high = std::isfinite(upper);
  if (low && high)
    return std::string(lower_open ? "(" : "[") + number_text(lower) + ", " + number_text(upper) +
           "]";
  if (low) return std::string(lower_open ? "> " : ">= ") + number_text(lower);
  if (high) return "<= " + number_text(upper);
  return "";
}

/// " in [a, b]", " >= a", or "" when unbounded.
std::string bounds_phrase(double lower, double upper, bool lower_open) {
  const std::string interval = interval_text(lower, upper, lower_open);
  if (interval.empty()) return "";
  return (interval[0] == '[' || interval[0] == '(' ? " in " : " ") + interval;
}

bool inside(double x, double lower, double upper, bool lower_open) {
  return (lower_open ? x > lower : x >= lower) && x <= upper;
}

}  // namespace

std::string_view to_string(ParameterKind kind) {
  switch (kind) {
    case ParameterKind::kFlag:
      return "flag";
    case ParameterKind::kInteger:
      return "integer";
    case ParameterKind::kReal:
      return "real";
    case ParameterKind::kChoice:
      return "choice";
    case ParameterKind::kIntegerList:
      return "integer_list";
  }
  return "unknown";
}

std::string cli_spelling(std::string_view name) {
  std::string out = "--";
  for (const char c : name) out += c == '_' ? '-' : c;
  return out;
}

std::string value_text(const ParameterValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const long long* i = std::get_if<long long>(&value)) return std::to_string(*i);
  if (const double* x = std::get_if<double>(&value)) return number_text(*x);
  if (const std::string* s = std::get_if<std::string>(&value)) return *s;
  std::string out;
  for (const long long m : std::get<std::vector<long long>>(value)) {
    if (!out.empty()) out += ',';
    out += std::to_string(m);
  }
  return out;
}

std::optional<ParameterValue> parse_parameter_text(ParameterKind kind, std::string_view text) {
  // Each value is made in place in the optional (GCC 12 warns, wrongly, of an uninitialised
  // vector when a variant temporary is moved into it).
  using Out = std::optional<ParameterValue>;
  switch (kind) {
    case ParameterKind::kFlag: {
      const std::string_view t = trimmed(text);
      if (t == "true" || t == "1" || t == "on")
        return Out(std::in_place, std::in_place_type<bool>, true);
      if (t == "false" || t == "0" || t == "off")
        return Out(std::in_place, std::in_place_type<bool>, false);
      return std::nullopt;
    }
    case ParameterKind::kInteger:
      if (const auto v = parse_number<long long>(text))
        return Out(std::in_place, std::in_place_type<long long>, *v);
      return std::nullopt;
    case ParameterKind::kReal:
      if (const auto v = parse_number<double>(text))
        return Out(std::in_place, std::in_place_type<double>, *v);
      return std::nullopt;
    case ParameterKind::kChoice:
      return Out(std::in_place, std::in_place_type<std::string>, trimmed(text));
    case ParameterKind::kIntegerList: {
      std::vector<long long> list;
      const std::string_view all = trimmed(text);
      std::size_t from = 0;
      while (!(all.empty() || all == "0")) {
        const std::size_t comma = all.find(',', from);
        const auto v = parse_number<long long>(all.substr(from, comma - from));
        if (!v) return std::nullopt;
        list.push_back(*v);
        if (comma == std::string_view::npos) break;
        from = comma + 1;
      }
      return Out(std::in_place, std::in_place_type<std::vector<long long>>, std::move(list));
    }
  }
  return std::nullopt;
}

namespace detail {

std::string accepted_text(ParameterKind kind, double lower, double upper, bool lower_open,
                          const std::vector<long long>& allowed,
                          const std::vector<std::string>& choices) {
  const std::string bounds = bounds_phrase(lower, upper, lower_open);
  switch (kind) {
    case ParameterKind::kFlag:
      return "true or false";
    case ParameterKind::kInteger:
      if (!allowed.empty()) return listed(allowed, [](long long m) { return std::to_string(m); });
      return "an integer" + bounds;
    case ParameterKind::kReal:
      return "a number" + bounds;
    case ParameterKind::kChoice:
      return listed(choices, [](const std::string& s) { return s; });
    case ParameterKind::kIntegerList:
      return "comma-separated integers" + (bounds.empty() ? "" : ", each" + bounds) +
             " (or a single 0 for none)";
  }
  return "";
}

std::string bound_violation(ParameterKind kind, const ParameterValue& value, double lower,
                            double upper, bool lower_open, bool allow_infinity,
                            const std::vector<long long>& allowed) {
  std::string accepted = accepted_text(kind, lower, upper, lower_open, allowed, {});
  if (allow_infinity) accepted += " (inf = none)";
  if (const long long* i = std::get_if<long long>(&value)) {
    const bool ok = allowed.empty()
                        ? inside(static_cast<double>(*i), lower, upper, lower_open)
                        : std::find(allowed.begin(), allowed.end(), *i) != allowed.end();
    return ok ? "" : "be " + accepted + ", got " + std::to_string(*i);
  }
  if (const double* x = std::get_if<double>(&value)) {
    const bool ok = !std::isnan(*x) && inside(*x, lower, upper, lower_open) &&
                    (std::isfinite(*x) || (allow_infinity && *x > 0));
    return ok ? "" : "be " + accepted + ", got " + number_text(*x);
  }
  if (const auto* list = std::get_if<std::vector<long long>>(&value)) {
    for (const long long m : *list) {
      if (!inside(static_cast<double>(m), lower, upper, lower_open))
        return "each be" + bounds_phrase(lower, upper, lower_open) +
               " (or a single 0 for none), got " + std::to_string(m);
    }
  }
  return "";
}

}  // namespace detail
}  // namespace talus
