// Helpers of the end-to-end tests of the `talus` executable (test_cli*.cpp):
// running it with stdout and stderr captured, a scratch folder, input files
// (vehicles, way points, generated terrains), reading CSV and JSON output,
// and the error contract of bad input.
#pragma once

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace talus::cli_test {

/// A scratch folder of this test process (ctest runs tests in parallel).
inline std::filesystem::path scratch_dir() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("talus_cli_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

/// The file `name` in the scratch folder.
inline std::string scratch_file(const std::string& name) {
  return (scratch_dir() / name).string();
}

/// A bundled data file, `relative` to the data folder (e.g. "terrain/x.asc").
inline std::string data_file(const std::string& relative) {
  return std::string(TALUS_DATA_DIR) + "/" + relative;
}

/// `s` in single quotes, for the shell.
inline std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

inline void write_text(const std::string& file, const std::string& text) {
  std::ofstream(file) << text;
}

/// The whole of a file (which must exist).
inline std::string read_text(const std::string& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in.good()) << file << " is missing";
  return {std::istreambuf_iterator<char>(in), {}};
}

inline std::size_t count_lines(const std::string& s) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Runs `talus ARGS`, capturing stdout and stderr separately.
inline RunResult run_talus(const std::string& args) {
  const std::string err_file = scratch_file("stderr.txt");
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

/// Parses `text` (`what` names it in the failure), or returns `fallback`.
inline nlohmann::json parse_json(const std::string& text, const std::string& what,
                                 const nlohmann::json& fallback = nlohmann::json::object()) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    ADD_FAILURE() << what << " is not one JSON object: " << e.what() << "\n" << text;
    return fallback;
  }
}

/// Generates a terrain with `talus terrain generate ARGS -o NAME` in the
/// scratch folder and returns its file.
inline std::string generate_terrain(const std::string& name, const std::string& args) {
  const std::string file = scratch_file(name);
  const RunResult r = run_talus("terrain generate " + args + " -o " + quoted(file));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return file;
}

/// A flat 121 m x 121 m plane at 1 m spacing, (0, 0) at its south-west node.
inline std::string flat_terrain() {
  return generate_terrain("flat.asc", "plane --slope 0 --ncols 121 --nrows 121 --cellsize 1");
}

/// A point mass with friction mu, b/h = 1.2 and no drive, brake or speed limit
/// (or a top speed, if given), written to `name` in the scratch folder.
inline std::string point_mass_vehicle(const std::string& name, double mu, double max_speed = 0.0) {
  const std::string file = scratch_file(name);
  std::ostringstream text;
  text << "model: point_mass\nfriction: " << mu << "\ncg_height: 0.5\nhalf_track: 0.6\n";
  if (max_speed > 0.0) text << "max_speed: " << max_speed << "\n";
  write_text(file, text.str());
  return file;
}

/// Way points written as an x,y CSV to `name` in the scratch folder.
inline std::string write_points(const std::string& name,
                                const std::vector<std::array<double, 2>>& points) {
  std::ostringstream text;
  text.precision(17);
  text << "x,y\n";
  for (const auto& p : points) text << p[0] << "," << p[1] << "\n";
  const std::string file = scratch_file(name);
  write_text(file, text.str());
  return file;
}

/// One CSV field as a number (`inf` and `nan` included); a failure if it is not one.
inline double parse_number(const std::string& field) {
  char* end = nullptr;
  const double value = std::strtod(field.c_str(), &end);
  if (field.empty() || *end != '\0') {
    ADD_FAILURE() << "not a number: '" << field << "'";
    return std::numeric_limits<double>::quiet_NaN();
  }
  return value;
}

/// Reads a CSV, checking that its header is exactly `header` and that every
/// row has as many columns (a row that has not is a failure and is skipped).
/// Returns the fields of the rows after the header.
inline std::vector<std::vector<std::string>> read_csv(const std::string& file,
                                                      const std::string& header) {
  const auto columns = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
  std::ifstream in(file);
  std::string line;
  EXPECT_TRUE(std::getline(in, line)) << file << " is missing or empty";
  EXPECT_EQ(line, header);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) f.push_back(cell);
    if (f.size() != columns) {
      ADD_FAILURE() << "row " << rows.size() << " has " << f.size() << " columns: " << line;
      continue;
    }
    rows.push_back(std::move(f));
  }
  return rows;
}

/// A bad input and a fragment its error message must contain.
struct ErrorCase {
  std::string args;
  std::string fragment;
};

/// Runs `talus COMMAND ARGS` for every case and checks the contract of bad
/// input: exit code 1, one line on stderr, "talus: error: " and the case's
/// fragment, nothing on stdout, and `never_written` not written.
inline void expect_bad_input(const std::string& command, const std::vector<ErrorCase>& cases,
                             const std::string& never_written) {
  for (const ErrorCase& c : cases) {
    const RunResult r = run_talus(command + " " + c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args;
    EXPECT_EQ(count_lines(r.err), 1u) << c.args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("talus: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.fragment), std::string::npos) << c.fragment << " not in " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(std::filesystem::exists(never_written)) << c.args;
  }
}

}  // namespace talus::cli_test
