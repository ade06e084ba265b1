// End-to-end tests of `talus baseline hait`: the path.csv / summary.json /
// path.png contract on flat ground (a straight path of known length), exit
// code 2 for an enclosed goal and an invalid start (summary still written),
// exit code 1 with one line on stderr for bad input, and --help; and the
// Iagnemma navigator's run through the same command.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace talus::cli_test {
namespace {

std::string chassis() {
  return data_file("robots/marsokhod_chassis.yaml");
}
std::string wheeled() {
  return data_file("robots/rover4_sprung.yaml");
}

/// 12 m x 12 m flat at 0.25 m.
std::string flat_map() {
  return generate_terrain("baseline_flat.asc",
                          "plane --slope 0 --ncols 49 --nrows 49 --cellsize 0.25");
}

/// 12 m x 12 m at 0.25 m: a closed ring of 20 steep hills (2 m, sigma 0.35 m)
/// of radius 3.5 m around (6, 6), flat inside and outside.
std::string ring_map() {
  std::ostringstream args;
  args << "gaussian-hills --ncols 49 --nrows 49 --cellsize 0.25";
  for (int k = 0; k < 20; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 20.0;
    args << " --hill " << 6.0 + 3.5 * std::cos(a) << "," << 6.0 + 3.5 * std::sin(a) << ",2,0.35";
  }
  return generate_terrain("baseline_ring.asc", args.str());
}

const std::vector<std::string> kSummaryKeys = {
    "status",          "message",
    "nodes_created",   "nodes_developed",
    "placements",      "preprocessing_seconds",
    "search_seconds",  "length_m",
    "control_changes", "control_changes_before_smoothing",
    "robot",           "options"};

/// Runs the command into a fresh `dir`, checks the exit code, the summary on
/// stdout equal to summary.json with every contract key, and path.csv's
/// header and row shape. Returns the summary.
nlohmann::json run_baseline(const std::string& args, const std::string& dir, int expected_exit,
                            std::vector<std::vector<std::string>>* rows = nullptr) {
  std::filesystem::remove_all(dir);
  const RunResult r = run_talus("baseline hait " + args + " --out " + quoted(dir));
  EXPECT_EQ(r.exit_code, expected_exit) << r.err << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const nlohmann::json j = parse_json(r.out, "stdout");
  EXPECT_EQ(j, parse_json(read_text(dir + "/summary.json"), "summary.json"));
  for (const std::string& key : kSummaryKeys) {
    EXPECT_TRUE(j.contains(key)) << key << " missing from " << j.dump();
  }
  const auto csv = read_csv(dir + "/path.csv", "x,y,theta,control");
  if (rows) *rows = csv;
  return j;
}

TEST(CliBaseline, StraightPathOnFlatGroundWritesTheContract) {
  const std::string terrain = flat_map();
  const std::string dir = scratch_file("baseline_flat");
  std::vector<std::vector<std::string>> rows;
  const nlohmann::json j =
      run_baseline("--terrain " + quoted(terrain) + " --robot " + quoted(chassis()) +
                       " --start 2,6,0 --goal 10,6,0 --heuristic euclidean",
                   dir, 0, &rows);
  EXPECT_EQ(j.value("status", ""), "found");
  EXPECT_NEAR(j.value("length_m", 0.0), 8.0, 1e-6);
  EXPECT_EQ(j.value("control_changes", -1), 0);
  EXPECT_GE(j.value("nodes_created", 0), j.value("nodes_developed", 0));
  EXPECT_GE(j.value("placements", 0), 1);
  EXPECT_EQ(j["robot"].value("kind", ""), "articulated_chassis");
  EXPECT_EQ(j["options"].value("heuristic", ""), "euclidean");
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows.front()[3], "none");
  EXPECT_DOUBLE_EQ(parse_number(rows.front()[0]), 2.0);
  EXPECT_DOUBLE_EQ(parse_number(rows.front()[1]), 6.0);
  EXPECT_NEAR(parse_number(rows.back()[0]), 10.0, 1e-9);
  EXPECT_NEAR(parse_number(rows.back()[1]), 6.0, 1e-9);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k][3], "forward") << k;
    EXPECT_NEAR(parse_number(rows[k][1]), 6.0, 1e-9) << k;
    EXPECT_NEAR(parse_number(rows[k][2]), 0.0, 1e-9) << k;
  }
  // gnuplot is a test dependency (scripts/setup.sh installs it): the figure must be there.
  EXPECT_TRUE(std::filesystem::exists(dir + "/path.png"));
}

