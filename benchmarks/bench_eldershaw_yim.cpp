// The Eldershaw-Yim legged baseline on the eldershaw-plan terrain (24 m, 0.2 m
// nodes, seed 2001) with the spider: CG-cell validity evaluations per second
// (evaluate_cg_pose, no cache), and the tree-PRM query from (4, 4) to (20, 20)
// (64 heading slices, 8 m connect radius, margin 12: the local-planner calls
// dominate) with 1 and 2 local-planner worker threads. Medians, e.g.
//   ./build/benchmarks/bench_eldershaw_yim --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/eldershaw_yim/cg_space.hpp"
#include "talus/kinematic/eldershaw_yim/eldershaw_yim_planner.hpp"

namespace {

const talus::RuledTerrain& terrain() {
  static const talus::RuledTerrain t = [] {
    talus::EldershawYimOptions o;
    o.shape = {121, 121, 0.2, 0.0, 0.0};
    o.seed = 2001;
    return talus::RuledTerrain(talus::generate_eldershaw_yim(o));
  }();
  return t;
}

const talus::LeggedRobot& spider() {
  static const talus::LeggedRobot r =
      talus::load_legged_robot(TALUS_DATA_DIR "/robots/eldershaw_spider.yaml");
  return r;
}

void BM_CgCellEvaluations(benchmark::State& state) {
  const talus::Footmap footmap(terrain(), spider());
  const talus::CgLattice lattice(terrain().grid(), spider().foot_print, 16);
  std::size_t valid = 0, evaluated = 0, next = 0;
  for (auto _ : state) {
    const talus::CgCell c = lattice.cell(next);
    next = (next + 7919) % lattice.size();  // a prime stride: cells spread over the map
    valid += talus::evaluate_cg_pose(footmap, spider(), lattice.centre(c)) == talus::CgState::kValid
                 ? 1
                 : 0;
    ++evaluated;
  }
  state.counters["cells_per_second"] =
      benchmark::Counter(static_cast<double>(evaluated), benchmark::Counter::kIsRate);
  state.counters["valid_fraction"] = static_cast<double>(valid) / static_cast<double>(evaluated);
}
BENCHMARK(BM_CgCellEvaluations);

void BM_TreePrmQuery(benchmark::State& state) {
  talus::EldershawYimPlannerOptions o;
  o.theta_slices = 64;
  o.connect_radius = 8.0;
  o.local.margin = 12;
  o.local.heading_weight = 0.0;  // the robot's outer radius, as the CLI
  o.prm_points = 300;
  o.plan_feet = false;
  o.workers = static_cast<int>(state.range(0));
  std::size_t calls = 0, cells = 0;
  bool found = false;
  for (auto _ : state) {
    const talus::EldershawYimResult r =
        talus::plan_eldershaw_yim(terrain(), spider(), {4, 4, 0}, {20, 20, 0}, o);
    calls = r.local_planner_calls;
    cells = r.cells_materialised;
    found = r.found();
    benchmark::DoNotOptimize(calls);
  }
  state.counters["local_planner_calls"] = static_cast<double>(calls);
  state.counters["cg_cells_materialised"] = static_cast<double>(cells);
  state.counters["found"] = found ? 1.0 : 0.0;
}
BENCHMARK(BM_TreePrmQuery)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
