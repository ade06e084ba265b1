// End-to-end tests of `talus plan`. --stage global: the analytic cost on a
// flat plane, the candidates.csv / summary.json / fields.csv contracts, two
// candidates around a hill, the unreachable outcome (exit code 2, JSON on
// stdout) behind a wall of hills, input errors (exit 1) and a bundled DEM.
// --stage full: the analytic rest-to-rest time on a flat plane, the
// trajectory.csv / optima.csv / summary contracts, and no loss against the
// global candidates around a hill.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "profile_csv_test_support.hpp"

namespace talus::cli_test {
namespace {

/// 61 x 41 nodes at 1 m spacing, (0, 0) at the south-west node.
const std::string kPlanShape = "--ncols 61 --nrows 41 --cellsize 1";

std::string plan_flat_terrain() {
  return generate_terrain("plan_flat.asc", "plane --slope 0 " + kPlanShape);
}

/// A point mass with friction 0.7, b/h = 1.2 and the given top speed (none if 0).
std::string plan_vehicle(const std::string& name, double max_speed) {
  return point_mass_vehicle(name, 0.7, max_speed);
}

struct PlanVertex {
  int candidate;
  double x, y;
};

/// Reads candidates.csv, checking the exact header and the column count.
std::vector<PlanVertex> read_plan_candidates(const std::string& file) {
  std::vector<PlanVertex> rows;
  for (const std::vector<std::string>& f : read_csv(file, "candidate,x,y")) {
    rows.push_back({std::stoi(f[0]), std::stod(f[1]), std::stod(f[2])});
  }
  return rows;
}

/// The vertices of candidate `c`, in order.
std::vector<PlanVertex> plan_candidate(const std::vector<PlanVertex>& rows, int c) {
  std::vector<PlanVertex> out;
  std::copy_if(rows.begin(), rows.end(), std::back_inserter(out),
               [c](const PlanVertex& v) { return v.candidate == c; });
  return out;
}

/// candidates.csv agrees with the summary: each candidate's vertex count, from
/// the start node to the goal node, ordered by cost.
void expect_plan_candidates(const nlohmann::json& j, const std::string& dir) {
  EXPECT_LE(j.at("reachable_nodes"), j.at("nodes"));
  const std::vector<PlanVertex> rows = read_plan_candidates(dir + "/candidates.csv");
  const auto& candidates = j.at("candidates");
  std::size_t total = 0;
  double previous_cost = 0.0;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const nlohmann::json& cj = candidates[c];
    for (const char* key : {"cost_seconds", "length_m", "vertices"}) {
      EXPECT_TRUE(cj.contains(key)) << key << " missing from " << cj.dump();
    }
    const double cost = cj.at("cost_seconds").get<double>();
    EXPECT_GE(cost, previous_cost) << "candidates must be ordered by cost";
    previous_cost = cost;
    const std::vector<PlanVertex> v = plan_candidate(rows, static_cast<int>(c));
    ASSERT_EQ(v.size(), cj.at("vertices").get<std::size_t>()) << "candidate " << c;
    ASSERT_GE(v.size(), 2u);
    EXPECT_EQ(v.front().x, j.at("start_node")[0].get<double>()) << "candidate " << c;
    EXPECT_EQ(v.front().y, j.at("start_node")[1].get<double>()) << "candidate " << c;
    EXPECT_EQ(v.back().x, j.at("goal_node")[0].get<double>()) << "candidate " << c;
    EXPECT_EQ(v.back().y, j.at("goal_node")[1].get<double>()) << "candidate " << c;
    total += v.size();
  }
  EXPECT_EQ(rows.size(), total) << "candidates.csv rows of unknown candidates";
}

/// Runs `talus plan ARGS --out DIR` and checks what every run, reachable or
/// not, must satisfy: the summary on stdout equals DIR/summary.json, has the
/// contract's keys, and candidates.csv agrees with it. Returns the summary.
nlohmann::json run_plan_and_check(const std::string& args, const std::string& dir,
                                  int expected_exit_code) {
  std::filesystem::remove_all(dir);
  const RunResult r = run_talus("plan " + args + " --out " + quoted(dir));
  EXPECT_EQ(r.exit_code, expected_exit_code) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const nlohmann::json j = parse_json(r.out, "stdout");
  EXPECT_EQ(j, parse_json(read_text(dir + "/summary.json"), "summary.json"));
  for (const char* key : {"status", "message", "candidates", "nodes", "edges_evaluated",
                          "search_seconds", "reachable_nodes", "start_node", "goal_node",
                          "lattice_spacing", "connectivity", "expanded"}) {
    EXPECT_TRUE(j.contains(key)) << key << " missing from " << j.dump();
  }
  if (j.contains("candidates") && j.contains("start_node")) expect_plan_candidates(j, dir);
  return j;
}

/// The checks of a run that reaches the goal.
nlohmann::json run_plan_ok(const std::string& args, const std::string& dir) {
  const nlohmann::json j = run_plan_and_check(args, dir, 0);
  EXPECT_EQ(j.value("status", ""), "ok") << j.dump();
  EXPECT_TRUE(j.value("message", nlohmann::json()).is_null());
  EXPECT_FALSE(j.value("candidates", nlohmann::json::array()).empty());
  return j;
}

TEST(CliPlan, FlatPlaneSameRowCostsDistanceOverMaxSpeed) {
  const std::string terrain = plan_flat_terrain();
  const std::string args = "--terrain " + quoted(terrain) + " --start 5,20 --goal 55,20" +
                           " --vehicle " + quoted(plan_vehicle("v10.yaml", 10.0)) +
                           " --stage global";
  const std::string dir = scratch_file("flat_out");
  const nlohmann::json j = run_plan_ok(args, dir);
  const double expected = 50.0 / 10.0;
  ASSERT_FALSE(j.at("candidates").empty());
  EXPECT_NEAR(j.at("candidates")[0].at("cost_seconds").get<double>(), expected, 1e-9 * expected);
  EXPECT_NEAR(j.at("candidates")[0].at("length_m").get<double>(), 50.0, 1e-9 * 50.0);
  EXPECT_EQ(j.at("candidates")[0].at("vertices"), 51);  // straight along the row
  EXPECT_LE(j.at("candidates").size(), 3u);             // the default
  EXPECT_EQ(j.at("start_node"), nlohmann::json::array({5.0, 20.0}));
  EXPECT_EQ(j.at("goal_node"), nlohmann::json::array({55.0, 20.0}));
  EXPECT_EQ(j.at("nodes"), 61 * 41);
  EXPECT_EQ(j.at("reachable_nodes"), 61 * 41);
  EXPECT_EQ(j.at("lattice_spacing"), 1.0);  // 0 = the cell size
  EXPECT_EQ(j.at("connectivity"), 16);
  EXPECT_EQ(j.at("braking_rule"), true);
  EXPECT_EQ(j.at("turn_limit"), true);
  EXPECT_EQ(j.at("turn_limit_relaxed"), false);  // the vehicle has no steering limit
  EXPECT_EQ(j.at("surface_degree"), 3);
  EXPECT_GT(j.at("edges_evaluated").get<std::size_t>(), 0u);
  EXPECT_GT(j.at("expanded").get<std::size_t>(), 0u);
  for (const PlanVertex& v : plan_candidate(read_plan_candidates(dir + "/candidates.csv"), 0)) {
    EXPECT_EQ(v.y, 20.0);
  }

  // fields.csv: one row per node; the start's and the goal's own costs are 0.
  std::ifstream fields(dir + "/fields.csv");
  std::string line;
  ASSERT_TRUE(std::getline(fields, line));
  EXPECT_EQ(line, "x,y,cost_from_start,cost_to_goal");
  std::size_t rows = 0;
  while (std::getline(fields, line)) {
    double x = 0, y = 0, from_start = 0, to_goal = 0;
    char c1 = 0, c2 = 0, c3 = 0;
    std::istringstream row(line);
    ASSERT_TRUE(row >> x >> c1 >> y >> c2 >> from_start >> c3 >> to_goal) << line;
    if (x == 5.0 && y == 20.0) {
      EXPECT_EQ(from_start, 0.0);
      EXPECT_NEAR(to_goal, expected, 1e-9 * expected);
    }
    if (x == 55.0 && y == 20.0) {
      EXPECT_EQ(to_goal, 0.0);
      EXPECT_NEAR(from_start, expected, 1e-9 * expected);
    }
    ++rows;
  }
  EXPECT_EQ(rows, 61u * 41u);

  // The lattice options reach the search: 2.5 m spacing, 8 neighbours, and a
  // start off the lattice snaps to the nearest node (and the braking rule
  // off and the biquintic surface, which change nothing on flat ground, are
  // reported).
  const nlohmann::json coarse =
      run_plan_ok("--terrain " + quoted(terrain) + " --start 5.4,19.3 --goal 55,20 --vehicle " +
                      quoted(plan_vehicle("v10.yaml", 10.0)) +
                      " --stage global --lattice-spacing 2.5 --connectivity 8 --candidates 1"
                      " --no-braking-rule --surface-degree 5",
                  scratch_file("coarse_out"));
  EXPECT_EQ(coarse.at("nodes"), 25 * 17);
  EXPECT_EQ(coarse.at("lattice_spacing"), 2.5);
  EXPECT_EQ(coarse.at("connectivity"), 8);
  EXPECT_EQ(coarse.at("braking_rule"), false);
  EXPECT_EQ(coarse.at("surface_degree"), 5);
  EXPECT_EQ(coarse.at("start_node"), nlohmann::json::array({5.0, 20.0}));
  ASSERT_EQ(coarse.at("candidates").size(), 1u);
  EXPECT_NEAR(coarse.at("candidates")[0].at("cost_seconds").get<double>(), expected,
              1e-9 * expected);
  EXPECT_EQ(coarse.at("candidates")[0].at("vertices"), 21);
}

TEST(CliPlan, GaussianHillGivesTwoCandidatesOneOnEachSide) {
  // Slopes up to 0.6 * 8 / 5 = 0.97 > mu = 0.7 near the hill: the vehicle
  // goes round it, north or south.
  const std::string terrain =
      generate_terrain("hill.asc", "gaussian-hills --hill 30,20,8,5 " + kPlanShape);
  const std::string dir = scratch_file("hill_out");
  const nlohmann::json j =
      run_plan_ok("--terrain " + quoted(terrain) + " --start 5,20 --goal 55,20 --vehicle " +
                      quoted(plan_vehicle("v10.yaml", 10.0)) + " --stage global --candidates 2",
                  dir);
  ASSERT_EQ(j.at("candidates").size(), 2u) << j.dump();
  const std::vector<PlanVertex> rows = read_plan_candidates(dir + "/candidates.csv");
  int north = 0, south = 0;
  for (int c = 0; c < 2; ++c) {
    EXPECT_GT(j.at("candidates")[c].at("cost_seconds").get<double>(), 50.0 / 10.0);
    double y_max = -1e300, y_min = 1e300;
    for (const PlanVertex& v : plan_candidate(rows, c)) {
      y_max = std::max(y_max, v.y);
      y_min = std::min(y_min, v.y);
    }
    north += y_min >= 20.0 && y_max > 25.0;
    south += y_max <= 20.0 && y_min < 15.0;
  }
  EXPECT_EQ(north, 1);
  EXPECT_EQ(south, 1);
}

/// A full-stage summary's `seconds`: every stage is named, each a part of the run: the named
/// ones together no longer than its total, and with `other` (the planner's work between its
/// stages) exactly the total.
void expect_stages_add_up(const nlohmann::json& seconds) {
  const double missing = std::numeric_limits<double>::quiet_NaN();  // a double: NAN is a float
  double named = 0.0;
  for (const char* stage : {"read", "fit", "global", "local", "profile", "plots", "write"}) {
    EXPECT_GE(seconds.value(stage, missing), 0.0) << stage << " in " << seconds.dump();
    named += seconds.value(stage, missing);
  }
  const double total = seconds.value("total", 0.0);
  EXPECT_LE(named, total + 1e-6) << seconds.dump();
  EXPECT_NEAR(named + seconds.value("other", missing), total, 1e-9 * total + 1e-12)
      << seconds.dump();
}

/// The checks of a full-stage run that found a trajectory: the local stage's
/// summary keys, trajectory.csv (exact header, t increasing, ends at
/// travel_time) and optima.csv. Returns the summary.
nlohmann::json run_plan_full_ok(const std::string& args, const std::string& dir) {
  const nlohmann::json j = run_plan_ok(args, dir);
  for (const char* key : {"travel_time", "global_travel_time", "improvement_percent", "optima",
                          "seconds", "best_candidate", "best_control_points"}) {
    EXPECT_TRUE(j.contains(key)) << key << " missing from " << j.dump();
  }
  if (!j.contains("optima") || !j.contains("seconds")) return j;
  expect_stages_add_up(j.at("seconds"));
  EXPECT_EQ(j.at("optima").size(), j.at("candidates").size());
  for (const nlohmann::json& o : j.at("optima")) {
    for (const char* key : {"travel_time", "initial_time", "solver_status", "iterations"}) {
      EXPECT_TRUE(o.contains(key)) << key << " missing from " << o.dump();
    }
    // Every solver reports the projected-gradient norm at its result.
    if (!o.at("travel_time").is_null()) {
      EXPECT_TRUE(o.at("optimality").is_number()) << o.dump();
      EXPECT_GE(o.value("optimality", -1.0), 0.0);
    }
    EXPECT_GT(o.value("iterations", 0), 0);
    EXPECT_TRUE(o.contains("solver")) << o.dump();
  }
  // trajectory.csv is a consistent profile on its own, from the requested speeds to the
  // summary's time and length.
  const double travel_time = j.at("travel_time").get<double>();
  const std::vector<ProfileRow> rows = read_profile_csv(dir + "/trajectory.csv");
  EXPECT_GT(rows.size(), 100u);
  EXPECT_EQ(rows.size(), j.at("stations").get<std::size_t>());
  expect_consistent_rows(rows, travel_time, j.at("length_m").get<double>(),
                         j.at("start_speed").get<double>(), j.at("end_speed").get<double>());
  // The best candidate is the fastest of the optima, and its time is the plan's.
  const std::size_t best = j.at("best_candidate").get<std::size_t>();
  EXPECT_LT(best, j.at("optima").size());
  if (best >= j.at("optima").size()) return j;
  EXPECT_EQ(j.at("optima")[best].at("travel_time").get<double>(), travel_time);
  for (const nlohmann::json& o : j.at("optima")) {
    if (!o.at("travel_time").is_null()) {
      EXPECT_GE(o.at("travel_time").get<double>(), travel_time);
    }
  }
  const auto optima = read_csv(dir + "/optima.csv", "candidate,s,x,y,v");
  EXPECT_GT(optima.size(), 10u);
  EXPECT_LE(optima.size(), j.at("optima").size() * 2001);
  return j;
}

TEST(CliPlan, FullStageOnFlatPlaneMatchesRestToRestStraightLine) {
  // 50 m straight: accelerate at mu g = 0.7 * 9.81 to 10 m/s, cruise, brake.
  const std::string terrain = plan_flat_terrain();
  const std::string dir = scratch_file("full_flat_out");
  const nlohmann::json j =
      run_plan_full_ok("--terrain " + quoted(terrain) + " --start 5,20 --goal 55,20 --vehicle " +
                           quoted(plan_vehicle("v10.yaml", 10.0)) + " --candidates 1",
                       dir);
  const double a = 0.7 * 9.81, v = 10.0, length = 50.0;
  const double expected = 2.0 * v / a + (length - v * v / a) / v;
  EXPECT_EQ(j.value("stage", ""), "full");  // the default
  // The straight line is optimal; the optimiser keeps it to within 1e-5 (a 1e-3 error in g moves
  // the time by 5e-4).
  EXPECT_NEAR(j.value("travel_time", 0.0), expected, 1e-5 * expected) << j.dump();
  EXPECT_LE(j.value("travel_time", 0.0), j.value("global_travel_time", 0.0) * (1.0 + 1e-12));
}

TEST(CliPlan, FullStageWithStartAndEndSpeedsMatchesTheClosedForm) {
  // 50 m straight from 4 m/s to 2 m/s, top speed 10 m/s, a = mu g both ways:
  // t = (v - v0)/a + (v - v1)/a + (L - (v^2 - v0^2)/2a - (v^2 - v1^2)/2a) / v.
  const std::string dir = scratch_file("full_speeds_out");
  const nlohmann::json j = run_plan_full_ok(
      "--terrain " + quoted(plan_flat_terrain()) + " --start 5,20 --goal 55,20 --vehicle " +
          quoted(plan_vehicle("v10.yaml", 10.0)) + " --candidates 1 --v0 4 --v1 2",
      dir);
  const double a = 0.7 * 9.81, v = 10.0, v0 = 4.0, v1 = 2.0, length = 50.0;
  const double cruise = length - (v * v - v0 * v0) / (2 * a) - (v * v - v1 * v1) / (2 * a);
  const double expected = (v - v0) / a + (v - v1) / a + cruise / v;
  EXPECT_NEAR(j.value("travel_time", 0.0), expected, 1e-5 * expected) << j.dump();
  EXPECT_EQ(j.value("start_speed", -1.0), 4.0);
  EXPECT_EQ(j.value("end_speed", -1.0), 2.0);
}

TEST(CliPlan, StartAndGoalHeadingsAreKeptAndEchoed) {
  // Leaving north-east (0.6 rad) and arriving south-east (-0.9 rad) on flat ground: the end
  // tangents of trajectory.csv, extrapolated from the first (last) two steps' chords (each
  // chord's heading is the tangent's half a step in), point along them.
  const std::string dir = scratch_file("full_headings_out");
  const nlohmann::json j = run_plan_full_ok(
      "--terrain " + quoted(plan_flat_terrain()) + " --start 5,20 --goal 55,20 --vehicle " +
          quoted(plan_vehicle("v10.yaml", 10.0)) +
          " --candidates 1 --start-heading 0.6 --goal-heading -0.9",
      dir);
  EXPECT_EQ(j.value("start_heading", 0.0), 0.6);
  EXPECT_EQ(j.value("goal_heading", 0.0), -0.9);
  const std::vector<ProfileRow> rows = read_profile_csv(dir + "/trajectory.csv");
  ASSERT_GT(rows.size(), 100u);
  const auto heading = [&](std::size_t a, std::size_t b) {
    return std::atan2(rows[b].y - rows[a].y, rows[b].x - rows[a].x);
  };
  const std::size_t n = rows.size();
  EXPECT_NEAR(1.5 * heading(0, 1) - 0.5 * heading(1, 2), 0.6, 0.01);
  EXPECT_NEAR(1.5 * heading(n - 2, n - 1) - 0.5 * heading(n - 3, n - 2), -0.9, 0.01);
  // Without them the keys are null, and a heading must be a finite number.
  const nlohmann::json free = run_plan_full_ok(
      "--terrain " + quoted(plan_flat_terrain()) + " --start 5,20 --goal 55,20 --vehicle " +
          quoted(plan_vehicle("v10.yaml", 10.0)) + " --candidates 1",
      scratch_file("full_free_heading_out"));
  EXPECT_TRUE(free.at("start_heading").is_null());
  EXPECT_TRUE(free.at("goal_heading").is_null());
  const RunResult bad =
      run_talus("plan --terrain " + quoted(plan_flat_terrain()) +
                " --start 5,20 --goal 55,20 --vehicle " + quoted(plan_vehicle("v10.yaml", 10.0)) +
                " --start-heading inf --out " + quoted(scratch_file("bad_heading_out")));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--start-heading"), std::string::npos) << bad.err;
}

TEST(CliPlan, SmoothingFitAndLbfgsKeepTheFlatPlaneClosedForm) {
  // A smoothing fit of a plane is the plane, and every solver keeps the straight line: the
  // closed-form rest-to-rest time of FullStageOnFlatPlaneMatchesRestToRestStraightLine.
  const double a = 0.7 * 9.81, v = 10.0, length = 50.0;
  const double expected = 2.0 * v / a + (length - v * v / a) / v;
  for (const std::string extra : {"--smoothing 2", "--solver nlopt-lbfgs"}) {
    const std::string dir = scratch_file("full_variant_out");
    const nlohmann::json j = run_plan_full_ok(
        "--terrain " + quoted(plan_flat_terrain()) + " --start 5,20 --goal 55,20 --vehicle " +
            quoted(plan_vehicle("v10.yaml", 10.0)) + " --candidates 1 " + extra,
        dir);
    EXPECT_NEAR(j.value("travel_time", 0.0), expected, 1e-5 * expected) << extra << j.dump();
  }
  const nlohmann::json lbfgs =
      parse_json(read_text(scratch_file("full_variant_out") + "/summary.json"), "summary.json");
  EXPECT_EQ(lbfgs.value("solver", ""), "nlopt-lbfgs");
}

TEST(CliPlan, EveryAcceptedControlPointCountIsOptimised) {
  // The largest --control-points the CLI accepts runs the local stage with
  // that many points (it once fell back silently to the initial fit).
  const std::string terrain = plan_flat_terrain();
  const std::string dir = scratch_file("full_flat_m64_out");
  const nlohmann::json j = run_plan_full_ok(
      "--terrain " + quoted(terrain) + " --start 5,20 --goal 55,20 --vehicle " +
          quoted(plan_vehicle("v10.yaml", 10.0)) + " --candidates 1 --control-points 64",
      dir);
  ASSERT_EQ(j.at("optima").size(), 1u);
  const nlohmann::json& o = j.at("optima")[0];
  EXPECT_EQ(o.value("control_points", 0), 64) << o.dump();
  EXPECT_TRUE(o.at("solver_status").is_string()) << o.dump();
  EXPECT_TRUE(o.at("optimizer_message").is_null()) << o.dump();
}

TEST(CliPlan, FullStageAroundAHillIsNoSlowerThanTheGlobalCandidates) {
  // Low friction: the slopes of the hill (up to 0.97) are out of reach.
  const std::string terrain =
      generate_terrain("hill.asc", "gaussian-hills --hill 30,20,8,5 " + kPlanShape);
  const std::string dir = scratch_file("full_hill_out");
  const nlohmann::json j =
      run_plan_full_ok("--terrain " + quoted(terrain) + " --start 5,20 --goal 55,20 --vehicle " +
                           quoted(point_mass_vehicle("slippery.yaml", 0.4, 10.0)) +
                           " --stage full --candidates 2 --control-points 6 --solver nlopt-bobyqa",
                       dir);
  const double travel_time = j.value("travel_time", 0.0);
  const double global_time = j.value("global_travel_time", 0.0);
  EXPECT_GT(travel_time, 50.0 / 10.0);
  EXPECT_LE(travel_time, global_time) << j.dump();
  EXPECT_GE(j.value("improvement_percent", -1.0), 0.0);
  for (const nlohmann::json& o : j.at("optima")) {
    if (o.at("travel_time").is_null()) continue;
    EXPECT_LE(o.at("travel_time").get<double>(), o.at("initial_time").get<double>());
  }
  for (const char* file : {"/plan.png", "/profile.png", "/plan.gp", "/profile.gp"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + file)) << file;
  }
}

