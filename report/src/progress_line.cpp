#include "talus/report/progress_line.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <utility>

namespace talus {
namespace {

/// "4.1 s", "2 min 05 s".
std::string duration_text(double seconds) {
  char text[48];
  if (seconds < 60.0) {
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  } else {
    const long whole = std::lround(seconds);
    std::snprintf(text, sizeof text, "%ld min %02ld s", whole / 60, whole % 60);
  }
  return text;
}

constexpr std::chrono::milliseconds kRedrawInterval{100};

}  // namespace

bool stderr_is_terminal() {
  return ::isatty(STDERR_FILENO) == 1;
}

ProgressLine::ProgressLine(std::string label, bool enabled, std::ostream& out, bool terminal)
    : label_(std::move(label)), enabled_(enabled), terminal_(terminal), out_(out) {}

ProgressLine::ProgressLine(std::string label, bool enabled)
    : ProgressLine(std::move(label), enabled, std::cerr, stderr_is_terminal()) {}

ProgressLine::~ProgressLine() {
  finish();
}

std::string ProgressLine::text(const std::string& status, std::size_t done,
                               std::size_t total) const {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string line = label_ + ": " + status + ", " + duration_text(elapsed);
  if (done > 0 && done < total) {
    const double left = elapsed * static_cast<double>(total - done) / static_cast<double>(done);
    line += ", about " + duration_text(left) + " left";
  }
  return line;
}

void ProgressLine::update(const std::string& status, std::size_t done, std::size_t total) {
  if (!enabled_ || !terminal_) return;
  // A new status is always drawn; the same one again (its clock) at most ten times a second.
  const auto now = std::chrono::steady_clock::now();
  if (!shown_.empty() && status == status_ && now - last_draw_ < kRedrawInterval) return;
  last_draw_ = now;
  status_ = status;
  draw(text(status, done, total));
}

void ProgressLine::note(const std::string& line) {
  if (!enabled_) return;
  const std::string shown = shown_;
  if (terminal_ && !shown.empty()) out_ << "\r\033[K";
  out_ << line << "\n";
  if (terminal_ && !shown.empty()) out_ << shown;
  out_.flush();
}

void ProgressLine::finish() {
  if (!enabled_ || !terminal_ || shown_.empty()) return;
  out_ << "\r\033[K" << std::flush;
  shown_.clear();
}

void ProgressLine::draw(const std::string& line) {
  out_ << "\r" << line << "\033[K" << std::flush;
  shown_ = line;
}

}  // namespace talus
