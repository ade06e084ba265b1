#pragma once
/// @file
/// The experiment framework: each experiment reproduces a figure or table,
/// writing `<out>/<name>/` with CSV data, PNG figures, a `report.md` and a `summary.json` of its
/// headline numbers (ExperimentSummary).
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "talus/report/experiment_summary.hpp"
#include "talus/report/progress_line.hpp"

namespace talus::experiments {

/// What an experiment gets to run.
struct ExperimentContext {
  std::filesystem::path output_dir;  ///< `<out>/<name>/`, created before run() is called
  std::filesystem::path data_dir;    ///< folder holding `terrain/*.asc` (the bundled DEMs)
  bool quick = false;                ///< smaller problem sizes, for tests and smoke runs
  /// The headline numbers, written as `summary.json` after run() returns (shared so that the
  /// const context can carry it).
  std::shared_ptr<ExperimentSummary> summary = std::make_shared<ExperimentSummary>();
  /// Runs one `talus` command line (without the program name) in this
  /// process and returns its exit code; checks one without running it
  /// (InputError for an unknown option). Set by the CLI, for the experiments
  /// that run sweeps.
  std::function<int(const std::vector<std::string>&)> run_command;
  std::function<void(const std::vector<std::string>&)> check_command;
  /// Where the experiment is (ProgressLine: drawn on a terminal; its notes,
  /// one per finished case, go to stderr either way unless --quiet).
  std::shared_ptr<ProgressLine> progress = std::make_shared<ProgressLine>("experiment", false);
};

/// One registered experiment.
struct Experiment {
  std::string name;                                   ///< command-line name, e.g. "terrain-gallery"
  std::string description;                            ///< one line for `talus experiment list`
  std::function<void(const ExperimentContext&)> run;  ///< throws talus::Error on failure
};

/// Every experiment, in the order `talus experiment list` shows them.
std::vector<Experiment> all_experiments();

/// The bundled-data folder: `--data` if given, else $TALUS_DATA_DIR, else the
/// source tree's data/ (build tree), else the installed share/talus/data.
/// Throws InputError if none holds `terrain/`.
std::filesystem::path find_data_dir(const std::string& explicit_dir);

}  // namespace talus::experiments
