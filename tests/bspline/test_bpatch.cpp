#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/detail/smoothing_solver.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/terrain_generators.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

/// The tests' grids: nc x nr nodes at spacing h, off the origin unless told otherwise.
ElevationGrid sample(const terrain_test::HeightFunction& f, std::size_t nc, std::size_t nr,
                     double h, double x0 = 3.0, double y0 = -2.0) {
  return terrain_test::grid_of_nodes(f, nc, nr, h, x0, y0);
}

// A full bicubic polynomial (all 16 monomials x^a y^b, a, b <= 3).
double bicubic(double x, double y) {
  const double c[4][4] = {{1.0, -0.5, 0.2, 0.01},
                          {0.3, 0.07, -0.02, 0.003},
                          {-0.04, 0.01, 0.005, -0.001},
                          {0.002, -0.0007, 0.0003, 0.0001}};
  double z = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) z += c[a][b] * std::pow(x, a) * std::pow(y, b);
  return z;
}

TEST(BPatch, InterpolationIsExactAtEveryNode) {
  const ElevationGrid grid = sample(
      [](double x, double y) { return std::sin(x) * std::cos(0.7 * y) + 0.1 * x; }, 23, 17, 0.4);
  const BPatch patch = BPatch::interpolate(grid);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i)
      EXPECT_NEAR(patch.elevation(grid.node_position(i, j)), grid.at(i, j), 1e-12);
  EXPECT_LT(patch.residuals(grid).max_node_residual, 1e-12);
  EXPECT_EQ(patch.patches(), 22u * 16u);
}

TEST(BPatch, InterpolationReproducesBicubicPolynomialsWithDerivatives) {
  const ElevationGrid grid = sample(bicubic, 12, 9, 0.5);
  const BPatch patch = BPatch::interpolate(grid);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ux(patch.x_min(), patch.x_max()),
      uy(patch.y_min(), patch.y_max());
  for (int k = 0; k < 200; ++k) {
    const double x = ux(rng), y = uy(rng), e = 1e-4;
    const SurfacePoint sp = patch.evaluate({x, y});
    EXPECT_NEAR(sp.z, bicubic(x, y), 1e-10);
    // Derivatives of the exact polynomial by central differences (exact up to O(e^2) on a cubic).
    const double zx = (bicubic(x + e, y) - bicubic(x - e, y)) / (2 * e);
    const double zy = (bicubic(x, y + e) - bicubic(x, y - e)) / (2 * e);
    const double zxx = (bicubic(x + e, y) - 2 * bicubic(x, y) + bicubic(x - e, y)) / (e * e);
    const double zyy = (bicubic(x, y + e) - 2 * bicubic(x, y) + bicubic(x, y - e)) / (e * e);
    const double zxy = (bicubic(x + e, y + e) - bicubic(x + e, y - e) - bicubic(x - e, y + e) +
                        bicubic(x - e, y - e)) /
                       (4 * e * e);
    EXPECT_NEAR(sp.gradient.x(), zx, 1e-6);
    EXPECT_NEAR(sp.gradient.y(), zy, 1e-6);
    EXPECT_NEAR(sp.hessian(0, 0), zxx, 1e-4);
    EXPECT_NEAR(sp.hessian(1, 1), zyy, 1e-4);
    EXPECT_NEAR(sp.hessian(0, 1), zxy, 1e-4);
    EXPECT_EQ(sp.hessian(0, 1), sp.hessian(1, 0));
  }
}

/// The falling factorial a (a − 1) ... (a − k + 1): d^k/dx^k x^a = falling(a, k) x^(a−k).
double falling(int a, int k) {
  double f = 1.0;
  for (int i = 0; i < k; ++i) f *= a - i;
  return f;
}

/// ∂^(p+q) bicubic / ∂x^p ∂y^q, term by term: x^a -> a!/(a-p)! x^(a-p).
double bicubic_derivative(double x, double y, int p, int q) {
  const double c[4][4] = {{1.0, -0.5, 0.2, 0.01},
                          {0.3, 0.07, -0.02, 0.003},
                          {-0.04, 0.01, 0.005, -0.001},
                          {0.002, -0.0007, 0.0003, 0.0001}};
  double z = 0.0;
  for (int a = p; a < 4; ++a)
    for (int b = q; b < 4; ++b)
      z += c[a][b] * falling(a, p) * falling(b, q) * std::pow(x, a - p) * std::pow(y, b - q);
  return z;
}

