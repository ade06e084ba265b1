// The `talus` CLI against careless and hostile input (issue 18's families):
// every case must exit 1 with one line on stderr that names the problem,
// print nothing on stdout and leave no output behind, within a memory cap
// and a time limit. Run with a 384 MiB memory budget (TALUS_MEMORY_LIMIT_MB),
// under `prlimit --as` (512 MiB, uninstrumented build only: ASan reserves
// terabytes of address space) and `timeout`, so that a regression to
// unbounded memory or a hang fails instead of swapping.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cli_robustness_support.hpp"
#include "cli_test_support.hpp"

namespace talus::cli_test {
namespace {

namespace fs = std::filesystem;

std::string vehicle() {
  return point_mass_vehicle("robust_v10.yaml", 0.7, 10.0);
}

std::string path_file() {
  return write_points("robust_path.csv", {{{5, 20}}, {{35, 20}}});
}

std::string flat() {
  return generate_terrain("robust_flat.asc", "plane --ncols 61 --nrows 41 --cellsize 1");
}

TEST(CliRobustness, InputsThatAreNotRegularFilesOrClaimTooMuch) {
  const std::string out = scratch_file("robust_out.csv");
  const std::string claims = scratch_file("claims.asc");
  write_text(claims, "ncols 20000\nnrows 20000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n");
  const std::string fifo = scratch_file("robust.fifo");
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string limits = "limits --terrain " + quoted(flat()) + " --path " +
                             quoted(path_file()) + " --vehicle " + quoted(vehicle());
  expect_refused(
      {
          {"header claims 4e8 nodes", "terrain info " + quoted(claims), "file ends after 3 values"},
          {"terrain /dev/zero", "terrain info /dev/zero", "not a regular file"},
          {"terrain FIFO", "terrain info " + quoted(fifo), "not a regular file"},
          {"terrain folder", "terrain info " + quoted(scratch_dir().string()), "is a folder"},
          {"vehicle /dev/zero",
           "limits --terrain " + quoted(flat()) + " --path " + quoted(path_file()) +
               " --vehicle /dev/zero -o " + quoted(out),
           "not a regular file"},
          {"path /dev/zero",
           "limits --terrain " + quoted(flat()) + " --path /dev/zero --vehicle " +
               quoted(vehicle()) + " -o " + quoted(out),
           "not a regular file"},
          {"output is the terrain", limits + " -o " + quoted(flat()), "is the --terrain input"},
          {"output is the path", limits + " -o " + quoted(path_file()), "is the --path input"},
      },
      out);
}

TEST(CliRobustness, MalformedFilesGetMessagesThatSayWhatIsWrong) {
  const std::string out = scratch_file("robust_out.csv");
  const std::string tail = "xllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n";
  const auto grid = [&](const std::string& name, const std::string& text) {
    write_text(scratch_file(name), text);
    return "terrain info " + quoted(scratch_file(name));
  };
  const std::string duplicate = scratch_file("duplicate.yaml");
  write_text(duplicate,
             "model: point_mass\nfriction: 0.7\ncg_height: 0.5\nhalf_track: 0.6\nmax_speed: "
             "10\nfriction: 0.1\n");
  const std::string two_documents = scratch_file("two.yaml");
  write_text(two_documents, read_text(vehicle()) + "---\nmodel: rigid_body\n");
  const std::string limits_with = "limits --terrain " + quoted(flat()) + " --path " +
                                  quoted(path_file()) + " -o " + quoted(out) + " --vehicle ";
  const std::string aba = write_points("aba.csv", {{{10, 20}}, {{30, 20}}, {{10, 20}}});
  expect_refused(
      {
          {"two values on a header line", grid("n44.asc", "ncols 2 2\nnrows 2\n" + tail),
           "'ncols' has more than one value"},
          {"inf before any header", grid("inf.asc", "inf 2\n"), "the header is missing"},
          {"underflow",
           grid("tiny.asc", "ncols 2\nnrows 2\n" + tail.substr(0, tail.size() - 4) + "3 1e-400\n"),
           "out of the range of a double"},
          {"undeclared float NODATA",
           grid("void.asc", "ncols 2\nnrows 2\n" + tail.substr(0, tail.size() - 4) + "3 -3.4e38\n"),
           "declare it with NODATA_value"},
          {"escape sequence in a key", grid("esc.asc", "n\x1b[2Jcols 2\nnrows 2\n" + tail),
           "\\x1B[2J"},
          {"100 kB token", grid("long.asc", std::string(100'000, 'k') + " 2\n"), "(100000 bytes)"},
          {"duplicate YAML key", limits_with + quoted(duplicate), "'friction' appears twice"},
          {"second YAML document", limits_with + quoted(two_documents), "second YAML document"},
          {"A, B, A path",
           "limits --terrain " + quoted(flat()) + " --path " + quoted(aba) + " --vehicle " +
               quoted(vehicle()) + " -o " + quoted(out),
           "turns the path straight back"},
      },
      out);
}

TEST(CliRobustness, OptionsThatWouldWrapHangOrExhaustMemory) {
  const std::string out = scratch_file("robust_generated.asc");
  const std::string dir = scratch_file("robust_plan_out");
  const std::string plan = "plan --terrain " + quoted(flat()) + " --vehicle " + quoted(vehicle()) +
                           " --out " + quoted(dir) + " ";
  expect_refused(
      {
          {"negative peak count", "terrain generate fractal --peaks -1 -o " + quoted(out),
           "--peaks"},
          {"negative column count", "terrain generate fractal --ncols -1 -o " + quoted(out),
           "--ncols"},
          {"negative seed", "terrain generate fractal --seed -1 -o " + quoted(out), "whole number"},
          {"huge grid",
           "terrain generate plane --ncols 100000000 --nrows 100000000 -o " + quoted(out),
           "memory budget"},
          {"curvature to infinity", "terrain generate bowl --curvature 1e308 -o " + quoted(out),
           "beyond the supported magnitude"},
          {"unknown kind", "terrain generate fancy -o " + quoted(out),
           "unknown terrain kind 'fancy'"},
      },
      out);
  expect_refused(
      {
          {"start equal to goal", plan + "--start 5,20 --goal 5,20", "same point"},
          // In full (the default, auto, searches these 6 million nodes coarse to fine and
          // plans in about 200 MB).
          {"lattice finer than memory",
           plan + "--start 5,20 --goal 55,20 --stage global --lattice-spacing 0.02 "
                  "--resolution full",
           "increase the lattice spacing"},
          // Issue #39 item 6: before, every candidate ran into the memory budget and the plan
          // ended "infeasible" (exit 2), advising an option plan does not have.
          {"stations finer than a millimetre",
           plan + "--start 5,20 --goal 55,20 --station-spacing 1e-9", "at least 0.001 m"},
      },
      dir);
  const std::string profile_out = scratch_file("robust_profile.csv");
  expect_refused(
      {{"stations beyond memory",
        "profile --terrain " + quoted(flat()) + " --path " + quoted(path_file()) + " --vehicle " +
            quoted(vehicle()) + " --stations 10000000 -o " + quoted(profile_out),
        "use fewer stations"}},
      profile_out);
}

// Issue #39 item 6: values no vehicle or run has, refused with the documented range instead
// of burning CPU (before: a trajectory that never moves ran 2,000,000 solver steps for 13-17 s,
// cornering_stiffness 1e300 took 42 s, --jobs 1000000 started a worker per case).
TEST(CliRobustness, ImplausibleValuesAreRefusedWithTheirRange) {
  const std::string dir = scratch_file("robust_simulate_out");
  const auto body_vehicle = [](const std::string& name, const std::string& extra) {
    const std::string file = scratch_file(name);
    write_text(file,
               "model: rigid_body\nfriction: 0.7\ncg_height: 0.06\nhalf_track: 0.124\n"
               "half_wheelbase: 0.135\nmass: 2\n" +
                   extra);
    return file;
  };
  const std::string good = body_vehicle("robust_body.yaml", "");
  const std::string moving = scratch_file("robust_moving.csv");
  write_text(moving, "x,y,v\n5,20,1\n10,20,1\n15,20,0\n");
  const std::string standing = scratch_file("robust_standing.csv");
  write_text(standing, "x,y,v\n5,20,0\n10,20,0\n15,20,0\n");
  const auto simulate = [&](const std::string& vehicle_file, const std::string& trajectory) {
    return "simulate --terrain " + quoted(flat()) + " --vehicle " + quoted(vehicle_file) +
           " --trajectory " + quoted(trajectory) + " --out " + quoted(dir);
  };
  expect_refused(
      {
          {"a trajectory that never moves", simulate(good, standing), "never moves"},
          {"a tyre stiffer than any",
           simulate(body_vehicle("robust_tyre.yaml", "cornering_stiffness: 1e300\n"), moving),
           "cornering_stiffness must be in (0, 100]"},
          {"a suspension stiffer than any",
           simulate(body_vehicle("robust_spring.yaml", "suspension_stiffness: 1e300\n"), moving),
           "ride frequency"},
          {"a trace finer than memory", simulate(good, moving) + " --trace-interval 1e-9",
           "use a longer trace interval"},
      },
      dir);
  const std::string config = scratch_file("robust_sweep.yaml");
  write_text(config, "job: noop\nparameters:\n  value: [1, 2]\n");
  const std::string sweep_dir = scratch_file("robust_sweep_out");
  expect_refused({{"a million workers",
                   "sweep " + quoted(config) + " --out " + quoted(sweep_dir) + " --jobs 1000000",
                   "worker processes per core"}},
                 sweep_dir);
}

TEST(CliRobustness, APathAcrossNodataIsRefusedWhereItCrossesTheVoid) {
  // A void in the middle of the path's straight run; both way points on data.
  std::string grid =
      "ncols 31\nnrows 11\nxllcorner -0.5\nyllcorner -0.5\ncellsize 1\n"
      "NODATA_value -9999\n";
  for (int r = 0; r < 11; ++r) {
    for (int c = 0; c < 31; ++c) grid += (r == 5 && c == 15 ? "-9999" : "0") + std::string(" ");
    grid += "\n";
  }
  const std::string terrain = scratch_file("void_line.asc");
  write_text(terrain, grid);
  const std::string path = write_points("across_void.csv", {{{3, 5}}, {{27, 5}}});
  const std::string out = scratch_file("void_out.csv");
  for (const char* command : {"limits", "profile"}) {
    expect_refused(
        {{command,
          std::string(command) + " --terrain " + quoted(terrain) + " --path " + quoted(path) +
              " --vehicle " + quoted(vehicle()) + " --smoothing 1 -o " + quoted(out),
          "crosses a NODATA cell"}},
        out);
  }
}

TEST(CliRobustness, OutputFoldersHoldOneCompleteResult) {
  const std::string dir = scratch_file("robust_folder");
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_text(dir + "/plan.png", "the user's own figure");
  const std::string plan = "plan --terrain " + quoted(flat()) + " --vehicle " + quoted(vehicle()) +
                           " --start 5,20 --goal 55,20 --out " + quoted(dir);
  // A user's file of an output's name is never replaced, and nothing moves.
  RunResult r = run_capped(plan);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("was not written by talus"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(dir + "/plan.png"), "the user's own figure");
  EXPECT_FALSE(fs::exists(dir + "/summary.json"));
  fs::remove(dir + "/plan.png");

  // A full run, then a global run: the folder holds the global run's files
  // only (no stale trajectory.csv beside a summary that does not list it).
  ASSERT_EQ(run_capped(plan).exit_code, 0);
  EXPECT_TRUE(fs::exists(dir + "/trajectory.csv"));
  ASSERT_EQ(run_capped(plan + " --stage global").exit_code, 0);
  EXPECT_FALSE(fs::exists(dir + "/trajectory.csv"));
  EXPECT_TRUE(fs::exists(dir + "/candidates.csv"));
  EXPECT_EQ(parse_json(read_text(dir + "/summary.json"), "summary").value("stage", ""), "global");
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().filename().string().rfind(".talus-staging-", 0), std::string::npos)
        << "staging folder left: " << e.path();
  }
}

TEST(CliRobustness, OutputsOntoDevicesAndFifosAreRefusedAndLeftAlone) {
  // A private copy of /dev/null (never the real one: the tests run as root)
  // and a FIFO. Each -o command refuses them with one line, and the node is
  // still the same device afterwards (rename(2) would have replaced it).
  const std::string node = scratch_file("robust_null");
  fs::remove(node);
  const bool have_node = ::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
  const std::string fifo = scratch_file("robust_out.fifo");
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::vector<std::pair<std::string, std::string>> targets = {{fifo, "a FIFO"}};
  if (have_node) targets.push_back({node, "a character device"});
  for (const auto& [target, kind] : targets) {
    struct stat before {};
    ASSERT_EQ(::stat(target.c_str(), &before), 0);
    const std::string inputs = " --terrain " + quoted(flat()) + " --path " + quoted(path_file()) +
                               " --vehicle " + quoted(vehicle()) + " -o " + quoted(target);
    for (const std::string& args :
         {"profile" + inputs, "limits" + inputs,
          "terrain generate plane --ncols 5 --nrows 5 -o " + quoted(target)}) {
      const RunResult r = run_capped(args);
      EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.err;
      EXPECT_EQ(count_lines(r.err), 1u) << r.err;
      EXPECT_NE(r.err.find(kind + ", not a regular file"), std::string::npos) << r.err;
      struct stat after {};
      ASSERT_EQ(::stat(target.c_str(), &after), 0) << args << " removed " << target;
      EXPECT_EQ(after.st_mode, before.st_mode) << args;
      EXPECT_EQ(after.st_ino, before.st_ino) << args << " replaced " << target;
      EXPECT_EQ(after.st_rdev, before.st_rdev) << args;
    }
  }
  if (!have_node) GTEST_SKIP() << "mknod needs root: only the FIFO case ran";
}

TEST(CliRobustness, AnInterruptedPlanExits130AndLeavesThePreviousResult) {
  const std::string dir = scratch_file("robust_interrupted");
  fs::remove_all(dir);
  const std::string args = "plan --terrain " + quoted(flat()) + " --vehicle " + quoted(vehicle()) +
                           " --start 5,20 --goal 55,20 --stage global --out " + quoted(dir);
  ASSERT_EQ(run_capped(args).exit_code, 0);
  const std::string before = read_text(dir + "/summary.json");
  // A long plan on the same folder (32-connected, 0.05 m lattice: 10 s or more),
  // interrupted while it runs. A background command of a non-interactive shell
  // starts with SIGINT ignored, so a signal that came before talus installed
  // its handler (a slow start, e.g. under ASan on a loaded machine) was
  // ignored and the plan ran to the end; `env --default-signal=INT` starts it
  // with the default action, so an early SIGINT ends it with 130 as well.
  const std::string command = std::string("env --default-signal=INT '") + TALUS_CLI + "' " + args +
                              " --connectivity 32 --lattice-spacing 0.05 >/dev/null 2>&1 & "
                              "pid=$!; sleep 1; kill -INT $pid; wait $pid; echo $?";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char status[16] = {};
  ASSERT_NE(fgets(status, sizeof status, pipe), nullptr);
  pclose(pipe);
  EXPECT_EQ(std::stoi(status), 130);
  EXPECT_EQ(read_text(dir + "/summary.json"), before);  // the previous result, untouched
}

}  // namespace
}  // namespace talus::cli_test
