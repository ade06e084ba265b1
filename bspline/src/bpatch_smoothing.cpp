// The smoothing B-patch fit lives in its own translation unit: the CHOLMOD
// headers are heavy and nothing else needs them.
//
// Two solvers for the same normal equations (see bpatch.hpp):
// - tensor PCG (default): conjugate gradients, matrix-free products with the
//   banded per-axis matrices, preconditioned in a basis of per-axis
//   generalised eigenvectors (below);
// - CHOLMOD: the assembled sparse system, supernodal Cholesky. The fallback
//   when PCG does not converge (voids too many for the preconditioner's local
//   correction, at small lambda), and the reference for the tests.
#include <cblas.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <thread>
#include <unsupported/Eigen/KroneckerProduct>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/detail/smoothing_solver.hpp"
#include "talus/core/error.hpp"
#include "uniform_cubic.hpp"

// LAPACK (OpenBLAS on Debian), Fortran calling convention with the hidden
// lengths of the two character arguments.
extern "C" void dsygvd_(const int* itype, const char* jobz, const char* uplo, const int* n,
                        double* a, const int* lda, double* b, const int* ldb, double* w,
                        double* work, const int* lwork, int* iwork, const int* liwork, int* info,
                        std::size_t jobz_len, std::size_t uplo_len);

namespace talus {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Eigen::MatrixXd;
using Eigen::VectorXd;
/// Precision of the preconditioner's dense transforms.
using Real = float;
using MatrixR = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;

/// c = op(a) op(b), column-major, single precision (OpenBLAS sgemm).
void gemm(CBLAS_TRANSPOSE ta, CBLAS_TRANSPOSE tb, int m, int n, int k, const Real* a, int lda,
          const Real* b, int ldb, Real* c, int ldc) {
  cblas_sgemm(CblasColMajor, ta, tb, m, n, k, 1.0f, a, lda, b, ldb, 0.0f, c, ldc);
}

constexpr double kCollocation[3] = {1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0};

/// Gram matrices of the n + 2 uniform cubic basis functions over the node
/// interval [0, n - 1] in index units: values (M), first (G) and second (K)
/// derivatives. 4-point Gauss–Legendre is exact for these degree-6 products.
struct GramMatrices {
  SparseMatrix value, first, second;
};

GramMatrices gram_matrices(std::size_t n) {
  constexpr std::array<double, 4> kNodes = {-0.8611363115940526, -0.3399810435848563,
                                            0.3399810435848563, 0.8611363115940526};
  constexpr std::array<double, 4> kWeights = {0.3478548451374538, 0.6521451548625461,
                                              0.6521451548625461, 0.3478548451374538};
  Eigen::Matrix4d local_m = Eigen::Matrix4d::Zero(), local_g = local_m, local_k = local_m;
  for (std::size_t q = 0; q < kNodes.size(); ++q) {
    const double t = 0.5 * (kNodes[q] + 1.0), w = 0.5 * kWeights[q];
    const detail::CubicBasis b = detail::cubic_basis(t);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        local_m(r, c) += w * b.value[r] * b.value[c];
        local_g(r, c) += w * b.first[r] * b.first[c];
        local_k(r, c) += w * b.second[r] * b.second[c];
      }
  }
  std::vector<Eigen::Triplet<double>> m, g, k;
  for (long interval = 0; interval + 1 < static_cast<long>(n); ++interval)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        m.emplace_back(interval + r, interval + c, local_m(r, c));
        g.emplace_back(interval + r, interval + c, local_g(r, c));
        k.emplace_back(interval + r, interval + c, local_k(r, c));
      }
  const long size = static_cast<long>(n) + 2;
  GramMatrices out{SparseMatrix(size, size), SparseMatrix(size, size), SparseMatrix(size, size)};
  out.value.setFromTriplets(m.begin(), m.end());
  out.first.setFromTriplets(g.begin(), g.end());
  out.second.setFromTriplets(k.begin(), k.end());
  return out;
}

/// The data: node values with voids set to 0, and the 0/1 validity mask.
struct GridData {
  MatrixXd values, mask;  // ncols x nrows
};

GridData grid_data(const ElevationGrid& grid) {
  const auto nc = static_cast<long>(grid.ncols()), nr = static_cast<long>(grid.nrows());
  GridData d{MatrixXd::Zero(nc, nr), MatrixXd::Zero(nc, nr)};
  for (long j = 0; j < nr; ++j)
    for (long i = 0; i < nc; ++i) {
      const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      if (!grid.valid(ui, uj)) continue;
      d.values(i, j) = grid.at(ui, uj);
      d.mask(i, j) = 1.0;
    }
  return d;
}

