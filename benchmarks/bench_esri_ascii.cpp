// Reading an ESRI ASCII grid (issue "speed near the floor", item 4: a 3601² grid, an SRTM
// 1-arc-second tile's size, in at most 2 s). The grid is written once per size to a temporary
// file by write_esri_ascii (shortest round-trip numbers, like the fractal generator's files:
// about 18 bytes a value, 240 MB at 3601²), then read_esri_ascii is timed on it, the file in
// the page cache after the first read.
//   ./build/benchmarks/bench_esri_ascii --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/esri_ascii.hpp"

namespace {

/// The file of an n × n grid of smooth, irrational-looking elevations [m], written once.
const std::string& grid_file(std::size_t n) {
  static std::map<std::size_t, std::string> files;
  auto it = files.find(n);
  if (it != files.end()) return it->second;
  talus::ElevationGrid grid(n, n, 1.0, 0.0, 0.0);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i)
      grid.at(i, j) = 40.0 * std::sin(0.013 * static_cast<double>(i)) *
                          std::cos(0.017 * static_cast<double>(j)) +
                      1e-3 * static_cast<double>((i * 7919 + j * 104729) % 1000);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("talus_bench_esri_" + std::to_string(n) + ".asc"))
          .string();
  talus::write_esri_ascii(grid, path);
  return files.emplace(n, path).first->second;
}

void BM_ReadEsriAscii(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::string& path = grid_file(n);
  for (auto _ : state) {
    const talus::ElevationGrid grid = talus::read_esri_ascii(path);
    benchmark::DoNotOptimize(grid.at(n / 2, n / 2));
  }
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
  state.counters["values_per_second"] =
      benchmark::Counter(static_cast<double>(n * n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ReadEsriAscii)->Arg(1201)->Arg(3601)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
