#include "talus/report/path_map.hpp"

#include <fstream>
#include <sstream>

#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"

namespace talus {

void write_path_points(const std::vector<Vec2>& offsets, const std::string& header,
                       const std::filesystem::path& file) {
  std::ofstream out = open_output_file(file);
  out << header;
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    out << fmt("%.7g", offsets[i].x()) << ' ' << fmt("%.7g", offsets[i].y()) << " P" << i << '\n';
  }
  close_output_file(out, file);
}

std::string path_map_settings(const MapFrame& frame, const std::string& title, double max_speed,
                              const std::string& speed_label) {
  std::ostringstream gp;
  gp << frame.axes() << "set title " << gnuplot_string(title) << " font ',10'\n"
     << "# ColorBrewer RdYlBu: red = slow, blue = fast.\n"
     << "set palette defined (0 '#a50026', 0.25 '#f46d43', 0.5 '#fee090', 0.75 '#74add1', "
        "1 '#313695')\n"
     << "set cbrange [0:" << fmt("%g", max_speed) << "]\n"
     << "set cblabel " << gnuplot_string(speed_label) << "\nset colorbox\n"
     << "set key outside bottom center horizontal samplen 2\n";
  return gp.str();
}

std::string path_map_plot(const std::string& relief_file, const std::string& path_file,
                          const std::string& path_title, const std::string& extra_items,
                          const std::string& points_file) {
  std::ostringstream gp;
  gp << "plot " << gnuplot_string(relief_file) << " using 1:2:3:4:5 with rgbimage notitle, \\\n"
     << "     " << gnuplot_string(path_file)
     << " using 1:2 with lines lw 9 lc rgb 'black' notitle, \\\n"
     << "     '' using 1:2:3 with lines lw 7 lc palette title " << gnuplot_string(path_title)
     << ", \\\n"
     << extra_items << "     " << gnuplot_string(points_file)
     << " using 1:2 with points pt 7 ps 1.4 lc rgb 'black' title 'interpolation points', \\\n"
     << "     '' using 1:2:3 with labels offset char 1.2,0.8 font ',11' tc rgb 'black' notitle\n";
  return gp.str();
}

}  // namespace talus