// ---------------------------------------------------------------------------
// CHOLMOD: the assembled normal equations.

MatrixXd solve_cholmod(const ElevationGrid& grid, double lambda) {
  const std::size_t nc = grid.ncols(), nr = grid.nrows();
  const long mx = static_cast<long>(nc) + 2, my = static_cast<long>(nr) + 2;
  // Data term: one row per valid node, weights 1/6, 4/6, 1/6 on each axis.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(9 * nc * nr);
  VectorXd data = VectorXd::Zero(static_cast<long>(nc * nr));
  for (std::size_t j = 0; j < nr; ++j)
    for (std::size_t i = 0; i < nc; ++i) {
      if (!grid.valid(i, j)) continue;
      const long row = static_cast<long>(j * nc + i);
      data(row) = grid.at(i, j);
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < 3; ++a)
          entries.emplace_back(row, (static_cast<long>(j) + b) * mx + static_cast<long>(i) + a,
                               kCollocation[a] * kCollocation[b]);
    }
  SparseMatrix collocation(static_cast<long>(nc * nr), mx * my);
  collocation.setFromTriplets(entries.begin(), entries.end());

  const GramMatrices gx = gram_matrices(nc), gy = gram_matrices(nr);
  const SparseMatrix energy = SparseMatrix(Eigen::kroneckerProduct(gy.value, gx.second)) +
                              2.0 * SparseMatrix(Eigen::kroneckerProduct(gy.first, gx.first)) +
                              SparseMatrix(Eigen::kroneckerProduct(gy.second, gx.value));
  const SparseMatrix normal = SparseMatrix(collocation.transpose() * collocation) + lambda * energy;
  const VectorXd rhs = collocation.transpose() * data;

  Eigen::CholmodSupernodalLLT<SparseMatrix> cholesky;
  // AMD alone: CHOLMOD's default also tries METIS on these grid-like systems,
  // which costs more ordering time than it saves in the factorisation
  // (256 x 256: 1.3 s with AMD against 2.3 s by default, bench_bpatch).
  cholesky.cholmod().nmethods = 1;
  cholesky.cholmod().method[0].ordering = CHOLMOD_AMD;
  // CHOLMOD prints its warnings on stdout, where the CLI writes JSON; its
  // failures come back through info() and become a SolverError below.
  cholesky.cholmod().print = 0;
  cholesky.compute(normal);
  if (cholesky.info() != Eigen::Success) {
    throw SolverError(
        "smoothing B-patch fit: CHOLMOD could not factor the normal equations "
        "(are the valid nodes collinear?)");
  }
  const VectorXd solution = cholesky.solve(rhs);
  if (cholesky.info() != Eigen::Success || !solution.allFinite()) {
    throw SolverError("smoothing B-patch fit: CHOLMOD solve failed");
  }
  return Eigen::Map<const MatrixXd>(solution.data(), mx, my);
}

// ---------------------------------------------------------------------------
// Tensor PCG.
//
// With the control points as an mx x my matrix X (x index first), the normal
// operator is
//   N X = Cx^T (W o (Cx X Cy^T)) Cy + lambda (Kx X My + 2 Gx X Gy + Mx X Ky),
// Cx the nc x (nc + 2) collocation matrix, W the validity mask. Every per-axis
// matrix is banded (half-bandwidth <= 3), so N X costs O(nodes).
//
// Preconditioner: per axis, the generalised eigenvectors V of the pencil
// (A + lambda K, M), A = Cx^T Cx (V^T M V = I). In the basis Vy (x) Vx the
// void-free N is close to diagonal (exactly so on the mass term, and on the
// data term for lambda -> 0, where the two null vectors of A at each end are
// the stiff directions), and P = (Vy (x) Vx)^-T diag(N^) (Vy (x) Vx)^-1, diag(N^)
// the diagonal of N in that basis, keeps the PCG iteration count at 10-25 for
// lambda from 1e-8 to 1e4, independent of the grid size. All per-axis matrices
// are persymmetric (symmetric under reversing the index), so V splits into
// even and odd halves: the transforms are two half-size dense products per
// axis, done in single precision (OpenBLAS sgemm) since the preconditioner
// only steers the iteration; residuals and the iterate stay in double.