TEST(CliBaseline, VehicleDrivesThePathAtItsTimeOptimalProfile) {
  // marsokhod_point_mass.yaml: top speed 2 m/s, drive and brake 1 m/s^2. On flat ground the
  // straight 8 m path takes 8 / 2 + 2 = 6 s from rest to rest (2 s to reach 2 m/s over 2 m, the
  // same to stop), up to the first-order discretisation when the switches fall between stations.
  const std::string terrain = flat_map();
  const std::string vehicle = data_file("vehicles/marsokhod_point_mass.yaml");
  const std::string dir = scratch_file("baseline_vehicle");
  const nlohmann::json j = run_baseline(
      "--terrain " + quoted(terrain) + " --robot " + quoted(chassis()) +
          " --start 2,6,0 --goal 10,6,0 --heuristic euclidean --vehicle " + quoted(vehicle),
      dir, 0);
  EXPECT_EQ(j.value("vehicle", ""), vehicle);
  EXPECT_EQ(j.value("profile_status", ""), "ok") << j.dump();
  EXPECT_EQ(j.value("profile_pieces", 0), 1);
  EXPECT_NEAR(j.value("profile_length_m", 0.0), 8.0, 1e-6);
  EXPECT_GE(j.value("profile_travel_time", 0.0), 6.0 - 1e-9);
  EXPECT_LE(j.value("profile_travel_time", 0.0), 6.05);
  // No path, no profile: the summary says so.
  const std::string ring = ring_map();
  const nlohmann::json none =
      run_baseline("--terrain " + quoted(ring) + " --robot " + quoted(wheeled()) +
                       " --start 1.5,1.5,0 --goal 6,6,0 --vehicle " + quoted(vehicle),
                   scratch_file("baseline_vehicle_none"), 2);
  EXPECT_EQ(none.value("profile_status", ""), "no_path");
  EXPECT_TRUE(none.at("profile_travel_time").is_null());
  // A bad vehicle file is bad input: exit 1, one line, before any planning.
  const RunResult bad = run_talus("baseline hait --terrain " + quoted(terrain) + " --robot " +
                                  quoted(chassis()) + " --start 2,6,0 --goal 10,6,0 --vehicle " +
                                  quoted(scratch_file("no_such_vehicle.yaml")) + " --out " +
                                  quoted(scratch_file("baseline_vehicle_bad")));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.err.rfind("talus: error: ", 0), 0u) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(scratch_file("baseline_vehicle_bad") + "/summary.json"));
}

TEST(CliBaseline, SmoothingAndUncertaintyOptionsReachTheSummary) {
  const std::string terrain = flat_map();
  const std::string dir = scratch_file("baseline_options");
  const nlohmann::json j =
      run_baseline("--terrain " + quoted(terrain) + " --robot " + quoted(wheeled()) +
                       " --start 2,3,0 --goal 10,9,1.5707963 --smooth --terrain-uncertainty 0.02 "
                       "--position-uncertainty 0.1,0.2",
                   dir, 0);
  EXPECT_EQ(j.value("status", ""), "found") << j.dump();
  EXPECT_EQ(j["robot"].value("kind", ""), "wheeled");
  EXPECT_TRUE(j["options"].value("smooth", false));
  EXPECT_DOUBLE_EQ(j["options"].value("terrain_uncertainty", 0.0), 0.02);
  EXPECT_DOUBLE_EQ(j["options"].value("position_uncertainty", 0.0), 0.1);
  EXPECT_DOUBLE_EQ(j["options"].value("heading_uncertainty", 0.0), 0.2);
  // Smoothing never adds control changes.
  EXPECT_LE(j.value("control_changes", 1000), j.value("control_changes_before_smoothing", 0));
  // The path is at least the straight-line distance.
  EXPECT_GE(j.value("length_m", 0.0), std::hypot(8.0, 6.0) - 1e-9);
}

