// fit_residuals and thin_plate_energy_density (talus/bspline/fit_residuals.hpp):
// exact fits leave rounding only, a single disturbed node carries the whole
// residual and sits where the curvature is largest, and the statistics agree
// with a re-evaluation of the patch at the nodes.
#include <gtest/gtest.h>

#include <cmath>

#include "talus/bspline/fit_residuals.hpp"
#include "talus/core/error.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_of_nodes;

double bicubic(double x, double y) {
  return 0.3 + 0.02 * x - 0.01 * y + 1e-3 * x * y + 2e-4 * x * x * y - 1e-5 * x * x * x * y * y;
}

TEST(FitResiduals, InterpolatingFitOfABicubicLeavesRoundingOnly) {
  const ElevationGrid grid = grid_of_nodes(bicubic, 11, 9, 1.0, 0.0, 0.0);
  const BPatch fit = BPatch::interpolate(grid);
  const FitResiduals r = fit_residuals(grid, fit, fit);
  EXPECT_EQ(r.nodes, 11u * 9u);
  ASSERT_EQ(r.residual.size(), 11u * 9u);
  EXPECT_LT(r.max_abs, 1e-12);
  EXPECT_LE(r.rms, r.max_abs);
  EXPECT_LE(r.abs_quantile, r.max_abs);
  for (const double v : r.residual) EXPECT_LE(std::abs(v), r.max_abs);
}

TEST(FitResiduals, SmoothingFitOfAPlaneReproducesIt) {
  // A plane has no thin-plate energy, so the smoothing fit is the plane itself.
  const ElevationGrid grid = grid_of_nodes(
      [](double x, double y) { return 5.0 + 0.2 * x - 0.1 * y; }, 12, 10, 2.0, 100.0, 50.0);
  const BPatch smooth = BPatch::fit_smoothing(grid, 1.0);
  const FitResiduals r = fit_residuals(grid, smooth, smooth);
  EXPECT_LT(r.max_abs, 1e-9);
}

TEST(FitResiduals, StatisticsMatchTheResidualsAtTheNodes) {
  ElevationGrid grid = grid_of_nodes(
      [](double x, double y) { return std::sin(0.9 * x) * std::cos(0.7 * y) + 0.1 * x; }, 14, 12,
      1.0, 0.0, 0.0);
  grid.set_void(5, 4);
  grid.set_void(0, 11);
  const BPatch smooth = BPatch::fit_smoothing(grid, 1.0);
  const BPatch exact = BPatch::interpolate(fill_voids(grid, VoidFill::kNearest));
  FitResidualOptions options;
  options.abs_quantile = 1.0;
  const FitResiduals r = fit_residuals(grid, smooth, exact, options);
  EXPECT_EQ(r.nodes, 14u * 12u - 2u);
  double sum_sq = 0.0, max_abs = 0.0;
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const double v = r.residual[j * grid.ncols() + i];
      if (!grid.valid(i, j)) {
        EXPECT_TRUE(std::isnan(v)) << i << ", " << j;
        continue;
      }
      EXPECT_EQ(v, smooth.elevation(grid.node_position(i, j)) - grid.at(i, j));
      sum_sq += v * v;
      max_abs = std::max(max_abs, std::abs(v));
    }
  EXPECT_GT(max_abs, 1e-3);  // a real smoothing residual
  EXPECT_EQ(r.max_abs, max_abs);
  EXPECT_NEAR(r.rms, std::sqrt(sum_sq / static_cast<double>(r.nodes)), 1e-15);
  EXPECT_EQ(r.abs_quantile, max_abs);  // quantile 1 is the maximum
  EXPECT_GT(r.curvature_share, 0.0);
  EXPECT_LT(r.curvature_share, 1.0);
  // All nodes "most curved": the whole squared residual.
  options.curvature_fraction = 1.0;
  EXPECT_NEAR(fit_residuals(grid, smooth, exact, options).curvature_share, 1.0, 1e-12);
}

TEST(FitResiduals, ASingleDisturbedNodeCarriesTheResidualWhereTheCurvatureIs) {
  // The fit is the plane; the data add 1 m at one node. The residual is −1 m
  // there and rounding elsewhere, and the interpolating fit of the data bends
  // most at that node, so the most curved node carries all of Σ r².
  const auto plane = [](double x, double y) { return 2.0 + 0.1 * x + 0.05 * y; };
  const ElevationGrid base = grid_of_nodes(plane, 15, 13, 1.0, 0.0, 0.0);
  ElevationGrid data = base;
  data.at(7, 6) += 1.0;
  const BPatch fit = BPatch::interpolate(base);
  const BPatch reference = BPatch::interpolate(data);
  FitResidualOptions options;
  options.curvature_fraction = 1.0 / (15.0 * 13.0);  // exactly one node
  options.abs_quantile = 0.5;
  const FitResiduals r = fit_residuals(data, fit, reference, options);
  EXPECT_NEAR(r.residual[6 * 15 + 7], -1.0, 1e-12);
  EXPECT_NEAR(r.max_abs, 1.0, 1e-12);
  EXPECT_NEAR(r.rms, 1.0 / std::sqrt(15.0 * 13.0), 1e-12);
  EXPECT_NEAR(r.curvature_share, 1.0, 1e-12);
  EXPECT_LT(r.abs_quantile, 1e-12);  // the median node has no residual
}

TEST(FitResiduals, ThinPlateEnergyDensityInGridIndexUnits) {
  SurfacePoint p;
  p.hessian << 0.5, -0.25, -0.25, 2.0;
  // h = 2: h² H = [[2, -1], [-1, 8]] → 4 + 2 + 64.
  EXPECT_DOUBLE_EQ(thin_plate_energy_density(p, 2.0), 70.0);
  EXPECT_THROW(thin_plate_energy_density(p, 0.0), InputError);
  EXPECT_THROW(thin_plate_energy_density(p, std::nan("")), InputError);
}

TEST(FitResiduals, InvalidOptionsAndGridsWithoutDataAreRefused) {
  const ElevationGrid grid = grid_of_nodes(bicubic, 6, 6, 1.0, 0.0, 0.0);
  const BPatch fit = BPatch::interpolate(grid);
  FitResidualOptions options;
  options.curvature_fraction = 0.0;
  EXPECT_THROW(fit_residuals(grid, fit, fit, options), InputError);
  options.curvature_fraction = 1.5;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.abs_quantile = -0.1;
  EXPECT_THROW(options.validate(), InputError);
  ElevationGrid empty = grid;
  for (std::size_t j = 0; j < empty.nrows(); ++j)
    for (std::size_t i = 0; i < empty.ncols(); ++i) empty.set_void(i, j);
  EXPECT_THROW(fit_residuals(empty, fit, fit), InputError);
}

}  // namespace
}  // namespace talus
