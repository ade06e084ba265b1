#include "talus/optimal/driven_path_time.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"

namespace talus {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRepeated = 1e-9;   ///< [m] configurations closer than this count as one
constexpr double kStraight = 1e-12;  ///< [rad] a step turning less than this is straight

constexpr double kTangent = 1e-6;  ///< [rad] how far a chord may stray from its arc's

/// The geometry of the step from a to b (file comment).
struct Step {
  int direction = 1;
  double length = 0.0;     ///< l [m]
  double turn_rate = 0.0;  ///< κ = dθ/dl [rad/m]
  bool tangent = true;     ///< the chord is that of an arc tangent to both headings
};

Step step_between(const SE2Pose& a, const SE2Pose& b) {
  Step step;
  const Vec2 chord = b.position() - a.position();
  const double c = chord.norm();
  const double turn = std::remainder(b.theta - a.theta, 2.0 * std::numbers::pi);
  step.direction = chord.dot(Vec2(std::cos(a.theta), std::sin(a.theta))) < 0.0 ? -1 : 1;
  if (c > kRepeated) {
    // An arc tangent to the heading at both ends has its chord along θ₀ + Δθ/2 (forward) or
    // the opposite way (reverse).
    const double along = std::atan2(chord.y(), chord.x()) - (a.theta + 0.5 * turn);
    const double off = std::remainder(step.direction > 0 ? along : along - std::numbers::pi,
                                      2.0 * std::numbers::pi);
    step.tangent = std::abs(off) <= kTangent;
  }
  if (std::abs(turn) < kStraight) {
    step.length = c;
  } else {
    step.length = c * (0.5 * turn) / std::sin(0.5 * turn);
    step.turn_rate = step.length > 0.0 ? turn / step.length : 0.0;
  }
  return step;
}

}  // namespace

void DrivenPathOptions::validate() const {
  if (!(cusp_speed >= 0.0) || !std::isfinite(cusp_speed)) {
    throw InputError("driven path: cusp_speed must be a finite speed >= 0 [m/s]");
  }
}

std::string_view to_string(DrivenPathStatus status) {
  switch (status) {
    case DrivenPathStatus::kOk:
      return "ok";
    case DrivenPathStatus::kInfeasible:
      return "infeasible";
    case DrivenPathStatus::kNotTangent:
      return "not_tangent";
  }
  return "unknown";
}

std::string DrivenPathResult::brief_report() const {
  std::ostringstream out;
  out << "driven path " << to_string(status) << ": " << travel_time << " s over " << length
      << " m in " << pieces.size() << " piece" << (pieces.size() == 1 ? "" : "s") << "; " << seconds
      << " s";
  if (!message.empty()) out << " (" << message << ")";
  return out.str();
}

DrivenPathResult driven_path_time(const BPatch& surface, const Vehicle& vehicle,
                                  std::span<const SE2Pose> path, const DrivenPathOptions& options,
                                  TimeOptimalProfileSolver* solver) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  if (path.size() < 2) throw InputError("driven path: needs at least 2 configurations");
  for (const SE2Pose& q : path) {
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.theta)) {
      throw InputError("driven path: a configuration is not finite");
    }
  }
  TimeOptimalProfileSolver own_solver;
  TimeOptimalProfileSolver& profile_solver = solver != nullptr ? *solver : own_solver;
  ProfileOptions profile_options;
  profile_options.start_speed = options.cusp_speed;
  profile_options.end_speed = options.cusp_speed;

  // Steps (index k: from path[k] to path[k + 1]); repeated configurations dropped.
  std::vector<std::size_t> kept = {0};
  std::vector<Step> steps;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Step step = step_between(path[kept.back()], path[k]);
    if (step.length < kRepeated) continue;
    kept.push_back(k);
    steps.push_back(step);
  }
  DrivenPathResult result;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    if (steps[k].tangent) continue;
    result.status = DrivenPathStatus::kNotTangent;
    result.travel_time = kInf;
    result.message = "the step from configuration " + std::to_string(kept[k]) + " to " +
                     std::to_string(kept[k + 1]) +
                     " is neither a segment nor an arc along the heading (the path moves "
                     "sideways or turns on the spot)";
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
  }
  std::size_t begin = 0;  // first step of the current piece
  while (begin < steps.size()) {
    std::size_t end = begin + 1;  // one past its last step
    while (end < steps.size() && steps[end].direction == steps[begin].direction) ++end;
    DrivenPiece piece;
    piece.first = kept[begin];
    piece.last = kept[end];
    piece.direction = steps[begin].direction;
    std::vector<PathFrame> frames;
    double sigma = 0.0, s = 0.0;
    for (std::size_t m = begin; m <= end; ++m) {
      const SE2Pose& q = path[kept[m]];
      if (m > begin) sigma += steps[m - 1].length;
      double rate = m < end ? steps[m].turn_rate : steps[m - 1].turn_rate;
      if (m > begin && std::abs(steps[m - 1].turn_rate) > std::abs(rate)) {
        rate = steps[m - 1].turn_rate;
      }
      const double v = piece.direction;
      const Vec2 heading(std::cos(q.theta), std::sin(q.theta));
      const Vec2 left(-std::sin(q.theta), std::cos(q.theta));
      PathFrame f = lift_to_surface(q.position(), surface.evaluate(q.position()), v * heading,
                                    (v * rate) * left);
      if (!frames.empty()) {
        s += 0.5 * (frames.back().speed + f.speed) * (sigma - frames.back().parameter);
      }
      f.parameter = sigma;
      f.s = s;
      frames.push_back(f);
    }
    piece.planar_length = sigma;
    piece.length = s;
    piece.stations = frames.size();
    VelocityLimits limits(vehicle);
    limits.compute(frames, surface);
    const TimeOptimalProfile profile = profile_solver.solve(limits, profile_options);
    piece.status = profile.status;
    piece.travel_time = profile.status == ProfileStatus::kOk ? profile.travel_time : kInf;
    if (profile.status != ProfileStatus::kOk && result.status == DrivenPathStatus::kOk) {
      result.status = DrivenPathStatus::kInfeasible;
      result.message = "piece " + std::to_string(result.pieces.size()) + " (configurations " +
                       std::to_string(piece.first) + " to " + std::to_string(piece.last) +
                       "): " + profile.message;
    }
    result.travel_time += piece.travel_time;
    result.length += piece.length;
    result.planar_length += piece.planar_length;
    result.pieces.push_back(piece);
    begin = end;
  }
  if (result.status != DrivenPathStatus::kOk) result.travel_time = kInf;
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace talus
