// The whole plan on the fractal battery of issue #12 (target: a median of
// at most 2 s per case on one core), the default local stage (16 control
// points, two restarts) against the former default (an 8-point fit and a
// further start at 16, no restart) in the same run, on seeds 1-5: the
// terrain generated and fitted outside the timing, then talus::plan from
// scenarios::kBatteryStart to scenarios::kBatteryGoal with the battery's point-mass UGV. Counters:
// the best trajectory's travel time [s] and the local stage's objective
// evaluations. Medians:
//   ./build/benchmarks/bench_battery_plan --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true   (one command line)
#include <benchmark/benchmark.h>

#include <cstdint>
#include <map>

#include "talus/bspline/bpatch.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/scenarios/fractal_battery.hpp"

namespace {

namespace battery = talus::scenarios;

const talus::BPatch& surface(std::int64_t seed) {
  static std::map<std::int64_t, talus::BPatch> surfaces;
  auto it = surfaces.find(seed);
  if (it == surfaces.end()) {
    const talus::ElevationGrid grid =
        talus::generate_fractal_terrain(battery::battery_terrain(static_cast<std::uint64_t>(seed)));
    it = surfaces.emplace(seed, talus::BPatch::interpolate(grid)).first;
  }
  return it->second;
}

void BM_BatteryPlan(benchmark::State& state, bool former_default) {
  talus::PlannerOptions options;
  if (former_default) {
    options.local.control_points = 8;
    options.local.more_control_points = {16};
    options.local.restarts = 0;
  }
  const talus::BPatch& terrain = surface(state.range(0));
  const talus::PlanningProblem problem(terrain, battery::battery_point_mass_ugv(),
                                       battery::kBatteryStart, battery::kBatteryGoal);
  double travel_time = 0.0;
  std::size_t evaluations = 0;
  for (auto _ : state) {
    const talus::PlannerResult result = talus::plan(problem, options);
    if (result.status != talus::PlannerStatus::kOk) state.SkipWithError("no trajectory");
    travel_time = result.travel_time();
    evaluations = 0;
    for (const talus::CandidateOutcome& c : result.candidates) {
      if (c.optimization) evaluations += c.optimization->evaluations;
    }
  }
  state.counters["travel_time_s"] = travel_time;
  state.counters["evaluations"] = static_cast<double>(evaluations);
}
BENCHMARK_CAPTURE(BM_BatteryPlan, default_stage, false)
    ->DenseRange(1, 5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_BatteryPlan, former_default, true)
    ->DenseRange(1, 5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
