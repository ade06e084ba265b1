#pragma once
/// @file
/// `talus sweep CONFIG.yaml --out DIR`: loads the config, runs this process's
/// share of the cases (run_sweep) and, on rank 0 once every rank is done,
/// writes results.csv and report.md.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace talus::experiments {

struct SweepRequest {
  std::string config, output_dir;
  std::size_t jobs = 0;  ///< 0 = the core count
  bool resume = false;   ///< accepted for clarity: resuming is the default
  bool dry_run = false;
  double case_time_limit = 0.0;  ///< > 0 overrides the config's
  bool progress = true;          ///< false (--quiet): no progress on stderr
  std::function<int(const std::vector<std::string>&)> run_command;
  std::function<void(const std::vector<std::string>&)> check_command;
};

/// The sweep's vehicle check (SweepOptions::check_vehicle): parses the text
/// as a vehicle file, InputError naming `source` if it is not one.
void check_sweep_vehicle(const std::string& text, const std::string& source);

/// Runs the sweep; returns the lines to print (the brief report, or the
/// cases of a dry run). InputError for a bad config or DIR.
std::string sweep(const SweepRequest& request);

}  // namespace talus::experiments
