#include "talus/kinematic/hait/robot_validity.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

/// Accumulates checks in order; the first failure is kept and zeroes the margin.
class Checker {
 public:
  /// |v| < limit at the worst of the values given.
  void symmetric(ValidityCheck check, double worst_abs, double limit) {
    apply(check, 1.0 - worst_abs / limit);
  }
  /// lo < v < hi for v in [v_lo, v_hi], nominal value `nominal` strictly inside (lo, hi).
  void range(ValidityCheck check, double v_lo, double v_hi, double lo, double hi, double nominal) {
    const double below = (v_lo - lo) / (nominal - lo);
    const double above = (hi - v_hi) / (hi - nominal);
    apply(check, std::min(below, above));
  }
  void fail(ValidityCheck check) { apply(check, 0.0); }
  Validity result() const { return v_; }

 private:
  void apply(ValidityCheck check, double margin) {
    if (!v_.valid()) return;
    // NaN compares false and fails too.
    if (!(margin > 0.0)) {
      v_.failed = check;
      v_.margin = 0.0;
      return;
    }
    v_.margin = std::min(v_.margin, std::min(margin, 1.0));
  }
  Validity v_;
};

Interval point(double v) {
  return {v, v};
}
double worst_abs(const Interval& i) {
  return std::max(std::abs(i.lo), std::abs(i.hi));
}

/// The CCW-from-above order: reverse if the xy-projected signed area is negative.
Quad counter_clockwise(Quad q) {
  double area = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Vec3& a = q[k];
    const Vec3& b = q[(k + 1) % 4];
    area += a.x() * b.y() - b.x() * a.y();
  }
  if (area < 0.0) std::reverse(q.begin(), q.end());
  return q;
}

}  // namespace

const char* to_string(ValidityCheck check) {
  switch (check) {
    case ValidityCheck::kNone:
      return "none";
    case ValidityCheck::kPlacement:
      return "placement";
    case ValidityCheck::kRoll:
      return "roll";
    case ValidityCheck::kPitch:
      return "pitch";
    case ValidityCheck::kSpringExtension:
      return "spring_extension";
    case ValidityCheck::kAxleRollDifference:
      return "axle_roll_difference";
    case ValidityCheck::kBodyAngle:
      return "body_angle";
  }
  return "unknown";
}

Validity check_validity(const WheeledRobot& robot, const RobotPlacementInterval& in) {
  Checker c;
  if (!usable(in.status)) c.fail(ValidityCheck::kPlacement);
  c.symmetric(ValidityCheck::kRoll, worst_abs(in.roll), robot.max_roll);
  c.symmetric(ValidityCheck::kPitch, worst_abs(in.pitch), robot.max_pitch);
  double spring = 0.0;
  for (int j = 0; j < in.wheel_count; ++j) spring = std::max(spring, worst_abs(in.extensions[j]));
  c.symmetric(ValidityCheck::kSpringExtension, spring, robot.max_spring_extension);
  return c.result();
}

Validity check_validity(const WheeledRobot& robot, const RobotPlacement& p) {
  RobotPlacementInterval in;
  in.status = p.status;
  in.z = point(p.position.z());
  in.roll = point(p.roll);
  in.pitch = point(p.pitch);
  in.wheel_count = p.wheel_count;
  for (int j = 0; j < p.wheel_count; ++j) in.extensions[j] = point(p.extensions[j]);
  return check_validity(robot, in);
}

