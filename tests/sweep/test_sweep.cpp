// `talus sweep`: the config's designs and errors (library), and end to end
// through the CLI: nothing lost when the sweep is killed, crashed and hung
// workers, the lock, and results that do not depend on the job or rank count.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <thread>

#include "cli_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/sweep/mpi_session.hpp"
#include "talus/sweep/sweep_config.hpp"

namespace {

using talus::InputError;
using talus::MpiSession;
using talus::parse_sweep_config;
using talus::SweepConfig;
using namespace talus::cli_test;
namespace fs = std::filesystem;

const std::string kReadmeConfig = R"(job: plan
design: grid
parameters:
  terrain.generator: fractal
  terrain.ncols: 65
  terrain.nrows: 65
  terrain.seed: [1, 2, 3, 4]
  vehicle.file: data/vehicles/rover.yaml
  vehicle.friction: [0.5, 0.7]
  start: "2,2"
  goal: "13,13"
)";

TEST(SweepConfig, GridIsTheCartesianProductWithTheLastParameterFastest) {
  const SweepConfig config = parse_sweep_config(kReadmeConfig, "readme.yaml");
  ASSERT_EQ(config.cases.size(), 8u);
  EXPECT_EQ(config.swept, (std::vector<std::string>{"terrain.seed", "vehicle.friction"}));
  std::set<std::string> ids;
  for (std::size_t i = 0; i < 8; ++i) {
    const auto& p = config.cases[i].parameters;
    EXPECT_EQ(p.at("terrain.seed"), static_cast<int>(i / 2) + 1);
    EXPECT_EQ(p.at("vehicle.friction"), i % 2 == 0 ? 0.5 : 0.7);
    EXPECT_EQ(p.at("start"), "2,2");  // quoted: text, not a number
    EXPECT_EQ(config.cases[i].id.size(), 16u);
    ids.insert(config.cases[i].id);
  }
  EXPECT_EQ(ids.size(), 8u);
}

TEST(SweepConfig, CaseIdsDependOnTheParametersNotTheirOrder) {
  const SweepConfig a = parse_sweep_config(kReadmeConfig, "a.yaml");
  const SweepConfig b = parse_sweep_config(R"(job: plan
parameters:
  vehicle.friction: [0.7, 0.5]
  goal: "13,13"
  start: "2,2"
  terrain.seed: [4, 3, 2, 1]
  terrain.nrows: 65
  terrain.ncols: 65
  vehicle.file: data/vehicles/rover.yaml
  terrain.generator: fractal
)",
                                           "b.yaml");
  std::set<std::string> ids_a, ids_b;
  for (const auto& c : a.cases) ids_a.insert(c.id);
  for (const auto& c : b.cases) ids_b.insert(c.id);
  EXPECT_EQ(ids_a, ids_b);
  const SweepConfig other_job =
      parse_sweep_config("job: noop\nparameters:\n  value: [1, 2]\n", "c.yaml");
  const SweepConfig same_values =
      parse_sweep_config("job: profile\nparameters:\n  value: [1, 2]\n", "d.yaml");
  EXPECT_NE(other_job.cases[0].id, same_values.cases[0].id);
}