/// Symmetric banded matrix of size m, half-bandwidth 3: band(i, d) = H(i, i + d - 3)
/// (0 outside the matrix).
struct Banded {
  Eigen::Matrix<double, Eigen::Dynamic, 7> band;
  long size() const { return band.rows(); }
};

Banded banded(const SparseMatrix& h) {
  Banded b{Eigen::Matrix<double, Eigen::Dynamic, 7>::Zero(h.rows(), 7)};
  for (int k = 0; k < h.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(h, k); it; ++it) {
      const long d = it.col() - it.row() + 3;
      if (d < 0 || d > 6) throw SolverError("smoothing B-patch fit: unexpected bandwidth");
      b.band(it.row(), d) = it.value();
    }
  return b;
}

/// y += s B x on vectors of length B.size().
void band_axpy(const Banded& b, const double* x, double* y, double s) {
  const long m = b.size();
  for (long d = 0; d < 7; ++d) {
    const long off = d - 3, lo = std::max(0L, -off), hi = std::min(m, m - off);
    const double* coef = b.band.col(d).data();
    for (long i = lo; i < hi; ++i) y[i] += s * coef[i] * x[i + off];
  }
}

/// Per-axis data: the banded matrices and, once the preconditioner is built,
/// the even/odd eigenvector blocks and the diagonals of A, G, K in that basis.
struct Axis {
  long nodes = 0, size = 0;  // n, n + 2
  Banded a, m, g, k;
  long even = 0, odd = 0;           // (size + 1) / 2, size / 2
  MatrixR w_even, w_odd;            // eigenvectors in the folded coordinates
  VectorXd diag_a, diag_g, diag_k;  // per mode: [even modes, odd modes]
};

Axis make_axis(std::size_t n) {
  Axis axis;
  axis.nodes = static_cast<long>(n);
  axis.size = axis.nodes + 2;
  const GramMatrices gram = gram_matrices(n);
  std::vector<Eigen::Triplet<double>> c;
  for (long i = 0; i < axis.nodes; ++i)
    for (long a = 0; a < 3; ++a) c.emplace_back(i, i + a, kCollocation[a]);
  SparseMatrix colloc(axis.nodes, axis.size);
  colloc.setFromTriplets(c.begin(), c.end());
  axis.a = banded(SparseMatrix(colloc.transpose() * colloc));
  axis.m = banded(gram.value);
  axis.g = banded(gram.first);
  axis.k = banded(gram.second);
  axis.even = (axis.size + 1) / 2;
  axis.odd = axis.size / 2;
  return axis;
}

/// f(0, n / 2) and f(n / 2, n) on two threads (one if n is small or the
/// machine has one core): the column loops of the matrix-free product.
template <class F>
void in_two_halves(long n, const F& f) {
  if (n < 256 || std::thread::hardware_concurrency() < 2) {
    f(0L, n);
    return;
  }
  std::thread other(f, n / 2, n);
  f(0L, n / 2);
  other.join();
}

/// Widths (control points) added around the voids' basis supports for the
/// preconditioner's local void correction, tried in turn, and the largest
/// share of all control points that correction may cover (any share up to
/// kVoidPointsAlways points).
constexpr std::array<long, 2> kVoidMargins = {6, 2};
constexpr double kMaxVoidFraction = 0.1, kVoidPointsAlways = 20000.0;

constexpr double kHalfSqrt2 = 0.70710678118654752440;

/// Folds a vector of length m (stride `stride`) into its even part (first
/// (m + 1) / 2 entries) and odd part: an orthogonal change of basis.
template <class In, class Out>
void fold(const In* x, long stride, long m, Out* out, long out_stride) {
  const long h = m / 2, even = (m + 1) / 2;
  for (long i = 0; i < h; ++i) {
    const double u = static_cast<double>(x[i * stride]);
    const double v = static_cast<double>(x[(m - 1 - i) * stride]);
    out[i * out_stride] = static_cast<Out>(kHalfSqrt2 * (u + v));
    out[(even + i) * out_stride] = static_cast<Out>(kHalfSqrt2 * (u - v));
  }
  if (m % 2 == 1) out[h * out_stride] = static_cast<Out>(x[h * stride]);
}

/// Inverse of fold().
template <class In, class Out>
void unfold(const In* x, long stride, long m, Out* out, long out_stride) {
  const long h = m / 2, even = (m + 1) / 2;
  for (long i = 0; i < h; ++i) {
    const double e = static_cast<double>(x[i * stride]);
    const double o = static_cast<double>(x[(even + i) * stride]);
    out[i * out_stride] = static_cast<Out>(kHalfSqrt2 * (e + o));
    out[(m - 1 - i) * out_stride] = static_cast<Out>(kHalfSqrt2 * (e - o));
  }
  if (m % 2 == 1) out[h * out_stride] = static_cast<Out>(x[h * stride]);
}