// With --polish each candidate's last solve is the polish, listed in its
// attempts with its status; without it only the nested solve. From one
// 8-point fit and one solve, then with a further start at 10, then the
// defaults: a 16-point fit, two restarts and no further start.
TEST(CliPlan, PolishAddsTheNlpAsTheLastAttempt) {
  const std::string terrain =
      generate_terrain("hill_polish.asc", "gaussian-hills --hill 30,20,8,5 " + kPlanShape);
  const std::string shared =
      "--terrain " + quoted(terrain) + " --start 5,20 --goal 55,20 --vehicle " +
      quoted(point_mass_vehicle("slippery.yaml", 0.4, 10.0)) + " --candidates 1 --no-figures";
  const std::string args = shared + " --control-points 8 --restarts 0 --more-control-points 0";
  const nlohmann::json polished = run_plan_full_ok(args + " --polish", scratch_file("polish_on"));
  EXPECT_EQ(polished.at("polish"), true);
  const nlohmann::json& attempts = polished.at("optima").at(0).at("attempts");
  ASSERT_EQ(attempts.size(), 2u) << attempts.dump();
  EXPECT_EQ(attempts.at(1).at("start"), "polish");
  EXPECT_TRUE(attempts.at(1).at("solver_status").is_string());
  const nlohmann::json plain = run_plan_full_ok(args, scratch_file("polish_off"));
  EXPECT_EQ(plain.at("polish"), false);
  const nlohmann::json& only = plain.at("optima").at(0).at("attempts");
  ASSERT_EQ(only.size(), 1u) << only.dump();
  EXPECT_EQ(only.at(0).at("start"), "fit");
  // A further start from a 10-point fit adds its solve, tagged with its M.
  const nlohmann::json more =
      run_plan_full_ok(shared + " --control-points 8 --restarts 0 --more-control-points 10",
                       scratch_file("more_points"));
  const nlohmann::json& starts = more.at("optima").at(0).at("attempts");
  ASSERT_EQ(starts.size(), 2u) << starts.dump();
  EXPECT_EQ(starts.at(0).at("control_points"), 8);
  EXPECT_EQ(starts.at(1).at("control_points"), 10);
  EXPECT_LE(more.at("travel_time").get<double>(), plain.at("travel_time").get<double>() + 1e-9);
  EXPECT_EQ(plain.at("more_control_points").size(), 0u);
  // The defaults: the 16-point fit's solve, then a resume and a perturbed
  // restart (the nested solver stops on a cap here), no further start.
  const nlohmann::json defaults = run_plan_full_ok(shared, scratch_file("default_starts"));
  EXPECT_EQ(defaults.at("more_control_points").size(), 0u);
  EXPECT_EQ(defaults.at("restarts"), 2);
  const nlohmann::json& three = defaults.at("optima").at(0).at("attempts");
  ASSERT_EQ(three.size(), 3u) << three.dump();
  EXPECT_EQ(three.at(0).at("start"), "fit");
  EXPECT_EQ(three.at(1).at("start"), "resume");
  EXPECT_EQ(three.at(2).at("start"), "perturbed");
  for (const nlohmann::json& attempt : three) EXPECT_EQ(attempt.at("control_points"), 16);
  // The polish never returns a path slower than the fit.
  const nlohmann::json& o = polished.at("optima").at(0);
  EXPECT_LE(o.at("travel_time").get<double>(), o.at("initial_time").get<double>());
}