// Issue #39 item 4: a grid's size is known before any case is built; 10^20 cases grew to
// gigabytes before it ran out of memory, now it is one line at once (and the cap is met).
/// The InputError message of a grid of `axes` parameters of ten values each, or "".
std::string grid_error(int axes) {
  std::string config = "job: noop\nparameters:\n";
  for (int axis = 0; axis < axes; ++axis)
    config += "  p" + std::to_string(axis) + ": [0, 1, 2, 3, 4, 5, 6, 7, 8, 9]\n";
  try {
    parse_sweep_config(config, "grid.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SweepConfig, AGridBeyondTheCaseCapIsRefusedBeforeItIsBuilt) {
  EXPECT_NE(grid_error(20).find("at most 1000000"), std::string::npos) << grid_error(20);
  // Just above the cap: 10^7 cases, named in the message.
  EXPECT_NE(grid_error(7).find("1e+07 cases"), std::string::npos) << grid_error(7);
  EXPECT_EQ(grid_error(2), "");  // 100 cases
}

TEST(SweepConfig, RandomDesignIsReproducibleFromItsSeed) {
  const std::string text = R"(job: noop
design: random
samples: 50
seed: 7
parameters:
  value: {uniform: [0.25, 0.75]}
  sleep: {integers: [0, 3]}
  crash: [false]
)";
  const SweepConfig a = parse_sweep_config(text, "r.yaml");
  const SweepConfig b = parse_sweep_config(text, "r.yaml");
  const SweepConfig c = parse_sweep_config(
      text.substr(0, text.find("seed: 7")) + "seed: 8" + text.substr(text.find("seed: 7") + 7),
      "r.yaml");
  ASSERT_EQ(a.cases.size(), 50u);
  std::set<long long> integers;
  for (std::size_t i = 0; i < 50; ++i) {
    EXPECT_EQ(a.cases[i].parameters, b.cases[i].parameters);
    const double v = a.cases[i].parameters.at("value").get<double>();
    EXPECT_GE(v, 0.25);
    EXPECT_LT(v, 0.75);
    ASSERT_TRUE(a.cases[i].parameters.at("sleep").is_number_integer());
    integers.insert(a.cases[i].parameters.at("sleep").get<long long>());
  }
  EXPECT_EQ(integers, (std::set<long long>{0, 1, 2, 3}));  // both ends drawn
  EXPECT_NE(a.cases[0].parameters, c.cases[0].parameters);
}

TEST(SweepConfig, ListDesignMergesTheCommonParameters) {
  const SweepConfig config = parse_sweep_config(R"(job: noop
design: list
parameters:
  sleep: 0
cases:
  - {value: 1}
  - {value: 2, crash: true}
)",
                                                "l.yaml");
  ASSERT_EQ(config.cases.size(), 2u);
  EXPECT_EQ(config.cases[1].parameters.at("sleep"), 0);
  EXPECT_EQ(config.cases[1].parameters.at("crash"), true);
  EXPECT_EQ(config.swept, (std::vector<std::string>{"value", "crash"}));
}

TEST(SweepConfig, BadConfigsNameTheProblem) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"job: fly\nparameters:\n  a: 1\n", "unknown job 'fly'"},
      {"job: plan\nparameters:\n  a: 1\njobs: 2\n", "unknown key 'jobs'"},
      {"job: plan\ndesign: grid\n", "design grid has no parameters"},
      {"job: plan\nparameters: {}\n", "design grid has no parameters"},
      {"job: plan\nparameters:\n  seed: []\n", "empty list of values"},
      {"job: plan\ndesign: list\ncases: []\n", "non-empty `cases:`"},
      {"job: plan\ndesign: sobol\nparameters:\n  a: 1\n", "unknown design 'sobol'"},
      {"job: plan\ndesign: random\nparameters:\n  a: 1\n", "needs `samples:`"},
      {"job: plan\nparameters:\n  a: [1, 1]\n", "have the same parameters"},
      {"job: plan\nparameters:\n  a: 1\nretries: -1\n", "`retries:`"},
      {"job: plan\nparameters:\n  a: 1\n  a: 2\n", "a"},
      {"parameters:\n  a: 1\n", "missing `job:`"},
  };
  for (const auto& [text, fragment] : cases) {
    try {
      parse_sweep_config(text, "bad.yaml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("bad.yaml", 0), 0u) << message;
      EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " not in " << message;
    }
  }
}

