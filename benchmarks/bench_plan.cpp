// The whole time-optimal plan (issue target: a 256 x 256 DEM with 5
// candidates in < 5 s wall time on one core): B-patch fit, global search with
// 5 distinct candidates, Ipopt local optimisation of each with the adjoint
// gradient, each optimum's certificate (BM_FullPlan/certify:1, the default; :0 without it),
// and each optimum's profile at the default 0.1 m stations:
// talus::plan, what `talus plan` calls, without files and figures. Baseline in the same run: the
// global stage alone (fit included). Terrain: 256 x 256 nodes of the Mount
// St. Helens USGS DEM (30 m; columns 30.., rows 100.. from the south-west:
// the cone's western half and the lowlands), smoothing fit lambda = 1 as the
// global-search experiment uses, from (5 %, 50 %) to (95 %, 50 %) of the crop, with
// data/vehicles/rover.yaml. (The Big Tujunga SRTM crop was tried first: its
// lattice corridors are threads that no smooth path can follow dynamically,
// even with 160 control points; see the closing note of issue #6.)
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <limits>
#include <memory>
#include <string>

#include "talus/core/esri_ascii.hpp"
#include "talus/core/grid_window.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/planner.hpp"

namespace {

constexpr std::size_t kSize = 256;

const talus::ElevationGrid& dem() {
  static const talus::ElevationGrid grid = [] {
    const talus::ElevationGrid full = talus::read_esri_ascii(
        std::string(TALUS_DATA_DIR) + "/terrain/mount_st_helens_usgs30m.asc");
    // South-west node of the crop: column 30, row 100.
    return talus::crop_grid(full, talus::GridWindow{30, 100, kSize, kSize});
  }();
  return grid;
}

const talus::Vehicle& rover() {
  static const talus::Vehicle v =
      talus::load_vehicle(std::string(TALUS_DATA_DIR) + "/vehicles/rover.yaml");
  return v;
}

talus::Vec2 start_point(const talus::BPatch& t) {
  return {t.x_min() + 0.05 * (t.x_max() - t.x_min()), t.y_min() + 0.5 * (t.y_max() - t.y_min())};
}
talus::Vec2 goal_point(const talus::BPatch& t) {
  return {t.x_min() + 0.95 * (t.x_max() - t.x_min()), t.y_min() + 0.5 * (t.y_max() - t.y_min())};
}

talus::GlobalSearchOptions search_options() {
  talus::GlobalSearchOptions options;
  options.candidates = 5;
  return options;
}

void BM_GlobalStageOnly(benchmark::State& state) {
  for (auto _ : state) {
    const talus::BPatch terrain = talus::BPatch::fit_smoothing(dem(), 1.0);
    const talus::GlobalSearchResult global = talus::global_search(
        terrain, rover(), start_point(terrain), goal_point(terrain), search_options());
    if (global.status != talus::GlobalSearchStatus::kOk) state.SkipWithError("unreachable");
    benchmark::DoNotOptimize(global.candidates.data());
  }
}
BENCHMARK(BM_GlobalStageOnly)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Argument 1: the default plan, each optimum certified (PlannerOptions::certify); 0: without
/// the certificates, the local stage's own cost.
void BM_FullPlan(benchmark::State& state) {
  talus::PlannerOptions options;
  options.global = search_options();
  options.certify = state.range(0) != 0;
  double best = std::numeric_limits<double>::infinity(), global_best = best;
  std::size_t evaluations = 0;
  for (auto _ : state) {
    const auto terrain =
        std::make_shared<const talus::BPatch>(talus::BPatch::fit_smoothing(dem(), 1.0));
    const talus::PlannerResult result = talus::plan(
        talus::PlanningProblem(terrain, rover(), start_point(*terrain), goal_point(*terrain)),
        options);
    if (result.status != talus::PlannerStatus::kOk) state.SkipWithError("no trajectory");
    best = result.travel_time();
    global_best = result.global_travel_time();
    evaluations = 0;
    for (const talus::CandidateOutcome& c : result.candidates) {
      if (c.optimization) evaluations += c.optimization->evaluations;
    }
  }
  state.counters["travel_time_s"] = best;
  state.counters["global_candidate_s"] = global_best;
  state.counters["evaluations"] = static_cast<double>(evaluations);
}
BENCHMARK(BM_FullPlan)
    ->ArgName("certify")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