TEST(CliPlan, FullStageWithNoFeasibleTrajectoryExitsTwoWithTheSummary) {
  // The lattice reaches the goal (the global stage only needs v_max), but
  // starting at 10 m/s with 1 m/s² of brakes the vehicle needs 50 m to stop
  // and the goal is 20 m away: no candidate has an admissible profile.
  const std::string terrain = generate_terrain("flat_brakes.asc", "plane " + kPlanShape);
  const std::string vehicle = scratch_file("weak_brakes.yaml");
  write_text(vehicle,
             "model: point_mass\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\n"
             "max_speed: 10\nmax_decel: 1\n");
  const std::string dir = scratch_file("full_infeasible_out");
  const nlohmann::json j =
      run_plan_and_check("--terrain " + quoted(terrain) + " --start 10,20 --goal 30,20 --vehicle " +
                             quoted(vehicle) + " --v0 10 --candidates 2",
                         dir, 2);
  EXPECT_EQ(j.value("status", ""), "infeasible") << j.dump();
  // The message names why and where: the start speed, at the start.
  EXPECT_NE(j.value("message", "").find("start speed 10 m/s"), std::string::npos) << j.dump();
  EXPECT_NE(j.value("message", "").find("near (10.00, 20.00)"), std::string::npos) << j.dump();
  EXPECT_TRUE(j.at("travel_time").is_null());
  ASSERT_FALSE(j.at("optima").empty());
  for (const nlohmann::json& o : j.at("optima")) {
    EXPECT_EQ(o.value("status", ""), "infeasible") << o.dump();
    EXPECT_FALSE(o.value("message", "").empty());
  }
  EXPECT_EQ(read_text(dir + "/trajectory.csv"), "s,x,y,z,v,a,t,v_max,binding\n");
}