/// Q H Q^T for the fold Q, of a dense symmetric persymmetric H: block
/// diagonal, even block first.
MatrixXd fold_dense(const MatrixXd& h) {
  const long m = h.rows();
  MatrixXd cols(m, m), out(m, m);
  for (long j = 0; j < m; ++j) fold(h.col(j).data(), 1, m, cols.col(j).data(), 1);
  for (long i = 0; i < m; ++i) fold(cols.data() + i, m, m, out.data() + i, m);
  return out;
}

MatrixXd dense(const Banded& b) {
  const long m = b.size();
  MatrixXd out = MatrixXd::Zero(m, m);
  for (long i = 0; i < m; ++i)
    for (long d = 0; d < 7; ++d) {
      const long j = i + d - 3;
      if (j >= 0 && j < m) out(i, j) = b.band(i, d);
    }
  return out;
}

/// Generalised eigenvectors of (h, mass), both symmetric, mass SPD, via LAPACK
/// dsygvd; W^T mass W = I. Double precision: in single precision the smooth
/// modes of h = A + lambda K come out poorly for large lambda (PCG needs 50%
/// more iterations at lambda = 1e4). Returns false if LAPACK fails.
bool generalised_eigenvectors(MatrixXd a, MatrixXd b, MatrixXd& vectors) {
  const int n = static_cast<int>(a.rows()), itype = 1;
  VectorXd w(n);
  int info = 0, lwork = -1, liwork = -1, iwork_query = 0;
  double work_query = 0.0;
  dsygvd_(&itype, "V", "L", &n, a.data(), &n, b.data(), &n, w.data(), &work_query, &lwork,
          &iwork_query, &liwork, &info, 1, 1);
  if (info != 0) return false;
  lwork = static_cast<int>(work_query) + 1;
  liwork = iwork_query;
  std::vector<double> work(static_cast<std::size_t>(lwork));
  std::vector<int> iwork(static_cast<std::size_t>(liwork));
  dsygvd_(&itype, "V", "L", &n, a.data(), &n, b.data(), &n, w.data(), work.data(), &lwork,
          iwork.data(), &liwork, &info, 1, 1);
  if (info != 0 || !a.allFinite()) return false;
  vectors = std::move(a);
  return true;
}

/// v^T B v for a banded B.
double quadratic(const Banded& b, const VectorXd& v) {
  VectorXd bv = VectorXd::Zero(v.size());
  band_axpy(b, v.data(), bv.data(), 1.0);
  return v.dot(bv);
}

bool build_basis(Axis& axis, double lambda) {
  const MatrixXd h = fold_dense(dense(axis.a) + lambda * dense(axis.k));
  const MatrixXd mass = fold_dense(dense(axis.m));
  MatrixXd we, wo;
  if (!generalised_eigenvectors(h.topLeftCorner(axis.even, axis.even),
                                mass.topLeftCorner(axis.even, axis.even), we) ||
      !generalised_eigenvectors(h.bottomRightCorner(axis.odd, axis.odd),
                                mass.bottomRightCorner(axis.odd, axis.odd), wo)) {
    return false;
  }
  const long m = axis.size;
  axis.diag_a.resize(m);
  axis.diag_g.resize(m);
  axis.diag_k.resize(m);
  VectorXd folded(m), v(m);
  for (long mode = 0; mode < m; ++mode) {
    folded.setZero();
    if (mode < axis.even)
      folded.head(axis.even) = we.col(mode);
    else
      folded.tail(axis.odd) = wo.col(mode - axis.even);
    unfold(folded.data(), 1, m, v.data(), 1);
    axis.diag_a(mode) = quadratic(axis.a, v);
    axis.diag_g(mode) = quadratic(axis.g, v);
    axis.diag_k(mode) = quadratic(axis.k, v);
  }
  axis.w_even = we.cast<Real>();
  axis.w_odd = wo.cast<Real>();
  return true;
}

class TensorSystem {
 public:
  TensorSystem(const ElevationGrid& grid, double lambda)
      : lambda_(lambda),
        x_(make_axis(grid.ncols())),
        y_(grid.nrows() == grid.ncols() ? x_ : make_axis(grid.nrows())),
        data_(grid_data(grid)) {}

  long mx() const { return x_.size; }
  long my() const { return y_.size; }

