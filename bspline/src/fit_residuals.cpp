#include "talus/bspline/fit_residuals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "talus/core/error.hpp"
#include "talus/core/terrain_statistics.hpp"

namespace talus {

double thin_plate_energy_density(const SurfacePoint& point, double cellsize) {
  if (!(cellsize > 0.0) || !std::isfinite(cellsize)) {
    throw InputError("thin_plate_energy_density: the cell size must be positive and finite");
  }
  const Mat2 hess = point.hessian * (cellsize * cellsize);
  return hess(0, 0) * hess(0, 0) + 2.0 * hess(0, 1) * hess(0, 1) + hess(1, 1) * hess(1, 1);
}

void FitResidualOptions::validate() const {
  if (!(curvature_fraction > 0.0 && curvature_fraction <= 1.0)) {
    throw InputError("FitResidualOptions::curvature_fraction must lie in (0, 1], got " +
                     std::to_string(curvature_fraction));
  }
  if (!(abs_quantile >= 0.0 && abs_quantile <= 1.0)) {
    throw InputError("FitResidualOptions::abs_quantile must lie in [0, 1], got " +
                     std::to_string(abs_quantile));
  }
}

FitResiduals fit_residuals(const ElevationGrid& grid, const BPatch& fit,
                           const BPatch& curvature_reference, const FitResidualOptions& options) {
  options.validate();
  struct NodeResidual {
    double residual, curvature;
  };
  std::vector<NodeResidual> nodes;
  nodes.reserve(grid.ncols() * grid.nrows());
  FitResiduals result;
  result.residual.assign(grid.ncols() * grid.nrows(), std::numeric_limits<double>::quiet_NaN());
  double sum_sq = 0.0;
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      if (!grid.valid(i, j)) continue;
      const Vec2 p = grid.node_position(i, j);
      const double r = fit.elevation(p) - grid.at(i, j);
      result.residual[j * grid.ncols() + i] = r;
      nodes.push_back(
          {r, thin_plate_energy_density(curvature_reference.evaluate(p), grid.cellsize())});
      sum_sq += r * r;
      result.max_abs = std::max(result.max_abs, std::abs(r));
    }
  if (nodes.empty()) throw InputError("fit_residuals: the grid has no valid node");
  result.nodes = nodes.size();
  result.rms = std::sqrt(sum_sq / static_cast<double>(nodes.size()));

  std::sort(nodes.begin(), nodes.end(),
            [](const NodeResidual& a, const NodeResidual& b) { return a.curvature > b.curvature; });
  const auto top = static_cast<std::size_t>(
      std::ceil(options.curvature_fraction * static_cast<double>(nodes.size())));
  double top_sq = 0.0;
  for (std::size_t k = 0; k < top && k < nodes.size(); ++k)
    top_sq += nodes[k].residual * nodes[k].residual;
  result.curvature_share = sum_sq > 0.0 ? top_sq / sum_sq : 0.0;

  std::vector<double> magnitudes;
  magnitudes.reserve(nodes.size());
  for (const NodeResidual& node : nodes) magnitudes.push_back(std::abs(node.residual));
  result.abs_quantile = quantile(std::move(magnitudes), options.abs_quantile);
  return result;
}

}  // namespace talus
