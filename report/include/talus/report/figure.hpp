#pragma once
/// @file
/// The gnuplot figure builder every experiment draws with. A figure is a
/// script `<stem>.gp` saved beside its PNG `<stem>.png` and its data files,
/// all named relative to the folder (plot.hpp), so that a reader can restyle
/// it with `cd <folder> && gnuplot <stem>.gp` without rerunning anything.
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace talus {

/// The items of one gnuplot `plot` command, each a complete item such as
/// "'a.dat' using 1:2 with lines notitle".
using PlotItems = std::vector<std::string>;

/// A plot item that draws nothing but a legend line of `colour` titled
/// `title` (enhanced text), for series drawn in several colours at once.
std::string key_entry(std::string_view colour, std::string_view title);

/// Builds the script of one figure: append gnuplot text with `<<`, then
/// render(). The PNG is `<stem>.png` and the script `<stem>.gp` in `dir`.
class GnuplotFigure {
 public:
  GnuplotFigure(std::filesystem::path dir, std::string stem);

  /// The script's opening comment: what the figure shows (`what`, one line),
  /// how to re-render it, and its input files (`inputs`, may be empty).
  GnuplotFigure& describe(std::string_view what, std::string_view inputs);

  /// The pngcairo terminal of the given size and `set output '<stem>.png'`.
  GnuplotFigure& canvas(int width, int height);

  /// `set title ...` as plain text (enhanced-text markup escaped, so file
  /// names print literally) or, with `markup`, with enhanced text as written.
  GnuplotFigure& title(std::string_view text, std::string_view font = ",10", bool markup = false);

  /// Appends "plot A, \\\n     B\n": the items, one per line.
  GnuplotFigure& plot(const PlotItems& items);

  template <typename Text>
  GnuplotFigure& operator<<(const Text& text) {
    script_ << text;
    return *this;
  }

  /// `<stem><suffix>`, the name a data file of this figure gets in scripts.
  std::string name(std::string_view suffix) const { return stem_ + std::string(suffix); }
  /// `dir/<stem><suffix>`, where that data file is written.
  std::filesystem::path file(std::string_view suffix) const { return dir_ / name(suffix); }

  /// Writes the script; returns its path.
  std::filesystem::path save() const;
  /// Writes the script and runs gnuplot on it (run_gnuplot).
  void render() const;

 private:
  std::filesystem::path dir_;
  std::string stem_;
  std::ostringstream script_;
};

}  // namespace talus