TEST(CliPlan, WallOfHillsMakesTheGoalUnreachableWithExitCodeTwo) {
  // Hills 30 m high, sigma 3 m, every 5 m along y = 20 and beyond both edges:
  // a ridge whose flanks (slope up to 6) no vehicle with mu = 0.7 can climb.
  std::string hills = "gaussian-hills " + kPlanShape;
  for (int x = -10; x <= 70; x += 5) hills += " --hill " + std::to_string(x) + ",20,30,3";
  const std::string terrain = generate_terrain("wall.asc", hills);
  const std::string dir = scratch_file("wall_out");
  const nlohmann::json j =
      run_plan_and_check("--terrain " + quoted(terrain) + " --start 30,5 --goal 30,35 --vehicle " +
                             quoted(plan_vehicle("v10.yaml", 10.0)) + " --stage global",
                         dir, 2);
  EXPECT_EQ(j.value("status", ""), "unreachable") << j.dump();
  EXPECT_TRUE(j.value("candidates", nlohmann::json::array({1})).empty());
  EXPECT_FALSE(j.value("message", "").empty());
  EXPECT_GT(j.value("reachable_nodes", 0), 0);
  EXPECT_LT(j.value("reachable_nodes", 0), j.value("nodes", 0));
  EXPECT_EQ(read_text(dir + "/candidates.csv"), "candidate,x,y\n");
  // fields.csv: nodes beyond the wall are `inf` from the start; the cost to
  // the goal is not computed (`nan`).
  const std::string fields = read_text(dir + "/fields.csv");
  EXPECT_EQ(fields.rfind("x,y,cost_from_start,cost_to_goal\n", 0), 0u);
  EXPECT_EQ(std::count(fields.begin(), fields.end(), '\n'), 61 * 41 + 1);
  EXPECT_NE(fields.find("\n30,35,inf,nan\n"), std::string::npos);
  EXPECT_NE(fields.find("\n30,5,0,nan\n"), std::string::npos);
}

