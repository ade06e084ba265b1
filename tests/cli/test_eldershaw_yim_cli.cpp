// End-to-end tests of `talus baseline eldershaw-yim` on the generated
// Eldershaw-Yim terrain: path.csv from the start to the goal with every pose
// re-checked by evaluate_cg_pose on the same file, prm_points.csv /
// prm_edges.csv against the summary's counters (a forest: edges = points -
// trees), the direct mode's single local-planner call, a seed rerun byte for
// byte, 2 worker threads and 2 MPI ranks writing the serial files, and bad
// robot files and options as one-line errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli_test_support.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/eldershaw_yim/cg_space.hpp"
#include "talus/kinematic/eldershaw_yim/legged_robot.hpp"
#include "talus/sweep/mpi_session.hpp"

namespace talus::cli_test {
namespace {

std::string spider_file() {
  return data_file("robots/eldershaw_spider.yaml");
}

const std::string& terrain_file() {
  static const std::string file = generate_terrain("ey_terrain.asc", "eldershaw-yim --seed 3");
  return file;
}

std::string run_args(const std::string& out, const std::string& extra = "") {
  return "baseline eldershaw-yim --terrain " + quoted(terrain_file()) + " --robot " +
         quoted(spider_file()) + " --start 1,1,0 --goal 9,9,0 --out " + quoted(out) +
         " --foot-budget 3000 " + extra;
}

std::string slurp(const std::string& file) {
  return read_text(file);
}

TEST(EldershawYimCli, WritesAPathOfValidCgCellsAndTheRoadmap) {
  const std::string out = scratch_file("ey_prm");
  const RunResult r = run_talus(run_args(out, "--seed 5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json s = parse_json(slurp(out + "/summary.json"), "summary.json");
  ASSERT_EQ(s["status"], "found") << s.dump(2);
  EXPECT_EQ(s["options"]["seed"], 5);
  const auto path = read_csv(out + "/path.csv", "x,y,theta,control");
  ASSERT_EQ(path.size(), s["path_points"].get<std::size_t>());
  EXPECT_EQ(parse_number(path.front()[0]), 1.0);
  EXPECT_EQ(parse_number(path.back()[1]), 9.0);

  const RuledTerrain terrain(read_esri_ascii(terrain_file()));
  const LeggedRobot robot = load_legged_robot(spider_file());
  const Footmap footmap(terrain, robot);
  const CgLattice lattice(terrain.grid(), robot.foot_print, 16);
  std::size_t invalid = 0;
  double length = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const SE2Pose q{parse_number(path[k][0]), parse_number(path[k][1]), parse_number(path[k][2])};
    invalid +=
        evaluate_cg_pose(footmap, robot, lattice.centre(lattice.cell_of(q))) == CgState::kValid ? 0
                                                                                                : 1;
    if (k > 0)
      length += std::hypot(q.x - parse_number(path[k - 1][0]), q.y - parse_number(path[k - 1][1]));
  }
  EXPECT_EQ(invalid, 0u);
  EXPECT_NEAR(length, s["length_m"].get<double>(), 1e-9);
  EXPECT_EQ(s["footmap_invalid_nodes"].get<std::size_t>(), footmap.invalid_count());

  const auto points = read_csv(out + "/prm_points.csv", "point,ix,iy,itheta,x,y,theta");
  const auto edges = read_csv(out + "/prm_edges.csv", "new_point,old_point");
  EXPECT_EQ(points.size(), s["prm_points"].get<std::size_t>());
  EXPECT_EQ(edges.size(), s["prm_edges"].get<std::size_t>());
  EXPECT_EQ(edges.size(), points.size() - s["prm_trees"].get<std::size_t>());
  for (const auto& e : edges) EXPECT_GT(parse_number(e[0]), parse_number(e[1]));
  EXPECT_LE(s["cg_cells_materialised"].get<std::size_t>(), s["cg_cells"].get<std::size_t>());
  for (const char* stage : {"footmap_seconds", "materialise_seconds", "sample_seconds",
                            "connect_seconds", "recreate_seconds"})
    EXPECT_GE(s[stage].get<double>(), 0.0) << stage;
  const nlohmann::json& cells = s["cgmap_cells"];
  EXPECT_EQ(cells["valid"].get<std::size_t>() + cells["off_data"].get<std::size_t>() +
                cells["no_support"].get<std::size_t>() + cells["too_short"].get<std::size_t>(),
            static_cast<std::size_t>(lattice.nx() * lattice.ny()));

  // steps.csv: one row per foot-plan step, every leg's four columns.
  std::string header = "step,move,cg_x,cg_y,cg_theta";
  for (int l = 0; l < 8; ++l)
    for (const char* c : {",foot_x_", ",foot_y_", ",foot_z_", ",contact_"})
      header += c + std::to_string(l);
  const auto steps = read_csv(out + "/steps.csv", header);
  EXPECT_EQ(steps.size(), s["foot_plan_steps"].get<std::size_t>());
  EXPECT_EQ(s["options"]["foot_budget"], 3000);
  // Each round of section 3.3 feedback plans the feet again: resumed from the steps it keeps,
  // and afresh when that fails, each within the budget.
  EXPECT_LE(s["foot_planner_nodes"].get<std::size_t>(),
            3000u * (1 + 2 * s["feedback_events"].get<std::size_t>()));
  EXPECT_LE(s["foot_steps_reused"].get<std::size_t>(), s["foot_plan_steps"].get<std::size_t>());
  EXPECT_EQ(s["feedback_cells"].size(), s["feedback_events"].get<std::size_t>());
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const std::string& move = steps[k][1];
    EXPECT_TRUE(k == 0 ? move == "start"
                       : (move == "advance_cg" || move == "move_foot" || move == "lift_foot"))
        << k << " " << move;
    std::size_t contacts = 0;
    for (int l = 0; l < 8; ++l) contacts += steps[k][8 + 4 * l] == "1" ? 1 : 0;
    EXPECT_GE(contacts, 4u) << k;  // one per quadrant at least
  }
  if (s["foot_plan_status"] == "found") {
    EXPECT_EQ(parse_number(steps.back()[2]), 9.0);
    EXPECT_EQ(parse_number(steps.back()[3]), 9.0);
  }
}

TEST(EldershawYimCli, ASeedReproducesEveryFileByteForByte) {
  // Without gnuplot on the PATH (no figures: the CSV files are what is compared, and the
  // runs are faster); /bin/sh itself is called by its full path.
  auto run_plain = [](const std::string& out, const std::string& seed) {
    const std::string cmd = "PATH=/nonexistent '" + std::string(TALUS_CLI) + "' " +
                            run_args(out, "--feedback-rounds 0 --seed " + seed) +
                            " >/dev/null 2>&1";
    return std::system(cmd.c_str());
  };
  const std::string a = scratch_file("ey_seed_a"), b = scratch_file("ey_seed_b"),
                    c = scratch_file("ey_seed_c");
  ASSERT_EQ(run_plain(a, "11"), 0);
  ASSERT_EQ(run_plain(b, "11"), 0);
  ASSERT_EQ(run_plain(c, "12"), 0);
  for (const char* f : {"/path.csv", "/prm_points.csv", "/prm_edges.csv", "/steps.csv"})
    EXPECT_EQ(slurp(b + f), slurp(a + f)) << f;
  EXPECT_NE(slurp(c + "/prm_points.csv"), slurp(a + "/prm_points.csv"));
  EXPECT_FALSE(std::filesystem::exists(a + "/cgmap.png"));
}

/// The CLI through `launcher` (e.g. mpirun); without one, also without gnuplot on the PATH
/// (no figures: the CSV files are what is compared).
int run_cli(const std::string& launcher, const std::string& out, const std::string& extra) {
  const std::string cmd =
      (launcher.empty() ? "PATH=/nonexistent " : launcher) + "'" + std::string(TALUS_CLI) + "' " +
      run_args(out, "--feedback-rounds 0 --seed 11 " + extra) + " >/dev/null 2>&1";
  return std::system(cmd.c_str());
}

TEST(EldershawYimCli, WorkerThreadsWriteTheSerialFiles) {
  const std::string a = scratch_file("ey_workers_1"), b = scratch_file("ey_workers_2");
  ASSERT_EQ(run_cli("", a, "--workers 1"), 0);
  ASSERT_EQ(run_cli("", b, "--workers 2"), 0);
  for (const char* f : {"/path.csv", "/prm_points.csv", "/prm_edges.csv", "/steps.csv"})
    EXPECT_EQ(slurp(b + f), slurp(a + f)) << f;
  const nlohmann::json s = parse_json(slurp(b + "/summary.json"), "summary.json");
  EXPECT_EQ(s["workers"], 2);
  EXPECT_EQ(s["ranks"], 1);
  ASSERT_EQ(s["peak_rss_mib"].size(), 1u);
  EXPECT_GT(s["peak_rss_mib"][0].get<double>(), 0.0);
  EXPECT_NE(run_talus(run_args(scratch_file("ey_workers_0"), "--workers 0")).exit_code, 0);
}

TEST(EldershawYimCli, TwoMpiRanksWriteTheSerialFiles) {
  if (!MpiSession::mpirun_available())
    GTEST_SKIP() << "no mpirun (openmpi-bin), or an AddressSanitizer build";
  const std::string a = scratch_file("ey_ranks_1"), b = scratch_file("ey_ranks_2");
  ASSERT_EQ(run_cli("", a, "--workers 1"), 0);
  ASSERT_EQ(run_cli("env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun "
                    "--oversubscribe -n 2 ",
                    b, "--workers 1"),
            0);
  for (const char* f : {"/path.csv", "/prm_points.csv", "/prm_edges.csv", "/steps.csv"})
    EXPECT_EQ(slurp(b + f), slurp(a + f)) << f;
  const nlohmann::json sa = parse_json(slurp(a + "/summary.json"), "summary.json");
  const nlohmann::json sb = parse_json(slurp(b + "/summary.json"), "summary.json");
  EXPECT_EQ(sb["ranks"], 2);
  ASSERT_EQ(sb["peak_rss_mib"].size(), 2u);
  for (const auto& mib : sb["peak_rss_mib"]) EXPECT_GT(mib.get<double>(), 0.0);
  for (const char* k : {"local_planner_calls", "expansions", "cg_cells_materialised",
                        "cg_blocks_materialised", "recreate_calls"})
    EXPECT_EQ(sb[k], sa[k]) << k;
}

TEST(EldershawYimCli, DirectModeIsOneLocalPlannerCall) {
  const std::string out = scratch_file("ey_direct");
  const RunResult r = run_talus(run_args(out, "--direct --theta-slices 8"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json s = parse_json(slurp(out + "/summary.json"), "summary.json");
  ASSERT_EQ(s["status"], "found") << s.dump(2);
  EXPECT_EQ(s["local_planner_calls"], 1);
  EXPECT_EQ(s["prm_points"], 0);
  EXPECT_EQ(s["direct"], true);
  EXPECT_EQ(read_csv(out + "/prm_points.csv", "point,ix,iy,itheta,x,y,theta").size(), 0u);
}

TEST(EldershawYimCli, BadRobotsAndOptionsAreOneLineErrors) {
  const std::string bad_robot = scratch_file("ey_bad_robot.yaml");
  write_text(bad_robot, read_text(spider_file()) + "wheels: 4\n");
  const std::string never = scratch_file("ey_never");
  const std::string base = "--terrain " + quoted(terrain_file()) +
                           " --start 1,1,0 --goal 9,9,0 --out " + quoted(never) + " ";
  expect_bad_input(
      "baseline eldershaw-yim",
      {{base + "--robot " + quoted(bad_robot), "unknown key 'wheels'"},
       {base + "--robot " + quoted(spider_file()) + " --theta-slices 4", "--theta-slices"},
       {base + "--robot " + quoted(data_file("robots/rover4_sprung.yaml")),
        "key 'type' must be legged"},
       {base, "robot"}},
      never);
}

}  // namespace
}  // namespace talus::cli_test
