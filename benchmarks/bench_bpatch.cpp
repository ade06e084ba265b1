/// @file
/// Throughput of the B-patch terrain surface: point queries (evaluate,
/// elevation) against a bilinear baseline on the same grid, the interpolating
/// and smoothing fits, and Darboux frames along a SurfacePath.
///
/// All setup (reading the DEM, fitting, drawing query points, building the
/// synthetic grids and the path) happens outside the timed loops.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/detail/smoothing_solver.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/types.hpp"

namespace {

using talus::BPatch;
using talus::ElevationGrid;
using talus::Vec2;

constexpr std::size_t kQueryPoints = 4096;  // power of two: cycled with a mask
static_assert((kQueryPoints & (kQueryPoints - 1)) == 0);

/// The bundled 512 × 512 DEM, its interpolating fit and fixed query points.
struct DemSetup {
  ElevationGrid grid;
  BPatch patch;
  std::vector<Vec2> points;

  DemSetup()
      : grid(talus::read_esri_ascii(std::string(TALUS_DATA_DIR) +
                                    "/terrain/bigtujunga_srtm30m.asc")),
        patch(BPatch::interpolate(grid)) {
    std::mt19937_64 rng(20240611);
    std::uniform_real_distribution<double> ux(grid.x_min(), grid.x_max());
    std::uniform_real_distribution<double> uy(grid.y_min(), grid.y_max());
    points.reserve(kQueryPoints);
    for (std::size_t k = 0; k < kQueryPoints; ++k) {
      const double x = ux(rng);
      points.emplace_back(x, uy(rng));
    }
  }
};

const DemSetup& dem() {
  static const DemSetup setup;
  return setup;
}

/// N × N synthetic terrain, 30 m cells, a fixed sum of sines (no voids).
ElevationGrid synthetic_grid(std::size_t n) {
  ElevationGrid grid(n, n, 30.0, 0.0, 0.0);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const double x = static_cast<double>(i), y = static_cast<double>(j);
      grid.set(i, j,
               500.0 + 40.0 * std::sin(0.05 * x) * std::cos(0.07 * y) +
                   15.0 * std::sin(0.013 * (x + 2.0 * y)) + 3.0 * std::sin(0.9 * x + 0.4 * y) +
                   0.2 * x);
    }
  return grid;
}

void BM_BPatchEvaluate(benchmark::State& state) {
  const DemSetup& s = dem();
  std::size_t k = 0;
  for (auto _ : state) {
    const talus::SurfacePoint sp = s.patch.evaluate(s.points[k]);
    benchmark::DoNotOptimize(sp);
    k = (k + 1) & (kQueryPoints - 1);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_BPatchEvaluate);

void BM_BPatchElevation(benchmark::State& state) {
  const DemSetup& s = dem();
  std::size_t k = 0;
  for (auto _ : state) {
    const double z = s.patch.elevation(s.points[k]);
    benchmark::DoNotOptimize(z);
    k = (k + 1) & (kQueryPoints - 1);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_BPatchElevation);

void BM_GridBilinear(benchmark::State& state) {
  const DemSetup& s = dem();
  std::size_t k = 0;
  for (auto _ : state) {
    const double z = s.grid.bilinear(s.points[k]);
    benchmark::DoNotOptimize(z);
    k = (k + 1) & (kQueryPoints - 1);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_GridBilinear);

/// Items are grid nodes, so items_per_second is nodes fitted per second.
void BM_BPatchInterpolate(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const ElevationGrid grid = synthetic_grid(n);
  for (auto _ : state) {
    BPatch patch = BPatch::interpolate(grid);
    benchmark::DoNotOptimize(patch);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n * n));
}
// Wall-clock time: this is what "fits a 1024 x 1024 grid in < 1 s" means.
BENCHMARK(BM_BPatchInterpolate)
    ->Arg(256)
    ->Arg(512)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

void BM_BPatchSmoothing(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const ElevationGrid grid = synthetic_grid(n);
  for (auto _ : state) {
    BPatch patch = BPatch::fit_smoothing(grid, 1.0);
    benchmark::DoNotOptimize(patch);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n * n));
}
// Wall-clock time: the solver's dense products run on OpenBLAS threads and its
// matrix-free products on two threads, which the default (main-thread) CPU
// time would not count. fit_smoothing() solves by tensor PCG (see bpatch.hpp).
BENCHMARK(BM_BPatchSmoothing)
    ->Arg(64)
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

/// The same fit by the assembled sparse Cholesky (CHOLMOD, AMD ordering): the
/// previous solver, now the fallback for grids with large voids. Its ratio to
/// BM_BPatchSmoothing in the same run is the speed-up. 1024 x 1024 is left out
/// (about 40 s and 6 GB).
void BM_BPatchSmoothingCholmod(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const ElevationGrid grid = synthetic_grid(n);
  for (auto _ : state) {
    Eigen::MatrixXd control =
        talus::detail::smoothing_control_points(grid, 1.0, talus::detail::SmoothingSolver::cholmod);
    benchmark::DoNotOptimize(control.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n * n));
}
BENCHMARK(BM_BPatchSmoothingCholmod)
    ->Arg(256)
    ->Arg(512)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

/// Items are stations: items_per_second is frames per second, and
/// time_per_station the per-station geometry cost (arc-length inversion,
/// curve derivatives, surface evaluate, frame).
void BM_SurfacePathFrames(benchmark::State& state) {
  constexpr std::size_t kStations = 10000;
  const DemSetup& s = dem();
  // A winding curve through 10 points across the DEM, in fractions of its extent.
  const double fractions[10][2] = {{0.10, 0.15}, {0.22, 0.30}, {0.30, 0.22}, {0.42, 0.35},
                                   {0.48, 0.55}, {0.40, 0.68}, {0.55, 0.78}, {0.68, 0.70},
                                   {0.78, 0.82}, {0.90, 0.88}};
  const double wx = s.grid.x_max() - s.grid.x_min(), wy = s.grid.y_max() - s.grid.y_min();
  std::vector<Vec2> through;
  for (const auto& f : fractions)
    through.emplace_back(s.grid.x_min() + f[0] * wx, s.grid.y_min() + f[1] * wy);
  const talus::SurfacePath path(s.patch, talus::Curve2::interpolate(through));
  for (auto _ : state) {
    std::vector<talus::PathFrame> frames = path.sample(kStations);
    benchmark::DoNotOptimize(frames.data());
    benchmark::ClobberMemory();
  }
  const auto stations = static_cast<double>(state.iterations() * kStations);
  state.SetItemsProcessed(static_cast<std::int64_t>(stations));
  state.counters["time_per_station"] =
      benchmark::Counter(stations, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["path_length_m"] = path.length();
}
BENCHMARK(BM_SurfacePathFrames)->Unit(benchmark::kMillisecond);

}  // namespace
