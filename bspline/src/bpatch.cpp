#include "talus/bspline/bpatch.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "talus/core/error.hpp"
#include "talus/core/memory_budget.hpp"
#include "uniform_cubic.hpp"
#include "uniform_quintic.hpp"

namespace talus {
namespace {

/// Degree 3 needs 4 nodes a side; degree 5 needs 6, or its end rows repeat.
void require_fit_size(const ElevationGrid& grid, int degree) {
  const std::size_t least = degree == 5 ? 6 : 4;
  if (grid.ncols() < least || grid.nrows() < least) {
    std::ostringstream msg;
    msg << "a degree-" << degree << " B-patch needs at least " << least << " x " << least
        << " nodes, got " << grid.ncols() << " x " << grid.nrows();
    throw InputError(msg.str());
  }
}

/// The (n + degree − 1)-square matrix mapping control values to node values
/// along one axis. Degree 3: nodes weight (1, 4, 1)/6, one not-a-knot row
/// (fourth difference zero) at each end. Degree 5: nodes weight
/// (1, 26, 66, 26, 1)/120, two rows of zero sixth differences at each end
/// (the fifth derivative does not jump at the first two and the last two
/// interior knots); both reproduce polynomials of their degree.
Eigen::SparseMatrix<double> interpolation_matrix(std::size_t n, int degree) {
  const int end_rows = (degree - 1) / 2;
  const long m = static_cast<long>(n) + 2 * end_rows;
  std::vector<Eigen::Triplet<double>> entries;
  const std::vector<double> difference =
      degree == 3 ? std::vector<double>{1.0, -4.0, 6.0, -4.0, 1.0}
                  : std::vector<double>{1.0, -6.0, 15.0, -20.0, 15.0, -6.0, 1.0};
  const long width = static_cast<long>(difference.size());
  for (long row = 0; row < end_rows; ++row) {
    for (long k = 0; k < width; ++k) {
      entries.emplace_back(row, row + k, difference[k]);
      entries.emplace_back(m - 1 - row, m - width - row + k, difference[k]);
    }
  }
  const std::vector<double> at_node =
      degree == 3
          ? std::vector<double>{1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0}
          : std::vector<double>{1.0 / 120.0, 26.0 / 120.0, 66.0 / 120.0, 26.0 / 120.0, 1.0 / 120.0};
  for (long i = 0; i < static_cast<long>(n); ++i)
    for (long a = 0; a < static_cast<long>(at_node.size()); ++a)
      entries.emplace_back(i + end_rows, i + a, at_node[a]);
  Eigen::SparseMatrix<double> a(m, m);
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

/// Sum over cell (i, j)'s six by six controls of bu[a] bv[b] c(i + a, j + b).
double contract_quintic(const Eigen::MatrixXd& control, std::size_t i, std::size_t j,
                        const std::array<double, 6>& bu, const std::array<double, 6>& bv) {
  double z = 0.0;
  for (int b = 0; b < 6; ++b) {
    const double* column = control.col(static_cast<long>(j) + b).data() + i;
    double row = 0.0;
    for (int a = 0; a < 6; ++a) row += bu[a] * column[a];
    z += bv[b] * row;
  }
  return z;
}

}  // namespace

BPatch::BPatch(const ElevationGrid& grid, Eigen::MatrixXd control, int degree)
    : degree_(degree),
      ncols_(grid.ncols()),
      nrows_(grid.nrows()),
      h_(grid.cellsize()),
      inverse_h_(1.0 / grid.cellsize()),
      x_min_(grid.x_min()),
      y_min_(grid.y_min()) {
  auto data = std::make_shared<Coefficients>();
  data->control = std::move(control);
  data->cell_on_data.assign((ncols_ - 1) * (nrows_ - 1), 1);
  for (std::size_t j = 0; j + 1 < nrows_; ++j)
    for (std::size_t i = 0; i + 1 < ncols_; ++i)
      data->cell_on_data[j * (ncols_ - 1) + i] = grid.valid(i, j) && grid.valid(i + 1, j) &&
                                                 grid.valid(i, j + 1) && grid.valid(i + 1, j + 1);
  data_ = std::move(data);
}

BPatch BPatch::interpolate(const ElevationGrid& grid, int degree) {
  if (degree != 3 && degree != 5) {
    throw InputError("a B-patch's degree must be 3 (bicubic) or 5 (biquintic), got " +
                     std::to_string(degree));
  }
  require_fit_size(grid, degree);
  const std::size_t nc = grid.ncols(), nr = grid.nrows();
  require_memory(
      kInterpolationBytesPerNode * static_cast<double>(nc + 4) * static_cast<double>(nr + 4),
      "fitting a B-patch to " + std::to_string(nc) + " x " + std::to_string(nr) + " nodes",
      "crop or decimate the DEM first (gdal_translate -srcwin or -outsize)");
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
  const long pad = (degree - 1) / 2;  // control values beyond the nodes on each side
  Eigen::MatrixXd rhs =
      Eigen::MatrixXd::Zero(static_cast<long>(nc) + 2 * pad, static_cast<long>(nr));
  for (std::size_t j = 0; j < nr; ++j)
    for (std::size_t i = 0; i < nc; ++i)
      rhs(static_cast<long>(i) + pad, static_cast<long>(j)) = grid.at(i, j);

  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_x(interpolation_matrix(nc, degree));
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_y(interpolation_matrix(nr, degree));
  if (lu_x.info() != Eigen::Success || lu_y.info() != Eigen::Success) {
    throw SolverError("B-patch interpolation: the 1-D collocation matrix is singular");
  }
  const Eigen::MatrixXd half = lu_x.solve(rhs);  // (nc+2) × nr
  Eigen::MatrixXd rhs_y =
      Eigen::MatrixXd::Zero(static_cast<long>(nr) + 2 * pad, static_cast<long>(nc) + 2 * pad);
  rhs_y.middleRows(pad, static_cast<long>(nr)) = half.transpose();
  const Eigen::MatrixXd control_t = lu_y.solve(rhs_y);  // (nr + 2 pad) × (nc + 2 pad)
  return BPatch(grid, control_t.transpose(), degree);
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
  return data_->cell_on_data[j * (ncols_ - 1) + i] != 0;
}

double BPatch::elevation(const Vec2& p) const {
  std::size_t i, j;
  double tu, tv;
  locate(p, i, j, tu, tv);
  if (degree_ == 5)
    return contract_quintic(data_->control, i, j, detail::quintic_basis(tu, 0),
                            detail::quintic_basis(tv, 0));
  const detail::CubicBasis bu = detail::cubic_basis(tu), bv = detail::cubic_basis(tv);
  double z = 0.0;
  for (int b = 0; b < 4; ++b) {
    const double* column = data_->control.col(static_cast<long>(j) + b).data() + i;
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
  if (degree_ == 5) return evaluate_quintic(i, j, tu, tv);
  const detail::CubicBasis bu = detail::cubic_basis(tu), bv = detail::cubic_basis(tv);
  // Contract along u first (value, first, second derivative), then along v.
  double r0[4], r1[4], r2[4];
  for (int b = 0; b < 4; ++b) {
    const double* column = data_->control.col(static_cast<long>(j) + b).data() + i;
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

SurfacePoint BPatch::evaluate_quintic(std::size_t i, std::size_t j, double tu, double tv) const {
  using detail::quintic_basis;
  const auto u0 = quintic_basis(tu, 0), u1 = quintic_basis(tu, 1), u2 = quintic_basis(tu, 2);
  const auto v0 = quintic_basis(tv, 0), v1 = quintic_basis(tv, 1), v2 = quintic_basis(tv, 2);
  const double inv_h = inverse_h_, inv_h2 = inv_h * inv_h;
  SurfacePoint out;
  out.z = contract_quintic(data_->control, i, j, u0, v0);
  out.gradient = {contract_quintic(data_->control, i, j, u1, v0) * inv_h,
                  contract_quintic(data_->control, i, j, u0, v1) * inv_h};
  const double xy = contract_quintic(data_->control, i, j, u1, v1) * inv_h2;
  out.hessian << contract_quintic(data_->control, i, j, u2, v0) * inv_h2, xy, xy,
      contract_quintic(data_->control, i, j, u0, v2) * inv_h2;
  return out;
}

Eigen::Vector4d BPatch::third_derivatives(const Vec2& p) const {
  std::size_t i, j;
  double tu, tv;
  locate(p, i, j, tu, tv);
  if (degree_ == 5) {
    using detail::quintic_basis;
    const auto u0 = quintic_basis(tu, 0), u1 = quintic_basis(tu, 1), u2 = quintic_basis(tu, 2),
               u3 = quintic_basis(tu, 3);
    const auto v0 = quintic_basis(tv, 0), v1 = quintic_basis(tv, 1), v2 = quintic_basis(tv, 2),
               v3 = quintic_basis(tv, 3);
    const double inv_h3 = inverse_h_ * inverse_h_ * inverse_h_;
    return Eigen::Vector4d(contract_quintic(data_->control, i, j, u3, v0),
                           contract_quintic(data_->control, i, j, u2, v1),
                           contract_quintic(data_->control, i, j, u1, v2),
                           contract_quintic(data_->control, i, j, u0, v3)) *
           inv_h3;
  }
  const detail::CubicBasis bu = detail::cubic_basis(tu), bv = detail::cubic_basis(tv);
  const auto& third = detail::kCubicThird;
  double r0[4], r1[4], r2[4], r3[4];
  for (int b = 0; b < 4; ++b) {
    const double* column = data_->control.col(static_cast<long>(j) + b).data() + i;
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
      if (degree_ == 5) {
        const double r = std::abs(elevation(grid.node_position(i, j)) - grid.at(i, j));
        report.max_node_residual = std::max(report.max_node_residual, r);
        sum_sq += r * r;
        ++count;
        continue;
      }
      // At a node (t = 0) only three basis values are non-zero: 1/6, 4/6, 1/6.
      double z = 0.0;
      for (int b = 0; b < 3; ++b) {
        const double wb = (b == 1) ? 4.0 / 6.0 : 1.0 / 6.0;
        for (int a = 0; a < 3; ++a) {
          const double wa = (a == 1) ? 4.0 / 6.0 : 1.0 / 6.0;
          z += wa * wb * data_->control(static_cast<long>(i) + a, static_cast<long>(j) + b);
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
