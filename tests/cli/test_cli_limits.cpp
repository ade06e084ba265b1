// End-to-end tests of `talus limits`: the CSV and JSON contracts on the
// bundled examples, known answers on generated flat terrain, and errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/esri_ascii.hpp"

namespace talus::cli_test {
namespace {

const std::string kExampleTerrain = "terrain/west_bijou_escarpment_nasadem25m.asc";
const std::string kExamplePath = "paths/west_bijou_traverse.csv";

/// One parsed row of the limits CSV.
struct LimitsRow {
  double s, x, y, z, v_min, v_max;
  std::string binding;
  double k_t, k_q, k_r, kappa_n, kappa_g;
};

const char* const kExpectedHeader = "s,x,y,z,v_min,v_max,binding,k_t,k_q,k_r,kappa_n,kappa_g";

/// Reads the CSV, checking the header and the column count of every row.
std::vector<LimitsRow> read_limits_csv(const std::string& file) {
  std::vector<LimitsRow> rows;
  for (const std::vector<std::string>& f : read_csv(file, kExpectedHeader)) {
    rows.push_back({parse_number(f[0]), parse_number(f[1]), parse_number(f[2]), parse_number(f[3]),
                    parse_number(f[4]), parse_number(f[5]), f[6], parse_number(f[7]),
                    parse_number(f[8]), parse_number(f[9]), parse_number(f[10]),
                    parse_number(f[11])});
  }
  return rows;
}

/// The checks every limits CSV must pass, against its JSON summary.
void expect_consistent(const std::vector<LimitsRow>& rows, const nlohmann::json& summary) {
  static const std::set<std::string> kBindings = {"sliding", "tipover", "contact", "max_speed",
                                                  "none"};
  ASSERT_EQ(rows.size(), summary.at("stations").get<std::size_t>());
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows.front().s, 0.0);
  std::map<std::string, std::size_t> counts;
  std::size_t untraversable = 0;
  double min_v_max = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const LimitsRow& r = rows[k];
    if (k > 0) {
      EXPECT_GT(r.s, rows[k - 1].s) << "station " << k;
    }
    EXPECT_GE(r.v_min, 0.0) << "station " << k;
    EXPECT_GE(r.v_max, r.v_min) << "station " << k;
    EXPECT_TRUE(kBindings.count(r.binding)) << "station " << k << ": " << r.binding;
    EXPECT_EQ(std::isinf(r.v_max), r.binding == "none") << "station " << k;
    if (r.v_max == 0.0) ++untraversable;
    ++counts[r.binding];
    min_v_max = std::min(min_v_max, r.v_max);
    for (const double v :
         {r.s, r.x, r.y, r.z, r.v_min, r.k_t, r.k_q, r.k_r, r.kappa_n, r.kappa_g}) {
      EXPECT_TRUE(std::isfinite(v)) << "station " << k;
    }
    EXPECT_NEAR(r.k_t * r.k_t + r.k_q * r.k_q + r.k_r * r.k_r, 1.0, 1e-9) << "station " << k;
    EXPECT_GT(r.k_r, 0.0) << "station " << k;
  }
  EXPECT_NEAR(summary.at("length_m").get<double>(), rows.back().s,
              1e-9 * std::max(1.0, rows.back().s));
  EXPECT_EQ(summary.at("untraversable_stations").get<std::size_t>(), untraversable);
  if (std::isinf(min_v_max)) {
    EXPECT_TRUE(summary.at("min_v_max").is_null());
  } else {
    EXPECT_DOUBLE_EQ(summary.at("min_v_max").get<double>(), min_v_max);
  }
  std::size_t total = 0;
  for (const auto& [name, n] : summary.at("binding_counts").items()) {
    EXPECT_TRUE(kBindings.count(name)) << name;
    EXPECT_EQ(n.get<std::size_t>(), counts[name]) << name;
    total += n.get<std::size_t>();
  }
  EXPECT_EQ(total, rows.size());
  EXPECT_TRUE(summary.at("seconds").is_number());
}