// A start on ground no edge can leave is an expected outcome (exit 2, the summary naming
// the start node and why), not bad input (exit 1), for both stages.
TEST(CliPlan, AnUntraversableStartExitsTwoWithTheReason) {
  const std::string steep =
      quoted(generate_terrain("steep.asc", "plane --slope 0.8 --ncols 41 --nrows 41 --cellsize 1"));
  for (const std::string stage : {"global", "full"}) {
    const std::string dir = scratch_file("steep_out_" + stage);
    const nlohmann::json j =
        run_plan_and_check("--terrain " + steep + " --start 20,20 --goal 30,30 --vehicle " +
                               quoted(plan_vehicle("v10.yaml", 10.0)) + " --stage " + stage,
                           dir, 2);
    EXPECT_EQ(j.value("status", ""), "unreachable") << j.dump();
    EXPECT_NE(j.value("message", "").find("start node (20, 20) is on untraversable terrain"),
              std::string::npos)
        << j.dump();
    EXPECT_EQ(read_text(dir + "/candidates.csv"), "candidate,x,y\n");
  }
}

TEST(CliPlan, BadInputGivesOneLineOnStderrAndExitCodeOne) {
  const std::string flat = quoted(plan_flat_terrain());
  const std::string steep =
      quoted(generate_terrain("steep.asc", "plane --slope 0.8 --ncols 41 --nrows 41 --cellsize 1"));
  const std::string v10 = " --vehicle " + quoted(plan_vehicle("v10.yaml", 10.0));
  const std::string unlimited = " --vehicle " + quoted(plan_vehicle("unlimited.yaml", 0.0));
  const std::string dir = scratch_file("never_written");
  std::filesystem::remove_all(dir);
  const std::string tail = " --stage global --out " + quoted(dir);
  const std::vector<ErrorCase> cases = {
      {"--terrain " + flat + " --start 70,20 --goal 55,20" + v10 + tail, "--start (70, 20)"},
      {"--terrain " + flat + " --start 5,20 --goal 55,-1" + v10 + tail, "--goal (55, -1)"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --connectivity 12" + tail,
       "--connectivity must be 8, 16 or 32, got 12"},
      {"--terrain " + flat + " --start '1;2' --goal 55,20" + v10 + tail, "'1;2'"},
      {"--terrain " + flat + " --start 5,20 --goal 55" + v10 + tail, "--goal must be X,Y"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + unlimited + tail, "max_speed"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --candidates 0" + tail,
       "--candidates"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --smoothing -1" + tail,
       "--smoothing"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --surface-degree 4" + tail,
       "--surface-degree must be 3 (bicubic) or 5 (biquintic), got 4"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 +
           " --surface-degree 5 --smoothing 1" + tail,
       "drop --smoothing"},
      {"--terrain /nonexistent.asc --start 5,20 --goal 55,20" + v10 + tail, "/nonexistent.asc"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --stage fast --out " +
           quoted(dir),
       "--stage"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --solver snopt --out " +
           quoted(dir),
       "--solver: unknown solver 'snopt'"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --control-points 3 --out " +
           quoted(dir),
       "--control-points"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 +
           " --more-control-points 16,65 --out " + quoted(dir),
       "--more-control-points must each be in [4, 64] (or a single 0 for none), got 65"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 +
           " --more-control-points 16,0 --out " + quoted(dir),
       "got 0"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --v0 -1 --out " + quoted(dir),
       "--v0"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --v1 11 --out " + quoted(dir),
       "--v1 11"},
      {"--terrain " + flat + " --start 5,20 --goal 55,20" + v10 + " --stage global", "--out"},
  };
  expect_bad_input("plan", cases, dir);
}

