// Velocity limits + path geometry along a path on a real DEM (issue: < 20 ms
// for 10^5 stations on one core). Baseline in the same run: the exact
// arc-length-uniform sampling (SurfacePath::sample) at 10^4 stations.
#include <benchmark/benchmark.h>

#include <optional>
#include <string>
#include <vector>

#include "talus/core/esri_ascii.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"

namespace {

using talus::Vec2;

struct Setup {
  talus::ElevationGrid grid;
  talus::BPatch patch;
  std::optional<talus::SurfacePath> path;  // built in place: it points at `patch`
  talus::Vehicle vehicle;
};

talus::SurfacePath make_path(const talus::ElevationGrid& grid, const talus::BPatch& patch) {
  const double fractions[8][2] = {{0.10, 0.15}, {0.25, 0.32}, {0.32, 0.20}, {0.45, 0.38},
                                  {0.50, 0.60}, {0.62, 0.72}, {0.78, 0.68}, {0.90, 0.88}};
  const double wx = grid.x_max() - grid.x_min(), wy = grid.y_max() - grid.y_min();
  std::vector<Vec2> through;
  for (const auto& f : fractions)
    through.emplace_back(grid.x_min() + f[0] * wx, grid.y_min() + f[1] * wy);
  return talus::SurfacePath(patch, talus::Curve2::interpolate(through));
}

const Setup& setup() {
  static Setup s = [] {
    talus::ElevationGrid grid =
        talus::read_esri_ascii(std::string(TALUS_DATA_DIR) + "/terrain/bigtujunga_srtm30m.asc");
    talus::Vehicle vehicle;  // defaults: point mass, mu 0.7, h 0.5, b 0.6
    return Setup{grid, talus::BPatch::interpolate(grid), {}, vehicle};
  }();
  if (!s.path) s.path.emplace(make_path(s.grid, s.patch));
  return s;
}

void BM_VelocityLimitsAlongPath(benchmark::State& state) {
  const Setup& s = setup();
  const auto stations = static_cast<std::size_t>(state.range(0));
  talus::VelocityLimits limits(s.vehicle);
  for (auto _ : state) {
    limits.compute(*s.path, stations);
    benchmark::DoNotOptimize(limits.all_limits().data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["time_per_station"] =
      benchmark::Counter(static_cast<double>(state.iterations() * state.range(0)),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_VelocityLimitsAlongPath)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);

void BM_AccelerationBounds(benchmark::State& state) {
  const Setup& s = setup();
  const talus::VelocityLimits limits(s.vehicle, *s.path, 10000);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(limits.acceleration_bounds(k, 3.0));
    k = (k + 1) % limits.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_AccelerationBounds);

void BM_ExactArcLengthSampling(benchmark::State& state) {
  const Setup& s = setup();
  for (auto _ : state)
    benchmark::DoNotOptimize(s.path->sample(static_cast<std::size_t>(state.range(0))));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_ExactArcLengthSampling)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace
