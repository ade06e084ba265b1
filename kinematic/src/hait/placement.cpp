#include "talus/kinematic/hait/placement.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "talus/core/error.hpp"

namespace talus {
namespace {

Mat3 attitude(double theta, double roll, double pitch) {
  return (Eigen::AngleAxisd(theta, Vec3::UnitZ()) * Eigen::AngleAxisd(-pitch, Vec3::UnitY()) *
          Eigen::AngleAxisd(roll, Vec3::UnitX()))
      .toRotationMatrix();
}

/// Elevation and gradient at p, or the reason there is none (no exceptions in the hot path).
PlacementStatus sample(const RuledTerrain& t, const Vec2& p, double& z, Vec2& grad) {
  if (!t.contains(p)) return PlacementStatus::kOffMap;
  if (!t.has_data(p)) return PlacementStatus::kNoData;
  z = t.elevation(p);
  grad = t.gradient(p);
  return PlacementStatus::kConverged;
}

/// Everything one placement run needs: the wheel terrains and the options.
struct Placer {
  const WheeledRobot& robot;
  std::array<const RuledTerrain*, WheeledRobot::kMaxWheels> ground{};
  const RobotPlacementOptions& opt;

  /// L_j(p) for every wheel: the extension l_j that puts wheel j on its terrain,
  /// found by Newton's method on h(l) = z(A + l w) - T(xy(A + l w)), A being the
  /// wheel at rest and w the body's up axis. Fills extensions, contacts, energy.
  PlacementStatus contacts(RobotPlacement& p) const {
    const Mat3 rot = attitude(p.theta, p.roll, p.pitch);
    const Vec3 w = rot.col(2);
    p.energy = 0.0;
    for (int j = 0; j < p.wheel_count; ++j) {
      const Vec2& uv = robot.wheels[j];
      const Vec3 a = p.position + rot * Vec3(uv.x(), uv.y(), -robot.cg_height);
      double l = 0.0;
      for (int k = 0; k < opt.contact_iterations; ++k) {
        const Vec3 c = a + l * w;
        double z = 0.0;
        Vec2 g;
        const PlacementStatus s = sample(*ground[j], c.head<2>(), z, g);
        if (!usable(s)) return s;
        const double h = c.z() - z;
        if (std::abs(h) <= opt.contact_tolerance) break;
        double dh = w.z() - g.dot(w.head<2>());
        // Where the terrain is steeper than the body's tilt the derivative can
        // vanish; a vertical step (dh = w_z) still moves toward the surface.
        if (std::abs(dh) < 1e-3) dh = w.z();
        l -= h / dh;
      }
      const Vec3 c = a + l * w;
      double z = 0.0;
      Vec2 g;
      const PlacementStatus s = sample(*ground[j], c.head<2>(), z, g);
      if (!usable(s)) return s;
      p.extensions[j] = l;
      p.contacts[j] = Vec3(c.x(), c.y(), z);
      p.energy += l * l;
    }
    return PlacementStatus::kConverged;
  }

  /// Steps 9-10: the plane through the contacts that minimises the squared
  /// orthogonal distances, then (z, φ, ψ) putting the wheels' rest plane on it.
  void fit_plane(RobotPlacement& p) const {
    const int n = p.wheel_count;
    Vec3 c = Vec3::Zero();
    for (int j = 0; j < n; ++j) c += p.contacts[j];
    c /= n;
    Mat3 cov = Mat3::Zero();
    for (int j = 0; j < n; ++j) cov += (p.contacts[j] - c) * (p.contacts[j] - c).transpose();
    Eigen::SelfAdjointEigenSolver<Mat3> eig;
    eig.computeDirect(cov);
    Vec3 normal = eig.eigenvectors().col(0);  // smallest eigenvalue first
    if (normal.z() < 0) normal = -normal;
    const Vec3 f(std::cos(p.theta), std::sin(p.theta), 0.0);
    const Vec3 g(-std::sin(p.theta), std::cos(p.theta), 0.0);
    // With R = Rz(θ) Ry(-ψ) Rx(φ), the up axis in (f, g, z) is
    // (-cos φ sin ψ, -sin φ, cos φ cos ψ).
    p.roll = -std::asin(std::clamp(normal.dot(g), -1.0, 1.0));
    p.pitch = std::atan2(-normal.dot(f), normal.z());
    const Vec3 up = attitude(p.theta, p.roll, p.pitch).col(2);
    // Rest plane {G + R (u, v, -h)} = {P : up·P = up·G - h} must pass through c.
    const double rhs = up.dot(c) + robot.cg_height;
    p.position.z() = (rhs - up.x() * p.position.x() - up.y() * p.position.y()) / up.z();
  }

