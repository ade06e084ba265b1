#pragma once
/// @file
/// Figure plumbing shared by the experiments. Every figure is a gnuplot script
/// saved next to its PNG and its data files, with the data referenced by
/// relative names, so a reader can re-render or restyle it with
/// `cd <folder> && gnuplot <name>.gp` without rerunning the experiment.
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "talus/core/output_file.hpp"  // write_text_file, for the figures' callers

namespace talus {

/// The terminal line of every figure (GnuplotFigure::canvas), so all share one look.
/// Includes `set encoding utf8` so labels may use °, λ, ×, − directly.
std::string png_terminal(int width = 1000, int height = 800);

/// `text` as a single-quoted gnuplot string literal, for file names and for
/// labels that deliberately use enhanced-text markup (x_{min}, m^2). Single
/// quotes are doubled, as gnuplot requires; a newline becomes a concatenated
/// "\n" so multi-line titles work.
std::string gnuplot_string(std::string_view text);

/// Like gnuplot_string(), but escapes the enhanced-text control characters
/// (^ _ @ & ~ { }) so arbitrary text such as a DEM file name
/// ("bigtujunga_srtm30m") prints literally instead of as subscripts.
std::string gnuplot_plain_text(std::string_view text);

/// True if a `gnuplot` executable is on the PATH (`command -v gnuplot`).
bool gnuplot_available();

/// Throws talus::Error with install advice if gnuplot_available() is false.
/// Call it once before an experiment's expensive part, so a missing gnuplot
/// fails in a second rather than after minutes of computation.
void require_gnuplot();

/// Runs `gnuplot <script>` with the script's folder as the working directory
/// (so the script's relative data and output names resolve there), through
/// std::system with both paths shell-quoted. Writes nothing itself; gnuplot's
/// own warnings go to stderr. Throws talus::Error naming the script if the
/// script does not exist, gnuplot is missing, or gnuplot exits non-zero.
void run_gnuplot(const std::filesystem::path& script);

/// Opens `path` for writing (truncating), creating its parent folders.
/// Throws talus::Error naming the path if that fails.
std::ofstream open_output_file(const std::filesystem::path& path);

/// Flushes and closes `out`; throws talus::Error naming `path` if any write
/// failed (disk full, permissions), so a truncated data file never goes
/// unnoticed into a figure.
void close_output_file(std::ofstream& out, const std::filesystem::path& path);

}  // namespace talus
