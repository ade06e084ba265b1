#include "hait_figures.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "number_format.hpp"
#include "path_map.hpp"
#include "plot.hpp"
#include "relief.hpp"
#include "relief_raster.hpp"
#include "talus/bspline/bpatch.hpp"

namespace talus::experiments {
namespace {

constexpr std::size_t kRasterMaxSamples = 500;

/// Appends the shortest text that reads back as exactly `value`.
void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

}  // namespace

void render_hait_map(const std::filesystem::path& dir, const std::string& stem,
                     const HaitMapData& data) {
  const ElevationGrid& grid = *data.grid;
  // The picture needs a complete surface; the planner itself never sees this fill.
  const ElevationGrid filled = grid.void_count() > 0 ? fill_voids(grid, VoidFill::kNearest) : grid;
  const BPatch surface = BPatch::interpolate(filled);
  const Vec2 origin(grid.x_min(), grid.y_min());
  const double width = grid.x_max() - grid.x_min(), height = grid.y_max() - grid.y_min();
  const ReliefRaster raster = sample_relief(surface, origin, width, height, kRasterMaxSamples);
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (const SurfacePoint& p : raster.samples) {
    zmin = std::min(zmin, p.z);
    zmax = std::max(zmax, p.z);
  }
  const double exaggeration = hillshade_exaggeration(slope_p95(raster));
  write_relief_rgb(raster, {zmin, zmax, {315.0, 45.0}, exaggeration, 0.35, true},
                   "# interpolating B-patch of the grid: hypsometric colour x hillshade\n"
                   "# x - x_min [m], y - y_min [m], red, green, blue\n",
                   dir / (stem + "_relief.rgb"));

  // Blocks: every route, then start and goal with a heading arrow of 1 m.
  const std::filesystem::path routes = dir / (stem + "_routes.dat");
  std::ofstream out = open_output_file(routes);
  out << "# x - x_min [m], y - y_min [m]; blocks: " << data.routes.size()
      << " routes, then start and goal (x, y, dx, dy of a 1 m heading arrow)\n";
  for (const HaitRoute& r : data.routes) {
    for (const PathPoint& p : r.path) {
      out << fmt("%.8g", p.pose.x - origin.x()) << ' ' << fmt("%.8g", p.pose.y - origin.y())
          << '\n';
    }
    if (r.path.empty()) out << "NaN NaN\n";  // gnuplot refuses an empty block
    out << "\n\n";
  }
  for (const SE2Pose& q : {data.start, data.goal}) {
    out << fmt("%.8g", q.x - origin.x()) << ' ' << fmt("%.8g", q.y - origin.y()) << ' '
        << fmt("%.6g", std::cos(q.theta)) << ' ' << fmt("%.6g", std::sin(q.theta)) << '\n';
  }
  close_output_file(out, routes);

  const std::string data_file = stem + "_routes.dat";
  std::ostringstream gp;
  gp << png_terminal(1100, path_map_canvas_height(width, height)) << "set output "
     << gnuplot_string(stem + ".png") << "\n"
     << "set size ratio -1\n"
     << "set xrange [0:" << fmt("%.10g", width) << "]\nset yrange [0:" << fmt("%.10g", height)
     << "]\n"
     << "set xlabel 'x − x_{min} [m]  (east)'\nset ylabel 'y − y_{min} [m]  (north)'\n"
     << "set tics out nomirror\n"
     << "set title " << gnuplot_plain_text(data.title) << " font ',10'\n"
     << "set key outside bottom center horizontal samplen 2\n"
     << "plot " << gnuplot_string(stem + "_relief.rgb") << " using 1:2:3:4:5 with rgbimage notitle";
  for (std::size_t r = 0; r < data.routes.size(); ++r) {
    gp << ", \\\n     " << gnuplot_string(data_file) << " index " << r
       << " using 1:2 with lines lw 5 lc rgb 'black' notitle"
       << ", \\\n     '' index " << r << " using 1:2 with lines lw 3 lc rgb "
       << gnuplot_string(data.routes[r].colour) << " title "
       << gnuplot_plain_text(data.routes[r].label);
  }
  const std::size_t ends = data.routes.size();
  gp << ", \\\n     " << gnuplot_string(data_file) << " index " << ends
     << " every ::0::0 using 1:2 with points pt 7 ps 2 lc rgb '#1a9850' title 'start'"
     << ", \\\n     '' index " << ends
     << " every ::1::1 using 1:2 with points pt 5 ps 2 lc rgb '#d73027' title 'goal'"
     << ", \\\n     '' index " << ends
     << " using 1:2:3:4 with vectors head filled lw 2 lc rgb 'black' notitle\n";
  const std::filesystem::path script = dir / (stem + ".gp");
  write_text_file(script, std::string_view(gp.str()));
  run_gnuplot(script);
}

std::string baseline_path_csv(const std::vector<SE2Pose>& path,
                              const std::vector<std::string>& motions) {
  std::string csv = "x,y,theta,control\n";
  for (std::size_t k = 0; k < path.size(); ++k) {
    append_number(csv, path[k].x);
    csv += ',';
    append_number(csv, path[k].y);
    csv += ',';
    append_number(csv, path[k].theta);
    csv += ',';
    csv += k < motions.size() ? motions[k] : std::string("none");
    csv += '\n';
  }
  return csv;
}

}  // namespace talus::experiments
