#pragma once
/// @file
/// The small frame every notebook shares: its command line, its Markdown page
/// (talus::Report, talus::report) with the narration also echoed to stdout, the
/// facts it checks (a failed check makes the program exit 1, so its CTest
/// fails), and two figure kinds drawn with the project's gnuplot layer: line
/// plots of curves along s, and maps of routes over shaded relief.
///
/// Command line of every notebook:
///   NN_name [--quick] [--out DIR] [--data DIR]
/// --quick  small grids and few candidates (what CI runs, a few seconds each)
/// --out    where the pages go (default talus-out/notebooks); this notebook
///          writes DIR/NN_name/report.md and its figures beside it
/// --data   the repository's data/ folder (default: the source tree's)
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/types.hpp"
#include "talus/report/report.hpp"

namespace talus::notebooks {

/// One curve of a line plot: y(x) drawn with a gnuplot style such as
/// "lines lw 2 lc rgb '#2c7fb8'" or "points pt 7". The title is gnuplot
/// enhanced text: write v_{max} for a subscript.
struct Series {
  std::string title;
  std::vector<double> x, y;
  std::string style = "lines lw 2";
};

/// One route of a map: planar positions [m] in the terrain's frame; the
/// title is enhanced text as in Series.
struct Route {
  std::string title;
  std::vector<Vec2> points;
  std::string style = "lines lw 3 lc rgb '#e6550d'";
};

class Notebook {
 public:
  /// Parses the command line (throws talus::InputError on an unknown
  /// argument) and starts the page titled `title`; `name` is the folder name
  /// ("01_terrain_and_bpatch").
  Notebook(int argc, char** argv, std::string name, std::string_view title);

  bool quick() const { return quick_; }
  /// `relative` inside the data folder, e.g. data("vehicles/rover.yaml").
  std::string data(std::string_view relative) const;
  /// The folder of this notebook's page and figures.
  const std::filesystem::path& dir() const { return dir_; }

  /// A section heading.
  void section(std::string_view text);
  /// A paragraph of narration (Markdown), also printed.
  void say(std::string_view text);
  /// A table, also printed.
  void table(const Table& table);
  /// Records a fact this run must show: "✔ fact" or "✘ fact" on the page and
  /// on stdout; any failed check makes finish() return 1.
  bool check(bool holds, std::string_view fact);

  /// A line plot `stem`.png of the series; returns its file name. `settings`:
  /// further gnuplot lines, e.g. "set logscale xy\n".
  std::string plot(const std::string& stem, std::string_view title, std::string_view xlabel,
                   std::string_view ylabel, const std::vector<Series>& series,
                   std::string_view settings = "");
  /// A map `stem`.png of `surface` as shaded relief with the routes over it
  /// in order (and start/goal markers at the last route's ends); returns its file name.
  std::string map(const std::string& stem, std::string_view title, const BPatch& surface,
                  const std::vector<Route>& routes);
  /// Adds a figure (from plot() or map()) to the page.
  void figure(std::string_view caption, const std::string& file);

  /// Writes the page; returns the exit code (0 iff every check held).
  int finish();

 private:
  std::string name_;
  bool quick_ = false;
  std::filesystem::path data_dir_, dir_;
  Report report_;
  std::size_t checks_ = 0, failures_ = 0;
};

/// The West Bijou DEM (25 m cells) scaled by 1/25 in x, y and z, with its
/// south-west node at the origin: 1 m cells and unchanged slopes, so that a
/// rover's limits bind (data/terrain/README.md, "Rover-scale use"). 121 × 81 m.
ElevationGrid west_bijou_at_rover_scale(const Notebook& nb);

/// Way points [m] of the path notebooks 02 and 03 drive on that terrain:
/// across the escarpment with four turns.
std::vector<Vec2> rover_path_points();

/// `value` with printf conversion `format` (one double), for narration.
std::string num(const char* format, double value);

/// Runs `body` (a notebook's main) and turns any exception into one line
/// "notebook failed: ..." on stderr and exit code 1.
int run(const std::function<int()>& body);

}  // namespace talus::notebooks
