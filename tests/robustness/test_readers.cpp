// Hostile input to the readers: what is not a regular file, files larger than
// their limit, headers that claim more than the file holds, control bytes in
// messages, and the memory budget. Every case must be an InputError with a
// message naming the problem, fast and within bounded memory (CTest runs this
// suite under a prlimit address-space cap: see tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/memory_budget.hpp"
#include "talus/core/path_csv.hpp"

namespace talus {
namespace {

std::string scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "talus_robustness_readers";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = scratch(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

template <typename Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}

TEST(RobustReaders, RefuseWhatIsNotARegularFile) {
  const std::string folder = scratch("a_folder");
  std::filesystem::create_directories(folder);
  EXPECT_NE(error_of([&] { read_esri_ascii(folder); }).find("is a folder"), std::string::npos);
  EXPECT_NE(error_of([&] { read_path_csv(folder); }).find("is a folder"), std::string::npos);
  // A device without end and a FIFO nobody writes to: refused before reading.
  EXPECT_NE(error_of([] { read_esri_ascii("/dev/zero"); }).find("not a regular file"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_path_csv("/dev/zero"); }).find("not a regular file"),
            std::string::npos);
  const std::string fifo = scratch("fifo");
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(error_of([&] { read_esri_ascii(fifo); }).find("not a regular file"), std::string::npos);
  EXPECT_NE(error_of([] { read_esri_ascii("/no/such/file.asc"); }).find("cannot open"),
            std::string::npos);
}

TEST(RobustReaders, RefuseFilesAndStreamsAboveTheirLimit) {
  const std::string path = write("eleven.txt", "01234567890");
  EXPECT_EQ(read_input_file(path, 11), "01234567890");
  EXPECT_NE(error_of([&] { read_input_file(path, 10); }).find("larger than the limit"),
            std::string::npos);
  std::ifstream in(path, std::ios::binary);
  EXPECT_NE(error_of([&] { read_input_stream(in, "stream", 10); }).find("more than"),
            std::string::npos);
}

TEST(RobustReaders, AHeaderClaimingMoreThanTheFileHoldsAllocatesNothing) {
  // 100 bytes claiming 4e8 nodes: refused from the value count, before the
  // 3.5 GB grid (the suite's address-space cap would turn that into bad_alloc).
  const std::string path = write(
      "claims.asc", "ncols 20000\nnrows 20000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n");
  const std::string what = error_of([&] { read_esri_ascii(path); });
  EXPECT_NE(what.find("file ends after 3 values"), std::string::npos) << what;
  EXPECT_NE(
      error_of([] { ElevationGrid(1'000'000, 1'000'000, 1.0, 0.0, 0.0); }).find("memory budget"),
      std::string::npos);
}

TEST(RobustReaders, MisleadingHeadersGetMessagesThatSayWhatIsWrong) {
  const std::string tail = "xllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n";
  EXPECT_EQ(read_esri_ascii(write("bom.asc", "\xEF\xBB\xBFncols 2\nnrows 2\n" + tail)).ncols(), 2u);
  EXPECT_NE(error_of([&] {
              read_esri_ascii(write("n44.asc", "ncols 2 2\nnrows 2\n" + tail));
            }).find("'ncols' has more than one value"),
            std::string::npos);
  EXPECT_NE(
      error_of([&] { read_esri_ascii(write("inf.asc", "inf 2\n")); }).find("the header is missing"),
      std::string::npos);
  // An escape sequence in a key is shown escaped, never sent to the terminal.
  const std::string what =
      error_of([&] { read_esri_ascii(write("esc.asc", "n\x1b[2Jcols 2\n" + tail)); });
  EXPECT_EQ(what.find('\x1b'), std::string::npos) << what;
  EXPECT_NE(what.find("\\x1B[2J"), std::string::npos) << what;
}

TEST(RobustReaders, PrintableEscapesAndShortens) {
  EXPECT_EQ(printable("ab\x01\n\xff"), "ab\\x01\\n\\xFF");
  EXPECT_EQ(printable(std::string(100'000, 'x'), 8), "xxxxxxxx... (100000 bytes)");
  EXPECT_EQ(printable("plain"), "plain");
}

TEST(RobustReaders, TheMemoryBudgetFollowsTheEnvironmentAndRefusesWithAdvice) {
  ::setenv("TALUS_MEMORY_LIMIT_MB", "10", 1);
  EXPECT_EQ(memory_budget(), std::size_t{10} << 20);
  EXPECT_NO_THROW(require_memory(9.0 * (1 << 20), "a table", "use fewer rows"));
  const std::string what =
      error_of([] { require_memory(20.0 * (1 << 20), "a table", "use fewer rows (--rows)"); });
  EXPECT_NE(what.find("a table needs about 20 MiB, more than the memory budget of 10 MiB; use "
                      "fewer rows (--rows)"),
            std::string::npos)
      << what;
  ::unsetenv("TALUS_MEMORY_LIMIT_MB");
  EXPECT_GT(memory_budget(), std::size_t{10} << 20);
}

// A value that is not a positive number of MiB within range is refused, naming the variable:
// before, 1e30 wrapped to a budget of 0 MiB and abc, -1 and nan were silently ignored.
TEST(RobustReaders, AMemoryLimitThatIsNoNumberOfMiBIsAnInputError) {
  for (const char* bad : {"abc", "-1", "nan", "0", "1e30", "10MB", ""}) {
    ::setenv("TALUS_MEMORY_LIMIT_MB", bad, 1);
    const std::string what = error_of([] { memory_budget(); });
    EXPECT_NE(what.find("TALUS_MEMORY_LIMIT_MB must be a number of MiB in (0, 1e12]"),
              std::string::npos)
        << bad << ": " << what;
  }
  ::setenv("TALUS_MEMORY_LIMIT_MB", "1e12", 1);
  EXPECT_EQ(memory_budget(), static_cast<std::size_t>(1e12 * 1024.0 * 1024.0));
  ::unsetenv("TALUS_MEMORY_LIMIT_MB");
}

// Issue #39: a file name with a NUL byte (from Python or C++; argv cannot carry one) named
// the file before the NUL to the C library: "grid.asc\0.evil" read grid.asc. Now refused
// by every reader and writer, and nothing is written.
TEST(RobustReaders, AFileNameWithANulByteIsRefusedByReadersAndWriters) {
  const std::string real = write("nul_target.asc",
                                 "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n"
                                 "cellsize 1\n1 2\n3 4\n");
  const std::string with_nul = real + std::string(1, '\0') + ".evil";
  EXPECT_NE(error_of([&] { read_input_file(with_nul, 1000); }).find("NUL byte"), std::string::npos);
  EXPECT_NE(error_of([&] { read_esri_ascii(with_nul); }).find("NUL byte"), std::string::npos);
  const std::string fresh = scratch("nul_fresh.asc");
  std::filesystem::remove(fresh);
  ElevationGrid grid(2, 2, 1.0, 0.0, 0.0);
  EXPECT_NE(error_of([&] {
              write_esri_ascii(grid, fresh + std::string(1, '\0') + "x");
            }).find("NUL byte"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(fresh)) << "the part before the NUL was written";
}

}  // namespace
}  // namespace talus