  bool build_preconditioner() {
    if (!build_basis(x_, lambda_)) return false;
    if (y_.nodes == x_.nodes) {
      y_ = x_;
    } else if (!build_basis(y_, lambda_)) {
      return false;
    }
    diag_.resize(mx(), my());
    for (long j = 0; j < my(); ++j)
      for (long i = 0; i < mx(); ++i) {
        const double d =
            x_.diag_a(i) * y_.diag_a(j) +
            lambda_ * (x_.diag_k(i) + 2.0 * x_.diag_g(i) * y_.diag_g(j) + y_.diag_k(j));
        if (!(d > 0.0)) return false;
        diag_(i, j) = static_cast<Real>(1.0 / d);
      }
    return build_void_correction();
  }

  /// Cx^T (W o D) Cy, D the data.
  MatrixXd rhs() {
    MatrixXd out;
    collocation_transpose(data_.values.cwiseProduct(data_.mask), out);
    return out;
  }

  /// out = N x.
  void apply(const MatrixXd& x, MatrixXd& out) {
    // Data term: node values of x (masked), then Cx^T (.) Cy column by column.
    const long nc = x_.nodes, nr = y_.nodes, m_x = mx(), m_y = my();
    nodes_.resize(nc, m_y);
    for (long b = 0; b < m_y; ++b) {
      const double* xc = x.col(b).data();
      double* nd = nodes_.col(b).data();
      for (long i = 0; i < nc; ++i)
        nd[i] = kCollocation[0] * xc[i] + kCollocation[1] * xc[i + 1] + kCollocation[2] * xc[i + 2];
    }
    values_.resize(nc, nr);
    for (long j = 0; j < nr; ++j)
      values_.col(j) = (kCollocation[0] * nodes_.col(j) + kCollocation[1] * nodes_.col(j + 1) +
                        kCollocation[2] * nodes_.col(j + 2))
                           .cwiseProduct(data_.mask.col(j));
    out.resize(m_x, m_y);
    in_two_halves(m_y, [&](long begin, long end) { apply_columns(x, out, begin, end); });
  }

  /// out = P^-1 r.
  void precondition(const MatrixXd& r, MatrixXd& out) {
    const long m_x = mx(), m_y = my(), h = m_y / 2, even = y_.even;
    fold_x_.resize(m_x, m_y);
    xm_.resize(m_x);
    xg_.resize(m_x);
    // fold_x_ = Qx r Qy^T (x fold of each column, then pairs of columns).
    for (long j = 0; j < h; ++j) {
      fold(r.col(j).data(), 1, m_x, xm_.data(), 1);
      fold(r.col(m_y - 1 - j).data(), 1, m_x, xg_.data(), 1);
      fold_x_.col(j) = (kHalfSqrt2 * (xm_ + xg_)).cast<Real>();
      fold_x_.col(even + j) = (kHalfSqrt2 * (xm_ - xg_)).cast<Real>();
    }
    if (m_y % 2 == 1) {
      fold(r.col(h).data(), 1, m_x, xm_.data(), 1);
      fold_x_.col(h) = xm_.cast<Real>();
    }
    work_.resize(m_x, m_y);
    transform_blocks(true);
    fold_x_.array() *= diag_.array();
    transform_blocks(false);
    out.resize(m_x, m_y);
    for (long j = 0; j < h; ++j) {
      const VectorXd e = fold_x_.col(j).cast<double>(), o = fold_x_.col(even + j).cast<double>();
      xm_ = kHalfSqrt2 * (e + o);
      xg_ = kHalfSqrt2 * (e - o);
      unfold(xm_.data(), 1, m_x, out.col(j).data(), 1);
      unfold(xg_.data(), 1, m_x, out.col(m_y - 1 - j).data(), 1);
    }
    if (m_y % 2 == 1) {
      xm_ = fold_x_.col(h).cast<double>();
      unfold(xm_.data(), 1, m_x, out.col(h).data(), 1);
    }
    if (!omega_.empty()) {
      // Additive local solve on the control points around the voids.
      VectorXd local(static_cast<Eigen::Index>(omega_.size()));
      for (std::size_t k = 0; k < omega_.size(); ++k)
        local[static_cast<Eigen::Index>(k)] = r.data()[omega_[k]];
      const VectorXd correction = local_.solve(local);
      for (std::size_t k = 0; k < omega_.size(); ++k)
        out.data()[omega_[k]] += correction[static_cast<Eigen::Index>(k)];
    }
  }

