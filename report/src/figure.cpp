#include "talus/report/figure.hpp"

#include <utility>

#include "talus/report/plot.hpp"

namespace talus {
namespace {

std::string plot_command(const PlotItems& items) {
  std::string command = "plot ";
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (k > 0) command += ", \\\n     ";
    command += items[k];
  }
  return command + "\n";
}

}  // namespace

std::string key_entry(std::string_view colour, std::string_view title) {
  return "NaN with lines lw 4 lc rgb '" + std::string(colour) + "' title " + gnuplot_string(title);
}

GnuplotFigure::GnuplotFigure(std::filesystem::path dir, std::string stem)
    : dir_(std::move(dir)), stem_(std::move(stem)) {}

GnuplotFigure& GnuplotFigure::describe(std::string_view what, std::string_view inputs) {
  script_ << "# " << what << "\n# Re-render in this folder with: gnuplot " << stem_ << ".gp\n";
  if (!inputs.empty()) script_ << "# Inputs: " << inputs << "\n";
  return *this;
}

GnuplotFigure& GnuplotFigure::canvas(int width, int height) {
  script_ << png_terminal(width, height) << "set output " << gnuplot_string(stem_ + ".png") << "\n";
  return *this;
}

GnuplotFigure& GnuplotFigure::title(std::string_view text, std::string_view font, bool markup) {
  script_ << "set title " << (markup ? gnuplot_string(text) : gnuplot_plain_text(text));
  if (!font.empty()) script_ << " font '" << font << "'";
  script_ << "\n";
  return *this;
}

GnuplotFigure& GnuplotFigure::plot(const PlotItems& items) {
  script_ << plot_command(items);
  return *this;
}

std::filesystem::path GnuplotFigure::save() const {
  const std::filesystem::path script = file(".gp");
  write_text_file(script, script_.str());
  return script;
}

void GnuplotFigure::render() const {
  run_gnuplot(save());
}

}  // namespace talus
