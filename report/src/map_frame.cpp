#include "talus/report/map_frame.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"

namespace talus {

ContourLevels ContourLevels::within(double low, double high, double step) {
  return {std::ceil(low / step) * step, step, std::floor(high / step) * step};
}

std::string trace_contours(std::string_view data_file, int z_column, const ContourLevels& levels,
                           std::string_view contours_file) {
  std::ostringstream gp;
  gp << "# Contours, traced by gnuplot into a table.\n"
     << "set contour base\nunset surface\nset view map\nset cntrparam linear\n"
     << "set cntrparam levels incremental " << fmt("%.10g", levels.first) << ", "
     << fmt("%.10g", levels.step) << ", " << fmt("%.10g", levels.last) << "\n"
     << "set table " << gnuplot_string(contours_file) << "\n"
     << "splot " << gnuplot_string(data_file) << " using 1:2:" << z_column
     << " with lines notitle\n"
     << "unset table\nunset contour\nset surface\n";
  return gp.str();
}

MapFrame::MapFrame(const Vec2& origin, double width, double height, MapUnit unit)
    : origin_(origin), width_(width), height_(height), unit_(unit) {}

MapFrame MapFrame::of(const BPatch& surface, MapUnit unit) {
  return {{surface.x_min(), surface.y_min()},
          surface.x_max() - surface.x_min(),
          surface.y_max() - surface.y_min(),
          unit};
}

MapFrame MapFrame::of(const ElevationGrid& grid, MapUnit unit) {
  return {
      {grid.x_min(), grid.y_min()}, grid.x_max() - grid.x_min(), grid.y_max() - grid.y_min(), unit};
}

int MapFrame::canvas_height(int canvas_width, int extra) const {
  // About 260 px of the width go to the y label, tics and colour key, and
  // 220 px of the height to the title, x label and key below the plot.
  const double plot_width = canvas_width - 260.0;
  return extra + static_cast<int>(std::clamp(220.0 + plot_width * height_ / width_, 450.0, 1200.0));
}

std::string MapFrame::xy() const {
  return unit_ == MapUnit::kKilometre ? "($1/1000):($2/1000)" : "1:2";
}

std::string MapFrame::at(const Vec2& position) const {
  const double scale = unit_ == MapUnit::kKilometre ? 1e-3 : 1.0;
  const Vec2 p = offset(position) * scale;
  return fmt("%.6g", p.x()) + "," + fmt("%.6g", p.y());
}

std::string MapFrame::axes() const {
  const bool km = unit_ == MapUnit::kKilometre;
  const double scale = km ? 1e-3 : 1.0;
  const std::string unit = km ? "km" : "m";
  std::ostringstream gp;
  gp << "set size ratio -1\n"
     << "set xrange [0:" << fmt("%.10g", width_ * scale) << "]\n"
     << "set yrange [0:" << fmt("%.10g", height_ * scale) << "]\n"
     << "set xlabel " << gnuplot_string("x − x_{min} [" + unit + "]  (east)") << "\n"
     << "set ylabel " << gnuplot_string("y − y_{min} [" + unit + "]  (north)") << "\n"
     << "set tics out nomirror\nset format x '%g'\nset format y '%g'\n";
  return gp.str();
}

std::string MapFrame::contour_item(std::string_view contours_file, std::string_view style) const {
  return gnuplot_string(contours_file) + " using " + xy() + " with lines " + std::string(style);
}

std::string MapFrame::endpoint_items(std::string_view file, std::size_t index) const {
  // Black rims keep the markers readable on dark field colours too.
  const std::string block = gnuplot_string(file) + " index " + std::to_string(index);
  const std::string start = " every ::0::0 using " + xy() + " with points pt 7 ps ";
  const std::string goal = " every ::1::1 using " + xy() + " with points pt 5 ps ";
  return block + start + "2.4 lc rgb 'black' notitle, \\\n     " + block + start +
         "1.7 lc rgb '#1a9850' title 'start', \\\n     " + block + goal +
         "2.4 lc rgb 'black' notitle, \\\n     " + block + goal +
         "1.7 lc rgb '#d73027' title 'goal'";
}

std::string offset_row(const Vec2& position, const Vec2& origin) {
  return fmt("%.8g", position.x() - origin.x()) + ' ' + fmt("%.8g", position.y() - origin.y());
}

}  // namespace talus
