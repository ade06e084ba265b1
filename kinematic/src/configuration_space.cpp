#include "talus/kinematic/configuration_space.hpp"

#include <cmath>
#include <numbers>

namespace talus {

std::string control_name(const Control& u) {
  if (u.v == 0) return "none";
  std::string name = u.v > 0 ? "forward" : "reverse";
  if (u.omega == 0) return name;
  // The wheels are steered left when the heading turns the way the robot's
  // left side would take it: counter-clockwise forwards, clockwise in reverse.
  const bool left = (u.omega > 0) == (u.v > 0);
  return name + (left ? "-left" : "-right");
}

double wrap_angle(double theta) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  double t = std::fmod(theta, kTwoPi);
  if (t <= -std::numbers::pi) t += kTwoPi;
  if (t > std::numbers::pi) t -= kTwoPi;
  return t;
}

SE2Pose apply_control(const SE2Pose& q, const Control& u, double length, double radius) {
  const double v = static_cast<double>(u.v);
  if (u.omega == 0) {
    return {q.x + v * length * std::cos(q.theta), q.y + v * length * std::sin(q.theta), q.theta};
  }
  // dθ/dl = ω/ρ, (dx, dy)/dl = v (cos θ, sin θ), integrated in closed form.
  const double w = static_cast<double>(u.omega);
  const double theta = q.theta + w * length / radius;
  return {q.x + v * w * radius * (std::sin(theta) - std::sin(q.theta)),
          q.y - v * w * radius * (std::cos(theta) - std::cos(q.theta)), theta};
}

std::size_t control_changes(std::span<const PathPoint> path) {
  std::size_t changes = 0;
  for (std::size_t k = 2; k < path.size(); ++k) {
    if (!(path[k].control == path[k - 1].control)) ++changes;
  }
  return changes;
}

double path_length(std::span<const PathPoint> path, double radius) {
  double length = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const SE2Pose& a = path[k - 1].pose;
    const SE2Pose& b = path[k].pose;
    if (path[k].control.omega != 0) {
      length += radius * std::abs(wrap_angle(b.theta - a.theta));
    } else {
      length += std::hypot(b.x - a.x, b.y - a.y);
    }
  }
  return length;
}

}  // namespace talus