TEST(CliBaseline, EnclosedGoalExitsTwoWithTheSummary) {
  const std::string terrain = ring_map();
  const std::string dir = scratch_file("baseline_ring");
  const std::string args = "--terrain " + quoted(terrain) + " --robot " + quoted(wheeled()) +
                           " --start 1.5,1.5,0 --goal 6,6,0";
  // Euclidean guidance explores every reachable cell before giving up.
  std::vector<std::vector<std::string>> rows;
  const nlohmann::json e = run_baseline(args + " --heuristic euclidean", dir, 2, &rows);
  EXPECT_EQ(e.value("status", ""), "no_path") << e.dump();
  EXPECT_TRUE(e["length_m"].is_null());
  EXPECT_GT(e.value("nodes_created", 0), 1000);
  EXPECT_TRUE(rows.empty());
  EXPECT_FALSE(std::filesystem::exists(dir + "/path.png"));
  // The potential bitmap already knows the start cannot reach the goal.
  const nlohmann::json p = run_baseline(args, dir, 2);
  EXPECT_EQ(p.value("status", ""), "no_path") << p.dump();
}

TEST(CliBaseline, InvalidStartExitsTwoWithTheSummary) {
  const std::string terrain = ring_map();
  const std::string dir = scratch_file("baseline_invalid_start");
  // On a hill's flank, across the slope: far beyond the roll limit.
  const nlohmann::json j =
      run_baseline("--terrain " + quoted(terrain) + " --robot " + quoted(wheeled()) +
                       " --start 9.2,6,1.5707963 " + "--goal 1.5,1.5,0",
                   dir, 2);
  EXPECT_EQ(j.value("status", ""), "start_invalid") << j.dump();
  EXPECT_NE(j.value("message", "").find("start"), std::string::npos);
}

TEST(CliBaseline, BadInputExitsOneWithOneLine) {
  const std::string terrain = flat_map();
  const std::string bad_robot = scratch_file("bad_robot.yaml");
  write_text(bad_robot, "type: wheeled\nwheels: [[0.5, 0.4], [0.5, -0.4]]\ncg_height: 0.4\n");
  const std::string dir = scratch_file("baseline_bad");
  std::filesystem::remove_all(dir);
  const std::string base = "--terrain " + quoted(terrain) + " --robot " + quoted(chassis());
  const std::string ok_ends = " --start 2,6,0 --goal 10,6,0";
  const std::string out = " --out " + quoted(dir);
  expect_bad_input(
      "baseline hait",
      {{base + " --start 2,6 --goal 10,6,0" + out, "--start must be X,Y,THETA"},
       {base + " --start 2,6,x --goal 10,6,0" + out, "--start must be X,Y,THETA"},
       {base + " --start 2,6,0 --goal 10,6,0,1" + out, "--goal must be X,Y,THETA"},
       {base + " --start 2,6,0 --goal 30,6,0" + out, "off the terrain"},
       {base + ok_ends + " --heuristic dijkstra" + out, "--heuristic"},
       {base + ok_ends + " --position-uncertainty 0.3" + out, "--position-uncertainty"},
       {base + ok_ends + " --position-uncertainty 0.3,4" + out, "--position-uncertainty"},
       {base + ok_ends + " --terrain-uncertainty -1" + out, "--terrain-uncertainty"},
       {"--terrain " + quoted(scratch_file("missing.asc")) + " --robot " + quoted(chassis()) +
            ok_ends + out,
        "missing.asc"},
       {"--terrain " + quoted(terrain) + " --robot " + quoted(scratch_file("missing.yaml")) +
            ok_ends + out,
        "missing.yaml"},
       {"--terrain " + quoted(terrain) + " --robot " + quoted(bad_robot) + ok_ends + out,
        "bad_robot.yaml"}},
      dir + "/summary.json");
}