TEST(BPatch, ThirdDerivativesOfAnInterpolatedBicubicAreTheAnalyticOnes) {
  // Not-a-knot interpolation reproduces a bicubic polynomial exactly on the
  // whole domain (file comment of bpatch.hpp), boundary cells included, so its
  // third derivatives are the polynomial's. The 1e-11 allows the round-off of
  // the interpolation solve amplified by the third differences of the control
  // values and 1/h^3 = 8 (measured: 1.2e-13).
  const ElevationGrid grid = sample(bicubic, 12, 9, 0.5);
  const BPatch patch = BPatch::interpolate(grid);
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> ux(patch.x_min(), patch.x_max()),
      uy(patch.y_min(), patch.y_max());
  double scale = 0.0;
  for (int k = 0; k < 300; ++k) {
    const double x = ux(rng), y = uy(rng);
    const Eigen::Vector4d d3 = patch.third_derivatives({x, y});
    const double expected[4] = {bicubic_derivative(x, y, 3, 0), bicubic_derivative(x, y, 2, 1),
                                bicubic_derivative(x, y, 1, 2), bicubic_derivative(x, y, 0, 3)};
    for (int m = 0; m < 4; ++m) {
      EXPECT_NEAR(d3[m], expected[m], 1e-11) << m << " at " << x << ", " << y;
      scale = std::max(scale, std::abs(expected[m]));
    }
  }
  EXPECT_GT(scale, 0.01);  // all four are exercised, not all ~0
  EXPECT_THROW(patch.third_derivatives({patch.x_max() + 0.1, 0.0}), InputError);
}