TEST(CliPlan, BundledDemCornerToCornerIsSane) {
  // West Bijou escarpment (NASADEM, 25 m, 122 x 82 nodes), south-west to
  // north-east node, the 15 m/s rover.
  const std::string terrain = data_file("terrain/west_bijou_escarpment_nasadem25m.asc");
  const RunResult info = run_talus("terrain info " + quoted(terrain));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json d = parse_json(info.out, "terrain info");
  std::ostringstream args;
  args.precision(17);
  args << "--terrain " << quoted(terrain) << " --start " << d.at("xmin").get<double>() << ","
       << d.at("ymin").get<double>() << " --goal " << d.at("xmax").get<double>() << ","
       << d.at("ymax").get<double>() << " --vehicle " << quoted(data_file("vehicles/rover.yaml"))
       << " --stage global";
  const nlohmann::json j = run_plan_ok(args.str(), scratch_file("bijou_out"));
  EXPECT_EQ(j.at("nodes"), 122 * 82);
  EXPECT_EQ(j.at("candidates").size(), 3u) << j.dump();
  const double dx = d.at("xmax").get<double>() - d.at("xmin").get<double>();
  const double dy = d.at("ymax").get<double>() - d.at("ymin").get<double>();
  const double straight = std::hypot(dx, dy);
  for (const nlohmann::json& c : j.at("candidates")) {
    // No faster than the straight line at top speed; no wild detour either.
    EXPECT_GE(c.at("cost_seconds").get<double>(), straight / 15.0);
    EXPECT_LE(c.at("cost_seconds").get<double>(), 1.5 * straight / 15.0);
    EXPECT_GE(c.at("length_m").get<double>(), straight);
    EXPECT_LE(c.at("cost_seconds").get<double>(),
              2.0 * j.at("candidates")[0].at("cost_seconds").get<double>());
  }
}

