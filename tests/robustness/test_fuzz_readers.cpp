// Seeded random-mutation fuzzing of the three readers that take user files:
// ESRI ASCII grids, path CSVs and vehicle YAML. Each mutant must parse or
// throw talus::InputError: any other exception fails the test, and a crash,
// hang or memory error fails it too (the sanitizer build runs this under
// ASan/UBSan; CTest's timeout bounds the time). The seed is fixed, so a
// failure reproduces; TALUS_FUZZ_ITERATIONS raises the count for a long run,
// and TALUS_FUZZ_TRACE=FILE keeps the mutant being parsed in FILE.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/path_csv.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus {
namespace {

std::size_t iterations() {
  if (const char* n = std::getenv("TALUS_FUZZ_ITERATIONS")) return std::strtoul(n, nullptr, 10);
  return 20000;
}

/// Tokens that readers treat specially, spliced in by the mutator.
const std::vector<std::string> kDictionary = {
    "ncols",        "nrows",  "xllcorner",  "yllcenter", "cellsize",
    "NODATA_value", "-9999",  "nan",        "inf",       "-inf",
    "1e308",        "1e-400", "0",          "-1",        "99999999999",
    "\xEF\xBB\xBF", ",",      "\n",         "x,y",       ":",
    "---",          "{",      "[",          "&a",        "*a",
    "friction",     "model",  "point_mass", "\"",        "'",
    "\t",           "\r\n",   "\x00",       "\xff"};

/// One random edit: flip, insert, delete, duplicate a span, or splice a token.
std::string mutate(std::string text, std::mt19937_64& rng) {
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = text.empty() ? 0 : rng() % (text.size() + 1);
    switch (rng() % 5) {
      case 0:
        if (!text.empty()) text[rng() % text.size()] = static_cast<char>(rng() % 256);
        break;
      case 1:
        text.insert(at, 1, static_cast<char>(rng() % 256));
        break;
      case 2:
        if (!text.empty()) text.erase(rng() % text.size(), 1 + rng() % 8);
        break;
      case 3: {
        if (text.empty()) break;
        const std::size_t from = rng() % text.size(), length = 1 + rng() % 32;
        text.insert(at, text.substr(from, length));
        break;
      }
      default:
        text.insert(at, kDictionary[rng() % kDictionary.size()]);
    }
  }
  return text;
}

/// Runs `parse` on mutants of `seeds`; returns how many parsed (the rest threw InputError).
std::size_t fuzz(const std::vector<std::string>& seeds,
                 const std::function<void(const std::string&)>& parse, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::size_t accepted = 0;
  const char* trace = std::getenv("TALUS_FUZZ_TRACE");
  double slowest = 0.0;
  std::string slowest_input;
  for (std::size_t k = 0; k < iterations(); ++k) {
    const std::string input = mutate(seeds[k % seeds.size()], rng);
    if (trace) std::ofstream(trace, std::ios::binary) << input;  // the mutant of a crash
    const auto started = std::chrono::steady_clock::now();
    try {
      parse(input);
      ++accepted;
    } catch (const InputError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << "mutant " << k << " threw a non-InputError: " << e.what();
      return accepted;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (seconds > slowest) {
      slowest = seconds;
      slowest_input = input;
    }
  }
  std::printf("%zu of %zu mutants accepted; slowest %.3f s: %s\n", accepted, iterations(), slowest,
              printable(slowest_input, 120).c_str());
  return accepted;
}

TEST(FuzzReaders, EsriAsciiAcceptsOrRefusesWithInputError) {
  const std::vector<std::string> seeds = {
      "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n1 2 3\n4 -9999 "
      "6\n",
      "NCOLS 2\nNROWS 2\nXLLCENTER 5.5\nYLLCENTER -3\nCELLSIZE 0.25\n1.5e2 2\n3 4\n"};
  const std::size_t accepted = fuzz(
      seeds,
      [](const std::string& text) {
        std::istringstream in(text);
        const ElevationGrid grid = read_esri_ascii(in, "mutant.asc");
        ASSERT_GE(grid.ncols(), 2u);
      },
      1);
  EXPECT_GT(accepted, 0u);  // the mutator also makes valid grids: the seeds are exercised
}

TEST(FuzzReaders, PathCsvAcceptsOrRefusesWithInputError) {
  const std::vector<std::string> seeds = {"x,y\n0,0\n10.5,2\n20,-3e1\n",
                                          "x,y\r\n1,2\r\n3,4\r\n\r\n"};
  const std::size_t accepted = fuzz(
      seeds,
      [](const std::string& text) {
        std::istringstream in(text);
        ASSERT_GE(read_path_csv(in, "mutant.csv").size(), 2u);
      },
      2);
  EXPECT_GT(accepted, 0u);
}

TEST(FuzzReaders, VehicleYamlAcceptsOrRefusesWithInputError) {
  const std::vector<std::string> seeds = {
      "model: point_mass\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\nmax_speed: 15\n",
      "{\"model\": \"rigid_body\", \"friction\": 0.5, \"cg_height\": 1, \"half_track\": 1, "
      "\"half_wheelbase\": 1.5}\n"};
  const std::size_t accepted = fuzz(
      seeds, [](const std::string& text) { parse_vehicle(text, "mutant.yaml").validate(); }, 3);
  EXPECT_GT(accepted, 0u);
}

}  // namespace
}  // namespace talus