/// Runs a limits command that must succeed and returns its JSON summary.
nlohmann::json run_limits_ok(const std::string& args) {
  const RunResult r = run_talus("limits " + args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  return parse_json(r.out, "stdout", nlohmann::json::object({{"stations", 0}}));
}

/// A point mass with friction mu, tip-over ratio b/h = 1.2 and no top speed.
std::string unlimited_vehicle(double mu = 0.7) {
  return point_mass_vehicle("unlimited.yaml", mu);
}

TEST(CliLimits, ExampleFilesGiveTheDocumentedCsvAndJson) {
  const std::string out = scratch_file("example.csv");
  const nlohmann::json j =
      run_limits_ok("--terrain " + quoted(data_file(kExampleTerrain)) + " --path " +
                    quoted(data_file(kExamplePath)) + " --vehicle " +
                    quoted(data_file("vehicles/rover.yaml")) + " -o " + quoted(out));
  for (const char* key : {"stations", "length_m", "min_v_max", "untraversable_stations",
                          "binding_counts", "seconds"}) {
    EXPECT_TRUE(j.contains(key)) << key << " missing from " << j.dump();
  }
  const std::vector<LimitsRow> rows = read_limits_csv(out);
  expect_consistent(rows, j);
  // Default stations: one per metre of the way points' polyline, ceil(L) + 1.
  double planar = 0.0;
  {
    std::ifstream in(data_file(kExamplePath));
    std::string line;
    std::getline(in, line);
    double px = 0, py = 0;
    bool first = true;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      const double x = std::stod(line.substr(0, line.find(','))),
                   y = std::stod(line.substr(line.find(',') + 1));
      if (!first) planar += std::hypot(x - px, y - py);
      px = x, py = y, first = false;
    }
  }
  EXPECT_EQ(j.at("stations").get<std::size_t>(), static_cast<std::size_t>(std::ceil(planar)) + 1);
  // The rover's top speed is 15 m/s, so nothing is unlimited, and the
  // switchback on the escarpment is taken slower than that.
  for (const LimitsRow& r : rows) EXPECT_LE(r.v_max, 15.0 * (1 + 1e-12));
  EXPECT_GT(j.at("binding_counts").at("max_speed").get<std::size_t>(), 0u);
  EXPECT_GT(j.at("binding_counts").at("sliding").get<std::size_t>(), 0u);
  EXPECT_LT(j.at("min_v_max").get<double>(), 15.0);
  EXPECT_EQ(j.at("untraversable_stations"), 0);
  // The path starts and ends at the first and last way points, on the terrain.
  EXPECT_NEAR(rows.front().x, 556810.0, 1e-6);
  EXPECT_NEAR(rows.front().y, 4373910.0, 1e-6);
  EXPECT_NEAR(rows.back().x, 559260.0, 1e-6);
  EXPECT_NEAR(rows.back().y, 4374160.0, 1e-6);
  for (const LimitsRow& r : rows) {
    EXPECT_GT(r.z, 1690.0 - 5.0);
    EXPECT_LT(r.z, 1807.0 + 5.0);
  }
}

TEST(CliLimits, StationsOptionRigidBodyAndSmoothingFit) {
  const std::string out = scratch_file("rigid.csv");
  const nlohmann::json j =
      run_limits_ok("--terrain " + quoted(data_file(kExampleTerrain)) + " --path " +
                    quoted(data_file(kExamplePath)) + " --vehicle " +
                    quoted(data_file("vehicles/rover_rigid.yaml")) +
                    " --stations 300 --smoothing 1 -o " + quoted(out));
  EXPECT_EQ(j.at("stations"), 300);
  const std::vector<LimitsRow> rows = read_limits_csv(out);
  EXPECT_EQ(rows.size(), 300u);
  expect_consistent(rows, j);
}