TEST(CliPlan, HelpDocumentsTheContract) {
  const RunResult r = run_talus("plan --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* fragment : {"Usage",
                               "--stage",
                               "global",
                               "full",
                               "exact gradient",
                               "candidate,x,y",
                               "summary.json",
                               "cost_seconds",
                               "unreachable",
                               "Exit code 0",
                               "--time-limit",
                               "time_limit",
                               "--resolution",
                               "2 when",
                               "--candidates",
                               "--lattice-spacing",
                               "--connectivity",
                               "--smoothing",
                               "--control-points",
                               "--solver",
                               "nlopt-bobyqa",
                               "ipopt",
                               "--v0",
                               "--v1",
                               "s,x,y,z,v,a,t,v_max,binding",
                               "candidate,s,x,y,v",
                               "global_travel_time",
                               "nlopt-lbfgs"}) {
    EXPECT_NE(r.out.find(fragment), std::string::npos) << fragment << " not in " << r.out;
  }
}

TEST(CliPlan, TimeLimitAndMultiResolution) {
  const std::string base = "--terrain " + quoted(plan_flat_terrain()) +
                           " --start 5,20 --goal 55,20 --vehicle " +
                           quoted(plan_vehicle("v10.yaml", 10.0));
  // A limit of 1 ns has passed before the global search's first look at the
  // clock: no route, no trajectory, exit code 2, status time_limit.
  const std::string cut = scratch_file("time_limit_out");
  const nlohmann::json j = run_plan_and_check(base + " --time-limit 1e-9", cut, 2);
  EXPECT_EQ(j.value("status", ""), "time_limit") << j.dump();
  EXPECT_NE(j.value("message", "").find("no trajectory"), std::string::npos) << j.dump();
  EXPECT_TRUE(j.at("travel_time").is_null());
  EXPECT_EQ(j.value("time_limit", 0.0), 1e-9);
  // The multi-resolution search: the same straight line, no fields.csv.
  const std::string multi = scratch_file("multi_out");
  const nlohmann::json m = run_plan_ok(base + " --stage global --resolution multi", multi);
  EXPECT_EQ(m.value("resolution", ""), "multi");
  EXPECT_NEAR(m.at("candidates")[0].at("cost_seconds").get<double>(), 5.0, 1e-9 * 5.0);
  EXPECT_GT(m.value("coarse_nodes", 0), 0);
  EXPECT_TRUE(m.at("files").at("fields").is_null());
  EXPECT_FALSE(std::filesystem::exists(multi + "/fields.csv"));
  const std::string dir = scratch_file("never_written");
  std::filesystem::remove_all(dir);
  expect_bad_input("plan",
                   {{base + " --time-limit 0 --out " + quoted(dir), "--time-limit"},
                    {base + " --resolution coarse --out " + quoted(dir), "--resolution"}},
                   dir);
}

