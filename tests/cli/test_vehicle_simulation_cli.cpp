// End-to-end tests of `talus simulate`: a trajectory planned by `talus plan`
// with the paper's UGV is driven to the goal within the plan's time; a
// trajectory too fast for its curvature ends in a side-slip failure (exit
// code 2, outputs written); bad input is one error line and exit code 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>

#include "cli_test_support.hpp"

namespace talus::cli_test {
namespace {

const std::string kUgv = data_file("vehicles/iagnemma_ugv.yaml");

std::string flat_field() {
  return generate_terrain("sim_flat.asc", "plane --slope 0 --ncols 61 --nrows 41 --cellsize 0.25");
}

TEST(CliSimulate, DrivesAPlannedTrajectoryToTheGoal) {
  const std::string terrain = flat_field();
  const std::string plan_dir = scratch_file("sim_plan");
  const RunResult planned =
      run_talus("plan --terrain " + quoted(terrain) + " --start 1,5 --goal 14,4 --vehicle " +
                quoted(kUgv) + " --no-figures --out " + quoted(plan_dir));
  ASSERT_EQ(planned.exit_code, 0) << planned.err;
  const nlohmann::json plan = parse_json(read_text(plan_dir + "/summary.json"), "plan summary");
  const double plan_time = plan.value("travel_time", 0.0);
  ASSERT_GT(plan_time, 0.0);

  const std::string out = scratch_file("sim_out");
  const RunResult r =
      run_talus("simulate --terrain " + quoted(terrain) + " --vehicle " + quoted(kUgv) +
                " --trajectory " + quoted(plan_dir + "/trajectory.csv") + " --out " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json s = parse_json(read_text(out + "/summary.json"), "summary");
  EXPECT_EQ(s, parse_json(r.out, "stdout"));
  EXPECT_EQ(s.value("status", ""), "reached_goal");
  EXPECT_TRUE(s["failure"].is_null());
  EXPECT_GT(s.value("progress", 0.0), 0.97);
  // The rest-to-rest plan at the drive and brake limits: the PI loop lags
  // it a little. planned_time is the polyline's at the planned speeds with
  // the 0.3 m/s floor at the two rests, a little below the plan's.
  EXPECT_LT(s.value("planned_time", 0.0), plan_time);
  EXPECT_NEAR(s.value("planned_time", 0.0), plan_time, 0.05 * plan_time);
  EXPECT_NEAR(s.value("travel_time", 0.0), plan_time, 0.15 * plan_time);
  const nlohmann::json& m = s["margins"];
  EXPECT_GT(m.value("min_normal_load", 0.0), 0.0);
  EXPECT_LT(m.value("peak_lateral_load_ratio", 1.0), 0.1);  // a straight line
  EXPECT_LT(s["tracking"].value("max_cross_track", 1.0), 0.05);
  EXPECT_GT(s["solver"].value("steps", 0), 0);
  const auto rows = read_csv(out + "/trace.csv",
                             "t,x,y,z,roll,pitch,yaw,speed,desired_speed,steering,drive_force,s,"
                             "cross_track,lateral_load_ratio,side_slip,min_normal_load,"
                             "max_slip_angle");
  ASSERT_GT(rows.size(), 10u);
  EXPECT_EQ(parse_number(rows.front()[0]), 0.0);
  EXPECT_NEAR(parse_number(rows.back()[0]), s.value("travel_time", 0.0), 1e-9);
  EXPECT_NEAR(parse_number(rows.back()[1]), 14.0, 0.5);
  EXPECT_NEAR(parse_number(rows.back()[2]), 4.0, 0.1);
}

TEST(CliSimulate, ATrajectoryTooFastForItsCurveSlides) {
  const std::string terrain = flat_field();
  // Half a circle of radius 2 m at 5 m/s: v^2 / R = 12.5 > mu g = 6.9.
  std::ostringstream csv;
  csv.precision(17);
  csv << "x,y,v\n";
  for (int i = 0; i <= 60; ++i) {
    const double a = -0.5 * std::numbers::pi + std::numbers::pi * i / 60.0;
    csv << 6.0 + 2.0 * std::cos(a) << "," << 5.0 + 2.0 * std::sin(a) << ",5\n";
  }
  const std::string trajectory = scratch_file("sim_fast.csv");
  write_text(trajectory, csv.str());
  const std::string out = scratch_file("sim_fast_out");
  const RunResult r =
      run_talus("simulate --terrain " + quoted(terrain) + " --vehicle " + quoted(kUgv) +
                " --trajectory " + quoted(trajectory) + " --out " + quoted(out));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const nlohmann::json s = parse_json(read_text(out + "/summary.json"), "summary");
  EXPECT_EQ(s.value("status", ""), "side_slip");
  EXPECT_EQ(s.value("failure", ""), "side_slip");
  EXPECT_LT(s.value("progress", 1.0), 1.0);
  EXPECT_GT(s["margins"].value("peak_side_slip", 0.0), 0.4);
  EXPECT_TRUE(std::filesystem::exists(out + "/trace.csv"));
}

TEST(CliSimulate, BadInputIsOneErrorLine) {
  const std::string terrain = flat_field();
  const std::string good = scratch_file("sim_good.csv");
  write_text(good, "x,y,v\n1,5,1\n5,5,1\n");
  const std::string no_v = scratch_file("sim_no_v.csv");
  write_text(no_v, "x,y\n1,5\n5,5\n");
  const std::string bad_number = scratch_file("sim_bad_number.csv");
  write_text(bad_number, "x,y,v\n1,5,1\n5,oops,1\n");
  const std::string off = scratch_file("sim_off.csv");
  write_text(off, "x,y,v\n1,5,1\n50,5,1\n");
  const std::string rover = data_file("vehicles/rover.yaml");
  const std::string out = scratch_file("sim_never");
  const std::string base = "--terrain " + quoted(terrain) + " --out " + quoted(out);
  expect_bad_input(
      "simulate",
      {{base + " --vehicle " + quoted(kUgv) + " --trajectory " + quoted(no_v),
        "must name the columns x, y and v"},
       {base + " --vehicle " + quoted(kUgv) + " --trajectory " + quoted(bad_number),
        ":3: column y must be a finite number"},
       {base + " --vehicle " + quoted(kUgv) + " --trajectory " + quoted(off), "off the terrain"},
       {base + " --vehicle " + quoted(rover) + " --trajectory " + quoted(good),
        "needs the vehicle's body"},
       {base + " --vehicle " + quoted(kUgv) + " --trajectory " + quoted(good) + " --speed-scale 0",
        "--speed-scale must be a positive number"}},
      out);
}

// `talus navigate`: the layered scheme on a flat field, plan on every 4th
// node, navigation to the goal with the lookahead; files and columns as documented.
TEST(CliNavigate, PlansCoarseAndNavigatesFineToTheGoal) {
  const std::string terrain = flat_field();
  const std::string out = scratch_file("nav_out");
  const RunResult r = run_talus("navigate --terrain " + quoted(terrain) + " --vehicle " +
                                quoted(kUgv) + " --start 1,5 --goal 14,4 --out " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json s = parse_json(read_text(out + "/summary.json"), "summary");
  EXPECT_EQ(s.value("status", ""), "reached");
  EXPECT_TRUE(s["failure"].is_null());
  EXPECT_TRUE(s.value("lookahead", false));
  EXPECT_EQ(s.value("coarse_factor", 0), 4);
  const double navigation = s.value("navigation_time", 0.0), optimal = s.value("optimal_time", 0.0);
  EXPECT_GT(optimal, 13.0 / 6.0);  // at least the distance at the top speed
  EXPECT_NEAR(s.value("time_increase", 0.0), navigation / optimal - 1.0, 1e-9);
  std::istringstream trace(read_text(out + "/trace.csv"));
  std::string header, row;
  std::getline(trace, header);
  EXPECT_EQ(header, "t,x,y,z,roll,pitch,yaw,v,kappa,slip_angle,desired_v,lookahead_cap");
  std::size_t rows = 0;
  while (std::getline(trace, row)) ++rows;
  EXPECT_GT(rows, static_cast<std::size_t>(navigation / 0.02) - 2);
  EXPECT_EQ(read_text(out + "/waypoints.csv").rfind("x,y,v\n", 0), 0u);
  // The paper's figures 7-9, each listed in the summary and drawn from its data file: the
  // map's driven path has one row per trace sample.
  for (const char* figure : {"map", "speed", "angles"}) {
    const std::string png = out + "/navigation_" + figure + ".png";
    EXPECT_TRUE(std::filesystem::exists(png)) << png;
    EXPECT_EQ(s["files"].value(std::string("figure_") + figure, ""), png);
  }
  const std::string map = read_text(out + "/navigation_map.dat");
  const std::size_t path_block = map.find("\n\n\n") + 3;
  const std::string path = map.substr(path_block, map.find("\n\n\n", path_block) - path_block);
  EXPECT_EQ(static_cast<std::size_t>(std::count(path.begin(), path.end(), '\n')) + 1, rows);

  const std::string standard = scratch_file("nav_standard");
  const RunResult without =
      run_talus("navigate --terrain " + quoted(terrain) + " --vehicle " + quoted(kUgv) +
                " --start 1,5 --goal 14,4 --no-lookahead " + "--out " + quoted(standard));
  ASSERT_EQ(without.exit_code, 0) << without.err;
  const nlohmann::json w = parse_json(read_text(standard + "/summary.json"), "summary");
  EXPECT_FALSE(w.value("lookahead", true));
  EXPECT_EQ(w.value("lookahead_caps_applied", 1), 0);

  const std::string bare = scratch_file("nav_no_figures");
  ASSERT_EQ(run_talus("navigate --terrain " + quoted(terrain) + " --vehicle " + quoted(kUgv) +
                      " --start 1,5 --goal 14,4 --no-figures --out " + quoted(bare))
                .exit_code,
            0);
  EXPECT_FALSE(std::filesystem::exists(bare + "/navigation_map.png"));
  EXPECT_FALSE(
      parse_json(read_text(bare + "/summary.json"), "summary")["files"].contains("figure_map"));
  EXPECT_FALSE(s.value("detect_hazards", true));

  // --detect-hazards: flat ground has none to see, so the run is the one without it.
  const std::string sensing = scratch_file("nav_detect");
  ASSERT_EQ(
      run_talus("navigate --terrain " + quoted(terrain) + " --vehicle " + quoted(kUgv) +
                " --start 1,5 --goal 14,4 --no-figures --detect-hazards --out " + quoted(sensing))
          .exit_code,
      0);
  const nlohmann::json d = parse_json(read_text(sensing + "/summary.json"), "summary");
  EXPECT_TRUE(d.value("detect_hazards", false));
  EXPECT_EQ(d.value("navigation_time", 0.0), navigation);
}

TEST(CliNavigate, BadInputIsOneErrorLine) {
  const std::string terrain = flat_field();
  const std::string rover = data_file("vehicles/rover.yaml");
  const std::string out = scratch_file("nav_never");
  const std::string base = "--terrain " + quoted(terrain) + " --out " + quoted(out);
  expect_bad_input(
      "navigate",
      {{base + " --vehicle " + quoted(rover) + " --start 1,5 --goal 14,4", "needs its body"},
       {base + " --vehicle " + quoted(kUgv) + " --start 1,5 --goal 50,4", "off the terrain"},
       {base + " --vehicle " + quoted(kUgv) + " --start 1,5 --goal 14,4 --coarse-factor 0",
        "--coarse-factor must be >= 1"},
       {base + " --vehicle " + quoted(kUgv) + " --start 1,5 --goal 14,4 --coarse-factor 100",
        "leaves fewer than 2"},
       {base + " --vehicle " + quoted(kUgv) + " --start 1x5 --goal 14,4", "--start"}},
      out);
}

}  // namespace
}  // namespace talus::cli_test
