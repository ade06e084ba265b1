// End-to-end tests of `talus profile`: the CSV and JSON contracts on the
// bundled examples, analytic travel times on generated flat terrain, the
// infeasible outcome (exit code 2, JSON on stdout) and input errors (exit 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "profile_csv_test_support.hpp"

namespace talus::cli_test {
namespace {

/// Relative tolerance for travel times on flat straight paths of `stations` stations: the discrete
/// profile is exact except in the step straddling the switch, whose relative error is at most
/// (spacing / length)^2 = 1 / (stations - 1)^2 (1e-6 over 100 m at 0.1 m; a 1e-3 error in g or mu
/// moves the time by 5e-4).
double switch_step_tolerance(std::size_t stations) {
  const double steps = static_cast<double>(stations - 1);
  return 1.0 / (steps * steps);
}

const std::string kProfileExampleArgs =
    "--terrain " + quoted(data_file("terrain/west_bijou_escarpment_nasadem25m.asc")) + " --path " +
    quoted(data_file("paths/west_bijou_traverse.csv"));

/// Runs a profile command that must succeed and returns its JSON summary.
nlohmann::json run_profile_ok(const std::string& args) {
  const RunResult r = run_talus("profile " + args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  return parse_json(r.out, "stdout");
}

/// The keys every summary has, ok or infeasible.
void expect_profile_keys(const nlohmann::json& j) {
  for (const char* key :
       {"status", "travel_time", "stations", "switching_points", "solve_seconds", "message",
        "infeasible_station", "infeasible_s", "infeasible_binding", "length_m", "limits_seconds",
        "merged_stations", "start_speed", "end_speed", "seconds"}) {
    EXPECT_TRUE(j.contains(key)) << key << " missing from " << j.dump();
  }
}

/// The checks of a profile run whose path is infeasible: exit code 2, nothing
/// on stderr, the JSON summary on stdout. Returns the summary.
nlohmann::json expect_infeasible(const RunResult& r) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const nlohmann::json j = parse_json(r.out, "stdout");
  expect_profile_keys(j);
  EXPECT_EQ(j.at("status"), "infeasible");
  EXPECT_TRUE(j.at("travel_time").is_null());
  return j;
}

/// The checks every feasible profile CSV must pass, against its JSON summary.
void expect_consistent_profile(const std::vector<ProfileRow>& rows, const nlohmann::json& j) {
  static const std::set<std::string> kControls = {"accelerate", "decelerate", "limit"};
  expect_profile_keys(j);
  ASSERT_EQ(j.at("status"), "ok") << j.dump();
  ASSERT_EQ(rows.size(), j.at("stations").get<std::size_t>());
  expect_consistent_rows(rows, j.at("travel_time").get<double>(), j.at("length_m").get<double>(),
                         j.at("start_speed").get<double>(), j.at("end_speed").get<double>());
  EXPECT_EQ(j.at("merged_stations"), 0);
  EXPECT_TRUE(j.at("message").is_null());
  EXPECT_TRUE(j.at("infeasible_station").is_null());
  // The limits and the solve are parts of the run: together no longer than it.
  EXPECT_LE(j.at("limits_seconds").get<double>() + j.at("solve_seconds").get<double>(),
            j.at("seconds").get<double>());
  ASSERT_TRUE(j.at("switching_points").is_array());
  double previous_s = -1.0;
  for (const nlohmann::json& p : j.at("switching_points")) {
    const std::size_t station = p.at("station").get<std::size_t>();
    ASSERT_LT(station, rows.size());
    EXPECT_DOUBLE_EQ(p.at("s").get<double>(), rows[station].s);
    EXPECT_GT(p.at("s").get<double>(), previous_s);
    previous_s = p.at("s").get<double>();
    EXPECT_TRUE(kControls.count(p.at("from").get<std::string>())) << p.dump();
    EXPECT_TRUE(kControls.count(p.at("to").get<std::string>())) << p.dump();
    EXPECT_NE(p.at("from"), p.at("to"));
  }
}

/// The default station spacing h as `talus profile --help` states it, in
/// "ceil(length_m / h) + 1".
double documented_station_spacing() {
  const RunResult r = run_talus("profile --help");
  const std::string prefix = "ceil(length_m / ";
  const std::size_t at = r.out.find(prefix);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no `" << prefix << "` in the help:\n" << r.out;
    return 0.5;
  }
  const double spacing = std::strtod(r.out.c_str() + at + prefix.size(), nullptr);
  EXPECT_GT(spacing, 0.0);
  EXPECT_LE(spacing, 1.0);
  return spacing;
}

/// The documented default station count for a path of 3-D length `length`.
std::size_t expected_default_stations(double length) {
  const double n = std::ceil(length / documented_station_spacing()) + 1.0;
  return static_cast<std::size_t>(std::clamp(n, 100.0, 1e6));
}

TEST(CliProfile, ExampleFilesGiveTheDocumentedCsvAndJson) {
  const std::string out = scratch_file("example.csv");
  const nlohmann::json j =
      run_profile_ok(kProfileExampleArgs + " --vehicle " +
                     quoted(data_file("vehicles/rover.yaml")) + " -o " + quoted(out));
  const std::vector<ProfileRow> rows = read_profile_csv(out);
  expect_consistent_profile(rows, j);
  // Default stations: ceil(3-D length / spacing) + 1.
  const double length = j.at("length_m").get<double>();
  EXPECT_EQ(j.at("stations").get<std::size_t>(), expected_default_stations(length));
  EXPECT_GT(j.at("stations").get<std::size_t>(), 100u);
  EXPECT_GT(length, 2700.0);
  // From rest to rest: 2.7 km mostly at the rover's 15 m/s top speed, slower
  // through the switchback.
  const double travel_time = j.at("travel_time").get<double>();
  EXPECT_GT(travel_time, length / 15.0);
  EXPECT_LT(travel_time, 1.2 * length / 15.0);
  EXPECT_EQ(rows.front().v, 0.0);
  EXPECT_EQ(rows.back().v, 0.0);
  EXPECT_NEAR(j.at("peak_speed").get<double>(), 15.0, 1e-9);
  EXPECT_GE(j.at("switching_points").size(), 2u);
  bool slowed_by_sliding = false;
  for (const ProfileRow& r : rows) {
    EXPECT_LE(r.v_max, 15.0 * (1 + 1e-12));
    if (r.binding == "sliding" && r.v_max < 14.0 && r.v > 0.9 * r.v_max) slowed_by_sliding = true;
  }
  EXPECT_TRUE(slowed_by_sliding);
  EXPECT_NEAR(rows.front().x, 556810.0, 1e-6);
  EXPECT_NEAR(rows.back().y, 4374160.0, 1e-6);
}

TEST(CliProfile, StationsSmoothingRigidBodyAndStartEndSpeeds) {
  const std::string out = scratch_file("rigid.csv");
  const nlohmann::json j = run_profile_ok(
      kProfileExampleArgs + " --vehicle " + quoted(data_file("vehicles/rover_rigid.yaml")) +
      " --stations 300 --smoothing 1 --v0 5 --v1 2.5 -o " + quoted(out));
  EXPECT_EQ(j.at("stations"), 300);
  EXPECT_EQ(j.at("fit"), "smoothing");
  const std::vector<ProfileRow> rows = read_profile_csv(out);
  EXPECT_EQ(rows.size(), 300u);
  expect_consistent_profile(rows, j);
  EXPECT_NEAR(rows.front().v, 5.0, 1e-12);
  EXPECT_NEAR(rows.back().v, 2.5, 1e-9);
}

TEST(CliProfile, StraightPathOnFlatGroundFromRestToRestTakesTwoSqrtLOverMuG) {
  const double mu = 0.7, g = 9.81, length = 100.0;
  const std::string out = scratch_file("straight_profile.csv");
  const nlohmann::json j = run_profile_ok(
      "--terrain " + quoted(flat_terrain()) + " --path " +
      quoted(write_points("straight.csv", {{{10, 60}}, {{110, 60}}})) + " --vehicle " +
      quoted(point_mass_vehicle("unlimited.yaml", mu)) + " -o " + quoted(out));
  const std::vector<ProfileRow> rows = read_profile_csv(out);
  expect_consistent_profile(rows, j);
  EXPECT_EQ(j.at("stations").get<std::size_t>(), expected_default_stations(length));
  EXPECT_NEAR(j.at("length_m").get<double>(), length, 1e-9);
  const double expected = 2.0 * std::sqrt(length / (mu * g));
  EXPECT_NEAR(j.at("travel_time").get<double>(), expected,
              switch_step_tolerance(j.at("stations").get<std::size_t>()) * expected);
  EXPECT_NEAR(
      j.at("peak_speed").get<double>(), std::sqrt(mu * g * length),
      switch_step_tolerance(j.at("stations").get<std::size_t>()) * std::sqrt(mu * g * length));
  // Bang-bang: full friction forwards, then full friction backwards, once.
  ASSERT_EQ(j.at("switching_points").size(), 1u) << j.dump();
  EXPECT_EQ(j.at("switching_points")[0].at("from"), "accelerate");
  EXPECT_EQ(j.at("switching_points")[0].at("to"), "decelerate");
  EXPECT_NEAR(j.at("switching_points")[0].at("s").get<double>(), length / 2, 1.0);
  EXPECT_NEAR(rows.front().a, mu * g, 1e-9);
  EXPECT_NEAR(rows.back().a, -mu * g, 1e-9);
  // Nothing limits the speed on a straight flat path: v_max is written `inf`.
  const std::string text = read_text(out);
  EXPECT_NE(text.find(",inf,none\n"), std::string::npos) << text.substr(0, 300);
}

TEST(CliProfile, StartAndEndSpeedsOnFlatGroundMatchTheBangBangTime) {
  const double mu = 0.7, g = 9.81, length = 100.0, v0 = 5.0, v1 = 3.0;
  const std::string out = scratch_file("speeds_profile.csv");
  const nlohmann::json j = run_profile_ok(
      "--terrain " + quoted(flat_terrain()) + " --path " +
      quoted(write_points("speeds.csv", {{{10, 60}}, {{110, 60}}})) + " --vehicle " +
      quoted(point_mass_vehicle("unlimited.yaml", mu)) + " --v0 5 --v1 3 -o " + quoted(out));
  expect_consistent_profile(read_profile_csv(out), j);
  const double a = mu * g;
  const double peak = std::sqrt((2.0 * a * length + v0 * v0 + v1 * v1) / 2.0);
  const double expected = (peak - v0) / a + (peak - v1) / a;
  EXPECT_NEAR(j.at("travel_time").get<double>(), expected,
              switch_step_tolerance(j.at("stations").get<std::size_t>()) * expected);
  EXPECT_EQ(j.at("start_speed"), 5.0);
  EXPECT_EQ(j.at("end_speed"), 3.0);
}

TEST(CliProfile, SideSlopeSteeperThanFrictionIsInfeasibleWithExitCodeTwo) {
  // 0.8 rad slope rising to the north: tan(0.8) = 1.03 > mu = 0.6 (< b/h = 1.2).
  const std::string terrain = scratch_file("side_slope.asc");
  const RunResult g = run_talus(
      "terrain generate plane --slope 0.8 --aspect 1.5707963267948966 --ncols 41 --nrows 41 "
      "-o " +
      quoted(terrain));
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const std::string path = write_points("east.csv", {{{5, 20}}, {{35, 20}}});
  const std::string vehicle = point_mass_vehicle("mu06.yaml", 0.6);
  const std::string args =
      "--terrain " + quoted(terrain) + " --path " + quoted(path) + " --vehicle " + quoted(vehicle);

  // talus limits agrees that no station can be passed at any speed.
  const RunResult limits =
      run_talus("limits " + args + " -o " + quoted(scratch_file("side_limits.csv")));
  ASSERT_EQ(limits.exit_code, 0) << limits.err;
  const nlohmann::json lj = parse_json(limits.out, "stdout");
  EXPECT_EQ(lj.at("untraversable_stations"), lj.at("stations"));

  const std::string out = scratch_file("side_profile.csv");
  std::filesystem::remove(out);
  const nlohmann::json j = expect_infeasible(run_talus("profile " + args + " -o " + quoted(out)));
  EXPECT_FALSE(j.at("message").get<std::string>().empty());
  EXPECT_EQ(j.at("infeasible_binding"), "sliding");
  EXPECT_EQ(j.at("infeasible_station"), 0);
  EXPECT_EQ(j.at("infeasible_s"), 0.0);
  const std::size_t stations = j.at("stations").get<std::size_t>();
  EXPECT_EQ(stations, expected_default_stations(30.0));
  EXPECT_TRUE(j.at("switching_points").empty());
  // The CSV is still written: limits as usual, no motion.
  const std::vector<ProfileRow> rows = read_profile_csv(out);
  ASSERT_EQ(rows.size(), stations);
  for (const ProfileRow& row : rows) {
    EXPECT_EQ(row.v, 0.0);
    EXPECT_EQ(row.a, 0.0);
    EXPECT_TRUE(std::isinf(row.t));
    EXPECT_EQ(row.v_max, 0.0);
    EXPECT_EQ(row.binding, "sliding");
  }
  EXPECT_NEAR(rows.back().s, 30.0, 1e-9);
}

TEST(CliProfile, StartSpeedThatCannotBeBrakedInTimeIsInfeasible) {
  // mu = 0.1: stopping from the 10 m/s top speed takes 100 / (2 * 0.981) = 51 m > 20 m.
  const std::string args = "--terrain " + quoted(flat_terrain()) + " --path " +
                           quoted(write_points("short.csv", {{{10, 10}}, {{30, 10}}})) +
                           " --vehicle " + quoted(point_mass_vehicle("slippery.yaml", 0.1, 10.0)) +
                           " -o " + quoted(scratch_file("short_profile.csv"));
  const nlohmann::json j = expect_infeasible(run_talus("profile " + args + " --v0 10"));
  EXPECT_EQ(j.at("infeasible_station"), 0);
  EXPECT_NE(j.at("message").get<std::string>().find("start speed"), std::string::npos)
      << j.at("message");
  // From 5 m/s the vehicle stops in 12.7 m: feasible.
  const nlohmann::json ok = run_profile_ok(args + " --v0 5");
  EXPECT_EQ(ok.at("status"), "ok");
  EXPECT_EQ(ok.at("stations").get<std::size_t>(), expected_default_stations(20.0));
}

TEST(CliProfile, DefaultStationCountIsClampedBelowAt100) {
  const std::string out = scratch_file("tiny_profile.csv");
  const nlohmann::json j =
      run_profile_ok("--terrain " + quoted(flat_terrain()) + " --path " +
                     quoted(write_points("tiny.csv", {{{10, 10}}, {{14, 13}}})) + " --vehicle " +
                     quoted(point_mass_vehicle("unlimited.yaml", 0.7)) + " -o " + quoted(out));
  ASSERT_GT(documented_station_spacing(), 0.06);  // so that ceil(5 m / h) + 1 < 100
  EXPECT_EQ(j.at("stations"), 100);
  EXPECT_EQ(read_profile_csv(out).size(), 100u);
  const double expected = 2.0 * std::sqrt(5.0 / (0.7 * 9.81));
  EXPECT_NEAR(j.at("travel_time").get<double>(), expected,
              switch_step_tolerance(j.at("stations").get<std::size_t>()) * expected);
}

TEST(CliProfile, BadInputGivesOneLineOnStderrAndExitCodeOne) {
  const std::string rover = quoted(data_file("vehicles/rover.yaml"));
  const std::string out = scratch_file("never_written.csv");
  std::filesystem::remove(out);
  const std::string common = " -o " + quoted(out);
  const std::vector<ErrorCase> cases = {
      {kProfileExampleArgs + common, "--vehicle"},
      {kProfileExampleArgs + " --vehicle " + rover + " --v0 20" + common,
       "start speed 20 m/s is above the speed limit 15 m/s (max_speed)"},
      {kProfileExampleArgs + " --vehicle " + rover + " --v1 15.5" + common,
       "end speed 15.5 m/s is above the speed limit"},
      {kProfileExampleArgs + " --vehicle " + rover + " --v0 -1" + common, "--v0"},
      {kProfileExampleArgs + " --vehicle " + rover + " --v1 nan" + common, "--v1"},
      {kProfileExampleArgs + " --vehicle " + rover + " --stations 1" + common,
       "--stations must be at least 2, got 1"},
      {kProfileExampleArgs + " --vehicle " + rover + " --smoothing 0" + common, "--smoothing"},
      {"--terrain /nonexistent.asc --path " + quoted(data_file("paths/west_bijou_traverse.csv")) +
           " --vehicle " + rover + common,
       "/nonexistent.asc"},
      {kProfileExampleArgs + " --vehicle " + rover, "--output"},
  };
  expect_bad_input("profile", cases, out);
}

TEST(CliProfile, HelpDocumentsTheContract) {
  const RunResult r = run_talus("profile --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* fragment :
       {"Usage", "s,x,y,z,v,a,t,v_max,binding", "[100, 1000000]", "3-D length", "--v0", "--v1",
        "Exit code 0", "2 when", "infeasible", "switching_points", "solve_seconds"}) {
    EXPECT_NE(r.out.find(fragment), std::string::npos) << fragment << " not in " << r.out;
  }
}

}  // namespace
}  // namespace talus::cli_test
