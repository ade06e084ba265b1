// Global search over a fractal terrain: lattice sizes 128^2 .. 1024^2,
// 16-connected (issue target: 512^2 in < 0.5 s on one core including edge
// costs). "Fields" computes both cost-to-go fields and 3 distinct candidates
// (every edge gets evaluated); "AStar" is the single-source single-target
// search with lazily evaluated edges. "MultiFields" / "MultiAStar" are the
// same with GlobalSearchResolution::kMulti (coarse lattice 4x coarser, then
// the fine lattice in a corridor around its candidates); the counters
// report the corridor's nodes and how often it widened. "FieldsThreads/N/T"
// is "Fields" with the edge costs computed up front on T threads
// (GlobalSearchOptions::threads; T = 1 is the serial search itself, so the
// ratio T = 2 / T = 1 of one run is the speed-up). "Round/N/W" is one of the
// planner's feedback rounds: "Fields" again with a disc of 4 lattice spacings
// excluded on the best candidate, from scratch (W = 0) or with a
// GlobalSearchWorkspace that already holds the lattice's edge costs (W = 1):
// W = 1 / W = 0 of one run is what sharing the costs saves per round.
#include <benchmark/benchmark.h>

#include <map>

#include "talus/core/terrain_generators.hpp"
#include "talus/optimal/global_search.hpp"

namespace {

struct Case {
  talus::BPatch terrain;
  talus::Vehicle vehicle;
};

const Case& terrain_case(std::size_t n) {
  static std::map<std::size_t, Case> cases;
  auto it = cases.find(n);
  if (it == cases.end()) {
    talus::FractalTerrainOptions options;
    options.shape = {n, n, 0.25, 0.0, 0.0};
    options.height_scale = 0.02 * static_cast<double>(n);  // comparable roughness at every size
    options.seed = 3;
    talus::Vehicle vehicle;
    vehicle.max_speed = 10.0;
    it =
        cases
            .emplace(
                n, Case{talus::BPatch::fit_smoothing(talus::generate_fractal_terrain(options), 1.0),
                        vehicle})
            .first;
  }
  return it->second;
}

void run(benchmark::State& state, std::size_t candidates, bool fields,
         talus::GlobalSearchResolution resolution = talus::GlobalSearchResolution::kFull,
         std::size_t threads = 1) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const Case& c = terrain_case(n);
  const double w = c.terrain.x_max() - c.terrain.x_min();
  talus::GlobalSearchOptions options;
  options.connectivity = 16;
  options.candidates = candidates;
  options.cost_fields = fields;
  options.resolution = resolution;
  options.threads = threads;
  talus::GlobalSearchResult result;
  for (auto _ : state) {
    result =
        talus::global_search(c.terrain, c.vehicle, {0.1 * w, 0.1 * w}, {0.9 * w, 0.9 * w}, options);
    benchmark::DoNotOptimize(result.candidates.data());
  }
  if (result.status != talus::GlobalSearchStatus::kOk) state.SkipWithError(result.message.c_str());
  state.counters["nodes"] = static_cast<double>(result.nodes);
  state.counters["edges"] = static_cast<double>(result.edges_evaluated);
  state.counters["candidates"] = static_cast<double>(result.candidates.size());
  state.counters["best_cost_s"] =
      result.candidates.empty() ? 0.0 : result.candidates[0].cost_seconds;
  state.counters["widenings"] = static_cast<double>(result.corridor_widenings);
}

void BM_GlobalSearchFields(benchmark::State& state) {
  run(state, 3, true);
}
void BM_GlobalSearchAStar(benchmark::State& state) {
  run(state, 1, false);
}
void BM_GlobalSearchMultiFields(benchmark::State& state) {
  run(state, 3, true, talus::GlobalSearchResolution::kMulti);
}
void BM_GlobalSearchMultiAStar(benchmark::State& state) {
  run(state, 1, false, talus::GlobalSearchResolution::kMulti);
}
void BM_GlobalSearchFieldsThreads(benchmark::State& state) {
  run(state, 3, true, talus::GlobalSearchResolution::kFull,
      static_cast<std::size_t>(state.range(1)));
}
void BM_GlobalSearchRound(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const bool warm = state.range(1) != 0;
  const Case& c = terrain_case(n);
  const double w = c.terrain.x_max() - c.terrain.x_min();
  const talus::Vec2 start(0.1 * w, 0.1 * w), goal(0.9 * w, 0.9 * w);
  talus::GlobalSearchOptions options;
  options.candidates = 3;
  talus::GlobalSearchWorkspace workspace;
  const talus::GlobalSearchResult first =
      talus::global_search(c.terrain, c.vehicle, start, goal, options, workspace);
  if (first.status != talus::GlobalSearchStatus::kOk) {
    state.SkipWithError(first.message.c_str());
    return;
  }
  const std::vector<talus::Vec2>& best = first.candidates[0].vertices;
  options.excluded = {{best[best.size() / 2], 4.0 * c.terrain.cellsize()}};
  talus::GlobalSearchResult result;
  for (auto _ : state) {
    result = warm ? talus::global_search(c.terrain, c.vehicle, start, goal, options, workspace)
                  : talus::global_search(c.terrain, c.vehicle, start, goal, options);
    benchmark::DoNotOptimize(result.candidates.data());
  }
  state.counters["edges"] = static_cast<double>(result.edges_evaluated);
  state.counters["best_cost_s"] =
      result.candidates.empty() ? 0.0 : result.candidates[0].cost_seconds;
}

BENCHMARK(BM_GlobalSearchFields)
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK(BM_GlobalSearchRound)
    ->Args({512, 0})
    ->Args({512, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK(BM_GlobalSearchFieldsThreads)
    ->Args({512, 1})
    ->Args({512, 2})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK(BM_GlobalSearchAStar)
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK(BM_GlobalSearchMultiFields)
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK(BM_GlobalSearchMultiAStar)
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);

}  // namespace
