// A sweep resumes from DIR/results*.jsonl: those files are input like any other (issue 39's
// "sweep resume trusts results.jsonl"): a line nested 200 000 deep, a FIFO or a link to
// /dev/zero in their place must neither crash, block nor fill the memory.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "talus/core/error.hpp"
#include "talus/sweep/sweep_runner.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

/// A fresh folder under the test's temporary directory.
fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("talus-sweep-resume-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(SweepResume, ALineNestedBeyondARecordsDepthIsSkippedTheOthersKept) {
  const fs::path dir = fresh_dir("deep");
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  write(dir / "results.jsonl", "{\"case_id\": \"a\", \"status\": \"ok\"}\n" + deep + "\n" +
                                   "{\"case_id\": \"b\", \"figures\": {\"t\": [1, [2]]}}\n");
  const auto records = read_sweep_records(dir);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].at("case_id"), "a");
  EXPECT_EQ(records[1].at("case_id"), "b");  // depth 3 is a record's
  fs::remove_all(dir);
}

TEST(SweepResume, AFifoOrALinkToADeviceIsAnInputErrorAtOnce) {
  const fs::path dir = fresh_dir("special");
  ASSERT_EQ(::mkfifo((dir / "results.jsonl").c_str(), 0600), 0);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_THROW(read_sweep_records(dir), InputError);  // no writer: opening it would block
  fs::remove(dir / "results.jsonl");
  fs::create_symlink("/dev/zero", dir / "results.jsonl");
  try {
    read_sweep_records(dir);
    ADD_FAILURE() << "a link to /dev/zero was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("results.jsonl"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  fs::remove_all(dir);
}

TEST(SweepResume, AFolderWithoutResultsHasNoRecords) {
  const fs::path dir = fresh_dir("empty");
  EXPECT_TRUE(read_sweep_records(dir).empty());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace talus