TEST(BPatch, ThirdDerivativesAreExactDifferencesOfTheHessianWithinACell) {
  // Inside one cell the surface is a bicubic polynomial, so z_xx is linear in
  // x, z_xy quadratic in x and in y, z_yy linear in y: the central difference
  // of the Hessian with a step that stays in the cell is exact for each third
  // derivative (exact for polynomials of degree <= 2), on any surface. What is
  // left is round-off, ~eps |H| / e with e = 1e-3 (measured: 5.6e-12).
  const ElevationGrid grid = sample(
      [](double x, double y) { return std::sin(1.3 * x) * std::cos(0.9 * y) + 0.05 * x * y * y; },
      21, 17, 0.4);
  const BPatch patch = BPatch::interpolate(grid);
  std::mt19937_64 rng(29);
  std::uniform_int_distribution<int> ci(0, 19), cj(0, 15);
  std::uniform_real_distribution<double> frac(0.1, 0.9);
  const double h = patch.cellsize(), e = 1e-3;
  double scale = 0.0;
  for (int k = 0; k < 200; ++k) {
    const Vec2 p(patch.x_min() + (ci(rng) + frac(rng)) * h,
                 patch.y_min() + (cj(rng) + frac(rng)) * h);
    const Eigen::Vector4d d3 = patch.third_derivatives(p);
    const SurfacePoint px = patch.evaluate(p + Vec2(e, 0)), mx = patch.evaluate(p - Vec2(e, 0));
    const SurfacePoint py = patch.evaluate(p + Vec2(0, e)), my = patch.evaluate(p - Vec2(0, e));
    EXPECT_NEAR(d3[0], (px.hessian(0, 0) - mx.hessian(0, 0)) / (2 * e), 1e-10);
    EXPECT_NEAR(d3[1], (px.hessian(0, 1) - mx.hessian(0, 1)) / (2 * e), 1e-10);
    EXPECT_NEAR(d3[2], (py.hessian(0, 1) - my.hessian(0, 1)) / (2 * e), 1e-10);
    EXPECT_NEAR(d3[3], (py.hessian(1, 1) - my.hessian(1, 1)) / (2 * e), 1e-10);
    scale = std::max(scale, d3.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(scale, 0.5);  // the surface has real third derivatives (~1.3^3)
}

TEST(BPatch, DerivativesMatchFiniteDifferencesOnARealDem) {
  const ElevationGrid grid = read_esri_ascii(std::string(TALUS_DATA_DIR) +
                                             "/terrain/west_bijou_escarpment_nasadem25m.asc");
  const BPatch patch = BPatch::interpolate(grid);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(patch.x_min() + 1, patch.x_max() - 1),
      uy(patch.y_min() + 1, patch.y_max() - 1);
  for (int k = 0; k < 100; ++k) {
    const Vec2 p(ux(rng), uy(rng));
    const double e = 1e-3;
    const SurfacePoint sp = patch.evaluate(p);
    const SurfacePoint px = patch.evaluate(p + Vec2(e, 0)), mx = patch.evaluate(p - Vec2(e, 0));
    const SurfacePoint py = patch.evaluate(p + Vec2(0, e)), my = patch.evaluate(p - Vec2(0, e));
    EXPECT_NEAR(sp.gradient.x(), (px.z - mx.z) / (2 * e), 1e-6);
    EXPECT_NEAR(sp.gradient.y(), (py.z - my.z) / (2 * e), 1e-6);
    EXPECT_NEAR(sp.hessian(0, 0), (px.gradient.x() - mx.gradient.x()) / (2 * e), 1e-6);
    EXPECT_NEAR(sp.hessian(0, 1), (py.gradient.x() - my.gradient.x()) / (2 * e), 1e-6);
    EXPECT_NEAR(sp.hessian(1, 1), (py.gradient.y() - my.gradient.y()) / (2 * e), 1e-6);
    EXPECT_DOUBLE_EQ(patch.elevation(p), sp.z);
  }
}

TEST(BPatch, SurfaceIsTwiceContinuouslyDifferentiableAcrossCellEdges) {
  const ElevationGrid grid = sample(
      [](double x, double y) { return std::exp(-0.1 * (x * x + y * y)); }, 15, 15, 0.7, -5, -5);
  const BPatch patch = BPatch::interpolate(grid);
  const double edge = grid.node_position(6, 0).x(), e = 1e-9;
  for (double y : {-4.0, -1.3, 0.2, 3.9}) {
    const SurfacePoint left = patch.evaluate({edge - e, y}), right = patch.evaluate({edge + e, y});
    EXPECT_NEAR(left.z, right.z, 1e-8);
    EXPECT_NEAR(left.gradient.x(), right.gradient.x(), 1e-7);
    EXPECT_NEAR(left.hessian(0, 0), right.hessian(0, 0), 1e-6);
  }
}

// A biquintic polynomial: all 36 monomials x^a y^b, a, b <= 5, small
// coefficients so that the terms stay comparable on [0, 5]².
double biquintic_derivative(double x, double y, int p, int q) {
  double z = 0.0;
  for (int a = p; a < 6; ++a)
    for (int b = q; b < 6; ++b) {
      const double c = std::pow(-0.35, a) * std::pow(0.3, b) * (1.0 + 0.1 * (a - b));
      z += c * falling(a, p) * falling(b, q) * std::pow(x, a - p) * std::pow(y, b - q);
    }
  return z;
}

TEST(BPatchQuintic, InterpolationReproducesBiquinticPolynomialsToTheThirdDerivative) {
  // Zero sixth differences at the ends hold for the control values of any
  // quintic, so the degree-5 interpolant is the polynomial itself, boundary
  // cells included, with all its derivatives.
  const ElevationGrid grid = sample(
      [](double x, double y) { return biquintic_derivative(x, y, 0, 0); }, 11, 9, 0.5, 0.0, 0.0);
  const BPatch patch = BPatch::interpolate(grid, 5);
  EXPECT_EQ(patch.degree(), 5);
  EXPECT_EQ(patch.control_points().rows(), 15);
  EXPECT_EQ(patch.control_points().cols(), 13);
  EXPECT_LT(patch.residuals(grid).max_node_residual, 1e-12);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> ux(patch.x_min(), patch.x_max()),
      uy(patch.y_min(), patch.y_max());
  for (int k = 0; k < 200; ++k) {
    const double x = ux(rng), y = uy(rng);
    const SurfacePoint sp = patch.evaluate({x, y});
    const Eigen::Vector4d d3 = patch.third_derivatives({x, y});
    EXPECT_NEAR(sp.z, biquintic_derivative(x, y, 0, 0), 1e-11);
    EXPECT_NEAR(patch.elevation({x, y}), sp.z, 1e-14);
    EXPECT_NEAR(sp.gradient.x(), biquintic_derivative(x, y, 1, 0), 1e-10);
    EXPECT_NEAR(sp.gradient.y(), biquintic_derivative(x, y, 0, 1), 1e-10);
    EXPECT_NEAR(sp.hessian(0, 0), biquintic_derivative(x, y, 2, 0), 1e-9);
    EXPECT_NEAR(sp.hessian(0, 1), biquintic_derivative(x, y, 1, 1), 1e-9);
    EXPECT_NEAR(sp.hessian(1, 1), biquintic_derivative(x, y, 0, 2), 1e-9);
    EXPECT_NEAR(d3[0], biquintic_derivative(x, y, 3, 0), 1e-8);
    EXPECT_NEAR(d3[1], biquintic_derivative(x, y, 2, 1), 1e-8);
    EXPECT_NEAR(d3[2], biquintic_derivative(x, y, 1, 2), 1e-8);
    EXPECT_NEAR(d3[3], biquintic_derivative(x, y, 0, 3), 1e-8);
  }
}

TEST(BPatchQuintic, ThirdDerivativesAreContinuousAcrossCellEdgesWhereTheBicubicOnesJump) {
  // The reason for degree 5: the curvature's gradient along a path (what the
  // simultaneous NLP's Jacobian holds) is continuous. Across a knot line the
  // bicubic's third derivatives jump by O(1) on rough ground.
  FractalTerrainOptions options;
  options.shape = {33, 33, 0.25, 0.0, 0.0};
  options.height_scale = 1.0;
  options.seed = 4;
  const ElevationGrid grid = generate_fractal_terrain(options);
  const BPatch cubic = BPatch::interpolate(grid), quintic = BPatch::interpolate(grid, 5);
  EXPECT_LT(quintic.residuals(grid).max_node_residual, 1e-12);
  const double e = 1e-9;
  double cubic_jump = 0.0, quintic_jump = 0.0;
  for (std::size_t i = 2; i + 2 < grid.ncols(); i += 3) {
    const double edge = grid.node_position(i, 0).x();
    for (const double y : {1.1, 3.7, 6.3}) {
      const Vec2 left(edge - e, y), right(edge + e, y);
      cubic_jump = std::max(
          cubic_jump, (cubic.third_derivatives(left) - cubic.third_derivatives(right)).norm());
      quintic_jump =
          std::max(quintic_jump,
                   (quintic.third_derivatives(left) - quintic.third_derivatives(right)).norm());
      EXPECT_NEAR(quintic.evaluate(left).hessian(0, 0), quintic.evaluate(right).hessian(0, 0),
                  1e-5);
    }
  }
  EXPECT_GT(cubic_jump, 1.0);
  EXPECT_LT(quintic_jump, 1e-3);
}

TEST(BPatchQuintic, OnlyDegreesThreeAndFive) {
  const ElevationGrid grid = sample(bicubic, 8, 8, 1.0);
  EXPECT_THROW(BPatch::interpolate(grid, 4), InputError);
  EXPECT_THROW(BPatch::interpolate(grid, 7), InputError);
  EXPECT_EQ(BPatch::interpolate(grid).degree(), 3);
  EXPECT_NO_THROW(BPatch::interpolate(sample(bicubic, 6, 6, 1.0), 5));
  EXPECT_THROW(BPatch::interpolate(sample(bicubic, 5, 8, 1.0), 5), InputError);  // needs 6 a side
}

TEST(BPatch, PointsOffTheMapAreInputErrors) {
  const BPatch patch = BPatch::interpolate(sample(bicubic, 6, 6, 1.0, 0.0, 0.0));
  EXPECT_NO_THROW(patch.evaluate({5.0, 5.0}));  // the far corner is in the domain
  EXPECT_THROW(patch.evaluate({5.01, 2.0}), InputError);
  EXPECT_THROW(patch.evaluate({2.0, -0.01}), InputError);
  EXPECT_THROW(patch.elevation({std::nan(""), 2.0}), InputError);
  EXPECT_THROW(patch.evaluate({2.0, std::numeric_limits<double>::infinity()}), InputError);
}

TEST(BPatch, InterpolationRejectsVoidsAndTinyGrids) {
  ElevationGrid grid = sample(bicubic, 8, 8, 1.0);
  grid.set_void(3, 5);
  try {
    BPatch::interpolate(grid);
    ADD_FAILURE() << "voids accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("column 3, row 5"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(BPatch::interpolate(fill_voids(grid, VoidFill::kNearest)));
  EXPECT_THROW(BPatch::interpolate(sample(bicubic, 3, 8, 1.0)), InputError);
}

TEST(BPatchSmoothing, ReproducesAPlaneExactlyForAnyLambda) {
  // Planes carry no curvature energy, so the smoothing fit must return them.
  const auto plane = [](double x, double y) { return 2.0 + 0.3 * x - 0.8 * y; };
  const ElevationGrid grid = sample(plane, 20, 14, 2.0);
  for (double lambda : {1e-3, 1.0, 1e3}) {
    const BPatch patch = BPatch::fit_smoothing(grid, lambda);
    EXPECT_LT(patch.residuals(grid).max_node_residual, 1e-8) << lambda;
    const SurfacePoint sp = patch.evaluate({17.3, 9.1});
    EXPECT_NEAR(sp.gradient.x(), 0.3, 1e-9);
    EXPECT_NEAR(sp.gradient.y(), -0.8, 1e-9);
  }
}

TEST(BPatchSmoothing, LargerLambdaSmoothsMoreAndSmallLambdaApproachesInterpolation) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.5);
  ElevationGrid grid =
      sample([](double x, double y) { return std::sin(0.3 * x) + std::cos(0.2 * y); }, 30, 25, 1.0);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) grid.at(i, j) += noise(rng);
  double previous = 0.0;
  for (double lambda : {1e-6, 1e-2, 1.0, 100.0}) {
    const double rms = BPatch::fit_smoothing(grid, lambda).residuals(grid).rms_residual;
    EXPECT_GT(rms, previous) << lambda;
    previous = rms;
  }
  EXPECT_LT(BPatch::fit_smoothing(grid, 1e-8).residuals(grid).max_node_residual, 1e-3);
}

