// Time-optimal profile only (geometry and limits precomputed), N = 10^2 .. 10^5
// stations, and limits + profile at 10^4 stations. The target is
// <= 0.1 µs per station at N = 10^4 with linear scaling.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "talus/core/esri_ascii.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace {

using talus::Vec2;

/// A curved path across the bundled West Bijou DEM at rover scale (cells and
/// heights divided by 25: 1 m cells, same slopes), so that the limits bind.
struct Setup {
  talus::ElevationGrid grid;
  talus::BPatch patch;
  talus::Vehicle vehicle;
};

const Setup& setup() {
  static const Setup s = [] {
    const talus::ElevationGrid dem = talus::read_esri_ascii(
        std::string(TALUS_DATA_DIR) + "/terrain/west_bijou_escarpment_nasadem25m.asc");
    talus::ElevationGrid grid(dem.ncols(), dem.nrows(), 1.0, 0.0, 0.0);
    for (std::size_t j = 0; j < dem.nrows(); ++j)
      for (std::size_t i = 0; i < dem.ncols(); ++i) grid.at(i, j) = dem.at(i, j) / 25.0;
    talus::Vehicle vehicle;  // point mass, mu 0.7, h 0.5, b 0.6
    vehicle.max_speed = 15.0;
    vehicle.max_accel = 3.0;
    vehicle.max_decel = 6.0;
    return Setup{grid, talus::BPatch::interpolate(grid), vehicle};
  }();
  return s;
}

const talus::SurfacePath& path() {
  static const talus::SurfacePath p(
      setup().patch, talus::Curve2::interpolate({Vec2(5, 10), Vec2(30, 40), Vec2(55, 30),
                                                 Vec2(75, 60), Vec2(95, 45), Vec2(115, 70)}));
  return p;
}

void BM_ProfileOnly(benchmark::State& state) {
  const auto stations = static_cast<std::size_t>(state.range(0));
  const talus::VelocityLimits limits(setup().vehicle, path(), stations);
  talus::TimeOptimalProfileSolver solver;
  talus::TimeOptimalProfile profile;
  for (auto _ : state) {
    solver.solve(limits, {}, profile);
    benchmark::DoNotOptimize(profile.travel_time);
  }
  if (profile.status != talus::ProfileStatus::kOk) state.SkipWithError(profile.message.c_str());
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["time_per_station"] =
      benchmark::Counter(static_cast<double>(state.iterations() * state.range(0)),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ProfileOnly)->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond);

void BM_LimitsAndProfile(benchmark::State& state) {
  const auto stations = static_cast<std::size_t>(state.range(0));
  talus::VelocityLimits limits(setup().vehicle);
  talus::TimeOptimalProfileSolver solver;
  talus::TimeOptimalProfile profile;
  for (auto _ : state) {
    limits.compute(path(), stations);
    solver.solve(limits, {}, profile);
    benchmark::DoNotOptimize(profile.travel_time);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["time_per_station"] =
      benchmark::Counter(static_cast<double>(state.iterations() * state.range(0)),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_LimitsAndProfile)->Arg(10000)->Unit(benchmark::kMicrosecond);

}  // namespace
