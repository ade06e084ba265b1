// The profile path on a curved rover-scale path across West Bijou:
// - BM_ProfileOnly: the time-optimal solve alone (limits precomputed), N = 10^2 .. 10^5,
//   reusing one result object; its counter `vs_forward_backward` is the solve's time over
//   that of a plain forward–backward pass (BM_ForwardBackward) on the same limits, both
//   timed in the same benchmark run.
// - BM_ForwardBackward: the plain pass itself, the floor a streaming O(N) algorithm can
//   approach: backward x_i = min(v_max_i², x_{i+1} − 2 Δs a_min(i+1, v_{i+1})), forward
//   x_{i+1} = min(backward_{i+1}, x_i + 2 Δs a_max(i, v_i)) with the O(1)
//   acceleration-bound query at one end of each step (Euler in x = ṡ², no two-ended
//   admissibility), then the times.
// - BM_LimitsAndProfile: sampling + limits + solve from the path, N = 10^3 .. 10^5.
// - BM_LimitsAndProfileSine: the same on the sine instance (sine_path()).
// Counters read `profile.travel_time` through a const reference: the non-const
// DoNotOptimize's "+m,r" constraint let GCC hand back a clobbered double.
// Issue #13's targets: limits + solve <= 150 ns per station at N = 10^4 and 10^5; solve
// <= 60 ns per station. Run with --benchmark_repetitions=5
// --benchmark_report_aggregates_only=true and read the medians.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <string>
#include <utility>
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

/// The sine instance: the same terrain, a path y = 40 + 15 sin(2π x / 40 m) for x in
/// [5, 115] m interpolated through 3001 points, so that its arc-length table has about
/// 12,000 pieces (four per knot span) and station counts on either side of that cross
/// the sampler's switch between per-station quadrature and the trapezoid rule.
const talus::SurfacePath& sine_path() {
  static const talus::SurfacePath p = [] {
    std::vector<Vec2> points;
    for (int k = 0; k <= 3000; ++k) {
      const double x = 5.0 + 110.0 * k / 3000.0;
      points.emplace_back(x, 40.0 + 15.0 * std::sin(2.0 * 3.141592653589793 * x / 40.0));
    }
    return talus::SurfacePath(setup().patch, talus::Curve2::interpolate(points));
  }();
  return p;
}

/// The plain forward–backward pass (see the file comment) into preallocated vectors;
/// returns the travel time.
double forward_backward(const talus::VelocityLimits& limits, std::vector<double>& x,
                        std::vector<double>& t) {
  const std::size_t n = limits.size();
  x[n - 1] = 0.0;
  for (std::size_t i = n - 1; i-- > 0;) {
    const double ds = limits.frame(i + 1).s - limits.frame(i).s;
    const talus::AccelerationBounds b = limits.acceleration_bounds(i + 1, std::sqrt(x[i + 1]));
    const double v_max = limits.limits(i).v_max;
    x[i] =
        std::min(v_max * v_max, std::max(x[i + 1] - 2.0 * ds * (b.feasible ? b.a_min : 0.0), 0.0));
  }
  x[0] = 0.0;
  t[0] = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double ds = limits.frame(i + 1).s - limits.frame(i).s;
    const double v = std::sqrt(x[i]);
    const talus::AccelerationBounds b = limits.acceleration_bounds(i, v);
    x[i + 1] = std::min(x[i + 1], std::max(x[i] + 2.0 * ds * (b.feasible ? b.a_max : 0.0), 0.0));
    const double sum = v + std::sqrt(x[i + 1]);
    t[i + 1] = t[i] + (sum > 0.0 ? 2.0 * ds / sum : 0.0);
  }
  return t[n - 1];
}

/// This thread's CPU time [s] (the machine is shared: wall time would count other jobs).
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void set_per_station(benchmark::State& state) {
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["time_per_station"] =
      benchmark::Counter(static_cast<double>(state.iterations() * state.range(0)),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_ProfileOnly(benchmark::State& state) {
  const auto stations = static_cast<std::size_t>(state.range(0));
  const talus::VelocityLimits limits(setup().vehicle, path(), stations);
  talus::TimeOptimalProfileSolver solver;
  talus::TimeOptimalProfile profile;
  std::vector<double> x(stations), t(stations);
  double solve_time = 0.0, baseline_time = 0.0;
  for (auto _ : state) {
    const double a = thread_seconds();
    solver.solve(limits, {}, profile);
    benchmark::DoNotOptimize(std::as_const(profile).travel_time);
    const double b = thread_seconds();
    benchmark::DoNotOptimize(forward_backward(limits, x, t));
    const double c = thread_seconds();
    solve_time += b - a;
    baseline_time += c - b;
  }
  if (profile.status != talus::ProfileStatus::kOk) state.SkipWithError(profile.message.c_str());
  // The benchmark's own time covers both; the counters split them.
  set_per_station(state);
  const double per_station = 1e9 / static_cast<double>(state.iterations() * state.range(0));
  state.counters["solve_ns_per_station"] = solve_time * per_station;
  state.counters["fb_ns_per_station"] = baseline_time * per_station;
  state.counters["vs_forward_backward"] = solve_time / baseline_time;
  state.counters["travel_time"] = profile.travel_time;
}
BENCHMARK(BM_ProfileOnly)->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond);

void BM_ForwardBackward(benchmark::State& state) {
  const auto stations = static_cast<std::size_t>(state.range(0));
  const talus::VelocityLimits limits(setup().vehicle, path(), stations);
  std::vector<double> x(stations), t(stations);
  for (auto _ : state) benchmark::DoNotOptimize(forward_backward(limits, x, t));
  set_per_station(state);
  state.counters["travel_time"] = t.back();
}
BENCHMARK(BM_ForwardBackward)
    ->RangeMultiplier(10)
    ->Range(100, 100000)
    ->Unit(benchmark::kMicrosecond);

void limits_and_profile(benchmark::State& state, const talus::SurfacePath& on) {
  const auto stations = static_cast<std::size_t>(state.range(0));
  talus::VelocityLimits limits(setup().vehicle);
  talus::TimeOptimalProfileSolver solver;
  talus::TimeOptimalProfile profile;
  for (auto _ : state) {
    limits.compute(on, stations);
    solver.solve(limits, {}, profile);
    benchmark::DoNotOptimize(std::as_const(profile).travel_time);
  }
  if (profile.status != talus::ProfileStatus::kOk) state.SkipWithError(profile.message.c_str());
  set_per_station(state);
  state.counters["travel_time"] = profile.travel_time;
}

void BM_LimitsAndProfile(benchmark::State& state) {
  limits_and_profile(state, path());
}
void BM_LimitsAndProfileSine(benchmark::State& state) {
  limits_and_profile(state, sine_path());
}
BENCHMARK(BM_LimitsAndProfile)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(11000)
    ->Arg(11990)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_LimitsAndProfileSine)
    ->Arg(10000)
    ->Arg(11000)
    ->Arg(11990)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
