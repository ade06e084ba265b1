#include "notebook.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>

#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/map_frame.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/relief_raster.hpp"

namespace talus::notebooks {

namespace fs = std::filesystem;

Notebook::Notebook(int argc, char** argv, std::string name, std::string_view title)
    : name_(std::move(name)), data_dir_(TALUS_DATA_DIR), report_(title) {
  fs::path out = "talus-out/notebooks";
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--quick") {
      quick_ = true;
    } else if ((arg == "--out" || arg == "--data") && k + 1 < argc) {
      (arg == "--out" ? out : data_dir_) = argv[++k];
    } else {
      throw InputError("unknown argument '" + arg + "' (expected --quick, --out DIR, --data DIR)");
    }
  }
  dir_ = out / name_;
  fs::create_directories(dir_);
  require_gnuplot();
  std::printf("# %.*s%s\n", static_cast<int>(title.size()), title.data(), quick_ ? " (quick)" : "");
  report_.paragraph(std::string("[All notebooks](../index.md)") +
                    (quick_ ? " · rendered in quick mode (small grids)" : ""));
}

std::string Notebook::data(std::string_view relative) const {
  return (data_dir_ / relative).string();
}

void Notebook::section(std::string_view text) {
  report_.heading(text);
  std::printf("\n## %.*s\n", static_cast<int>(text.size()), text.data());
}

void Notebook::say(std::string_view text) {
  report_.paragraph(text);
  std::printf("%.*s\n", static_cast<int>(text.size()), text.data());
}

void Notebook::table(const Table& table) {
  report_.table(table);
  std::cout << table.markdown();
}

bool Notebook::check(bool holds, std::string_view fact) {
  ++checks_;
  if (!holds) ++failures_;
  const std::string line = std::string(holds ? "✔ " : "✘ FAILED: ") + std::string(fact);
  report_.bullet(line);
  std::printf("%s\n", line.c_str());
  return holds;
}

std::string Notebook::plot(const std::string& stem, std::string_view title, std::string_view xlabel,
                           std::string_view ylabel, const std::vector<Series>& series,
                           std::string_view settings) {
  GnuplotFigure figure(dir_, stem);
  const fs::path data = figure.file(".dat");
  std::ofstream out = open_output_file(data);
  out << "# x y, one block per series\n";
  PlotItems items;
  for (std::size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      out << csv_number(s.x[i], 9) << ' ' << csv_number(s.y[i], 9) << '\n';
    }
    if (s.x.empty()) out << "NaN NaN\n";  // gnuplot refuses an empty block
    out << "\n\n";
    items.push_back(gnuplot_string(figure.name(".dat")) + " index " + std::to_string(k) +
                    " using 1:2 with " + s.style + " title " + gnuplot_string(s.title));
  }
  close_output_file(out, data);
  figure.describe(title, figure.name(".dat")).canvas(1000, 500);
  figure.title(title) << "set xlabel " << gnuplot_string(xlabel) << "\nset ylabel "
                      << gnuplot_string(ylabel)
                      << "\nset grid\nset key outside bottom center horizontal samplen 2\n"
                      << settings;
  figure.plot(items).render();
  return stem + ".png";
}

std::string Notebook::map(const std::string& stem, std::string_view title, const BPatch& surface,
                          const std::vector<Route>& routes) {
  const MapFrame frame = MapFrame::of(surface);
  GnuplotFigure figure(dir_, stem);
  write_relief_image(surface, frame, "fitted B-patch", figure.file("_relief.rgb"),
                     quick_ ? 250 : 500);
  const fs::path data = figure.file("_routes.dat");
  std::ofstream out = open_output_file(data);
  out << "# x - x_min [m], y - y_min [m]; one block per route, then start and goal\n";
  PlotItems items{gnuplot_string(figure.name("_relief.rgb")) + " using " + frame.xy() +
                  ":3:4:5 with rgbimage notitle"};
  for (std::size_t k = 0; k < routes.size(); ++k) {
    for (const Vec2& p : routes[k].points) out << offset_row(p, frame.origin()) << '\n';
    if (routes[k].points.empty()) out << "NaN NaN\n";
    out << "\n\n";
    items.push_back(gnuplot_string(figure.name("_routes.dat")) + " index " + std::to_string(k) +
                    " using " + frame.xy() + " with " + routes[k].style + " title " +
                    gnuplot_string(routes[k].title));
  }
  if (!routes.empty() && !routes.back().points.empty()) {
    out << offset_row(routes.back().points.front(), frame.origin()) << '\n'
        << offset_row(routes.back().points.back(), frame.origin()) << '\n';
    items.push_back(frame.endpoint_items(figure.name("_routes.dat"), routes.size()));
  }
  close_output_file(out, data);
  figure.describe(title, figure.name("_relief.rgb") + ", " + figure.name("_routes.dat"))
      .canvas(900, frame.canvas_height(900, 60));
  figure << frame.axes() << "set key outside bottom center horizontal samplen 2\n";
  figure.title(title).plot(items).render();
  return stem + ".png";
}

void Notebook::figure(std::string_view caption, const std::string& file) {
  report_.figure(caption, file);
  std::printf("[figure %s: %.*s]\n", (dir_ / file).string().c_str(),
              static_cast<int>(caption.size()), caption.data());
}

int Notebook::finish() {
  report_.heading("Checks");
  report_.paragraph(std::to_string(checks_ - failures_) + " of " + std::to_string(checks_) +
                    " checks held in this run.");
  report_.write(dir_);
  std::printf("\n%zu of %zu checks held; page: %s\n", checks_ - failures_, checks_,
              (dir_ / "report.md").string().c_str());
  return failures_ == 0 ? 0 : 1;
}

ElevationGrid west_bijou_at_rover_scale(const Notebook& nb) {
  const ElevationGrid dem =
      read_esri_ascii(nb.data("terrain/west_bijou_escarpment_nasadem25m.asc"));
  ElevationGrid grid(dem.ncols(), dem.nrows(), 1.0, 0.0, 0.0);
  for (std::size_t j = 0; j < dem.nrows(); ++j)
    for (std::size_t i = 0; i < dem.ncols(); ++i) grid.at(i, j) = dem.at(i, j) / 25.0;
  return grid;
}

std::vector<Vec2> rover_path_points() {
  return {Vec2(8, 12), Vec2(28, 40), Vec2(48, 18), Vec2(76, 30), Vec2(92, 66), Vec2(112, 60)};
}

std::string num(const char* format, double value) {
  return fmt(format, value);
}

int run(const std::function<int()>& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "notebook failed: %s\n", e.what());
    return 1;
  }
}

}  // namespace talus::notebooks
