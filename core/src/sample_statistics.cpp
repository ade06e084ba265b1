#include "talus/core/sample_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "talus/core/error.hpp"

namespace talus {

double upper_median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto mid = values.begin() + static_cast<long>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

double power_law_exponent(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) {
    throw InputError("power_law_exponent: " + std::to_string(x.size()) + " x values but " +
                     std::to_string(y.size()) + " y values");
  }
  if (x.size() < 2) {
    throw InputError("power_law_exponent: needs at least 2 points, got " +
                     std::to_string(x.size()));
  }
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!(std::isfinite(x[k]) && x[k] > 0.0 && std::isfinite(y[k]) && y[k] > 0.0)) {
      throw InputError("power_law_exponent: point " + std::to_string(k) +
                       " is not positive and finite");
    }
  }
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    mx += std::log(x[k]);
    my += std::log(y[k]);
  }
  mx /= static_cast<double>(x.size());
  my /= static_cast<double>(x.size());
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxy += (std::log(x[k]) - mx) * (std::log(y[k]) - my);
    sxx += (std::log(x[k]) - mx) * (std::log(x[k]) - mx);
  }
  if (sxx == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return sxy / sxx;
}

}  // namespace talus
