#include "talus/navigation/navigation_lookahead.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"

namespace talus {

void NavigationLookaheadOptions::validate() const {
  if (!(horizon > 0.0) || !std::isfinite(horizon))
    throw InputError("NavigationLookaheadOptions.horizon must be > 0 [s]");
  if (!(step > 0.0) || !(step <= horizon))
    throw InputError("NavigationLookaheadOptions.step must be in (0, horizon] [s]");
  if (!(safety_factor > 0.0 && safety_factor <= 1.0))
    throw InputError("NavigationLookaheadOptions.safety_factor must be in (0, 1]");
}

double slope_sine_along(const Vec2& gradient, double heading) {
  const double rise = gradient.x() * std::cos(heading) + gradient.y() * std::sin(heading);
  return rise / std::sqrt(1.0 + rise * rise);
}

double reduced_model_speed(const Vehicle& vehicle, double slope_sine, double speed,
                           double commanded, double gain, double dt) {
  const double drive =
      std::clamp(gain * (commanded - speed), -vehicle.max_decel, vehicle.max_accel);
  return std::max(0.0, speed + (drive - vehicle.gravity * slope_sine) * dt);
}

std::vector<double> safe_speed_profile(const BPatch& surface, const Vehicle& vehicle,
                                       const std::vector<Vec2>& points) {
  if (points.size() < 2) throw InputError("safe_speed_profile: needs at least 2 points");
  std::vector<double> safe(points.size(), 0.0);
  // The path leaves the map: no speed is safe from here (the navigator
  // brakes; the simulation reports left_terrain if it goes on).
  for (const Vec2& p : points)
    if (!surface.contains(p)) return safe;
  // Drop repeated points (a stopped prediction) so the cubic is defined.
  std::vector<Vec2> distinct = {points.front()};
  std::vector<std::size_t> index_of(points.size(), 0);
  for (std::size_t k = 1; k < points.size(); ++k) {
    if ((points[k] - distinct.back()).norm() > 1e-6) distinct.push_back(points[k]);
    index_of[k] = distinct.size() - 1;
  }
  if (distinct.size() < 2) {
    // Standing still: the limits at the one point, as a zero-length path cannot carry them.
    std::fill(safe.begin(), safe.end(), std::isfinite(vehicle.max_speed) ? vehicle.max_speed : 0.0);
    return safe;
  }
  // The cubic through points near the map's edge can swing off it between
  // them: then, as for a point off the map, nothing is safe.
  std::optional<SurfacePath> lifted;
  try {
    lifted.emplace(surface, Curve2::interpolate(distinct));
  } catch (const InputError&) {
    return safe;
  }
  const SurfacePath& path = *lifted;
  // Stations equally spaced in arc length, at least two per predicted point.
  const std::size_t stations = std::max<std::size_t>(8, 2 * distinct.size());
  // The prediction turns within the steering limit by construction (a
  // kinematic bicycle); the cubic through its points overshoots that
  // curvature by a little on saturated arcs, which the steering check would
  // call untraversable and cap to 0. So the limits here leave steering out.
  Vehicle unsteered = vehicle;
  unsteered.max_steering = std::numeric_limits<double>::infinity();
  const VelocityLimits limits(unsteered, path, stations);
  std::vector<double> envelope(stations);
  envelope.back() = limits.limits(stations - 1).v_max;
  for (std::size_t k = stations - 1; k-- > 0;) {
    const double v_max = limits.limits(k).v_max;
    const double ds = limits.frame(k + 1).s - limits.frame(k).s;
    // The strongest admissible deceleration at the speed braked to next.
    const AccelerationBounds bounds = limits.acceleration_bounds(k, envelope[k + 1]);
    const double decel = bounds.feasible ? std::max(0.0, -bounds.a_min) : 0.0;
    envelope[k] = std::min(v_max, std::sqrt(envelope[k + 1] * envelope[k + 1] + 2.0 * decel * ds));
  }
  // Back to the points: each point's arc length along the cubic (chord-length
  // parameters, as Curve2::interpolate uses), the envelope linearly between stations.
  double chord_total = 0.0;
  std::vector<double> chord(distinct.size(), 0.0);
  for (std::size_t k = 1; k < distinct.size(); ++k) {
    chord_total += (distinct[k] - distinct[k - 1]).norm();
    chord[k] = chord_total;
  }
  const double spacing = path.length() / static_cast<double>(stations - 1);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::size_t d = index_of[k];
    const double sigma = d + 1 == distinct.size() ? 1.0 : chord[d] / chord_total;
    const double s = std::clamp(path.frame_at_parameter(sigma).s, 0.0, path.length());
    const double position = s / spacing;
    const auto lower = std::min(static_cast<std::size_t>(position), stations - 2);
    const double w = std::clamp(position - static_cast<double>(lower), 0.0, 1.0);
    safe[k] = (1.0 - w) * envelope[lower] + w * envelope[lower + 1];
  }
  return safe;
}

}  // namespace talus
