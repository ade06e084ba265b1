#pragma once
/// @file
/// ProgressLine: where a long command is, as one line on a terminal that is
/// rewritten in place ("talus plan: local optimisation, candidate 2 of 3,
/// 4.1 s, about 3 s left"), and nothing at all when the stream is not a
/// terminal (a CI log, a pipe) or the user asked for quiet. Notes (one per
/// finished case, say) are permanent lines in either mode. A new status is
/// drawn at once; the same status again (its clock) at most ten times a
/// second, so callers may update it from hot loops.
/// Driven by the library's progress callbacks (PlannerOptions::progress,
/// the sweep runner, the experiments), never by parsing output.
#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace talus {

class ProgressLine {
 public:
  /// A line labelled `label` on `out`; `terminal` says whether `out` is one
  /// (stderr_is_terminal() for std::cerr); `enabled` false (--quiet) silences
  /// the line and the notes.
  ProgressLine(std::string label, bool enabled, std::ostream& out, bool terminal);
  /// On std::cerr, drawn only when stderr is a terminal.
  explicit ProgressLine(std::string label, bool enabled = true);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Shows `status` with the elapsed time and, when `done` of `total` steps
  /// are finished (0 < done < total), the time left at the pace so far.
  void update(const std::string& status, std::size_t done = 0, std::size_t total = 0);
  /// A permanent line (on a terminal the progress line is redrawn under it).
  void note(const std::string& line);
  /// Clears the line (on a terminal); later updates draw it again.
  void finish();

  /// True when the line is drawn (enabled, on a terminal); notes show either way.
  bool drawn() const { return enabled_ && terminal_; }
  /// The text update() would show (for tests and for callers' own logs).
  std::string text(const std::string& status, std::size_t done, std::size_t total) const;

 private:
  void draw(const std::string& line);

  std::string label_;
  bool enabled_, terminal_;
  std::ostream& out_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_draw_{};
  std::string status_;  ///< the status last drawn
  std::string shown_;   ///< what the terminal shows now (empty: nothing)
};

/// True when the process's stderr is a terminal.
bool stderr_is_terminal();

}  // namespace talus