TEST(SweepConfig, RobotFileIsTheBaselinesRobotTakenFromTheBaseFolder) {
  SweepConfig config = parse_sweep_config(
      "job: baseline hait\nparameters:\n  robot.file: robots/r.yaml\n  start: \"1,1,0\"\n",
      "robot.yaml");
  config.base_dir = "/base";
  const talus::PreparedCase prepared =
      talus::prepare_case(config, config.cases.front(), "/cases/one");
  ASSERT_EQ(prepared.commands.size(), 1u);
  const std::vector<std::string> expected = {"baseline", "hait",  "--robot", "/base/robots/r.yaml",
                                             "--start",  "1,1,0", "--out",   "/cases/one/out"};
  EXPECT_EQ(prepared.commands.front(), expected);
  config = parse_sweep_config("job: baseline hait\nparameters:\n  robot.mass: 3\n", "r.yaml");
  EXPECT_THROW(talus::prepare_case(config, config.cases.front(), "/cases/one"), InputError);
}

// --- end to end -------------------------------------------------------------

/// A fresh scratch folder for one sweep.
fs::path fresh_dir(const std::string& name) {
  const fs::path dir = scratch_dir() / name;
  fs::remove_all(dir);
  return dir;
}

std::string write_config(const std::string& name, const std::string& text) {
  const std::string file = scratch_file(name);
  write_text(file, text);
  return file;
}

/// results.csv without the columns that time the run (seconds, attempts).
std::string results_without_timings(const fs::path& dir) {
  std::ifstream in(dir / "results.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_NE(header.find(",seconds,attempts,reason"), std::string::npos) << header;
  std::string out;
  for (std::string line; std::getline(in, line);) {
    // The last three fields: seconds, attempts, reason (reason never has commas here).
    std::size_t cut = line.size();
    for (int k = 0; k < 3; ++k) cut = line.rfind(',', cut - 1);
    out += line.substr(0, cut) + "|" + line.substr(line.rfind(',') + 1) + "\n";
  }
  return header + "\n" + out;
}

std::vector<nlohmann::json> jsonl_records(const fs::path& file) {
  std::vector<nlohmann::json> records;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) records.push_back(nlohmann::json::parse(line));
  return records;
}

/// Planes of three slopes for a vehicle of two friction coefficients: six
/// small plans with travel times that differ.
std::string plane_config() {
  return write_config("planes.yaml",
                      "job: plan\nparameters:\n"
                      "  terrain.generator: plane\n"
                      "  terrain.ncols: 21\n  terrain.nrows: 21\n"
                      "  terrain.slope: [0, 0.1, 0.2]\n"
                      "  vehicle.file: " +
                          data_file("vehicles/rover.yaml") +
                          "\n"
                          "  vehicle.friction: [0.5, 0.7]\n"
                          "  start: \"1,1\"\n  goal: \"19,17\"\n"
                          "  candidates: 1\n  no_figures: true\n");
}

/// Starts `talus ARGS` (after `launcher`, e.g. mpirun, if given) in its own
/// process group, output discarded; returns its pid.
pid_t start_talus(const std::string& args, const std::string& launcher = "") {
  const std::string command =
      "exec " + launcher + "'" + std::string(TALUS_CLI) + "' " + args + " >/dev/null 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);
  return pid;
}

std::size_t lines_in(const fs::path& file) {
  return fs::exists(file) ? count_lines(read_text(file.string())) : 0;
}

TEST(SweepCli, TheReadmeConfigRunsAsWrittenFromTheRepositoryRoot) {
  const fs::path dir = fresh_dir("readme_sweep");
  const fs::path root = fs::path(TALUS_DATA_DIR).parent_path();
  // As the README runs it: from the repository root, with the config's relative paths.
  const std::string command = "cd " + quoted(root.string()) + " && '" + std::string(TALUS_CLI) +
                              "' sweep data/sweeps/example.yaml --out " + quoted(dir.string()) +
                              " --jobs 2 >" + quoted(scratch_file("readme.out")) + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(scratch_file("readme.out"));
  std::ifstream in(dir / "results.csv");
  std::string header;
  std::getline(in, header);
  for (const char* column : {"case_id,", ",terrain.seed,", ",vehicle.friction,", ",status,",
                             ",travel_time,", ",seconds,"}) {
    EXPECT_NE(header.find(column), std::string::npos) << column << " not in " << header;
  }
  EXPECT_EQ(lines_in(dir / "results.csv"), 9u);
  EXPECT_EQ(jsonl_records(dir / "results.jsonl").size(), 8u);
  EXPECT_TRUE(fs::exists(dir / "report.md"));
}