TEST(BPatchSmoothing, IgnoresVoidsAndFillsThemSmoothly) {
  const auto quad = [](double x, double y) { return 0.01 * x * x + 0.5 * y; };
  ElevationGrid grid = sample(quad, 16, 16, 1.0);
  for (std::size_t i = 6; i < 10; ++i)
    for (std::size_t j = 6; j < 10; ++j) grid.set_void(i, j);
  const BPatch patch = BPatch::fit_smoothing(grid, 1e-4);
  const BPatchFitReport report = patch.residuals(grid);
  EXPECT_EQ(report.voids, 16u);
  EXPECT_LT(report.max_node_residual, 1e-3);
  const Vec2 hole = grid.node_position(8, 8);
  EXPECT_NEAR(patch.elevation(hole), quad(hole.x(), hole.y()), 0.05);
  EXPECT_FALSE(patch.on_data(hole));
  EXPECT_TRUE(patch.on_data(grid.node_position(1, 1) + Vec2(0.5, 0.5)));
}

// The smoothing fit's default solver (tensor PCG) against the assembled
// CHOLMOD solve of the same normal equations: the same minimiser, up to the
// solvers' tolerance, for small, unit and large lambda, square grids with an
// even and an odd number of control points per axis (the preconditioner folds
// each axis into even and odd halves), and a non-square grid.
using detail::SmoothingSolver;
using detail::SmoothingSolveReport;

