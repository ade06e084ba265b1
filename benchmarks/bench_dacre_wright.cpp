// The Dacre-Wright-Simeon free-space structuring on a seeded 64 x 64 rough
// terrain (0.25 m cells) with the six-wheel robot, p_max = 6: the whole octree
// (§4.2) and one incremental query (§4.3). The targets (medians, one
// core): whole octree < 0.1 s, incremental query < 10 ms.
//   ./build/benchmarks/bench_dacre_wright --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/dacre_wright/configuration_octree.hpp"
#include "talus/kinematic/dacre_wright/dacre_wright_planner.hpp"
#include "talus/kinematic/dacre_wright/region_admissibility.hpp"

namespace {

const talus::RuledTerrain& map64() {
  static const talus::RuledTerrain t = [] {
    talus::FractalTerrainOptions f;
    f.shape = {64, 64, 0.25, 0.0, 0.0};
    f.height_scale = 0.6;
    f.seed = 1993;
    return talus::RuledTerrain(talus::generate_fractal_terrain(f));
  }();
  return t;
}

const talus::WheeledRobot& robot() {
  static const talus::WheeledRobot r =
      talus::load_dacre_wright_robot(TALUS_DATA_DIR "/robots/dacre_wright_six_wheel.yaml");
  return r;
}

void BM_WholeOctree(benchmark::State& state) {
  talus::OctreeOptions o;
  o.max_level = 6;
  std::size_t analyses = 0;
  double fraction = 0;
  for (auto _ : state) {
    talus::ConfigurationOctree oct(robot(), map64(), o);
    oct.build_full();
    analyses = oct.analyses();
    fraction = oct.free_volume_fraction();
    benchmark::DoNotOptimize(analyses);
  }
  state.counters["voxels_analysed"] = static_cast<double>(analyses);
  state.counters["free_volume_fraction"] = fraction;
}
BENCHMARK(BM_WholeOctree)->Unit(benchmark::kMillisecond);

void BM_IncrementalQuery(benchmark::State& state) {
  talus::DacreWrightOptions o;
  o.octree.max_level = 6;
  const talus::SE2Pose start{3.0, 3.0, 0.0}, goal{12.5, 12.5, 1.5};
  std::size_t analyses = 0;
  bool found = false;
  for (auto _ : state) {
    const talus::DacreWrightResult r = talus::plan_dacre_wright(map64(), robot(), start, goal, o);
    analyses = r.voxels_analysed();
    found = r.found();
    benchmark::DoNotOptimize(analyses);
  }
  state.counters["voxels_analysed"] = static_cast<double>(analyses);
  state.counters["found"] = found ? 1.0 : 0.0;
}
BENCHMARK(BM_IncrementalQuery)->Unit(benchmark::kMillisecond);

void BM_AnalyseBox(benchmark::State& state) {
  const talus::CsBox box{7.0, 7.25, 7.0, 7.25, 0.5, 0.6};
  for (auto _ : state) {
    benchmark::DoNotOptimize(talus::analyse_box(robot(), map64(), box));
  }
}
BENCHMARK(BM_AnalyseBox);

}  // namespace