// Issue #39 item 6: a case is ok only when its job printed its result. A `help: true`
// parameter becomes `--help`: the job prints its usage and exits 0; that case was "ok"
// with no figures, now it is no_result with the reason, and the other case is ok.
TEST(SweepCli, ACaseWhoseJobPrintsNoResultIsNotOk) {
  const fs::path dir = fresh_dir("help_sweep");
  const std::string config =
      write_config("help.yaml",
                   "job: plan\ndesign: list\nparameters:\n"
                   "  terrain.generator: plane\n  terrain.ncols: 21\n  terrain.nrows: 21\n"
                   "  vehicle.file: " +
                       data_file("vehicles/rover.yaml") +
                       "\n  start: \"1,1\"\n  goal: \"19,17\"\n  candidates: 1\n"
                       "  no_figures: true\n"
                       "cases:\n  - {stage: global}\n  - {stage: global, help: true}\n");
  const RunResult r =
      run_talus("sweep " + quoted(config) + " --out " + quoted(dir.string()) + " --jobs 1");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::vector<nlohmann::json> records = jsonl_records(dir / "results.jsonl");
  ASSERT_EQ(records.size(), 2u);
  int ok = 0, no_result = 0;
  for (const nlohmann::json& record : records) {
    const bool helped = record.at("parameters").contains("help");
    EXPECT_EQ(record.at("status"), helped ? "no_result" : "ok") << record.dump();
    if (helped) {
      EXPECT_NE(record.at("reason").get<std::string>().find("without a JSON result"),
                std::string::npos);
    }
    ok += record.at("status") == "ok";
    no_result += record.at("status") == "no_result";
  }
  EXPECT_EQ(ok, 1);
  EXPECT_EQ(no_result, 1);
}

// job: navigate runs `talus navigate` per case: near-optimal and standard navigation of the
// paper's UGV across a flat field both reach the goal; each record carries the navigation's
// summary (status, optimal and navigation times), and only the lookahead run caps its speed.
TEST(SweepCli, NavigateJobRunsTheLayeredSchemePerCase) {
  const std::string config =
      write_config("navigate.yaml",
                   "job: navigate\nparameters:\n"
                   "  terrain.generator: plane\n"
                   "  terrain.ncols: 61\n  terrain.nrows: 25\n  terrain.cellsize: 0.25\n"
                   "  vehicle.file: " +
                       data_file("vehicles/iagnemma_ugv.yaml") +
                       "\n  start: \"1,3\"\n  goal: \"13,3\"\n"
                       "  no_lookahead: [false, true]\n  no_figures: true\n");
  const fs::path dir = fresh_dir("navigate_sweep");
  const RunResult r =
      run_talus("sweep " + quoted(config) + " --out " + quoted(dir.string()) + " --jobs 2");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const auto records = jsonl_records(dir / "results.jsonl");
  ASSERT_EQ(records.size(), 2u);
  for (const nlohmann::json& record : records) {
    EXPECT_EQ(record.at("status"), "reached") << record.dump();
    const nlohmann::json& f = record.at("figures");
    EXPECT_GT(f.at("optimal_time").get<double>(), 12.0 / 6.0);  // 12 m at the 6 m/s top speed
    EXPECT_GT(f.at("navigation_time").get<double>(), f.at("optimal_time").get<double>() * 0.5);
    EXPECT_EQ(f.at("lookahead").get<bool>(), record.at("parameters").at("no_lookahead") == false);
    if (!f.at("lookahead").get<bool>()) {
      EXPECT_EQ(f.at("lookahead_caps_applied"), 0);
    }
  }
  std::ifstream in(dir / "results.csv");
  std::string header;
  std::getline(in, header);
  for (const char* column : {",no_lookahead,", ",status,", ",navigation_time,", ",optimal_time,"})
    EXPECT_NE(header.find(column), std::string::npos) << column << " not in " << header;
}

