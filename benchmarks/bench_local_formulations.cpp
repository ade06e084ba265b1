// The local stage alone, nested (with and without the polish) against the
// simultaneous formulation, on the
// smooth case of tests/optimal/test_simultaneous_stage.cpp: an 8 m Gaussian hill
// (σ 7 m) on an 80 × 60 m map at 1 m cells, a point mass with μ 0.4, from
// (5, 30) to (75, 30), started from the global search's best candidate
// (computed once, outside the timing). Counters: the exact travel time of
// the result at the search stations [s], whether the solver reports
// convergence (1) and its iterations. Medians:
//   ./build/benchmarks/bench_local_formulations --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "talus/core/elevation_grid.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/path_optimizer.hpp"

namespace {

const talus::BPatch& hill() {
  static const talus::BPatch terrain = [] {
    talus::ElevationGrid grid(81, 61, 1.0, 0.0, 0.0);
    for (std::size_t j = 0; j < grid.nrows(); ++j) {
      for (std::size_t i = 0; i < grid.ncols(); ++i) {
        const talus::Vec2 p = grid.node_position(i, j);
        const double r2 = (p.x() - 40) * (p.x() - 40) + (p.y() - 30) * (p.y() - 30);
        grid.at(i, j) = 8.0 * std::exp(-r2 / (2 * 7.0 * 7.0));
      }
    }
    return talus::BPatch::interpolate(grid);
  }();
  return terrain;
}

talus::Vehicle vehicle() {
  talus::Vehicle v;
  v.friction = 0.4;
  v.cg_height = 0.5;
  v.half_track = 0.6;
  v.max_speed = 10.0;
  return v;
}

const std::vector<talus::Vec2>& candidate() {
  static const std::vector<talus::Vec2> vertices = [] {
    talus::GlobalSearchOptions search;
    search.candidates = 1;
    return talus::global_search(hill(), vehicle(), {5, 30}, {75, 30}, search)
        .candidates.at(0)
        .vertices;
  }();
  return vertices;
}

void BM_LocalStage(benchmark::State& state, talus::PathFormulation formulation, bool polish) {
  talus::PathOptimizerOptions options;
  options.formulation = formulation;
  options.polish = polish;
  const std::vector<talus::Vec2>& start = candidate();
  double time = 0.0, converged = 0.0, iterations = 0.0;
  for (auto _ : state) {
    const talus::OptimizedPath best = talus::optimize_path(hill(), vehicle(), start, options);
    time = best.travel_time;
    converged = best.converged ? 1.0 : 0.0;
    iterations = static_cast<double>(best.iterations);
    benchmark::DoNotOptimize(time);
  }
  state.counters["travel_time_s"] = time;
  state.counters["converged"] = converged;
  state.counters["iterations"] = iterations;
}

BENCHMARK_CAPTURE(BM_LocalStage, nested, talus::PathFormulation::kNested, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LocalStage, nested_polished, talus::PathFormulation::kNested, true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LocalStage, simultaneous, talus::PathFormulation::kSimultaneous, false)
    ->Unit(benchmark::kMillisecond);

}  // namespace