 private:
  /// The preconditioner above knows nothing of the voids: where a void leaves
  /// control points without data (a hole, small lambda) it is far off. Add the
  /// exact inverse of N restricted to the control points whose basis functions
  /// reach a void node, widened by kVoidMargins (additive Schwarz): P^-1 +
  /// R^T N_omega^-1 R, still SPD. With too many voids for any margin there is
  /// no correction (plain PCG, CHOLMOD if it stalls). False if the local
  /// factorisation fails.
  bool build_void_correction() {
    const long nc = x_.nodes, nr = y_.nodes, m_x = mx(), m_y = my();
    if (data_.mask.minCoeff() != 0.0) return true;
    std::vector<char> in;
    for (const long margin : kVoidMargins) {
      in.assign(static_cast<std::size_t>(m_x * m_y), 0);
      for (long j = 0; j < nr; ++j)
        for (long i = 0; i < nc; ++i) {
          if (data_.mask(i, j) != 0.0) continue;
          for (long b = std::max(0L, j - margin); b <= std::min(m_y - 1, j + 2 + margin); ++b)
            for (long a = std::max(0L, i - margin); a <= std::min(m_x - 1, i + 2 + margin); ++a)
              in[static_cast<std::size_t>(a + b * m_x)] = 1;
        }
      const auto count = static_cast<double>(std::count(in.begin(), in.end(), char{1}));
      if (count <= std::max(kMaxVoidFraction * static_cast<double>(m_x * m_y), kVoidPointsAlways))
        break;
      in.clear();
    }
    // Too many voids for a local correction: plain PCG (CHOLMOD if it stalls).
    if (in.empty()) return true;
    std::vector<long> index(in.size(), -1);
    for (long k = 0; k < m_x * m_y; ++k)
      if (in[static_cast<std::size_t>(k)] != 0) {
        index[static_cast<std::size_t>(k)] = static_cast<long>(omega_.size());
        omega_.push_back(k);
      }
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t row = 0; row < omega_.size(); ++row) {
      const long a = omega_[row] % m_x, b = omega_[row] / m_x;
      for (long b2 = std::max(0L, b - 3); b2 <= std::min(m_y - 1, b + 3); ++b2)
        for (long a2 = std::max(0L, a - 3); a2 <= std::min(m_x - 1, a + 3); ++a2) {
          const long col = index[static_cast<std::size_t>(a2 + b2 * m_x)];
          if (col < 0) continue;
          const long dx = a2 - a + 3, dy = b2 - b + 3;
          double v = lambda_ * (y_.m.band(b, dy) * x_.k.band(a, dx) +
                                2.0 * y_.g.band(b, dy) * x_.g.band(a, dx) +
                                y_.k.band(b, dy) * x_.m.band(a, dx));
          // Data: valid nodes (i, j) whose basis support holds both points.
          for (long j = std::max({0L, b - 2, b2 - 2}); j <= std::min({nr - 1, b, b2}); ++j)
            for (long i = std::max({0L, a - 2, a2 - 2}); i <= std::min({nc - 1, a, a2}); ++i)
              v += data_.mask(i, j) * kCollocation[a - i] * kCollocation[a2 - i] *
                   kCollocation[b - j] * kCollocation[b2 - j];
          if (v != 0.0) entries.emplace_back(static_cast<long>(row), col, v);
        }
    }
    const auto size = static_cast<Eigen::Index>(omega_.size());
    SparseMatrix local(size, size);
    local.setFromTriplets(entries.begin(), entries.end());
    local_.cholmod().nmethods = 1;
    local_.cholmod().method[0].ordering = CHOLMOD_AMD;
    local_.cholmod().print = 0;
    local_.compute(local);
    return local_.info() == Eigen::Success;
  }

  /// Columns [begin, end) of N x, given values_ (the masked node values of x).
  void apply_columns(const MatrixXd& x, MatrixXd& out, long begin, long end) const {
    const long nc = x_.nodes, nr = y_.nodes, m_x = mx(), m_y = my();
    VectorXd column(nc), xm(m_x), xg(m_x), xk(m_x);
    for (long b = begin; b < end; ++b) {
      // Data term: Cy (values columns b - 2 .. b), then Cx^T.
      column.setZero();
      for (long t = 0; t < 3; ++t) {
        const long j = b - t;
        if (j >= 0 && j < nr) column += kCollocation[t] * values_.col(j);
      }
      out.col(b).setZero();
      double* o = out.col(b).data();
      for (long i = 0; i < nc; ++i) {
        const double u = column[i];
        o[i] += kCollocation[0] * u;
        o[i + 1] += kCollocation[1] * u;
        o[i + 2] += kCollocation[2] * u;
      }
      // Curvature energy: column b of x My, x Gy, x Ky, then Kx, Gx, Mx.
      xm.setZero();
      xg.setZero();
      xk.setZero();
      for (long d = 0; d < 7; ++d) {
        const long jj = b + d - 3;
        if (jj < 0 || jj >= m_y) continue;
        const auto xc = x.col(jj);
        xm += y_.m.band(b, d) * xc;
        xg += y_.g.band(b, d) * xc;
        xk += y_.k.band(b, d) * xc;
      }
      band_axpy(x_.k, xm.data(), o, lambda_);
      band_axpy(x_.g, xg.data(), o, 2.0 * lambda_);
      band_axpy(x_.m, xk.data(), o, lambda_);
    }
  }

  /// out = Cx^T v Cy for v of nc x nr.
  void collocation_transpose(const MatrixXd& v, MatrixXd& out) {
    back_.setZero(x_.nodes, my());
    for (long j = 0; j < y_.nodes; ++j)
      for (long b = 0; b < 3; ++b) back_.col(j + b) += kCollocation[b] * v.col(j);
    out.setZero(mx(), my());
    for (long b = 0; b < my(); ++b)
      for (long i = 0; i < x_.nodes; ++i) {
        const double u = back_(i, b);
        out(i, b) += kCollocation[0] * u;
        out(i + 1, b) += kCollocation[1] * u;
        out(i + 2, b) += kCollocation[2] * u;
      }
  }

  /// Forward: block <- Wx^T block Wy; backward: block <- Wx block Wy^T, for
  /// the four (x parity, y parity) blocks of fold_x_ (leading dimension mx).
  void transform_blocks(bool forward) {
    const int ld = static_cast<int>(mx());
    const std::array<const MatrixR*, 2> wx = {&x_.w_even, &x_.w_odd}, wy = {&y_.w_even, &y_.w_odd};
    const std::array<long, 2> xoff = {0, x_.even}, yoff = {0, y_.even};
    const int width = static_cast<int>(my());
    for (int p = 0; p < 2; ++p) {
      const int sx = static_cast<int>(wx[p]->rows());
      if (sx == 0) continue;
      // x: one product over all columns of the parity-p rows.
      gemm(forward ? CblasTrans : CblasNoTrans, CblasNoTrans, sx, width, sx, wx[p]->data(), sx,
           fold_x_.data() + xoff[p], ld, work_.data() + xoff[p], ld);
      // y: one product per column parity.
      for (int q = 0; q < 2; ++q) {
        const int sy = static_cast<int>(wy[q]->rows());
        if (sy == 0) continue;
        gemm(CblasNoTrans, forward ? CblasNoTrans : CblasTrans, sx, sy, sy,
             work_.data() + xoff[p] + yoff[q] * mx(), ld, wy[q]->data(), sy,
             fold_x_.data() + xoff[p] + yoff[q] * mx(), ld);
      }
    }
  }

  double lambda_;
  Axis x_, y_;
  GridData data_;
  MatrixR diag_;  // 1 / diag(N^), mode layout
  MatrixXd nodes_, values_, back_;
  VectorXd xm_, xg_;
  MatrixR fold_x_, work_;
  std::vector<long> omega_;  // control points (linear index) of the void correction
  Eigen::CholmodSupernodalLLT<SparseMatrix> local_;
};

