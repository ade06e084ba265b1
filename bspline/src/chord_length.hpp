#pragma once
// Chord-length parameters of a point sequence, normalised to [0, 1]: the
// parametrisation of both curve interpolation and curve fitting.
#include <string>
#include <vector>

#include "talus/core/error.hpp"

namespace talus::detail {

/// `what` names the caller in errors ("curve interpolation", "curve fit").
template <typename Point>
std::vector<double> chord_length_parameters(const std::vector<Point>& points,
                                            const std::string& what) {
  std::vector<double> u(points.size(), 0.0);
  for (std::size_t k = 1; k < points.size(); ++k) {
    if (!points[k].allFinite() || !points[k - 1].allFinite()) {
      throw InputError(what + ": point " + std::to_string(k) + " is not finite");
    }
    const double chord = (points[k] - points[k - 1]).norm();
    if (!(chord > 0.0)) {
      throw InputError(what + ": points " + std::to_string(k - 1) + " and " + std::to_string(k) +
                       " coincide");
    }
    u[k] = u[k - 1] + chord;
  }
  for (double& value : u) value /= u.back();
  return u;
}

}  // namespace talus::detail