ElevationGrid noisy_terrain(std::size_t nc, std::size_t nr, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.3);
  ElevationGrid grid = sample(
      [](double x, double y) { return 20.0 * std::sin(0.3 * x) * std::cos(0.2 * y) + 0.5 * x; }, nc,
      nr, 1.0);
  for (std::size_t j = 0; j < nr; ++j)
    for (std::size_t i = 0; i < nc; ++i) grid.at(i, j) += noise(rng);
  return grid;
}

double elevation_range(const ElevationGrid& grid) {
  double lo = 1e300, hi = -1e300;
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i)
      if (grid.valid(i, j)) {
        lo = std::min(lo, grid.at(i, j));
        hi = std::max(hi, grid.at(i, j));
      }
  return hi - lo;
}

/// The surface at the nodes: weights 1/6, 4/6, 1/6 on each axis.
Eigen::MatrixXd node_values(const Eigen::MatrixXd& control) {
  const double w[3] = {1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0};
  Eigen::MatrixXd z = Eigen::MatrixXd::Zero(control.rows() - 2, control.cols() - 2);
  for (Eigen::Index j = 0; j < z.cols(); ++j)
    for (Eigen::Index i = 0; i < z.rows(); ++i)
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < 3; ++a) z(i, j) += w[a] * w[b] * control(i + a, j + b);
  return z;
}

