#pragma once
/// @file
/// The two solvers behind BPatch::fit_smoothing(), exposed so that tests and
/// benchmarks can run each one on its own and compare them. Not part of the
/// stable API: call BPatch::fit_smoothing().
#include <cstddef>

#include <Eigen/Core>

#include "talus/core/elevation_grid.hpp"

namespace talus::detail {

enum class SmoothingSolver {
  automatic,  ///< what fit_smoothing() does: tensor PCG, CHOLMOD if that does not converge
  cholmod,    ///< sparse Cholesky of the assembled normal equations
  tensor_pcg  ///< preconditioned CG only; SolverError if it does not converge
};

/// What the solve did.
struct SmoothingSolveReport {
  bool used_cholmod = false;   ///< the answer came from CHOLMOD
  std::size_t iterations = 0;  ///< PCG iterations (0 if PCG was not tried)
  bool pcg_converged = false;  ///< PCG met its tolerance
};

/// The (ncols + 2) x (nrows + 2) control points of the smoothing fit, solved
/// with `solver`. Same input checks and errors as BPatch::fit_smoothing().
Eigen::MatrixXd smoothing_control_points(const ElevationGrid& grid, double lambda,
                                         SmoothingSolver solver,
                                         SmoothingSolveReport* report = nullptr);

}  // namespace talus::detail
