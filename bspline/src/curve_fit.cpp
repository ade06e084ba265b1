#include "talus/bspline/curve_fit.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <string>

#include "chord_length.hpp"
#include "talus/core/error.hpp"

namespace talus {

Curve2 fit_clamped_cubic(const std::vector<Vec2>& polyline, std::size_t control_points) {
  const std::size_t n = polyline.size();
  if (n < 2) throw InputError("curve fit needs at least 2 vertices, got " + std::to_string(n));
  if (control_points < 4) {
    throw InputError("a clamped cubic needs at least 4 control points, got " +
                     std::to_string(control_points));
  }
  // The interior control points are fitted to the interior vertices: there
  // must be at least as many of those as unknowns, or the fit is not unique.
  if (control_points > n + 2 && n > 2) {
    throw InputError("curve fit: " + std::to_string(control_points) +
                     " control points are too many for " + std::to_string(n) + " vertices");
  }
  const std::vector<double> u = detail::chord_length_parameters(polyline, "curve fit");

  std::vector<double> breaks;
  const std::size_t spans = control_points - 3;
  for (std::size_t k = 0; k <= spans; ++k) breaks.push_back(static_cast<double>(k) / spans);
  const KnotVector knots = KnotVector::clamped(3, breaks);

  std::vector<Vec2> control(control_points, Vec2::Zero());
  control.front() = polyline.front();
  control.back() = polyline.back();
  const std::size_t unknowns = control_points - 2;
  if (n > 2) {
    // Rows: interior vertices; columns: interior control points. The fixed
    // end control points move to the right-hand side.
    Eigen::MatrixXd a =
        Eigen::MatrixXd::Zero(static_cast<long>(n - 2), static_cast<long>(unknowns));
    Eigen::MatrixXd b(static_cast<long>(n - 2), 2);
    Eigen::MatrixXd basis(1, 4);
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const std::size_t span = knots.find_span(u[k]);
      knots.basis_derivatives(span, u[k], basis);
      Vec2 rhs = polyline[k];
      for (int j = 0; j < 4; ++j) {
        const std::size_t index = span - 3 + static_cast<std::size_t>(j);
        if (index == 0) {
          rhs -= basis(0, j) * control.front();
        } else if (index == control_points - 1) {
          rhs -= basis(0, j) * control.back();
        } else {
          a(static_cast<long>(k - 1), static_cast<long>(index - 1)) = basis(0, j);
        }
      }
      b.row(static_cast<long>(k - 1)) = rhs.transpose();
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
    if (qr.rank() < static_cast<long>(unknowns)) {
      throw InputError("curve fit: some knot span holds too few vertices for " +
                       std::to_string(control_points) + " control points; use fewer");
    }
    const Eigen::MatrixXd solution = qr.solve(b);
    for (std::size_t k = 0; k < unknowns; ++k)
      control[k + 1] = solution.row(static_cast<long>(k)).transpose();
  } else {
    // Two vertices: control points on the chord at their Greville abscissae,
    // which makes the curve the straight segment with uniform speed.
    const std::vector<double>& t = knots.knots();
    for (std::size_t k = 1; k + 1 < control_points; ++k) {
      const double greville = (t[k + 1] + t[k + 2] + t[k + 3]) / 3.0;
      control[k] = (1.0 - greville) * polyline.front() + greville * polyline.back();
    }
  }
  return Curve2(knots, std::move(control));
}

std::vector<Vec2> resample_polyline(const std::vector<Vec2>& polyline, std::size_t count) {
  if (polyline.size() < 2 || count < 2)
    throw InputError("resample_polyline needs >= 2 vertices and >= 2 points");
  std::vector<double> s{0.0};
  for (std::size_t k = 1; k < polyline.size(); ++k) {
    s.push_back(s.back() + (polyline[k] - polyline[k - 1]).norm());
  }
  std::vector<Vec2> out;
  out.reserve(count);
  std::size_t segment = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const double target = s.back() * static_cast<double>(k) / static_cast<double>(count - 1);
    while (segment + 2 < polyline.size() && s[segment + 1] < target) ++segment;
    const double length = s[segment + 1] - s[segment];
    const double t = length > 0.0 ? std::clamp((target - s[segment]) / length, 0.0, 1.0) : 0.0;
    out.push_back((1.0 - t) * polyline[segment] + t * polyline[segment + 1]);
  }
  out.back() = polyline.back();
  return out;
}

}  // namespace talus