void expect_tensor_matches_cholmod(const ElevationGrid& grid, double lambda) {
  SmoothingSolveReport report;
  const Eigen::MatrixXd fast =
      detail::smoothing_control_points(grid, lambda, SmoothingSolver::tensor_pcg, &report);
  const Eigen::MatrixXd reference =
      detail::smoothing_control_points(grid, lambda, SmoothingSolver::cholmod);
  EXPECT_TRUE(report.pcg_converged) << lambda;
  EXPECT_FALSE(report.used_cholmod) << lambda;
  ASSERT_EQ(fast.rows(), static_cast<Eigen::Index>(grid.ncols() + 2));
  ASSERT_EQ(fast.cols(), static_cast<Eigen::Index>(grid.nrows() + 2));
  EXPECT_LT((fast - reference).cwiseAbs().maxCoeff(), 1e-6 * elevation_range(grid))
      << "lambda " << lambda << ", " << grid.ncols() << " x " << grid.nrows() << ", "
      << report.iterations << " iterations";
}

TEST(BPatchSmoothing, TensorSolverMatchesCholmodWithoutVoids) {
  for (const auto& [nc, nr] : {std::pair<std::size_t, std::size_t>{30, 30}, {31, 31}, {41, 26}})
    for (double lambda : {1e-6, 1.0, 100.0})
      expect_tensor_matches_cholmod(noisy_terrain(nc, nr, 11), lambda);
}

TEST(BPatchSmoothing, TensorSolverMatchesCholmodWithScatteredVoids) {
  ElevationGrid grid = noisy_terrain(41, 29, 12);
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<std::size_t> ui(0, 40), uj(0, 28);
  for (int k = 0; k < 8; ++k) grid.set_void(ui(rng), uj(rng));
  ASSERT_GT(grid.void_count(), 5u);
  for (double lambda : {1e-6, 1.0, 100.0}) expect_tensor_matches_cholmod(grid, lambda);
}

TEST(BPatchSmoothing, TensorSolverMatchesCholmodAroundAHole) {
  // A 6 x 6 hole: at small lambda its control points are fixed by the
  // curvature energy alone, which the preconditioner's local void correction
  // (not the void-free part) gets right.
  ElevationGrid grid = noisy_terrain(32, 32, 14);
  for (std::size_t j = 12; j < 18; ++j)
    for (std::size_t i = 10; i < 16; ++i) grid.set_void(i, j);
  for (double lambda : {1e-6, 1.0, 100.0}) expect_tensor_matches_cholmod(grid, lambda);
}