// A time limit spent before the search could start on a tile-size lattice (600 x 600 nodes,
// searched coarse to fine): the route level still finds a route, the plan is a trajectory along
// it (status time_limit, exit 0), the figures are left out, and the stages add up to the total.
TEST(CliPlan, ASpentTimeLimitOnATileSizeMapStillGivesATrajectory) {
  const std::string terrain =
      generate_terrain("plan_tile.asc", "plane --slope 0.05 --ncols 600 --nrows 600 --cellsize 1");
  const std::string dir = scratch_file("tile_time_limit_out");
  const nlohmann::json j = run_plan_and_check(
      "--terrain " + quoted(terrain) + " --start 10,10 --goal 590,590 --vehicle " +
          quoted(plan_vehicle("v10.yaml", 10.0)) + " --resolution multi --time-limit 1e-9",
      dir, 0);
  EXPECT_EQ(j.value("status", ""), "time_limit") << j.dump();
  EXPECT_NE(j.value("search_message", "").find("the route level's"), std::string::npos) << j.dump();
  ASSERT_TRUE(j.at("travel_time").is_number()) << j.dump();
  // At most the top speed's time along the straight line, at least 10 % above it (the route is
  // a 5 m lattice path through a fit, and the trajectory starts and ends at rest).
  const double straight = std::hypot(580.0, 580.0) / 10.0;
  EXPECT_GT(j.at("travel_time").get<double>(), straight);
  EXPECT_LT(j.at("travel_time").get<double>(), 1.1 * straight);
  EXPECT_EQ(j.value("figures_skipped", ""), "the time limit had passed");
  EXPECT_FALSE(std::filesystem::exists(dir + "/plan.png"));
  expect_stages_add_up(j.at("seconds"));
}

}  // namespace
}  // namespace talus::cli_test
