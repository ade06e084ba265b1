// The capped run and the refusal check of the CLI robustness suites
// (test_cli_robustness.cpp, test_cli_raster_robustness.cpp).
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace talus::cli_test {

/// `talus ARGS` under the memory cap and a 20 s limit (hangs end as exit 124).
inline RunResult run_capped(const std::string& args) {
  // The same budget in every build (the sanitizer build has no cap).
  std::string wrapper = "TALUS_MEMORY_LIMIT_MB=384 timeout 20 ";
#ifdef TALUS_ROBUSTNESS_MEMORY_CAP
  wrapper += "prlimit --as=" TALUS_ROBUSTNESS_MEMORY_CAP " ";
#endif
  const std::string err_file = scratch_file("robust_stderr.txt");
  const std::string command = wrapper + "'" + TALUS_CLI + "' " + args + " 2>'" + err_file + "'";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) result.out.append(buffer, n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.err = read_text(err_file);
  return result;
}

struct Case {
  std::string name;      ///< the family, for failure messages
  std::string args;      ///< after `talus`
  std::string fragment;  ///< the message must contain it
};

/// Every case: exit 1, one printable line starting "talus: error: " with the
/// fragment, empty stdout, and `never_written` absent afterwards.
inline void expect_refused(const std::vector<Case>& cases, const std::string& never_written) {
  for (const Case& c : cases) {
    std::filesystem::remove_all(never_written);
    const RunResult r = run_capped(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.name << ": " << c.args << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << c.name << ": " << r.err;
    EXPECT_EQ(r.err.rfind("talus: error: ", 0), 0u) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.fragment), std::string::npos)
        << c.name << ": '" << c.fragment << "' not in " << r.err;
    for (const char ch : r.err) {
      EXPECT_TRUE(ch == '\n' || (static_cast<unsigned char>(ch) >= 0x20 && ch != 0x7f))
          << c.name << ": control byte in the message";
    }
    EXPECT_TRUE(r.out.empty()) << c.name << ": " << r.out;
    EXPECT_FALSE(std::filesystem::exists(never_written)) << c.name << " left " << never_written;
  }
}

}  // namespace talus::cli_test