TEST(CliLimits, CircleOnFlatGroundIsLimitedBySlidingAtSqrtMuGR) {
  const double mu = 0.7, g = 9.81, radius = 40.0;
  std::vector<std::array<double, 2>> points;
  for (int k = 0; k < 28; ++k) {  // 270 degrees, a way point every 10 degrees
    const double a = k * std::numbers::pi / 18.0;
    points.push_back({60.0 + radius * std::cos(a), 60.0 + radius * std::sin(a)});
  }
  const std::string out = scratch_file("circle.csv");
  const nlohmann::json j =
      run_limits_ok("--terrain " + quoted(flat_terrain()) + " --path " +
                    quoted(write_points("circle_path.csv", points)) + " --vehicle " +
                    quoted(unlimited_vehicle(mu)) + " --stations 400 -o " + quoted(out));
  const std::vector<LimitsRow> rows = read_limits_csv(out);
  ASSERT_EQ(rows.size(), 400u);
  expect_consistent(rows, j);
  EXPECT_NEAR(rows.back().s, 1.5 * std::numbers::pi * radius,
              0.002 * 1.5 * std::numbers::pi * radius);
  const double expected = std::sqrt(mu * g * radius);
  for (std::size_t k = 40; k < 360; ++k) {  // interior stations
    EXPECT_NEAR(rows[k].v_max, expected, 0.005 * expected) << "station " << k;
    EXPECT_EQ(rows[k].binding, "sliding") << "station " << k;
    EXPECT_EQ(rows[k].v_min, 0.0);
    EXPECT_NEAR(rows[k].kappa_g, 1.0 / radius, 0.005 / radius);  // counter-clockwise: left turn
    EXPECT_NEAR(rows[k].kappa_n, 0.0, 1e-9);
    EXPECT_NEAR(rows[k].k_r, 1.0, 1e-12);
  }
  EXPECT_EQ(j.at("binding_counts").at("sliding"), 400);
}

TEST(CliLimits, StraightPathOnFlatGroundIsUnlimitedAndWritesInf) {
  const std::string out = scratch_file("straight.csv");
  const nlohmann::json j = run_limits_ok(
      "--terrain " + quoted(flat_terrain()) + " --path " +
      quoted(write_points("straight_path.csv", {{{10, 60}}, {{60, 60}}, {{110, 60}}})) +
      " --vehicle " + quoted(unlimited_vehicle()) + " -o " + quoted(out));
  EXPECT_EQ(j.at("stations"), 101);  // default: ceil(100 m) + 1
  EXPECT_TRUE(j.at("min_v_max").is_null());
  EXPECT_EQ(j.at("binding_counts").at("none"), 101);
  const std::string text = read_text(out);
  EXPECT_NE(text.find(",0,inf,none,"), std::string::npos) << text.substr(0, 300);
  const std::vector<LimitsRow> rows = read_limits_csv(out);
  expect_consistent(rows, j);
  for (const LimitsRow& r : rows) EXPECT_TRUE(std::isinf(r.v_max) && r.v_max > 0);
  EXPECT_NEAR(rows.back().s, 100.0, 1e-9);
}

TEST(CliLimits, DefaultStationCountIsClampedBelowAt100) {
  const std::string out = scratch_file("short.csv");
  const nlohmann::json j =
      run_limits_ok("--terrain " + quoted(flat_terrain()) + " --path " +
                    quoted(write_points("short_path.csv", {{{10, 10}}, {{30, 10}}})) +
                    " --vehicle " + quoted(unlimited_vehicle()) + " -o " + quoted(out));
  EXPECT_EQ(j.at("stations"), 100);
  EXPECT_EQ(read_limits_csv(out).size(), 100u);
}

TEST(CliLimits, SideSlopeSteeperThanFrictionIsUntraversable) {
  const std::string terrain = scratch_file("slope.asc");
  // 0.7 rad side slope: tan(0.7) = 0.84 > mu = 0.7, but < b/h = 1.2.
  const RunResult g = run_talus(
      "terrain generate plane --slope 0.7 --aspect 0 --ncols 41 --nrows 41 -o " + quoted(terrain));
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const std::string out = scratch_file("slope.csv");
  const nlohmann::json j = run_limits_ok(
      "--terrain " + quoted(terrain) + " --path " +
      quoted(write_points("contour_path.csv", {{{20, 5}}, {{20, 35}}})) + " --vehicle " +
      quoted(unlimited_vehicle()) + " --stations 50 -o " + quoted(out));
  const std::vector<LimitsRow> rows = read_limits_csv(out);
  expect_consistent(rows, j);
  EXPECT_EQ(j.at("untraversable_stations"), 50);
  EXPECT_EQ(j.at("min_v_max"), 0.0);
  for (const LimitsRow& r : rows) {
    EXPECT_EQ(r.v_max, 0.0);
    EXPECT_EQ(r.v_min, 0.0);
    EXPECT_EQ(r.binding, "sliding");
    EXPECT_NEAR(r.k_q, -std::sin(0.7), 1e-9);  // ground rises to the east, on the right
  }
}