double max_abs(const MatrixXd& m) {
  return m.cwiseAbs().maxCoeff();
}

/// PCG (flexible, Polak–Ribiere beta, since the single-precision
/// preconditioner is not exactly symmetric). Stops when the preconditioned
/// residual, an estimate of the remaining error in the control points, is
/// below kTolerance times the data's elevation range.
constexpr double kTolerance = 1e-9;
constexpr std::size_t kMaxIterations = 120;
/// From this iteration on, PCG gives up (and CHOLMOD takes over) when the mean
/// convergence rate so far would not reach the tolerance by kMaxIterations.
/// Void-free grids converge in 15-25 iterations for lambda in [1e-8, 1e4].
constexpr std::size_t kStagnationCheck = 40;

double elevation_scale(const ElevationGrid& grid) {
  double lo = 0.0, hi = 0.0;
  bool any = false;
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      if (!grid.valid(i, j)) continue;
      const double z = grid.at(i, j);
      lo = any ? std::min(lo, z) : z;
      hi = any ? std::max(hi, z) : z;
      any = true;
    }
  return hi > lo ? hi - lo : std::max(std::abs(hi), 1.0);
}

bool solve_pcg(const ElevationGrid& grid, double lambda, MatrixXd& solution,
               detail::SmoothingSolveReport& report) {
  TensorSystem system(grid, lambda);
  if (!system.build_preconditioner()) return false;
  const double tolerance = kTolerance * elevation_scale(grid);

  MatrixXd r = system.rhs(), z, p, q;
  solution.setZero(system.mx(), system.my());
  system.precondition(r, z);
  p = z;
  double rz = (r.array() * z.array()).sum();
  const double initial = max_abs(z);
  if (initial <= tolerance) {
    report.pcg_converged = true;
    return true;
  }
  const Eigen::Index size = r.size();
  for (std::size_t it = 1; it <= kMaxIterations; ++it) {
    system.apply(p, q);
    const double pq = (p.array() * q.array()).sum();
    if (!(pq > 0.0) || !std::isfinite(pq)) return false;
    const double alpha = rz / pq;
    {
      double *xd = solution.data(), *rd = r.data();
      const double *pd = p.data(), *qd = q.data();
      for (Eigen::Index k = 0; k < size; ++k) {
        xd[k] += alpha * pd[k];
        rd[k] -= alpha * qd[k];
      }
    }
    system.precondition(r, z);
    report.iterations = it;
    double rz_new = 0.0, zq = 0.0, z_max = 0.0;
    {
      const double *rd = r.data(), *zd = z.data(), *qd = q.data();
      for (Eigen::Index k = 0; k < size; ++k) {
        rz_new += rd[k] * zd[k];
        zq += zd[k] * qd[k];
        z_max = std::max(z_max, std::abs(zd[k]));
      }
    }
    if (!std::isfinite(rz_new) || !std::isfinite(zq)) return false;
    if (z_max <= tolerance) {
      report.pcg_converged = solution.allFinite();
      return report.pcg_converged;
    }
    // Stagnation: on grids with large voids the void-free preconditioner can
    // need hundreds of iterations; give up early and let CHOLMOD solve it.
    if (it >= kStagnationCheck) {
      const double rate = std::pow(z_max / initial, 1.0 / static_cast<double>(it));
      if (!(rate < 1.0) || static_cast<double>(it) + std::log(tolerance / z_max) / std::log(rate) >
                               static_cast<double>(kMaxIterations)) {
        return false;
      }
    }
    const double beta = -alpha * zq / rz;
    p = z + beta * p;
    rz = rz_new;
  }
  return false;
}

