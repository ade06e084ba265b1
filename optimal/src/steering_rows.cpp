#include "steering_rows.hpp"

#include <cmath>

#include "planar_curvature.hpp"

namespace talus::detail {

SteeringRows::SteeringRows(const KnotVector& knots) : points_(knots.num_basis()) {
  const double begin = knots.domain_begin(), end = knots.domain_end();
  const std::size_t spans = points_ - 3;
  const std::size_t samples = kSamplesPerSpan * spans + 1;
  Eigen::MatrixXd values(3, 4);
  for (std::size_t k = 0; k < samples; ++k) {
    const double share = (k + 1 == samples) ? 1.0 : static_cast<double>(k) / (samples - 1);
    const double sigma = begin + share * (end - begin);
    const std::size_t span = knots.find_span(sigma);
    knots.basis_derivatives(span, sigma, values);
    sigma_.push_back(share);
    first_.push_back(span - 3);
    basis_.push_back(values);
    for (std::size_t i = span - 3; i <= span; ++i) {
      if (i == 0 || i + 1 == points_) continue;  // start and goal are fixed
      for (int axis = 0; axis < 2; ++axis) pattern_.push_back({k, i, axis});
    }
  }
}

bool SteeringRows::evaluate(const std::vector<Vec2>& control, double* values,
                            double* jacobian) const {
  std::size_t entry = 0;
  for (std::size_t k = 0; k < size(); ++k) {
    Eigen::Matrix<double, 2, 3> p = Eigen::Matrix<double, 2, 3>::Zero();
    for (int b = 0; b < 4; ++b) {
      const Vec2& c = control[first_[k] + static_cast<std::size_t>(b)];
      for (int d = 0; d < 3; ++d) p.col(d) += basis_[k](d, b) * c;
    }
    if (!p.allFinite() || !(p.col(1).norm() > 0.0)) return false;
    const PlanarCurvature curvature = planar_curvature(p);
    if (values != nullptr) values[k] = curvature.value;
    if (jacobian == nullptr) continue;
    for (int b = 0; b < 4; ++b) {
      const std::size_t i = first_[k] + static_cast<std::size_t>(b);
      if (i == 0 || i + 1 == points_) continue;
      for (int axis = 0; axis < 2; ++axis) {
        jacobian[entry++] = basis_[k](1, b) * curvature.jacobian[2 + axis] +
                            basis_[k](2, b) * curvature.jacobian[4 + axis];
      }
    }
  }
  return true;
}

std::size_t SteeringRows::first_beyond(const std::vector<Vec2>& control,
                                       double max_curvature) const {
  const std::size_t n = size();
  std::vector<Vec2> positions(n), tangents(n);
  double mean_speed = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    Eigen::Matrix<double, 2, 3> p = Eigen::Matrix<double, 2, 3>::Zero();
    for (int b = 0; b < 4; ++b) {
      const Vec2& c = control[first_[k] + static_cast<std::size_t>(b)];
      for (int d = 0; d < 3; ++d) p.col(d) += basis_[k](d, b) * c;
    }
    if (!p.allFinite() || !(p.col(1).norm() > 0.0)) return k;
    if (std::abs(planar_curvature(p).value) > max_curvature) return k;
    positions[k] = p.col(0);
    tangents[k] = p.col(1);
    mean_speed += tangents[k].norm() / static_cast<double>(n);
  }
  // Between two points whose headings differ by Δθ, a path that never turns
  // tighter than κ_max has a chord of at least the arc's at the limit. The
  // optimiser drifts to near-stops because the stations bunch on the stopped
  // stretch and thin out on the turns.
  for (std::size_t k = 0; k < n; ++k) {
    if (tangents[k].norm() < kMinSpeedShare * mean_speed) return k;
    if (k == 0) continue;
    const Vec2 before = tangents[k - 1].normalized(), heading = tangents[k].normalized();
    const double turn =
        std::atan2(before.x() * heading.y() - before.y() * heading.x(), before.dot(heading));
    const double chord = (positions[k] - positions[k - 1]).norm();
    if (2.0 * std::sin(0.5 * std::abs(turn)) > (1.0 + 1e-9) * max_curvature * chord) return k;
  }
  return n;
}

}  // namespace talus::detail
