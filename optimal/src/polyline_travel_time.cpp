#include "talus/optimal/polyline_travel_time.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "talus/bspline/curve_fit.hpp"

namespace talus {

double polyline_travel_time(const BPatch& surface, const Vehicle& vehicle,
                            const std::vector<Vec2>& polyline, const TrajectoryOptions& options,
                            TimeOptimalProfileSolver* solver) {
  double length = 0.0;
  for (std::size_t k = 1; k < polyline.size(); ++k)
    length += (polyline[k] - polyline[k - 1]).norm();
  if (length < 1e-6) return 0.0;
  const auto m = static_cast<std::size_t>(std::clamp(std::ceil(length), 4.0, 48.0));
  const Curve2 curve = fit_clamped_cubic(
      resample_polyline(polyline, std::max<std::size_t>(10 * m, polyline.size())), m);
  return evaluate_trajectory(surface, vehicle, curve, options, solver).travel_time();
}

}  // namespace talus
