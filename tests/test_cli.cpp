// End-to-end tests of the `talus` executable: output contracts and errors.
#include <gtest/gtest.h>

#include <unistd.h>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "talus/core/esri_ascii.hpp"

namespace {

/// A scratch folder of this test process (ctest runs tests in parallel).
std::filesystem::path scratch_dir() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("talus_cli_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Runs `talus ARGS`, capturing stdout and stderr separately.
RunResult run_talus(const std::string& args) {
  const auto dir = scratch_dir();
  const std::string err_file = (dir / "stderr.txt").string();
  const std::string command = std::string("'") + TALUS_CLI + "' " + args + " 2>'" + err_file + "'";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_file);
  result.err.assign(std::istreambuf_iterator<char>(err), {});
  return result;
}

std::string dem(const char* name) {
  return std::string(TALUS_DATA_DIR) + "/terrain/" + name;
}

std::size_t count_lines(const std::string& s) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
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
  EXPECT_GE(e.at("fit_seconds").get<double>(), 0.0);
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
  std::ifstream fa(a), fb(b);
  const std::string ta((std::istreambuf_iterator<char>(fa)), {}),
      tb((std::istreambuf_iterator<char>(fb)), {});
  EXPECT_EQ(ta, tb);
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