TEST(BPatchSmoothing, ManyVoidsFallBackToCholmodWithTheSameFit) {
  // A third of the nodes void, scattered: too many for the local correction
  // (over 20000 control points and 10% of all), and at small lambda the
  // void-free preconditioner stalls. The tensor solver says so;
  // fit_smoothing() answers with CHOLMOD.
  ElevationGrid grid = noisy_terrain(150, 150, 16);
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<std::size_t> u(0, 149);
  for (int k = 0; k < 8000; ++k) grid.set_void(u(rng), u(rng));
  EXPECT_THROW(detail::smoothing_control_points(grid, 1e-6, SmoothingSolver::tensor_pcg),
               SolverError);
  SmoothingSolveReport report;
  const Eigen::MatrixXd automatic =
      detail::smoothing_control_points(grid, 1e-6, SmoothingSolver::automatic, &report);
  EXPECT_TRUE(report.used_cholmod);
  EXPECT_FALSE(report.pcg_converged);
  const Eigen::MatrixXd reference =
      detail::smoothing_control_points(grid, 1e-6, SmoothingSolver::cholmod);
  EXPECT_EQ((automatic - reference).cwiseAbs().maxCoeff(), 0.0);
}

TEST(BPatchSmoothing, DefaultSolverIsTheTensorOneOnVoidFreeGrids) {
  const ElevationGrid grid = noisy_terrain(25, 20, 15);
  SmoothingSolveReport report;
  const Eigen::MatrixXd automatic =
      detail::smoothing_control_points(grid, 1e-8, SmoothingSolver::automatic, &report);
  EXPECT_FALSE(report.used_cholmod);
  EXPECT_TRUE(report.pcg_converged);
  EXPECT_GT(report.iterations, 0u);
  EXPECT_EQ(BPatch::fit_smoothing(grid, 1e-8).control_points(), automatic);
  // lambda = 1e-8 is close to interpolation: the control points are only
  // determined to ~1e-6 of the range in double precision (by CHOLMOD too), the
  // surface at the nodes much better.
  const Eigen::MatrixXd reference =
      detail::smoothing_control_points(grid, 1e-8, SmoothingSolver::cholmod);
  EXPECT_LT((automatic - reference).cwiseAbs().maxCoeff(), 1e-4 * elevation_range(grid));
  EXPECT_LT((node_values(automatic) - node_values(reference)).cwiseAbs().maxCoeff(),
            1e-8 * elevation_range(grid));
}

TEST(BPatchSmoothing, RejectsBadLambdaAndTooFewNodes) {
  const ElevationGrid grid = sample(bicubic, 8, 8, 1.0);
  EXPECT_THROW(BPatch::fit_smoothing(grid, 0.0), InputError);
  EXPECT_THROW(BPatch::fit_smoothing(grid, -1.0), InputError);
  EXPECT_THROW(BPatch::fit_smoothing(grid, std::nan("")), InputError);
  ElevationGrid empty = grid;
  for (std::size_t j = 0; j < 8; ++j)
    for (std::size_t i = 0; i < 8; ++i)
      if (i + j > 0) empty.set_void(i, j);
  EXPECT_THROW(BPatch::fit_smoothing(empty, 1.0), InputError);
}

}  // namespace
}  // namespace talus

namespace talus {
namespace {

// Issue #39 item 4: the fit of a large DEM is budgeted before its matrices are allocated
// (48 bytes a node), one line naming the size and what to do.
TEST(BPatchBudget, AFitBeyondTheMemoryBudgetIsRefusedBeforeAllocating) {
  const ElevationGrid grid(1500, 1500, 1.0, 0.0, 0.0);  // 20 MB; its fit 108 MB
  ::setenv("TALUS_MEMORY_LIMIT_MB", "64", 1);
  std::string message;
  try {
    BPatch::interpolate(grid);
  } catch (const InputError& e) {
    message = e.what();
  }
  ::unsetenv("TALUS_MEMORY_LIMIT_MB");
  EXPECT_NE(message.find("fitting a B-patch to 1500 x 1500 nodes"), std::string::npos) << message;
  EXPECT_NE(message.find("crop or decimate"), std::string::npos) << message;
}

}  // namespace
}  // namespace talus