void check_input(const ElevationGrid& grid, double lambda) {
  if (!(lambda > 0.0) || !std::isfinite(lambda)) {
    throw InputError("smoothing weight lambda must be positive and finite, got " +
                     std::to_string(lambda) + " (lambda = 0 is the interpolating fit)");
  }
  if (grid.ncols() < 4 || grid.nrows() < 4) {
    throw InputError("a B-patch needs at least 4 x 4 nodes, got " + std::to_string(grid.ncols()) +
                     " x " + std::to_string(grid.nrows()));
  }
  if (grid.ncols() * grid.nrows() - grid.void_count() < 3) {
    throw InputError("smoothing fit needs at least 3 valid nodes, the grid has " +
                     std::to_string(grid.ncols() * grid.nrows() - grid.void_count()));
  }
}

}  // namespace

namespace detail {

MatrixXd smoothing_control_points(const ElevationGrid& grid, double lambda, SmoothingSolver solver,
                                  SmoothingSolveReport* report) {
  check_input(grid, lambda);
  SmoothingSolveReport local;
  SmoothingSolveReport& out = report != nullptr ? *report : local;
  out = SmoothingSolveReport{};
  if (solver != SmoothingSolver::cholmod) {
    MatrixXd solution;
    if (solve_pcg(grid, lambda, solution, out)) return solution;
    if (solver == SmoothingSolver::tensor_pcg) {
      throw SolverError("smoothing B-patch fit: PCG did not converge in " +
                        std::to_string(out.iterations) + " iterations");
    }
  }
  out.used_cholmod = true;
  return solve_cholmod(grid, lambda);
}

}  // namespace detail

BPatch BPatch::fit_smoothing(const ElevationGrid& grid, double lambda) {
  return BPatch(grid,
                detail::smoothing_control_points(grid, lambda, detail::SmoothingSolver::automatic));
}

}  // namespace talus
