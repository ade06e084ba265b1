#include "talus/navigation/trajectory_space_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {
namespace {

void require(bool ok, const char* what, double value, const char* expected) {
  if (ok) return;
  std::ostringstream msg;
  msg << what << " must be " << expected << ", got " << value;
  throw InputError(msg.str());
}

/// The paper's (8)/(10) on one side: 0 below the limit, rising to `gain` at
/// κ_MAX, `gain` beyond; `limit` and `kappa` taken positive (mirrored sides).
double barrier(double gain, double kappa, double limit, double kappa_max) {
  if (kappa >= kappa_max) return gain;
  if (kappa < limit) return 0.0;
  const double r = (kappa - kappa_max) / (limit - kappa_max);
  return gain * (1.0 - r * r);
}

/// Both sides: κ against κ+ = limits.second, and −κ against −κ− (the mirror).
/// Between the limits both are 0; where the limits do not straddle 0 (a side
/// slope too steep to drive straight) one of them is active at κ = 0 too.
double two_sided(double gain, double kappa, std::pair<double, double> limits, double kappa_max) {
  return barrier(gain, kappa, limits.second, kappa_max) +
         barrier(gain, -kappa, -limits.first, kappa_max);
}

double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

}  // namespace

void TrajectorySpaceInputs::validate() const {
  const double inf = std::numeric_limits<double>::infinity();
  require(std::isfinite(gravity_lateral), "TrajectorySpaceInputs.gravity_lateral", gravity_lateral,
          "finite");
  require(gravity_normal > 0.0 && gravity_normal < inf, "TrajectorySpaceInputs.gravity_normal",
          gravity_normal, "positive");
  require(friction > 0.0 && friction < inf, "TrajectorySpaceInputs.friction", friction, "positive");
  require(half_track > 0.0 && half_track < inf, "TrajectorySpaceInputs.half_track", half_track,
          "positive");
  require(cg_height > 0.0 && cg_height < inf, "TrajectorySpaceInputs.cg_height", cg_height,
          "positive");
  require(max_curvature > 0.0 && max_curvature < inf, "TrajectorySpaceInputs.max_curvature",
          max_curvature, "positive");
  require(std::isfinite(desired_curvature), "TrajectorySpaceInputs.desired_curvature",
          desired_curvature, "finite");
  require(desired_speed >= 0.0 && desired_speed < inf, "TrajectorySpaceInputs.desired_speed",
          desired_speed, "finite and >= 0");
  require(max_speed > 0.0 && max_speed < inf, "TrajectorySpaceInputs.max_speed", max_speed,
          "positive");
  require(velocity_unit > 0.0 && velocity_unit < inf, "TrajectorySpaceInputs.velocity_unit",
          velocity_unit, "positive");
  for (const TrajectorySpaceHazard& h : hazards) {
    require(h.kappa_max > h.kappa_min, "TrajectorySpaceHazard.kappa_max - kappa_min",
            h.kappa_max - h.kappa_min, "positive");
    require(h.distance >= 0.0 && h.distance < inf, "TrajectorySpaceHazard.distance", h.distance,
            "finite and >= 0");
    require(h.waypoint_angle >= 0.0 && h.waypoint_angle < inf,
            "TrajectorySpaceHazard.waypoint_angle", h.waypoint_angle, "finite and >= 0");
  }
  const TrajectorySpaceGains& g = gains;
  for (const auto& [name, value] :
       {std::pair{"rollover", g.rollover}, std::pair{"side_slip", g.side_slip},
        std::pair{"waypoint", g.waypoint}, std::pair{"velocity", g.velocity},
        std::pair{"velocity_power", g.velocity_power}, std::pair{"hazard", g.hazard},
        std::pair{"hazard_distance", g.hazard_distance}, std::pair{"hazard_angle", g.hazard_angle},
        std::pair{"hazard_speed", g.hazard_speed}}) {
    require(value >= 0.0 && value < inf, "TrajectorySpaceGains", value, "finite and >= 0");
    (void)name;
  }
}

void DescentOptions::validate() const {
  require(step > 0.0 && std::isfinite(step), "DescentOptions.step", step, "positive");
  require(flat_gradient >= 0.0 && std::isfinite(flat_gradient), "DescentOptions.flat_gradient",
          flat_gradient, "finite and >= 0");
}

std::pair<double, double> rollover_limits(const TrajectorySpaceInputs& in, double v) {
  const double inf = std::numeric_limits<double>::infinity();
  if (v == 0.0) return {-inf, inf};
  const double d = in.half_track, h = in.cg_height, v2 = v * v;
  return {(-d * in.gravity_normal + h * in.gravity_lateral) / (h * v2),
          (d * in.gravity_normal + h * in.gravity_lateral) / (h * v2)};
}

