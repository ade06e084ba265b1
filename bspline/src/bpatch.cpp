#include "talus/bspline/bpatch.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "talus/core/error.hpp"
#include "uniform_cubic.hpp"

namespace talus {
namespace {

void require_fit_size(const ElevationGrid& grid) {
  if (grid.ncols() < 4 || grid.nrows() < 4) {
    std::ostringstream msg;
    msg << "a B-patch needs at least 4 x 4 nodes, got " << grid.ncols() << " x " << grid.nrows();
    throw InputError(msg.str());
  }
}

/// The (n + 2) × (n + 2) matrix mapping control values to node values along
/// one axis: not-a-knot rows (fourth difference zero) at both ends.
Eigen::SparseMatrix<double> interpolation_matrix(std::size_t n) {
  const long m = static_cast<long>(n) + 2;
  std::vector<Eigen::Triplet<double>> entries;
  const double fourth[5] = {1.0, -4.0, 6.0, -4.0, 1.0};
  for (long k = 0; k < 5; ++k) {
    entries.emplace_back(0, k, fourth[k]);
    entries.emplace_back(m - 1, m - 5 + k, fourth[k]);
  }
  for (long i = 0; i < static_cast<long>(n); ++i) {
    entries.emplace_back(i + 1, i, 1.0 / 6.0);
    entries.emplace_back(i + 1, i + 1, 4.0 / 6.0);
    entries.emplace_back(i + 1, i + 2, 1.0 / 6.0);
  }
  Eigen::SparseMatrix<double> a(m, m);
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

}  // namespace

BPatch::BPatch(const ElevationGrid& grid, Eigen::MatrixXd control)
    : ncols_(grid.ncols()),
      nrows_(grid.nrows()),
      h_(grid.cellsize()),
      inverse_h_(1.0 / grid.cellsize()),
      x_min_(grid.x_min()),
      y_min_(grid.y_min()),
      control_(std::move(control)),
      cell_on_data_((grid.ncols() - 1) * (grid.nrows() - 1), 1) {
  for (std::size_t j = 0; j + 1 < nrows_; ++j)
    for (std::size_t i = 0; i + 1 < ncols_; ++i)
      cell_on_data_[j * (ncols_ - 1) + i] = grid.valid(i, j) && grid.valid(i + 1, j) &&
                                            grid.valid(i, j + 1) && grid.valid(i + 1, j + 1);
}

BPatch BPatch::interpolate(const ElevationGrid& grid) {
  require_fit_size(grid);
  const std::size_t nc = grid.ncols(), nr = grid.nrows();
  if (grid.void_count() > 0) {
    for (std::size_t j = 0; j < nr; ++j)
      for (std::size_t i = 0; i < nc; ++i)
        if (!grid.valid(i, j)) {
          std::ostringstream msg;
          msg << "cannot interpolate a grid with NODATA nodes (" << grid.void_count()
              << " voids; first at column " << i << ", row " << j
              << " from the south): use the smoothing fit, or fill the voids first";
          throw InputError(msg.str());
        }
  }
  // Tensor-product system A_x C A_y^T = Z, solved one axis at a time.
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(static_cast<long>(nc) + 2, static_cast<long>(nr));
  for (std::size_t j = 0; j < nr; ++j)
    for (std::size_t i = 0; i < nc; ++i)
      rhs(static_cast<long>(i) + 1, static_cast<long>(j)) = grid.at(i, j);

  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_x(interpolation_matrix(nc));
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_y(interpolation_matrix(nr));
  if (lu_x.info() != Eigen::Success || lu_y.info() != Eigen::Success) {
    throw SolverError("B-patch interpolation: the 1-D collocation matrix is singular");
  }
  const Eigen::MatrixXd half = lu_x.solve(rhs);  // (nc+2) × nr
  Eigen::MatrixXd rhs_y =
      Eigen::MatrixXd::Zero(static_cast<long>(nr) + 2, static_cast<long>(nc) + 2);
  rhs_y.middleRows(1, static_cast<long>(nr)) = half.transpose();
  const Eigen::MatrixXd control_t = lu_y.solve(rhs_y);  // (nr+2) × (nc+2)
  return BPatch(grid, control_t.transpose());
}

bool BPatch::contains(const Vec2& p) const {
  return p.x() >= x_min_ && p.x() <= x_max() && p.y() >= y_min_ && p.y() <= y_max();
}

[[noreturn]] void BPatch::throw_outside(const Vec2& p) const {
  std::ostringstream msg;
  msg.precision(12);
  msg << "point (" << p.x() << ", " << p.y() << ") is outside the terrain domain [" << x_min_
      << ", " << x_max() << "] x [" << y_min_ << ", " << y_max() << "]";
  throw InputError(msg.str());
}

void BPatch::locate(const Vec2& p, std::size_t& i, std::size_t& j, double& tu, double& tv) const {
  const double u = (p.x() - x_min_) * inverse_h_;
  const double v = (p.y() - y_min_) * inverse_h_;
  const double umax = static_cast<double>(ncols_ - 1), vmax = static_cast<double>(nrows_ - 1);
  // A hair of slack absorbs rounding in callers that compute x_max themselves.
  constexpr double kSlack = 1e-9;
  if (!(u >= -kSlack && u <= umax + kSlack && v >= -kSlack && v <= vmax + kSlack)) [[unlikely]] {
    throw_outside(p);
  }
  const double uc = std::clamp(u, 0.0, umax), vc = std::clamp(v, 0.0, vmax);
  i = std::min(static_cast<std::size_t>(uc), ncols_ - 2);
  j = std::min(static_cast<std::size_t>(vc), nrows_ - 2);
  tu = uc - static_cast<double>(i);
  tv = vc - static_cast<double>(j);
}

bool BPatch::on_data(const Vec2& p) const {
  std::size_t i, j;
  double tu, tv;
  locate(p, i, j, tu, tv);
  return cell_on_data_[j * (ncols_ - 1) + i] != 0;
}

double BPatch::elevation(const Vec2& p) const {
  std::size_t i, j;
  double tu, tv;
  locate(p, i, j, tu, tv);
  const detail::CubicBasis bu = detail::cubic_basis(tu), bv = detail::cubic_basis(tv);
  double z = 0.0;
  for (int b = 0; b < 4; ++b) {
    const double* column = control_.col(static_cast<long>(j) + b).data() + i;
    double row = 0.0;
    for (int a = 0; a < 4; ++a) row += bu.value[a] * column[a];
    z += bv.value[b] * row;
  }
  return z;
}

SurfacePoint BPatch::evaluate(const Vec2& p) const {
  std::size_t i, j;
  double tu, tv;
  locate(p, i, j, tu, tv);
  const detail::CubicBasis bu = detail::cubic_basis(tu), bv = detail::cubic_basis(tv);
  // Contract along u first (value, first, second derivative), then along v.
  double r0[4], r1[4], r2[4];
  for (int b = 0; b < 4; ++b) {
    const double* column = control_.col(static_cast<long>(j) + b).data() + i;
    r0[b] = r1[b] = r2[b] = 0.0;
    for (int a = 0; a < 4; ++a) {
      r0[b] += bu.value[a] * column[a];
      r1[b] += bu.first[a] * column[a];
      r2[b] += bu.second[a] * column[a];
    }
  }
  double z = 0, zu = 0, zv = 0, zuu = 0, zuv = 0, zvv = 0;
  for (int b = 0; b < 4; ++b) {
    z += bv.value[b] * r0[b];
    zu += bv.value[b] * r1[b];
    zv += bv.first[b] * r0[b];
    zuu += bv.value[b] * r2[b];
    zuv += bv.first[b] * r1[b];
    zvv += bv.second[b] * r0[b];
  }
  const double inv_h = inverse_h_, inv_h2 = inv_h * inv_h;
  SurfacePoint out;
  out.z = z;
  out.gradient = {zu * inv_h, zv * inv_h};
  out.hessian << zuu * inv_h2, zuv * inv_h2, zuv * inv_h2, zvv * inv_h2;
  return out;
}

Eigen::Vector4d BPatch::third_derivatives(const Vec2& p) const {
  std::size_t i, j;
  double tu, tv;
  locate(p, i, j, tu, tv);
  const detail::CubicBasis bu = detail::cubic_basis(tu), bv = detail::cubic_basis(tv);
  const auto& third = detail::kCubicThird;
  double r0[4], r1[4], r2[4], r3[4];
  for (int b = 0; b < 4; ++b) {
    const double* column = control_.col(static_cast<long>(j) + b).data() + i;
    r0[b] = r1[b] = r2[b] = r3[b] = 0.0;
    for (int a = 0; a < 4; ++a) {
      r0[b] += bu.value[a] * column[a];
      r1[b] += bu.first[a] * column[a];
      r2[b] += bu.second[a] * column[a];
      r3[b] += third[a] * column[a];
    }
  }
  Eigen::Vector4d out = Eigen::Vector4d::Zero();
  for (int b = 0; b < 4; ++b) {
    out[0] += bv.value[b] * r3[b];
    out[1] += bv.first[b] * r2[b];
    out[2] += bv.second[b] * r1[b];
    out[3] += third[b] * r0[b];
  }
  const double inv_h3 = inverse_h_ * inverse_h_ * inverse_h_;
  return out * inv_h3;
}

BPatchFitReport BPatch::residuals(const ElevationGrid& grid) const {
  if (grid.ncols() != ncols_ || grid.nrows() != nrows_) {
    throw InputError("B-patch residuals: grid shape differs from the fitted grid");
  }
  BPatchFitReport report;
  double sum_sq = 0.0;
  std::size_t count = 0;
  for (std::size_t j = 0; j < nrows_; ++j)
    for (std::size_t i = 0; i < ncols_; ++i) {
      if (!grid.valid(i, j)) {
        ++report.voids;
        continue;
      }
      // At a node (t = 0) only three basis values are non-zero: 1/6, 4/6, 1/6.
      double z = 0.0;
      for (int b = 0; b < 3; ++b) {
        const double wb = (b == 1) ? 4.0 / 6.0 : 1.0 / 6.0;
        for (int a = 0; a < 3; ++a) {
          const double wa = (a == 1) ? 4.0 / 6.0 : 1.0 / 6.0;
          z += wa * wb * control_(static_cast<long>(i) + a, static_cast<long>(j) + b);
        }
      }
      const double r = std::abs(z - grid.at(i, j));
      report.max_node_residual = std::max(report.max_node_residual, r);
      sum_sq += r * r;
      ++count;
    }
  report.rms_residual = count ? std::sqrt(sum_sq / static_cast<double>(count)) : 0.0;
  return report;
}

}  // namespace talus