TEST(SweepCli, ResultsDoNotDependOnTheJobCount) {
  const std::string config = plane_config();
  const fs::path one = fresh_dir("jobs1"), two = fresh_dir("jobs2");
  ASSERT_EQ(run_talus("sweep " + quoted(config) + " --out " + quoted(one.string()) + " --jobs 1")
                .exit_code,
            0);
  ASSERT_EQ(run_talus("sweep " + quoted(config) + " --out " + quoted(two.string()) + " --jobs 2")
                .exit_code,
            0);
  const std::string a = results_without_timings(one);
  EXPECT_EQ(a, results_without_timings(two));
  EXPECT_EQ(count_lines(a), 7u);
  // Steeper planes are slower: the sweep measured something.
  const auto records = jsonl_records(one / "results.jsonl");
  ASSERT_EQ(records.size(), 6u);
  EXPECT_EQ(records[0].at("status"), "ok");
  EXPECT_LT(records[0].at("figures").at("travel_time").get<double>(),
            records[4].at("figures").at("travel_time").get<double>());
  EXPECT_TRUE(fs::exists(one / "sweep_1.png"));
}

const std::string kMpirun =
    "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_warn_on_fork=0 "
    "mpirun --oversubscribe -n 2 ";

/// Records in every results file of `dir`.
std::size_t records_in(const fs::path& dir) {
  return lines_in(dir / "results.jsonl") + lines_in(dir / "results.rank-1.jsonl");
}

/// Starts the plane sweep (through `launcher`, empty or mpirun), kills it
/// and its workers with SIGKILL after two records, tears the last line, and
/// resumes: one record per case, the uninterrupted run's values.
void kill_and_resume(const std::string& launcher, const std::string& name) {
  const std::string config = plane_config();
  const fs::path reference = fresh_dir(name + "_uninterrupted"), dir = fresh_dir(name);
  ASSERT_EQ(
      run_talus("sweep " + quoted(config) + " --out " + quoted(reference.string()) + " --jobs 1")
          .exit_code,
      0);

  const pid_t pid = start_talus(
      "sweep " + quoted(config) + " --out " + quoted(dir.string()) + " --jobs 2", launcher);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (records_in(dir) < 2 && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  kill(-pid, SIGKILL);  // mpirun, its ranks and their workers: one process group
  waitpid(pid, nullptr, 0);
  const std::size_t at_kill = records_in(dir);
  ASSERT_GE(at_kill, 2u);
  ASSERT_LT(at_kill, 6u) << "the sweep ended before it was killed: the test proves nothing";
  {  // the kill may land while a line is written: make sure one is torn
    std::ofstream torn(dir / "results.jsonl", std::ios::app);
    torn << R"({"case_id":"0123456789abcdef","status":"o)";
  }
  const RunResult resumed =
      run_talus("sweep " + quoted(config) + " --out " + quoted(dir.string()) + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find(std::to_string(at_kill) + " already done"), std::string::npos)
      << resumed.out;
  std::vector<nlohmann::json> records =
      jsonl_records(dir / "results.jsonl");  // the torn line is gone
  if (fs::exists(dir / "results.rank-1.jsonl")) {
    for (auto& r : jsonl_records(dir / "results.rank-1.jsonl")) records.push_back(r);
  }
  std::set<std::string> ids;
  for (const auto& r : records) ids.insert(r.at("case_id").get<std::string>());
  EXPECT_EQ(records.size(), 6u);
  EXPECT_EQ(ids.size(), 6u);
  EXPECT_EQ(results_without_timings(dir), results_without_timings(reference));
}