std::pair<double, double> slip_limits(const TrajectorySpaceInputs& in, double v) {
  const double inf = std::numeric_limits<double>::infinity();
  if (v == 0.0) return {-inf, inf};
  const double v2 = v * v;
  return {(in.gravity_lateral - in.friction * in.gravity_normal) / v2,
          (in.gravity_lateral + in.friction * in.gravity_normal) / v2};
}

TrajectorySpaceTerms trajectory_space_field(const TrajectorySpaceInputs& in,
                                            const TrajectoryPoint& p) {
  const TrajectorySpaceGains& g = in.gains;
  TrajectorySpaceTerms t;
  const double kmax = in.max_curvature;
  t.rollover = two_sided(g.rollover, p.curvature, rollover_limits(in, p.speed), kmax);
  t.side_slip = two_sided(g.side_slip, p.curvature, slip_limits(in, p.speed), kmax);
  const double dk = p.curvature - in.desired_curvature;
  t.waypoint = g.waypoint * dk * dk;
  const double dv = (p.speed - in.desired_speed) / in.velocity_unit;
  t.velocity = g.velocity * std::pow(std::abs(dv), g.velocity_power);
  const double v_units = p.speed / in.velocity_unit;
  for (const TrajectorySpaceHazard& h : in.hazards) {
    const double centre = 0.5 * (h.kappa_max + h.kappa_min);
    const double sigma = 0.5 * (h.kappa_max - h.kappa_min);
    const double x = p.curvature - centre;
    t.hazards +=
        g.hazard * (g.hazard_speed * v_units + 1.0) /
        ((g.hazard_distance * h.distance + 1.0) * (g.hazard_angle * h.waypoint_angle + 1.0)) *
        std::exp(-x * x / (2.0 * sigma));
  }
  return t;
}

std::pair<double, double> trajectory_space_gradient(const TrajectorySpaceInputs& in,
                                                    const TrajectoryPoint& p) {
  const double hv = 1e-4 * std::max(1.0, p.speed), hk = 1e-5 * in.max_curvature;
  const auto f = [&](double v, double k) {
    return trajectory_space_field(in, TrajectoryPoint{v, k}).total();
  };
  const double v_lo = std::max(0.0, p.speed - hv), v_hi = std::min(in.max_speed, p.speed + hv);
  const double k_lo = std::max(-in.max_curvature, p.curvature - hk);
  const double k_hi = std::min(in.max_curvature, p.curvature + hk);
  const double dv =
      v_hi > v_lo ? (f(v_hi, p.curvature) - f(v_lo, p.curvature)) / (v_hi - v_lo) : 0.0;
  const double dk = k_hi > k_lo ? (f(p.speed, k_hi) - f(p.speed, k_lo)) / (k_hi - k_lo) : 0.0;
  return {dv, dk};
}

TrajectoryPoint descend(const TrajectorySpaceInputs& in, const TrajectoryPoint& p,
                        std::mt19937_64& rng, const DescentOptions& options) {
  in.validate();
  options.validate();
  const auto clamp = [&](TrajectoryPoint q) {
    q.speed = std::clamp(q.speed, 0.0, in.max_speed);
    q.curvature = std::clamp(q.curvature, -in.max_curvature, in.max_curvature);
    return q;
  };
  const TrajectoryPoint start = clamp(p);
  const auto [gv, gk] = trajectory_space_gradient(in, start);
  // Scaled coordinates u = v / max_speed, w = κ / κ_MAX: dPF/du = max_speed dPF/dv.
  double du = gv * in.max_speed, dw = gk * in.max_curvature;
  const double norm = std::hypot(du, dw);
  if (norm <= options.flat_gradient) {
    const double angle = 2.0 * std::numbers::pi * uniform(rng);
    return clamp({start.speed + options.step * std::cos(angle) * in.max_speed,
                  start.curvature + options.step * std::sin(angle) * in.max_curvature});
  }
  du /= norm;
  dw /= norm;
  const double here = trajectory_space_field(in, start).total();
  double length = options.step;
  for (int k = 0; k <= 10; ++k, length *= 0.5) {
    const TrajectoryPoint q = clamp({start.speed - length * du * in.max_speed,
                                     start.curvature - length * dw * in.max_curvature});
    if (trajectory_space_field(in, q).total() <= here) return q;
  }
  return start;
}

}  // namespace talus