  RobotPlacement run(double x, double y, double theta) const {
    RobotPlacement p;
    p.wheel_count = static_cast<int>(robot.wheels.size());
    p.theta = theta;
    p.position = Vec3(x, y, 0.0);
    double z0 = 0.0;
    Vec2 g;
    p.status = sample(*ground[0], Vec2(x, y), z0, g);
    if (!usable(p.status)) return p;
    p.position.z() = z0 + robot.cg_height;
    p.status = contacts(p);
    if (!usable(p.status)) return p;
    RobotPlacement best = p;
    for (int i = 1; i <= opt.max_iterations; ++i) {
      RobotPlacement next = best;
      fit_plane(next);
      next.iterations = i;
      next.status = contacts(next);
      if (!usable(next.status)) return next;
      if (next.energy >= best.energy - opt.energy_tolerance) {
        // No longer improving: keep the previous placement (step 14).
        if (next.energy < best.energy) best = next;
        best.iterations = i;
        best.status = PlacementStatus::kConverged;
        return best;
      }
      best = next;
      if (best.energy < opt.energy_tolerance) {
        best.status = PlacementStatus::kConverged;
        return best;
      }
    }
    best.status = PlacementStatus::kIterationLimit;
    return best;
  }
};

void require(bool ok, const char* field, double value, const char* expected) {
  if (!ok) {
    std::ostringstream msg;
    msg << "RobotPlacementOptions." << field << " must be " << expected << ", got " << value;
    throw InputError(msg.str());
  }
}

}  // namespace

const char* to_string(PlacementStatus status) {
  switch (status) {
    case PlacementStatus::kConverged:
      return "converged";
    case PlacementStatus::kIterationLimit:
      return "iteration_limit";
    case PlacementStatus::kOffMap:
      return "off_map";
    case PlacementStatus::kNoData:
      return "no_data";
  }
  return "unknown";
}

void RobotPlacementOptions::validate() const {
  require(max_iterations > 0, "max_iterations", max_iterations, "> 0");
  require(energy_tolerance > 0 && std::isfinite(energy_tolerance), "energy_tolerance",
          energy_tolerance, "positive and finite");
  require(contact_iterations > 0, "contact_iterations", contact_iterations, "> 0");
  require(contact_tolerance > 0 && std::isfinite(contact_tolerance), "contact_tolerance",
          contact_tolerance, "positive and finite");
}

Mat3 RobotPlacement::rotation() const {
  return attitude(theta, roll, pitch);
}

RobotPlacement place_robot_mixed(const WheeledRobot& robot, const RuledTerrain& lower,
                                 const RuledTerrain& upper, unsigned upper_mask, double x, double y,
                                 double theta, const RobotPlacementOptions& options) {
  if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(theta))) {
    std::ostringstream msg;
    msg << "place_robot: configuration (" << x << ", " << y << ", " << theta << ") must be finite";
    throw InputError(msg.str());
  }
  options.validate();
  const int n = static_cast<int>(robot.wheels.size());
  if (n < 3 || n > WheeledRobot::kMaxWheels)
    throw InputError("place_robot: the robot has " + std::to_string(n) +
                     " wheels; validate() it first");
  Placer placer{robot, {}, options};
  for (int j = 0; j < n; ++j) placer.ground[j] = ((upper_mask >> j) & 1u) ? &upper : &lower;
  return placer.run(x, y, theta);
}

RobotPlacement place_robot(const WheeledRobot& robot, const RuledTerrain& terrain, double x,
                           double y, double theta, const RobotPlacementOptions& options) {
  return place_robot_mixed(robot, terrain, terrain, 0u, x, y, theta, options);
}

RobotPlacementInterval place_robot_interval(const WheeledRobot& robot, const RuledTerrain& terrain,
                                            const RuledTerrain& lower, const RuledTerrain& upper,
                                            double x, double y, double theta,
                                            const RobotPlacementOptions& options) {
  const int n = static_cast<int>(robot.wheels.size());
  RobotPlacementInterval out;
  out.wheel_count = n;
  const RobotPlacement nominal = place_robot(robot, terrain, x, y, theta, options);
  out.placements = 1;
  out.status = nominal.status;
  if (!usable(nominal.status)) return out;
  out.z = {nominal.position.z(), nominal.position.z()};
  out.roll = {nominal.roll, nominal.roll};
  out.pitch = {nominal.pitch, nominal.pitch};
  for (int j = 0; j < n; ++j) out.extensions[j] = {nominal.extensions[j], nominal.extensions[j]};

  // Linearised fit in the body frame: heights z_j = a + b u_j + c v_j by least
  // squares. Row 1 (2) of (XᵀX)⁻¹Xᵀ gives how each wheel's ground height moves
  // the pitch (roll) slope, and the residual operator I - H how it moves each
  // l_j (a raised ground compresses the spring: l_j moves by -(I - H)_jk dz_k).
  Eigen::MatrixXd X(n, 3);
  for (int j = 0; j < n; ++j) X.row(j) << 1.0, robot.wheels[j].x(), robot.wheels[j].y();
  const Eigen::MatrixXd pinv = (X.transpose() * X).ldlt().solve(X.transpose());
  const Eigen::MatrixXd resid = Eigen::MatrixXd::Identity(n, n) - X * pinv;
  const auto mask_of = [n](const Eigen::VectorXd& coeff) {
    unsigned m = 0;
    for (int k = 0; k < n; ++k)
      if (coeff(k) > 1e-12) m |= 1u << k;
    return m;
  };
  const unsigned all = (1u << n) - 1u;
  std::vector<unsigned> masks = {0u, all};
  const auto add = [&](unsigned m) {
    for (unsigned c : {m, all & ~m})
      if (std::find(masks.begin(), masks.end(), c) == masks.end()) masks.push_back(c);
  };
  add(mask_of(pinv.row(1).transpose()));
  add(mask_of(pinv.row(2).transpose()));
  for (int j = 0; j < n; ++j) add(mask_of(resid.row(j).transpose()));

  for (unsigned m : masks) {
    const RobotPlacement p = place_robot_mixed(robot, lower, upper, m, x, y, theta, options);
    ++out.placements;
    if (!usable(p.status)) {
      out.status = p.status;
      return out;
    }
    out.z.include(p.position.z());
    out.roll.include(p.roll);
    out.pitch.include(p.pitch);
    for (int j = 0; j < n; ++j) out.extensions[j].include(p.extensions[j]);
  }
  return out;
}

}  // namespace talus
