#include "talus/report/number_format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace talus {

std::string fmt(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string sig3(double value) {
  if (value == 0.0 || !std::isfinite(value)) return fmt("%g", value);
  const int digits = static_cast<int>(std::floor(std::log10(std::abs(value)))) + 1;
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", std::max(0, 3 - digits), value);
  std::string text = buffer;
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  return text;
}

std::string csv_number(double value, int digits) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace talus
