#pragma once
/// @file
/// BPatch: the smooth terrain surface z(x, y), a bicubic tensor-product
/// B-spline over an elevation grid.
///
/// The knots are uniform at the grid's node spacing h, so the surface has
/// (ncols + 2) × (nrows + 2) control points and is C² everywhere; its domain
/// is the grid's node rectangle [x_min, x_max] × [y_min, y_max]. Two fits:
/// - interpolate(): exact at every node; the two extra conditions per row and
///   column are "not-a-knot" (no jump of the third derivative at the second
///   and second-to-last knot), so any bicubic polynomial is reproduced exactly.
/// - fit_smoothing(): least squares on the valid nodes plus λ times the
///   thin-plate curvature energy ∫∫ (z_uu² + 2 z_uv² + z_vv²) du dv measured in
///   grid-index units u = (x - x_min)/h, v = (y - y_min)/h. Both terms are in
///   m², so λ is dimensionless: λ = 1 smooths over about one cell on any grid.
///   The normal equations (one SPD system in the control points) are solved
///   by preconditioned conjugate gradients using the tensor-product structure:
///   matrix-free products with the banded per-axis matrices, and a
///   preconditioner diagonal in the basis of per-axis generalised eigenvectors
///   of (A + λ K, M) (A the collocation Gram, K and M the curvature and value
///   Grams), applied with dense per-axis products (OpenBLAS). 15-25 iterations
///   for λ in [1e-8, 1e4] on any grid size; 1024 × 1024 in 2.7 s and 125 MB
///   (bench_bpatch on a loaded 2-core machine, where CHOLMOD took 128 s and
///   5.7 GB). The iteration stops when its error estimate is below 1e-9 of
///   the elevation range. Around NODATA voids the preconditioner adds an
///   exact local solve (sparse Cholesky, SuiteSparse CHOLMOD) on the control
///   points near them; when the voids are too many for that (over 10% of the
///   control points and over 20000) and PCG stalls, the whole system is
///   solved by CHOLMOD instead.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/instance_id.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// Elevation and its first and second derivatives at one point.
struct SurfacePoint {
  double z = 0.0;                ///< elevation [m]
  Vec2 gradient = Vec2::Zero();  ///< (z_x, z_y) [-]
  Mat2 hessian = Mat2::Zero();   ///< [[z_xx, z_xy], [z_xy, z_yy]] [1/m]
};

/// How fit_smoothing() and interpolate() treat NODATA nodes.
struct BPatchFitReport {
  double max_node_residual = 0.0;  ///< max |z(node) - data| over valid nodes [m]
  double rms_residual = 0.0;       ///< RMS of the same [m]
  std::size_t voids = 0;           ///< NODATA nodes (excluded from the fit)
};

class BPatch {
 public:
  /// Interpolating fit. A grid with NODATA nodes is an InputError naming the
  /// first one; fill it first (fill_voids) if that is what you want.
  /// Needs at least 4 × 4 nodes (6 × 6 for degree 5). `degree` 3 (default: the bicubic B-patch,
  /// C²) or 5 (biquintic, C⁴: curvatures with continuous derivatives, which
  /// the simultaneous NLP's constraint Jacobian needs to converge; about
  /// twice the evaluation cost); anything else is an InputError. Its matrices need about
  /// kInterpolationBytesPerNode bytes a node, checked against the memory budget first.
  static BPatch interpolate(const ElevationGrid& grid, int degree = 3);
  /// Peak memory of interpolate() per grid node [bytes]: the right-hand sides, the
  /// half-solved and the solved control values (a padded double each), the transposed
  /// result and the cell mask, alive together.
  static constexpr double kInterpolationBytesPerNode = 48.0;
  /// Smoothing fit with curvature weight lambda > 0 (see the file comment);
  /// NODATA nodes are left out of the data term. Throws InputError for
  /// lambda <= 0 or fewer than 3 valid nodes, SolverError if CHOLMOD (the
  /// fallback) fails.
  static BPatch fit_smoothing(const ElevationGrid& grid, double lambda);

  double x_min() const { return x_min_; }
  double y_min() const { return y_min_; }
  double x_max() const { return x_min_ + static_cast<double>(ncols_ - 1) * h_; }
  double y_max() const { return y_min_ + static_cast<double>(nrows_ - 1) * h_; }
  double cellsize() const { return h_; }
  std::size_t ncols() const { return ncols_; }
  std::size_t nrows() const { return nrows_; }
  /// Polynomial degree in each direction: 3 (bicubic) or 5 (biquintic;
  /// interpolate() only, fit_smoothing() is bicubic).
  int degree() const { return degree_; }
  /// Number of polynomial pieces, (ncols - 1) (nrows - 1).
  std::size_t patches() const { return (ncols_ - 1) * (nrows_ - 1); }
  /// (ncols + degree − 1) × (nrows + degree − 1) control values, entry (a, b)
  /// weighting the basis functions centred on node (a − (degree − 1)/2,
  /// b − (degree − 1)/2).
  const Eigen::MatrixXd& control_points() const { return data_->control; }

  bool contains(const Vec2& p) const;
  /// False where the source grid had a NODATA node at a corner of p's cell:
  /// the surface there is extrapolated by the fit, not measured.
  bool on_data(const Vec2& p) const;

  /// z at p. Throws InputError if p is outside the domain or not finite.
  double elevation(const Vec2& p) const;
  /// z, gradient and Hessian at p, O(1), no allocation. Throws InputError if
  /// p is outside the domain or not finite.
  SurfacePoint evaluate(const Vec2& p) const;
  /// Third derivatives (z_xxx, z_xxy, z_xyy, z_yyy) [1/m²] at p, as the
  /// piece holding p has them (degree 3: they jump across cell edges;
  /// degree 5: continuous). For
  /// differentiating curvatures with respect to position. Same errors as
  /// evaluate().
  Eigen::Vector4d third_derivatives(const Vec2& p) const;

  /// Residuals of the surface at the valid nodes of `grid` (same geometry).
  BPatchFitReport residuals(const ElevationGrid& grid) const;

  /// This surface's identity (core/instance_id.hpp): caches built for it
  /// (GlobalSearchWorkspace) recognise it by this, not by its address. Every
  /// fit has a new one; a copy is the same surface (its coefficients are
  /// shared and immutable) and keeps it.
  std::uint64_t identity() const { return data_->identity.value(); }

 private:
  BPatch(const ElevationGrid& grid, Eigen::MatrixXd control, int degree = 3);
  SurfacePoint evaluate_quintic(std::size_t i, std::size_t j, double tu, double tv) const;
  void locate(const Vec2& p, std::size_t& i, std::size_t& j, double& tu, double& tv) const;
  [[noreturn]] void throw_outside(const Vec2& p) const;

  int degree_ = 3;
  std::size_t ncols_ = 0, nrows_ = 0;
  double h_ = 1.0, inverse_h_ = 1.0, x_min_ = 0.0, y_min_ = 0.0;
  /// The fit's coefficients, immutable and shared by every copy of the
  /// surface: a BPatch is a cheap value (a copy costs a reference count, not
  /// the grid), so paths, problems and results hold the surface itself and
  /// nothing has to be kept alive by its caller.
  struct Coefficients {
    Eigen::MatrixXd control;
    std::vector<unsigned char> cell_on_data;  ///< per cell, (ncols-1) × (nrows-1)
    InstanceId identity;
  };
  std::shared_ptr<const Coefficients> data_;
};

}  // namespace talus
