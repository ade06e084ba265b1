#include "talus/kinematic/baseline_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <system_error>
#include <utility>

namespace talus {
namespace {

/// `text` as one finite number with nothing but spaces around it.
bool parse_finite(std::string_view text, double& value) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

}  // namespace

BaselineOptionError::BaselineOptionError(const std::string& key, const std::string& reason)
    : InputError("option " + key + ": " + reason), key_(key), reason_(reason) {}

BaselineOptionReader::BaselineOptionReader(std::vector<BaselineOptionSpec> specs,
                                           const BaselineOptions& options)
    : specs_(std::move(specs)), values_(options) {
  for (const auto& [key, value] : values_) {
    bool known = false;
    for (const BaselineOptionSpec& s : specs_) known = known || s.key == key;
    if (!known) {
      std::string accepted;
      for (const BaselineOptionSpec& s : specs_) accepted += (accepted.empty() ? "" : ", ") + s.key;
      throw BaselineOptionError(key, "unknown option; accepted: " + accepted);
    }
  }
  for (const BaselineOptionSpec& s : specs_) {
    if (s.required && text(s.key).empty()) throw BaselineOptionError(s.key, "is required");
  }
}

const BaselineOptionSpec& BaselineOptionReader::spec(const std::string& key) const {
  for (const BaselineOptionSpec& s : specs_) {
    if (s.key == key) return s;
  }
  throw InputError("BaselineOptionReader: no option '" + key + "' among the specs");
}

const std::string& BaselineOptionReader::text(const std::string& key) const {
  const BaselineOptionSpec& s = spec(key);
  const auto it = values_.find(key);
  return it == values_.end() ? s.default_value : it->second;
}

double BaselineOptionReader::number(const std::string& key, double min, double max) const {
  double value = 0.0;
  const std::string& t = text(key);
  if (!parse_finite(t, value) || value < min || value > max) {
    std::ostringstream msg;
    msg << "must be a finite number in [" << min << ", " << max << "], got '" << t << "'";
    throw BaselineOptionError(key, msg.str());
  }
  return value;
}

std::size_t BaselineOptionReader::count(const std::string& key, std::size_t min) const {
  const std::string& t = text(key);
  std::size_t value = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size() || value < min) {
    throw BaselineOptionError(
        key, "must be a whole number >= " + std::to_string(min) + ", got '" + t + "'");
  }
  return value;
}

bool BaselineOptionReader::flag(const std::string& key) const {
  const std::string& t = text(key);
  if (t == "true") return true;
  if (t == "false" || t.empty()) return false;
  throw BaselineOptionError(key, "must be true or false, got '" + t + "'");
}

std::vector<double> BaselineOptionReader::numbers(const std::string& key, std::size_t n) const {
  const std::string& t = text(key);
  if (t.empty()) return {};
  std::vector<double> values;
  std::string_view rest(t);
  while (true) {
    const std::size_t comma = rest.find(',');
    double v = 0.0;
    if (!parse_finite(rest.substr(0, comma), v)) break;
    values.push_back(v);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  const std::size_t commas = static_cast<std::size_t>(std::count(t.begin(), t.end(), ','));
  if (values.size() != n || commas + 1 != n) {
    throw BaselineOptionError(key, "must be " + std::to_string(n) +
                                       " finite numbers separated by commas, got '" + t + "'");
  }
  return values;
}

}  // namespace talus
