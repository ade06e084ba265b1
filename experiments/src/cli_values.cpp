#include "cli_values.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <system_error>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/output_file.hpp"

namespace talus::experiments {
namespace {

std::string trim(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  const std::size_t end = text.find_last_not_of(" \t");
  return text.substr(begin, end - begin + 1);
}

/// The whole of `text` as a finite double, or nothing.
std::optional<double> parse_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const char* begin = text.data();
  if (*begin == '+') ++begin;  // from_chars refuses a leading '+'
  double value = 0.0;
  const auto [end, error] = std::from_chars(begin, text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

}  // namespace

std::optional<std::vector<double>> parse_numbers(const std::string& text, std::size_t count) {
  std::vector<double> values;
  std::stringstream fields(text);
  std::string field;
  while (std::getline(fields, field, ',')) {
    const std::optional<double> v = parse_number(trim(field));
    if (!v) return std::nullopt;
    values.push_back(*v);
  }
  if (values.size() != count || (!text.empty() && text.back() == ',')) return std::nullopt;
  return values;
}

std::string format_number(double value) {
  std::ostringstream out;
  out.precision(15);
  out << value;
  return out.str();
}

void check_output_is_not_an_input(const std::string& option, const std::string& output,
                                  const std::vector<std::pair<std::string, std::string>>& inputs) {
  namespace fs = std::filesystem;
  require_regular_output(output, option);
  std::error_code error;
  for (const auto& [input_option, input] : inputs) {
    const bool same =
        fs::exists(output, error) && fs::exists(input, error)
            ? fs::equivalent(output, input, error)
            : fs::weakly_canonical(output, error) == fs::weakly_canonical(input, error);
    if (same && !error) {
      throw InputError(option + " " + printable(output, 200) + " is the " + input_option +
                       " input: writing it would destroy that file; choose another output");
    }
  }
}

}  // namespace talus::experiments
