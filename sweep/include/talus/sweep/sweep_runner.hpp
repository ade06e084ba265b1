#pragma once
/// @file
/// Runs a parameter sweep's cases (sweep_config.hpp) so that nothing is lost.
///
/// - Each case runs in its own worker process (fork of this process, no
///   exec): a case that crashes or hangs cannot take the sweep with it. A
///   worker that dies of a signal, or runs longer than the case time limit
///   (then it and its children are killed), is run again up to the config's
///   `retries`, then recorded as `failed` with the reason. A job that stops
///   with an input error (exit code 1) is recorded as `error` at once: it
///   would fail the same way again.
/// - Results go to DIR/results.jsonl (rank R > 0 of an MPI run: DIR/
///   results.rank-R.jsonl), one JSON object per finished case — every input
///   parameter, status, the job's key figures (the scalar fields of the JSON
///   it prints, timings left out), seconds, attempts, host, rank — appended
///   with one write() as each case ends (no user-space buffer: a killed sweep
///   loses nothing it recorded).
/// - Resuming is the default: cases whose id is in a results file are
///   skipped; a torn last line (the sweep was killed while writing it) is cut
///   off and its case redone. A second sweep on the same DIR is refused (a
///   lock, DIR/.talus-sweep.lock).
/// - Ranks: with a CaseDealer (case_dealer.hpp; `talus sweep` under mpirun)
///   rank 0 hands the cases out one at a time as worker slots free up, so
///   ranks that drew quick cases take more; without one, rank r of R runs
///   the cases whose index is r mod R. Every case is computed by a
///   single-threaded worker from its own parameters, so results do not
///   depend on the job count, the rank count or which rank ran a case. Each
///   rank writes its own results file (no result travels by MPI: a rank
///   killed mid-sweep loses nothing it recorded) and rank 0 merges them
///   into results.csv.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/sweep/case_dealer.hpp"
#include "talus/sweep/sweep_config.hpp"

namespace talus {

/// Most worker processes per core SweepOptions::jobs accepts.
inline constexpr std::size_t kJobsPerCore = 4;

struct SweepOptions {
  std::filesystem::path output_dir;
  /// Worker processes at a time; 0 = the machine's core count; at most
  /// kJobsPerCore per core (more only thrash).
  std::size_t jobs = 0;
  /// Only list the cases (ids, parameters) that would run.
  bool dry_run = false;
  /// Overrides the config's case_time_limit when > 0 [s].
  double case_time_limit = 0.0;
  int rank = 0;   ///< this process's rank in [0, ranks)
  int ranks = 1;  ///< processes sharing the sweep (MPI)
  /// Progress on stderr: a rewritten line when it is a terminal, else one line per case.
  bool progress = true;
  /// Runs one command line (without the program name) in the worker process
  /// and returns its exit code; its stdout and stderr go to the case's
  /// stdout.txt and stderr.txt. The CLI passes its own dispatcher.
  std::function<int(const std::vector<std::string>&)> run_command;
  /// Throws InputError if a command line names an option its command does
  /// not have: called for every case before any runs.
  std::function<void(const std::vector<std::string>&)> check_command;
  /// Throws InputError if a case's vehicle file (vehicle.file with its
  /// vehicle.* overrides) is not a valid vehicle: called for every such case
  /// before any runs (prepare_case). The CLI passes the vehicle parser.
  SweepFileCheck check_vehicle;
  /// Called once on every rank with whether this rank took its lock; true
  /// iff every rank did (MPI: a collective). Default: `mine`.
  std::function<bool(bool mine)> all_ranks_agree;
  /// Hands out the cases across ranks (not owned; null: the static share,
  /// index mod ranks). Must outlive run_sweep.
  CaseDealer* dealer = nullptr;
  /// InputError naming the field.
  void validate() const;
};

enum class SweepStatus {
  kComplete,  ///< every case of this rank has a result (some may be failed or error)
  kDryRun,    ///< nothing ran
};
std::string_view to_string(SweepStatus status);

struct SweepResult {
  SweepStatus status = SweepStatus::kComplete;
  std::size_t cases = 0;    ///< in the design
  std::size_t mine = 0;     ///< this rank's share (with a dealer: the cases it ran or skipped)
  std::size_t skipped = 0;  ///< already in a results file
  std::size_t ran = 0;
  std::size_t ok = 0;         ///< ran with exit code 0
  std::size_t no_result = 0;  ///< ran and said there is no path or profile (exit code 2)
  std::size_t failed = 0;     ///< crashed or hung on every attempt
  std::size_t errors = 0;     ///< the job refused its input
  std::size_t retries = 0;    ///< attempts beyond the first
  double seconds = 0.0;
  std::vector<std::string> dry_run_lines;  ///< with dry_run: "id  parameters" per case
  std::string brief_report() const;
};

/// Runs this rank's unfinished cases of `config`. InputError before any case
/// runs for a case the job cannot take, an unusable DIR or a DIR in use.
SweepResult run_sweep(const SweepConfig& config, const SweepOptions& options);

/// Every record in DIR's results files, the last one per case id (a torn
/// last line is skipped).
std::vector<nlohmann::ordered_json> read_sweep_records(const std::filesystem::path& dir);

/// Writes DIR/results.csv (one row per case in design order: case_id, every
/// parameter, status, the key figures, seconds, attempts, reason) and
/// DIR/report.md with a figure per swept numeric parameter and the status
/// counts. Returns the number of cases with a record.
std::size_t write_sweep_report(const SweepConfig& config, const std::filesystem::path& dir);

}  // namespace talus
