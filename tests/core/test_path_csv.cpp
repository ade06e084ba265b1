// The strict path CSV reader: good input in its accepted variants, and every
// kind of bad input as an InputError naming the file and line.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "talus/core/error.hpp"
#include "talus/core/path_csv.hpp"

namespace talus {
namespace {

std::vector<Vec2> parse_path(const std::string& text) {
  std::istringstream in(text);
  return read_path_csv(in, "path.csv");
}

/// Expects an InputError whose message names the source, the given line and `fragment`.
void expect_path_error(const std::string& text, int line, const std::string& fragment) {
  try {
    parse_path(text);
    ADD_FAILURE() << "no InputError for:\n" << text;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("path.csv:" + std::to_string(line) + ": "), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(PathCsv, ReadsPointsInOrder) {
  const std::vector<Vec2> p = parse_path("x,y\n0,0\n10.5,-2\n1e2,+3.25\n");
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0], Vec2(0.0, 0.0));
  EXPECT_EQ(p[1], Vec2(10.5, -2.0));
  EXPECT_EQ(p[2], Vec2(100.0, 3.25));
}

TEST(PathCsv, AcceptsBomCrlfSurroundingWhitespaceAndTrailingBlankLines) {
  const std::vector<Vec2> p =
      parse_path("\xEF\xBB\xBF x , y \r\n 556810.25 ,\t4373910\r\n-1,-2\r\n\r\n  \n\n");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], Vec2(556810.25, 4373910.0));
  EXPECT_EQ(p[1], Vec2(-1.0, -2.0));
}

TEST(PathCsv, AcceptsAMissingFinalNewlineAndNonConsecutiveRepeats) {
  const std::vector<Vec2> p = parse_path("x,y\n0,0\n1,0\n0,0");
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[2], Vec2(0.0, 0.0));
}

TEST(PathCsv, ReadsNumbersExactly) {
  const std::vector<Vec2> p = parse_path("x,y\n0.1,4374160.123456789\n-0.30000000000000004,2\n");
  EXPECT_EQ(p[0].x(), 0.1);
  EXPECT_EQ(p[0].y(), 4374160.123456789);
  EXPECT_EQ(p[1].x(), -0.30000000000000004);
}

TEST(PathCsv, RejectsAnEmptyFile) {
  expect_path_error("", 1, "empty file");
  expect_path_error("\xEF\xBB\xBF", 1, "empty file");
}

TEST(PathCsv, RejectsAMissingOrWrongHeader) {
  expect_path_error("0,0\n1,1\n", 1, "header 'x,y'");
  expect_path_error("\nx,y\n0,0\n1,1\n", 1, "header 'x,y'");
  expect_path_error("y,x\n0,0\n1,1\n", 1, "header 'x,y'");
  expect_path_error("X,Y\n0,0\n1,1\n", 1, "header 'x,y'");
  expect_path_error("x,y,z\n0,0,0\n1,1,1\n", 1, "got 'x,y,z'");
  expect_path_error("x;y\n0;0\n1;1\n", 1, "header 'x,y'");
}

TEST(PathCsv, RejectsAWrongColumnCount) {
  expect_path_error("x,y\n0,0\n1,1,1\n", 3, "expected 2 columns x,y, got 3");
  expect_path_error("x,y\n0,0\n1\n", 3, "expected 2 columns x,y, got 1");
  expect_path_error("x,y\n0 0\n1,1\n", 2, "got 1");
  expect_path_error("x,y\n0,0\n1,1,\n", 3, "got 3");
}

TEST(PathCsv, RejectsNonNumericValues) {
  expect_path_error("x,y\n0,0\n1,abc\n", 3, "y value 'abc' is not a number");
  expect_path_error("x,y\n0,0\n1m,2\n", 3, "x value '1m' is not a number");
  expect_path_error("x,y\n0,0\n,2\n", 3, "x value is empty");
  expect_path_error("x,y\n0,0\n0x10,2\n", 3, "is not a number");
  expect_path_error("x,y\n0,0\n+-1,2\n", 3, "is not a number");
  expect_path_error("x,y\n0,0\n1 2,3\n", 3, "x value '1 2' is not a number");
  expect_path_error("x,y\n0,0\n1e999,3\n", 3, "out of range");
}

TEST(PathCsv, RejectsNanAndInf) {
  expect_path_error("x,y\n0,0\nnan,1\n", 3, "not finite");
  expect_path_error("x,y\n0,0\n1,inf\n", 3, "not finite");
  expect_path_error("x,y\n-INFINITY,0\n1,1\n", 2, "not finite");
}

TEST(PathCsv, RejectsFewerThanTwoPoints) {
  expect_path_error("x,y\n", 1, "at least 2 points, got 0");
  expect_path_error("x,y\n\n\n", 1, "at least 2 points, got 0");
  expect_path_error("x,y\n5,5\n\n", 2, "at least 2 points, got 1");
}

TEST(PathCsv, RejectsConsecutiveIdenticalPoints) {
  expect_path_error("x,y\n0,0\n1,1\n1.0,1e0\n2,2\n", 4,
                    "point 2 (1, 1) repeats the previous point");
}

TEST(PathCsv, RejectsDataAfterABlankLine) {
  expect_path_error("x,y\n0,0\n\n1,1\n", 4, "after the blank line 3");
}

TEST(PathCsv, ReadsAFileAndNamesItInErrors) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("talus_path_csv_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string good = (dir / "good.csv").string(), bad = (dir / "bad.csv").string();
  std::ofstream(good) << "x,y\n1,2\n3,4\n";
  std::ofstream(bad) << "x,y\n1,2\n3,four\n";
  EXPECT_EQ(read_path_csv(good).size(), 2u);
  try {
    read_path_csv(bad);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad + ":3: "), std::string::npos) << e.what();
  }
  try {
    read_path_csv((dir / "missing.csv").string());
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.csv: cannot open"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace talus

namespace talus {
namespace {

// Issue #39 item 4: a 10^7-point path reached 1.6 GB before running out of memory. The
// reader stops at the first point beyond kMaxPathPoints, naming its line.
TEST(PathCsv, APathBeyondTheMostPointsIsRefusedAtItsFirstExtraLine) {
  std::string text = "x,y\n";
  text.reserve(16 * (kMaxPathPoints + 2));
  for (std::size_t k = 0; k <= kMaxPathPoints; ++k) text += std::to_string(k) + ",0\n";
  std::istringstream in(text);
  try {
    read_path_csv(in, "long.csv");
    ADD_FAILURE() << "a path of " << kMaxPathPoints + 1 << " points was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("long.csv:" + std::to_string(kMaxPathPoints + 2) + ":"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("thin the path"), std::string::npos) << e.what();
  }
  text.resize(text.rfind(std::to_string(kMaxPathPoints) + ",0\n"));  // exactly the most
  std::istringstream ok(text);
  EXPECT_EQ(read_path_csv(ok, "long.csv").size(), kMaxPathPoints);
}

}  // namespace
}  // namespace talus
