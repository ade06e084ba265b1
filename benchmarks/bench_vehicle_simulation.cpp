// Speed of the vehicle simulation (vehicle_simulation.hpp) as a real-time
// factor (simulated seconds per wall second, the "real_time_factor" counter),
// for the paper's UGV: coasting on level ground (smooth, no control changes),
// constant-steer cornering near the friction limit, and tracking a slalom with
// pure pursuit at 100 Hz over a rough surface (a control change, hence a CVODE
// restart, every tick). The machine is shared: compare the cases of one run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/dynamics/trajectory_tracking.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/vehicle_simulation.hpp"
#include "talus/navigation/potential_field_navigation.hpp"

namespace {

using namespace talus;

Vehicle ugv() {
  return load_vehicle(std::string(TALUS_DATA_DIR) + "/vehicles/iagnemma_ugv.yaml");
}

BPatch surface(double amplitude) {
  ElevationGrid grid(121, 61, 0.25, -15.0, -7.5);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const Vec2 p = grid.node_position(i, j);
      grid.set(i, j, amplitude * std::sin(0.9 * p.x()) * std::cos(1.3 * p.y()));
    }
  return BPatch::interpolate(grid);
}

void report(benchmark::State& state, double simulated, double wall, long steps) {
  state.counters["real_time_factor"] = simulated / wall;  // wall clock: inflated by load
  // Simulated seconds per CPU second of the benchmark (kIsRate divides by it).
  state.counters["sim_s_per_cpu_s"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  state.counters["steps_per_sim_s"] = static_cast<double>(steps) / simulated;
}

/// Runs the simulation once per benchmark iteration and reports its rates.
void simulate_repeatedly(benchmark::State& state, const BPatch& terrain, const Vehicle& v,
                         const VehicleState& start, const VehicleController& controller,
                         const VehicleSimulationOptions& options) {
  double simulated = 0.0, wall = 0.0;
  long steps = 0;
  for (auto _ : state) {
    const VehicleSimulationResult r = simulate_vehicle(terrain, v, start, controller, options);
    simulated += r.end_time;
    wall += r.seconds;
    steps += r.diagnostics.steps;
    benchmark::DoNotOptimize(r.final.state.position);
  }
  report(state, simulated, wall, steps);
}

void BM_Coasting(benchmark::State& state) {
  const BPatch flat = surface(0.0);
  const Vehicle v = ugv();
  VehicleSimulationOptions o;
  o.end_time = 5.0;
  const VehicleState s = resting_state(flat, v, Vec2(-12.0, 0.0), 0.0, 2.0);
  const VehicleController c = [](double, const VehicleState&) { return VehicleControls{}; };
  simulate_repeatedly(state, flat, v, s, c, o);
}
BENCHMARK(BM_Coasting)->Unit(benchmark::kMillisecond);

void BM_CorneringNearTheLimit(benchmark::State& state) {
  const BPatch flat = surface(0.0);
  const Vehicle v = ugv();
  VehicleSimulationOptions o;
  o.end_time = 3.0;
  const VehicleState s = resting_state(flat, v, Vec2(0.0, -2.7), 0.0, 3.8);
  const double m = v.body->mass;
  const VehicleController c = [m](double, const VehicleState& x) {
    return VehicleControls{0.1, m * 10.0 * (3.8 - x.velocity.x()), false};
  };
  simulate_repeatedly(state, flat, v, s, c, o);
}
BENCHMARK(BM_CorneringNearTheLimit)->Unit(benchmark::kMillisecond);

void BM_TrackingASlalomOnRoughGround(benchmark::State& state) {
  const BPatch rough = surface(0.05);
  const Vehicle v = ugv();
  ReferenceTrajectory path;
  for (int i = 0; i <= 200; ++i) {
    const double x = -12.0 + 24.0 * i / 200.0;
    path.points.emplace_back(x, 1.5 * std::sin(0.5 * x));
    path.speed.push_back(3.0);
  }
  double simulated = 0.0, wall = 0.0;
  long steps = 0;
  for (auto _ : state) {
    const TrackingResult r = track_trajectory(rough, v, path);
    simulated += r.travel_time;
    wall += r.simulation.seconds;
    steps += r.simulation.diagnostics.steps;
    benchmark::DoNotOptimize(r.max_cross_track);
  }
  report(state, simulated, wall, steps);
}
BENCHMARK(BM_TrackingASlalomOnRoughGround)->Unit(benchmark::kMillisecond);

/// Potential-field navigation over the crest of the lookahead test
/// (tests/navigation/test_vehicle_simulation_navigation.cpp: 0.25 m high, σ 0.7 m) to a
/// goal 20 m away at 5.5 m/s, standard (arg 0) or with the §IV lookahead
/// (arg 1). Counter us_per_tick: the whole run's wall time per control tick
/// (simulation included); the lookahead's own cost is the difference between
/// the two, measured in the same run (issue #16's target: < 1 ms per tick).
void BM_NavigationTick(benchmark::State& state) {
  ElevationGrid grid(131, 41, 0.2, -2.0, -4.0);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const double x = grid.node_position(i, j).x();
      grid.set(i, j, 0.25 * std::exp(-(x - 9.0) * (x - 9.0) / (2.0 * 0.7 * 0.7)));
    }
  const BPatch crest = BPatch::interpolate(grid);
  const Vehicle v = ugv();
  ReferenceTrajectory goal;
  goal.points = {Vec2(20.0, 0.0)};
  goal.speed = {5.5};
  PotentialFieldNavigationOptions options;
  options.lookahead.enabled = state.range(0) != 0;
  double wall = 0.0;
  std::size_t ticks = 0;
  for (auto _ : state) {
    const auto started = std::chrono::steady_clock::now();
    const PotentialFieldNavigationResult r =
        navigate_potential_field(crest, v, Vec2(0, 0), 0.0, goal, {}, options);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    ticks += r.commands.size();
    benchmark::DoNotOptimize(r.navigation_time);
  }
  state.counters["us_per_tick"] = 1e6 * wall / static_cast<double>(std::max<std::size_t>(ticks, 1));
}
BENCHMARK(BM_NavigationTick)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
