#pragma once
/// @file
/// How well a fitted B-patch reproduces the elevation grid it was fitted to:
/// the residual fit − data at every node, its maximum and RMS, a percentile of
/// its magnitude, and how much of it sits where the terrain is most curved.
/// The smoothing fit (BPatch::fit_smoothing) trades residual for a lower
/// thin-plate energy, so its residuals concentrate on ridges and valley
/// floors; the interpolating fit's residuals are rounding only.
#include <cstddef>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"

namespace talus {

/// Thin-plate energy density in grid-index units at a surface point, the
/// quantity BPatch::fit_smoothing penalises: with H the Hessian [1/m] and h
/// the cell size [m], (h² H)_uu² + 2 (h² H)_uv² + (h² H)_vv² [m²].
/// Throws InputError if the cell size is not positive and finite.
double thin_plate_energy_density(const SurfacePoint& point, double cellsize);

struct FitResidualOptions {
  /// Share of the valid nodes, those of largest thin-plate energy density of
  /// the curvature reference, whose part of Σ r² is reported as
  /// curvature_share; in (0, 1].
  double curvature_fraction = 0.10;
  /// Quantile of |r| reported as abs_quantile (nearest rank, quantile() of
  /// terrain_statistics.hpp); in [0, 1]. 0.99 clips a colour scale so that a
  /// handful of extreme nodes do not wash out the rest.
  double abs_quantile = 0.99;
  /// Throws InputError naming the field.
  void validate() const;
};

struct FitResiduals {
  /// fit(node) − data at node (i, j), stored at j ncols + i (rows from the
  /// south, as ElevationGrid::values()); NaN at NODATA nodes [m].
  std::vector<double> residual;
  std::size_t nodes = 0;      ///< valid nodes (those with a residual)
  double max_abs = 0.0;       ///< max |r| [m]
  double rms = 0.0;           ///< sqrt(Σ r² / nodes) [m]
  double abs_quantile = 0.0;  ///< FitResidualOptions::abs_quantile of |r| [m]
  /// Share of Σ r² carried by the ceil(curvature_fraction × nodes) valid nodes
  /// of largest thin-plate energy density of the curvature reference: about
  /// curvature_fraction if the residual ignores curvature, up to 1 if it lives
  /// only there; 0 if every residual is 0.
  double curvature_share = 0.0;
};

/// Residuals of `fit` at the valid nodes of `grid`, with the curvature taken
/// from `curvature_reference` (typically the interpolating fit, which follows
/// the data's own curvature; `fit` itself is fine too). Throws InputError if
/// the options are invalid, the grid has no valid node, or a node lies outside
/// a patch's domain.
FitResiduals fit_residuals(const ElevationGrid& grid, const BPatch& fit,
                           const BPatch& curvature_reference,
                           const FitResidualOptions& options = {});

}  // namespace talus
