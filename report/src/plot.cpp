#include "talus/report/plot.hpp"

#include <sys/wait.h>

#include <cstdlib>
#include <string>
#include <system_error>

#include "talus/core/error.hpp"

namespace talus {
namespace {

/// POSIX shell single-quoting: everything literal, a ' becomes '\''.
std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  quoted += '\'';
  return quoted;
}

/// Single-quoted gnuplot literal; `escape_enhanced` adds a backslash before
/// the enhanced-text control characters (inside single quotes one backslash
/// is what gnuplot's enhanced-text parser expects).
std::string quote_for_gnuplot(std::string_view text, bool escape_enhanced) {
  std::string quoted = "'";
  for (const char c : text) {
    switch (c) {
      case '\'':
        quoted += "''";
        break;
      case '\n':
        // Single-quoted strings know no escapes; splice in a double-quoted one.
        quoted += "'.\"\\n\".'";
        break;
      case '^':
      case '_':
      case '@':
      case '&':
      case '~':
      case '{':
      case '}':
        if (escape_enhanced) quoted += '\\';
        quoted += c;
        break;
      default:
        quoted += c;
    }
  }
  quoted += '\'';
  return quoted;
}

}  // namespace

std::string png_terminal(int width, int height) {
  return "set encoding utf8\nset terminal pngcairo size " + std::to_string(width) + "," +
         std::to_string(height) + " enhanced font 'DejaVu Sans,11'\n";
}

std::string gnuplot_string(std::string_view text) {
  return quote_for_gnuplot(text, false);
}

std::string gnuplot_plain_text(std::string_view text) {
  return quote_for_gnuplot(text, true);
}

bool gnuplot_available() {
  const int status = std::system("command -v gnuplot >/dev/null 2>&1");
  return status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

void require_gnuplot() {
  if (!gnuplot_available()) {
    throw Error(
        "gnuplot was not found on the PATH; the experiments render their figures with it "
        "(Debian/Ubuntu: apt-get install gnuplot-nox)");
  }
}

void run_gnuplot(const std::filesystem::path& script) {
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(script, ec);
  if (ec || !std::filesystem::is_regular_file(absolute, ec)) {
    throw Error("gnuplot script not found: " + script.string());
  }
  if (std::system(nullptr) == 0) throw Error("cannot run gnuplot: no command shell available");
  // Running in the script's folder lets the script name its data and output
  // files without paths, which keeps it valid wherever the folder is moved.
  const std::string command = "cd " + shell_quote(absolute.parent_path().string()) +
                              " && gnuplot " + shell_quote(absolute.filename().string());
  const int status = std::system(command.c_str());
  if (status == -1) throw Error("could not start a shell to run gnuplot on " + script.string());
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  // Only now look up gnuplot: the common case pays no extra shell, and a
  // failure gets the most useful of the two explanations.
  require_gnuplot();
  if (WIFSIGNALED(status)) {
    throw Error("gnuplot was killed by signal " + std::to_string(WTERMSIG(status)) +
                " while running " + script.string());
  }
  throw Error("gnuplot failed (exit status " + std::to_string(WEXITSTATUS(status)) + ") on " +
              script.string() + "; its messages are above");
}

std::ofstream open_output_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  if (ec) {
    throw Error("cannot create folder " + path.parent_path().string() + ": " + ec.message());
  }
  std::ofstream out(path, std::ios::out | std::ios::trunc);
  if (!out) throw Error("cannot open " + path.string() + " for writing");
  return out;
}

void close_output_file(std::ofstream& out, const std::filesystem::path& path) {
  out.flush();
  const bool ok = static_cast<bool>(out);
  out.close();
  if (!ok || out.fail()) throw Error("writing " + path.string() + " failed");
}

}  // namespace talus
