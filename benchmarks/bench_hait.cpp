// The Haït–Siméon–Taïx planner: the potential-rs search of the
// hait-heuristics problem (issue #7 target: < 50 ms search time on one core;
// the paper took 1.83 s), and placement throughput (placements/s) for both
// robots, with a bilinear elevation look-up and the chassis placed without
// the θ-sliced table as same-run baselines.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"
#include "talus/kinematic/hait/placement.hpp"
#include "talus/scenarios/hait_robots.hpp"

namespace {

const talus::HaitScenario& scenario() {
  static const talus::HaitScenario s = talus::hait_heuristics_scenario(false);
  return s;
}
const talus::RuledTerrain& terrain() {
  static const talus::RuledTerrain t(scenario().grid);
  return t;
}
const talus::Robot& chassis() {
  static const talus::Robot r = talus::scenarios::load_hait_chassis(TALUS_DATA_DIR);
  return r;
}
const talus::Robot& wheeled() {
  static const talus::Robot r = talus::scenarios::load_hait_wheeled(TALUS_DATA_DIR);
  return r;
}

/// 4096 seeded configurations 2 m inside the map.
const std::vector<talus::SE2Pose>& configurations() {
  static const std::vector<talus::SE2Pose> q = [] {
    std::mt19937_64 rng(42);
    const auto u = [&rng](double lo, double hi) {
      return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
    };
    const double w = terrain().grid().x_max();
    std::vector<talus::SE2Pose> out;
    for (int k = 0; k < 4096; ++k) out.push_back({u(2, w - 2), u(2, w - 2), u(-M_PI, M_PI)});
    return out;
  }();
  return q;
}

/// Manual time = the planner's own search_seconds (preprocessing excluded).
void BM_HaitSearchPotentialRs(benchmark::State& state) {
  const talus::HaitScenario& s = scenario();
  talus::HaitOptions options;
  options.heuristic = talus::HaitHeuristic::kPotentialRs;
  talus::HaitResult r;
  for (auto _ : state) {
    r = talus::plan_hait(terrain(), chassis(), s.start, s.goal, options);
    state.SetIterationTime(r.search_seconds);
  }
  if (r.status != talus::HaitStatus::kFound) state.SkipWithError(r.message.c_str());
  state.counters["nodes_created"] = static_cast<double>(r.nodes_created);
  state.counters["placements"] = static_cast<double>(r.placements);
  state.counters["preprocessing_s"] = r.preprocessing_seconds;
}
BENCHMARK(BM_HaitSearchPotentialRs)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_BilinearElevation(benchmark::State& state) {
  const auto& q = configurations();
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(terrain().elevation(q[k].position()));
    k = (k + 1) % q.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BilinearElevation);

void BM_PlaceRobotWheeled(benchmark::State& state) {
  const auto& robot = std::get<talus::WheeledRobot>(wheeled());
  const auto& q = configurations();
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(talus::place_robot(robot, terrain(), q[k].x, q[k].y, q[k].theta));
    k = (k + 1) % q.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PlaceRobotWheeled);

void BM_ChassisTablePlace(benchmark::State& state) {
  static const talus::ChassisPlacementTable table(std::get<talus::ArticulatedChassis>(chassis()),
                                                  terrain());
  const auto& q = configurations();
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(table.place(q[k].x, q[k].y, q[k].theta));
    k = (k + 1) % q.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ChassisTablePlace);

void BM_PlaceChassisDirect(benchmark::State& state) {
  const auto& c = std::get<talus::ArticulatedChassis>(chassis());
  const auto& q = configurations();
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(talus::place_chassis(c, terrain(), q[k].x, q[k].y, q[k].theta));
    k = (k + 1) % q.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PlaceChassisDirect);

}  // namespace