// The Iagnemma navigator through the same command (its options from the
// registry): the path is the driven path, from the start to within the
// waypoint radius of the goal.
TEST(CliBaseline, IagnemmaDrivesToTheGoalAndWritesTheContract) {
  const std::string terrain = flat_map();
  const std::string dir = scratch_file("baseline_iagnemma");
  std::filesystem::remove_all(dir);
  const RunResult r = run_talus("baseline iagnemma --terrain " + quoted(terrain) + " --robot " +
                                quoted(data_file("vehicles/iagnemma_ugv.yaml")) +
                                " --start 2,6,0 --goal 10,6,0 --out " + quoted(dir));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = parse_json(r.out, "stdout");
  EXPECT_EQ(j, parse_json(read_text(dir + "/summary.json"), "summary.json"));
  EXPECT_EQ(j.value("baseline", ""), "iagnemma");
  EXPECT_EQ(j.value("status", ""), "found");
  EXPECT_GT(j.value("control_ticks", 0), 0);
  EXPECT_EQ(j.value("vehicle_failed", true), false);
  EXPECT_EQ(j["robot"].value("kind", ""), "vehicle");
  EXPECT_EQ(j["options"].value("lookahead", false), true);
  const auto rows = read_csv(dir + "/path.csv", "x,y,theta,control");
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(j.value("path_points", 0u), rows.size());
  EXPECT_DOUBLE_EQ(parse_number(rows.front()[0]), 2.0);
  EXPECT_DOUBLE_EQ(parse_number(rows.front()[1]), 6.0);
  EXPECT_LE(std::hypot(parse_number(rows.back()[0]) - 10.0, parse_number(rows.back()[1]) - 6.0),
            0.2);
  const RunResult help = run_talus("baseline iagnemma --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* fragment : {"--robot", "--lookahead", "--route-clearance", "--waypoint-radius",
                               "--sensor-radius", "--speed", "--budget", "control ticks"}) {
    EXPECT_NE(help.out.find(fragment), std::string::npos) << fragment << " not in --help";
  }
}

TEST(CliBaseline, HelpDocumentsTheOptions) {
  const RunResult r = run_talus("baseline hait --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* fragment :
       {"--terrain", "--robot", "--start", "--goal", "--heuristic", "euclidean", "potential-rs",
        "--smooth", "--terrain-uncertainty", "--position-uncertainty", "--out", "radians",
        "path.csv", "summary.json", "x,y,theta,control", "Exit code"}) {
    EXPECT_NE(r.out.find(fragment), std::string::npos) << fragment << " not in --help";
  }
  const RunResult b = run_talus("baseline --help");
  EXPECT_EQ(b.exit_code, 0);
  EXPECT_NE(b.out.find("hait"), std::string::npos);
  EXPECT_NE(b.out.find("iagnemma"), std::string::npos);
  EXPECT_NE(b.out.find("talus"), std::string::npos);  // Talus's own planner, registered beside
}

// Each planner's --help documents its own outputs only (issue #40): the octree files under
// dacre-wright, the foot plan under eldershaw-yim, neither under the others.
TEST(CliBaseline, HelpDocumentsEachPlannersOwnOutputsOnly) {
  const std::map<std::string, std::vector<std::string>> own = {
      {"dacre-wright", {"voxels.csv", "channel.csv", "octree.png"}},
      {"eldershaw-yim", {"prm_points.csv", "steps.csv", "cgmap.png"}},
      {"hait", {}},
      {"iagnemma", {}},
      {"talus", {}}};
  for (const auto& [name, files] : own) {
    const RunResult r = run_talus("baseline " + name + " --help");
    ASSERT_EQ(r.exit_code, 0) << name;
    EXPECT_NE(r.out.find("path.csv"), std::string::npos) << name;
    EXPECT_NE(r.out.find("Exit code"), std::string::npos) << name;
    for (const auto& [other, other_files] : own)
      for (const std::string& file : other_files)
        EXPECT_EQ(r.out.find(file) != std::string::npos, other == name) << name << ": " << file;
  }
}

}  // namespace
}  // namespace talus::cli_test