Validity check_validity(const ArticulatedChassis& ch, const ChassisPlacementInterval& in) {
  Checker c;
  if (!usable(in.status)) c.fail(ValidityCheck::kPlacement);
  // Eq. 4: the mean roll at the extremes of all three intervals.
  const double roll_lo = (in.roll_front.lo + in.roll_middle.lo + in.roll_rear.lo) / 3.0;
  const double roll_hi = (in.roll_front.hi + in.roll_middle.hi + in.roll_rear.hi) / 3.0;
  c.symmetric(ValidityCheck::kRoll, std::max(std::abs(roll_lo), std::abs(roll_hi)), ch.max_roll);
  // Global pitch (ψ_F - ψ_R)/2 over the intervals.
  const double pitch_lo = 0.5 * (in.pitch_front.lo - in.pitch_rear.hi);
  const double pitch_hi = 0.5 * (in.pitch_front.hi - in.pitch_rear.lo);
  c.range(ValidityCheck::kPitch, pitch_lo, pitch_hi, ch.min_pitch, ch.max_pitch, 0.0);
  // Eqs. 5-6: one axle at its largest roll and the other at its smallest.
  const auto diff = [](const Interval& a, const Interval& b) {
    return std::max(std::abs(a.lo - b.hi), std::abs(a.hi - b.lo));
  };
  c.symmetric(ValidityCheck::kAxleRollDifference,
              std::max(diff(in.roll_middle, in.roll_rear), diff(in.roll_middle, in.roll_front)),
              ch.max_axle_roll_difference);
  // Body angle at both pitches' minima and maxima.
  c.range(ValidityCheck::kBodyAngle, kPi + in.pitch_front.lo + in.pitch_rear.lo,
          kPi + in.pitch_front.hi + in.pitch_rear.hi, ch.min_body_angle, ch.max_body_angle, kPi);
  return c.result();
}

Validity check_validity(const ArticulatedChassis& chassis, const ChassisPlacement& p) {
  ChassisPlacementInterval in;
  in.status = p.status;
  in.z = point(p.z);
  in.roll_front = point(p.roll_front);
  in.roll_middle = point(p.roll_middle);
  in.roll_rear = point(p.roll_rear);
  in.pitch_front = point(p.pitch_front);
  in.pitch_rear = point(p.pitch_rear);
  return check_validity(chassis, in);
}

std::vector<Quad> lower_faces(const WheeledRobot& robot, const RobotPlacement& p) {
  if (!usable(p.status)) return {};
  const Mat3 rot = p.rotation();
  const BodyBox& b = robot.body;
  const double w = -robot.cg_height + b.clearance;
  const auto world = [&](double u, double v) { return Vec3(p.position + rot * Vec3(u, v, w)); };
  return {counter_clockwise({world(-b.rear, -b.half_width), world(b.front, -b.half_width),
                             world(b.front, b.half_width), world(-b.rear, b.half_width)})};
}

std::vector<Quad> lower_faces(const ArticulatedChassis& ch, const ChassisPlacement& p) {
  if (!usable(p.status)) return {};
  const Vec3 m(p.x, p.y, p.z);
  const Vec3 f(std::cos(p.theta), std::sin(p.theta), 0.0);
  const Vec3 g(-std::sin(p.theta), std::cos(p.theta), 0.0);
  const double len = ch.axle_spacing + ch.body.overhang;
  std::vector<Quad> faces;
  for (int direction : {+1, -1}) {
    const double psi = direction > 0 ? p.pitch_front : p.pitch_rear;
    const double roll = 0.5 * (p.roll_middle + (direction > 0 ? p.roll_front : p.roll_rear));
    // Body axis from M toward the outer axle, then the lateral and up axes of
    // the body rolled about it.
    const Vec3 e = direction * std::cos(psi) * f + std::sin(psi) * Vec3::UnitZ();
    // The axles' roll is measured from the horizontal (§3.1.2): the body's
    // lateral axis is the mean axle direction, made normal to the body axis.
    const Vec3 axle = std::cos(roll) * g + std::sin(roll) * Vec3::UnitZ();
    const Vec3 lat = (axle - axle.dot(e) * e).normalized();
    const Vec3 up = (direction * e).cross(lat);  // forward × left = up
    const Vec3 base = m + ch.body.clearance * up;
    const Vec3 outer = base + len * e;
    const double hw = ch.body.half_width;
    faces.push_back(
        counter_clockwise({base - hw * lat, outer - hw * lat, outer + hw * lat, base + hw * lat}));
  }
  return faces;
}

}  // namespace talus