TEST(CliLimits, BadInputGivesOneLineOnStderrAndExitCodeOne) {
  const std::string terrain = quoted(data_file(kExampleTerrain));
  const std::string path = quoted(data_file(kExamplePath));
  const std::string rover = quoted(data_file("vehicles/rover.yaml"));
  const std::string off_map =
      write_points("off_map.csv", {{{556810, 4373910}}, {{557160, 4374060}}, {{560000, 4374100}}});
  const std::string malformed = scratch_file("malformed.csv");
  write_text(malformed, "x,y\n556810,4373910\n557160;4374060\n");
  const std::string no_header = scratch_file("no_header.csv");
  write_text(no_header, "556810,4373910\n557160,4374060\n");
  const std::string unknown_key = scratch_file("unknown_key.yaml");
  write_text(unknown_key,
             "model: point_mass\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\n"
             "wheel_count: 4\n");
  // A grid with one NODATA node, under the second way point.
  talus::ElevationGrid grid(21, 21, 1.0, 0.0, 0.0, 5.0);
  grid.set_void(10, 10);
  const std::string voids = scratch_file("voids.asc");
  talus::write_esri_ascii(grid, voids);
  const std::string through_void =
      write_points("through_void.csv", {{{2, 2}}, {{10.5, 10.5}}, {{18, 3}}});
  const std::string out = scratch_file("never_written.csv");
  std::filesystem::remove(out);

  const std::string common = " -o " + quoted(out);
  const std::vector<ErrorCase> cases = {
      {"--terrain " + terrain + " --path " + quoted(off_map) + " --vehicle " + rover + common,
       "path point 2 (560000, 4374100)"},
      {"--terrain " + terrain + " --path " + quoted(malformed) + " --vehicle " + rover + common,
       "malformed.csv:3: expected 2 columns x,y, got 1"},
      {"--terrain " + terrain + " --path " + quoted(no_header) + " --vehicle " + rover + common,
       "no_header.csv:1: "},
      {"--terrain " + terrain + " --path " + path + " --vehicle " + quoted(unknown_key) + common,
       "unknown key 'wheel_count'"},
      {"--terrain " + terrain + " --path " + path + " --vehicle " + rover + " --stations 1" +
           common,
       "--stations must be at least 2, got 1"},
      {"--terrain " + terrain + " --path " + path + " --vehicle " + rover + " --stations 0" +
           common,
       "--stations"},
      {"--terrain " + terrain + " --path " + path + " --vehicle " + rover + " --smoothing -1" +
           common,
       "--smoothing"},
      {"--terrain " + quoted(voids) + " --path " + quoted(through_void) + " --vehicle " + rover +
           " --smoothing 1" + common,
       "path point 1 (10.5, 10.5)"},
      {"--terrain " + quoted(voids) + " --path " + quoted(through_void) + " --vehicle " + rover +
           common,
       "NODATA"},
      {"--terrain /nonexistent.asc --path " + path + " --vehicle " + rover + common,
       "/nonexistent.asc"},
      {"--terrain " + terrain + " --path " + path + common, "--vehicle"},
  };
  expect_bad_input("limits", cases, out);
}

TEST(CliLimits, HelpDocumentsTheContract) {
  const RunResult r = run_talus("limits --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Usage"), std::string::npos);
  EXPECT_NE(r.out.find("[100, 100000]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("s,x,y,z,v_min,v_max,binding,k_t,k_q,k_r,kappa_n,kappa_g"),
            std::string::npos);
}

}  // namespace
}  // namespace talus::cli_test