TEST(SweepCli, AKilledSweepResumesToOneRowPerCaseWithTheSameValues) {
  kill_and_resume("", "killed");
}

TEST(SweepCli, AKilledMpiSweepResumesToOneRowPerCaseWithTheSameValues) {
  if (!MpiSession::mpirun_available())
    GTEST_SKIP() << "no mpirun (openmpi-bin), or an AddressSanitizer build";
  kill_and_resume(kMpirun, "killed_mpi");
}

TEST(SweepCli, ACrashingWorkerIsRetriedThenRecordedAsFailed) {
  const std::string config =
      write_config("crash.yaml",
                   "job: noop\ndesign: list\nretries: 2\ncases:\n  - {value: 1}\n"
                   "  - {value: 2, crash: true}\n  - {value: 3}\n");
  const fs::path dir = fresh_dir("crash");
  const RunResult r = run_talus("sweep " + quoted(config) + " --out " + quoted(dir.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto records = jsonl_records(dir / "results.jsonl");
  ASSERT_EQ(records.size(), 3u);
  for (const auto& record : records) {
    const int value = record.at("parameters").at("value");
    if (value == 2) {
      EXPECT_EQ(record.at("status"), "failed");
      EXPECT_EQ(record.at("attempts"), 3);
      EXPECT_NE(record.at("reason").get<std::string>().find("signal 6"), std::string::npos)
          << record.dump();
    } else {
      EXPECT_EQ(record.at("status"), "ok");
      EXPECT_EQ(record.at("figures").at("value"), value);
      EXPECT_EQ(record.at("attempts"), 1);
    }
  }
  EXPECT_NE(r.out.find("2 retries"), std::string::npos) << r.out;
}

TEST(SweepCli, AHangingCaseIsStoppedAtTheCaseTimeLimit) {
  const std::string config = write_config(
      "hang.yaml",
      "job: noop\ndesign: list\nretries: 1\ncases:\n  - {sleep: 600}\n  - {value: 5}\n");
  const fs::path dir = fresh_dir("hang");
  const RunResult r = run_talus("sweep " + quoted(config) + " --out " + quoted(dir.string()) +
                                " --case-time-limit 0.2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto records = jsonl_records(dir / "results.jsonl");
  ASSERT_EQ(records.size(), 2u);
  const auto& hung = records[0].at("parameters").contains("sleep") ? records[0] : records[1];
  EXPECT_EQ(hung.at("status"), "failed");
  EXPECT_EQ(hung.at("attempts"), 2);
  EXPECT_NE(hung.at("reason").get<std::string>().find("case time limit of 0.2 s"),
            std::string::npos);
}

TEST(SweepCli, ASecondSweepOnTheSameFolderIsRefused) {
  const std::string config =
      write_config("slow.yaml", "job: noop\ndesign: list\ncases:\n  - {sleep: 30}\n");
  const fs::path dir = fresh_dir("locked");
  const pid_t first = start_talus("sweep " + quoted(config) + " --out " + quoted(dir.string()));
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!fs::exists(dir / "cases") && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // past the lock
  const RunResult second = run_talus("sweep " + quoted(config) + " --out " + quoted(dir.string()));
  kill(-first, SIGKILL);
  waitpid(first, nullptr, 0);
  EXPECT_EQ(second.exit_code, 1);
  EXPECT_NE(second.err.find("in use by another sweep"), std::string::npos) << second.err;
  EXPECT_EQ(count_lines(second.err), 1u);
}

TEST(SweepCli, BadConfigsFailBeforeAnyCaseRuns) {
  const fs::path dir = fresh_dir("bad");
  const std::string planes =
      "job: plan\nparameters:\n  terrain.generator: plane\n"
      "  vehicle.file: " +
      data_file("vehicles/rover.yaml") + "\n";
  const std::vector<ErrorCase> cases = {
      {quoted(write_config("b1.yaml", planes + "  bogus_option: [1, 2]\n")),
       "`talus plan` has no option --bogus-option"},
      {quoted(write_config("b2.yaml", planes + "  terrain.wobble: 3\n")),
       "`talus terrain generate plane` has no option --wobble"},
      {quoted(write_config("b3.yaml", planes + "  vehicle.wheels: 6\n")), "wheels"},
      {quoted(write_config("b4.yaml", "job: plan\ndesign: grid\n")), "has no parameters"},
      {quoted(write_config("b5.yaml", "job: walk\nparameters:\n  a: 1\n")), "unknown job 'walk'"},
      {quoted(scratch_file("missing.yaml")), "missing.yaml"},
  };
  expect_bad_input(
      "sweep",
      [&] {
        std::vector<ErrorCase> with_out;
        for (ErrorCase c : cases) {
          c.args += " --out " + quoted(dir.string());
          with_out.push_back(c);
        }
        return with_out;
      }(),
      (dir / "results.jsonl").string());
}

TEST(SweepCli, TwoMpiRanksGiveTheResultsOfOneJob) {
  if (!MpiSession::mpirun_available())
    GTEST_SKIP() << "no mpirun (openmpi-bin), or an AddressSanitizer build";
  const std::string config = plane_config();
  const fs::path one = fresh_dir("mpi_jobs1"), ranks = fresh_dir("mpi_ranks2");
  ASSERT_EQ(run_talus("sweep " + quoted(config) + " --out " + quoted(one.string()) + " --jobs 1")
                .exit_code,
            0);
  const std::string command = kMpirun + "'" + std::string(TALUS_CLI) + "' sweep " + quoted(config) +
                              " --out " + quoted(ranks.string()) + " --jobs 1 >" +
                              quoted(scratch_file("mpi.out")) + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(scratch_file("mpi.out"));
  EXPECT_EQ(results_without_timings(ranks), results_without_timings(one));
  EXPECT_EQ(records_in(ranks), 6u);  // each case once, on whichever rank it was dealt to
}

TEST(SweepCli, MpiRanksTakeTheNextCaseWhenTheyFreeUp) {
  if (!MpiSession::mpirun_available())
    GTEST_SKIP() << "no mpirun (openmpi-bin), or an AddressSanitizer build";
  // One slow case first, then quick ones: with the cases dealt one at a
  // time, the rank that drew the slow case runs only it (a static share,
  // index mod 2, would give each rank three).
  const std::string config = write_config("uneven.yaml", R"(job: noop
design: list
parameters:
  crash: false
cases:
  - {value: 0, sleep: 3}
  - {value: 1}
  - {value: 2}
  - {value: 3}
  - {value: 4}
  - {value: 5}
)");
  const fs::path dir = fresh_dir("mpi_uneven");
  const std::string command = kMpirun + "'" + std::string(TALUS_CLI) + "' sweep " + quoted(config) +
                              " --out " + quoted(dir.string()) + " --jobs 1 >" +
                              quoted(scratch_file("uneven.out")) + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(scratch_file("uneven.out"));
  std::map<int, std::vector<int>> values_by_rank;
  for (const fs::path& file : {dir / "results.jsonl", dir / "results.rank-1.jsonl"}) {
    for (const auto& r : jsonl_records(file)) {
      values_by_rank[r.at("rank").get<int>()].push_back(r.at("figures").at("value").get<int>());
    }
  }
  ASSERT_EQ(values_by_rank.size(), 2u);
  const int slow_rank = std::count(values_by_rank[0].begin(), values_by_rank[0].end(), 0) ? 0 : 1;
  EXPECT_EQ(values_by_rank[slow_rank], std::vector<int>{0});
  EXPECT_EQ(values_by_rank[1 - slow_rank].size(), 5u);
}

}  // namespace
