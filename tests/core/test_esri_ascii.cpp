#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"

namespace talus {
namespace {

ElevationGrid parse(const std::string& text) {
  std::istringstream in(text);
  return read_esri_ascii(in, "test.asc");
}

/// Expects an InputError whose message names the source and the given line.
void expect_error_at_line(const std::string& text, int line, const std::string& fragment) {
  try {
    parse(text);
    ADD_FAILURE() << "no InputError for:\n" << text;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test.asc:" + std::to_string(line) + ":"), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

const char* const kHeader =
    "ncols 3\nnrows 2\nxllcorner 100\nyllcorner 200\ncellsize 10\nNODATA_value -9999\n";

TEST(EsriAscii, ReadsCornerHeaderAndFlipsRowsToSouthFirst) {
  const ElevationGrid grid = parse(std::string(kHeader) + "1 2 3\n4 5 -9999\n");
  EXPECT_EQ(grid.ncols(), 3u);
  EXPECT_EQ(grid.nrows(), 2u);
  EXPECT_DOUBLE_EQ(grid.x_min(), 105.0);  // centre of the south-west cell
  EXPECT_DOUBLE_EQ(grid.y_min(), 205.0);
  EXPECT_DOUBLE_EQ(grid.at(0, 1), 1.0);  // first line of values is the northern row
  EXPECT_DOUBLE_EQ(grid.at(0, 0), 4.0);
  EXPECT_FALSE(grid.valid(2, 0));
  EXPECT_EQ(grid.void_count(), 1u);
}

TEST(EsriAscii, ReadsCentreHeaderAnyCaseAnyWhitespaceAndNoNodataKey) {
  const ElevationGrid grid = parse(
      "NCOLS\t2\r\n  nrows 2\r\nXLLCENTER 1.5\r\nyllcenter -2.5\r\nCellSize 0.5\r\n"
      "1.5 2e1\r\n\r\n  -3 +4\r\n");
  EXPECT_DOUBLE_EQ(grid.x_min(), 1.5);
  EXPECT_DOUBLE_EQ(grid.y_min(), -2.5);
  EXPECT_DOUBLE_EQ(grid.at(1, 1), 20.0);
  EXPECT_DOUBLE_EQ(grid.at(1, 0), 4.0);
  EXPECT_EQ(grid.void_count(), 0u);
}

TEST(EsriAscii, AcceptsRowsWrappedOverSeveralLines) {
  const ElevationGrid grid = parse(std::string(kHeader) + "1 2\n3 4\n5\n6\n");
  EXPECT_DOUBLE_EQ(grid.at(2, 0), 6.0);
}

TEST(EsriAscii, RoundTripIsExact) {
  ElevationGrid grid(7, 5, 0.3, -12.34, 56.78);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i)
      grid.at(i, j) = std::sin(0.37 * static_cast<double>(i)) * 1e3 / 3.0 + static_cast<double>(j);
  grid.set_void(3, 2);
  std::stringstream buffer;
  write_esri_ascii(grid, buffer);
  const ElevationGrid back = read_esri_ascii(buffer, "buffer");
  ASSERT_EQ(back.ncols(), grid.ncols());
  ASSERT_EQ(back.nrows(), grid.nrows());
  EXPECT_NEAR(back.x_min(), grid.x_min(), 1e-12);
  EXPECT_NEAR(back.y_min(), grid.y_min(), 1e-12);
  EXPECT_DOUBLE_EQ(back.cellsize(), grid.cellsize());
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      ASSERT_EQ(back.valid(i, j), grid.valid(i, j));
      if (grid.valid(i, j)) {
        EXPECT_EQ(back.at(i, j), grid.at(i, j));  // bit-exact
      }
    }
}

TEST(EsriAscii, RejectsWrongCounts) {
  expect_error_at_line(std::string(kHeader) + "1 2 3\n4 5\n", 8, "expected ncols x nrows");
  expect_error_at_line(std::string(kHeader) + "1 2 3\n4 5 6\n7\n", 9, "more values");
  expect_error_at_line(std::string(kHeader) + "1 2 3 4\n5 6\n", 7, "expected ncols = 3");
}

TEST(EsriAscii, RejectsNonNumericAndNonFiniteValues) {
  expect_error_at_line(std::string(kHeader) + "1 2 3\n4 x 6\n", 8, "'x' is not a number");
  expect_error_at_line(std::string(kHeader) + "1 2 3\n4 5.5.5 6\n", 8, "not a number");
  expect_error_at_line(std::string(kHeader) + "1 nan 3\n4 5 6\n", 7, "not finite");
  expect_error_at_line(std::string(kHeader) + "1 2 3\n4 5 inf\n", 8, "not finite");
  expect_error_at_line(std::string(kHeader) + "1 2 3\n4 5 1e999\n", 8,
                       "out of the range of a double");
  expect_error_at_line(std::string(kHeader) + "1 2 3\n4 5 1e-400\n", 8,
                       "out of the range of a double");
  expect_error_at_line(std::string(kHeader) + "1 2 3\n4 5 abc\n", 8, "not a number");
}

TEST(EsriAscii, RejectsBadHeaders) {
  expect_error_at_line("nrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", 1,
                       "missing header key ncols");
  expect_error_at_line("ncols 2\nnrows 2\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", 1, "xllcorner");
  expect_error_at_line("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0\n1 2\n3 4\n", 5,
                       "cellsize must be positive");
  expect_error_at_line("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -3\n1 2\n3 4\n", 5,
                       "cellsize must be positive");
  expect_error_at_line("ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", 1,
                       "integer");
  expect_error_at_line("ncols 2\nncols 2\n", 2, "appears twice");
  expect_error_at_line("ncols two\nnrows 2\n", 1, "expected a finite number");
  expect_error_at_line("ncols\nnrows 2\n", 1, "has no value");
  expect_error_at_line(
      "ncols 2\nnrows 2\nxllcorner 0\nxllcenter 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", 4, "both");
  expect_error_at_line("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n", 5,
                       "no elevation values");
}

TEST(EsriAscii, RejectsFilesThatAreNotGrids) {
  expect_error_at_line("", 1, "empty file");
  expect_error_at_line("<html><body>404</body></html>\n", 1, "not an ESRI ASCII grid");
  expect_error_at_line("\x89PNG\r\n\x1a\n", 1, "not an ESRI ASCII grid");
  EXPECT_THROW(read_esri_ascii("/nonexistent/file.asc"), InputError);
}

TEST(EsriAscii, EveryBundledDemLoadsWithoutVoids) {
  for (const char* name : {"bigtujunga_srtm30m", "mount_st_helens_usgs30m",
                           "rub_al_khali_dunes_srtm90m", "west_bijou_escarpment_nasadem25m",
                           "mars_gale_mola_megdr15km", "mars_valles_marineris_mola_megdr15km"}) {
    const ElevationGrid grid =
        read_esri_ascii(std::string(TALUS_DATA_DIR) + "/terrain/" + name + ".asc");
    EXPECT_EQ(grid.void_count(), 0u) << name;
    EXPECT_GE(grid.ncols(), 96u) << name;
  }
  const ElevationGrid bigtujunga =
      read_esri_ascii(std::string(TALUS_DATA_DIR) + "/terrain/bigtujunga_srtm30m.asc");
  const auto range = bigtujunga.elevation_range();
  ASSERT_TRUE(range);
  EXPECT_DOUBLE_EQ(range->first, 467.0);  // data/terrain/README.md: min / max 467 / 1992 m
  EXPECT_DOUBLE_EQ(range->second, 1992.0);
}

}  // namespace
}  // namespace talus
