// End-to-end tests of the `talus` executable: output contracts and errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.hpp"
#include "talus/core/esri_ascii.hpp"

namespace talus::cli_test {
namespace {

std::string dem(const char* name) {
  return data_file(std::string("terrain/") + name);
}

TEST(Cli, TerrainInfoPrintsTheDocumentedJson) {
  const RunResult r =
      run_talus("terrain info '" + dem("west_bijou_escarpment_nasadem25m.asc") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("ncols"), 122);
  EXPECT_EQ(j.at("nrows"), 82);
  EXPECT_DOUBLE_EQ(j.at("cellsize").get<double>(), 25.0);
  EXPECT_NEAR(j.at("xmin").get<double>(), 556596.207595 + 12.5, 1e-6);
  EXPECT_NEAR(j.at("xmax").get<double>() - j.at("xmin").get<double>(), 121 * 25.0, 1e-6);
  EXPECT_NEAR(j.at("ymax").get<double>() - j.at("ymin").get<double>(), 81 * 25.0, 1e-6);
  EXPECT_DOUBLE_EQ(j.at("zmin").get<double>(), 1690.0);  // data/terrain/README.md
  EXPECT_DOUBLE_EQ(j.at("zmax").get<double>(), 1807.0);
  EXPECT_EQ(j.at("voids"), 0);
}

TEST(Cli, TerrainFitInterpolatesExactlyAndSmoothingLeavesResiduals) {
  const std::string file = dem("rub_al_khali_dunes_srtm90m.asc");
  const RunResult exact = run_talus("terrain fit '" + file + "'");
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  const auto e = nlohmann::json::parse(exact.out);
  EXPECT_LT(e.at("max_node_residual").get<double>(), 1e-8);
  EXPECT_EQ(e.at("patches"), 112 * 120);
  EXPECT_TRUE(e.at("fit_seconds").is_number());
  const RunResult smooth = run_talus("terrain fit '" + file + "' --smoothing 1");
  ASSERT_EQ(smooth.exit_code, 0) << smooth.err;
  const auto s = nlohmann::json::parse(smooth.out);
  EXPECT_GT(s.at("rms_residual").get<double>(), 0.01);
  EXPECT_LT(s.at("rms_residual").get<double>(), s.at("max_node_residual").get<double>());
}

TEST(Cli, GeneratedTerrainsAreReproducibleAndReadable) {
  const auto dir = scratch_dir();
  const std::string a = (dir / "a.asc").string(), b = (dir / "b.asc").string();
  for (const std::string& out : {a, b}) {
    const RunResult r =
        run_talus("terrain generate fractal --ncols 65 --nrows 33 --seed 9 -o '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(read_text(a), read_text(b));
  const talus::ElevationGrid grid = talus::read_esri_ascii(a);
  EXPECT_EQ(grid.ncols(), 65u);
  EXPECT_EQ(grid.nrows(), 33u);
  for (const char* kind :
       {"plane --slope 0.2", "cylinder --radius 500 --dip", "sphere-cap --radius 500",
        "gaussian-hills --hill 60,60,5,10 --hill 20,30,-2,5", "bowl", "eldershaw-yim"}) {
    const RunResult r = run_talus(std::string("terrain generate ") + kind + " -o '" + a + "'");
    EXPECT_EQ(r.exit_code, 0) << kind << ": " << r.err;
    EXPECT_NO_THROW(talus::read_esri_ascii(a)) << kind;
  }
}

TEST(Cli, BadInputGivesOneLineOnStderrAndExitCodeOne) {
  const auto dir = scratch_dir();
  const std::string bad = (dir / "bad.asc").string();
  std::ofstream(bad) << "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 oops 6\n";
  for (const std::string& args :
       {"terrain info '" + bad + "'", std::string("terrain info /nonexistent.asc"),
        "terrain fit '" + bad + "'",
        "terrain fit '" + dem("rub_al_khali_dunes_srtm90m.asc") + "' --smoothing -1",
        std::string("terrain generate fractal --fractal-dimension 3.5 -o '") +
            (dir / "x.asc").string() + "'",
        std::string("terrain generate sphere-cap --radius 1 -o '") + (dir / "x.asc").string() + "'",
        std::string("terrain frobnicate"),
        std::string("experiment no-such-experiment --out '") + dir.string() + "'"}) {
    const RunResult r = run_talus(args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(count_lines(r.err), 1u) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("talus: error: ", 0), 0u) << r.err;
  }
  const RunResult r = run_talus("terrain info '" + bad + "'");
  EXPECT_NE(r.err.find("bad.asc:7"), std::string::npos) << r.err;  // names file and line
}

// optimiser-quality compares with the fixed reference stored in the data folder (issue #36
// item 2); without it, or with a broken one, it stops before planning with one line naming the
// file and what is wrong, and writes no report.
TEST(Cli, OptimiserQualityNeedsItsStoredReference) {
  const auto data = scratch_dir() / "data_without_reference";
  std::filesystem::create_directories(data / "terrain");
  std::filesystem::create_directories(data / "references");
  const std::string file = (data / "references" / "optimiser_quality.json").string();
  const std::string out = (scratch_dir() / "oq_out").string();
  const std::string args = "experiment optimiser-quality --quick --quiet --data '" + data.string() +
                           "' --out '" + out + "'";
  const struct {
    const char* text;  ///< the stored file's content; nullptr = no file
    const char* names;
  } cases[] = {
      {nullptr, "no such file"},
      {"{\"commit\": \"abc\", \"configurations\": [], \"cases\": [", "not JSON"},
      {"{\"commit\": \"abc\", \"configurations\": [\"default\"], \"cases\": "
       "[{\"case\": \"fractal seed 1\", \"travel_time\": -1, \"configuration\": \"default\"}]}",
       "fractal seed 1"},
      {"{\"commit\": \"abc\", \"cases\": []}", "configurations"},
  };
  for (const auto& c : cases) {
    std::filesystem::remove(file);
    if (c.text) std::ofstream(file) << c.text;
    const RunResult r = run_talus(args);
    EXPECT_EQ(r.exit_code, 1) << (c.text ? c.text : "no file");
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("references/optimiser_quality.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out + "/optimiser-quality/report.md"));
  }
}

TEST(Cli, ExperimentListNamesTheGallery) {
  const RunResult r = run_talus("experiment list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("terrain-gallery"), std::string::npos);
}

TEST(Cli, HelpWorksEverywhere) {
  for (const char* args : {"--help", "terrain --help", "terrain fit --help",
                           "terrain generate fractal --help", "experiment --help"}) {
    const RunResult r = run_talus(args);
    EXPECT_EQ(r.exit_code, 0) << args;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << args;
  }
}

}  // namespace
}  // namespace talus::cli_test
