#include "hait_figures.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <utility>

#include "talus/bspline/bpatch.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/map_frame.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/relief_raster.hpp"

namespace talus::experiments {
namespace {

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
  const MapFrame frame = MapFrame::of(grid);
  GnuplotFigure figure(dir, stem);
  write_relief_image(BPatch::interpolate(filled), frame, "interpolating B-patch of the grid",
                     figure.file("_relief.rgb"));

  // Blocks: every route, then start and goal with a heading arrow of 1 m.
  const std::filesystem::path routes = figure.file("_routes.dat");
  std::ofstream out = open_output_file(routes);
  out << "# x - x_min [m], y - y_min [m]; blocks: " << data.routes.size()
      << " routes, then start and goal (x, y, dx, dy of a 1 m heading arrow)\n";
  for (const HaitRoute& r : data.routes) {
    for (const PathPoint& p : r.path) {
      out << offset_row({p.pose.x, p.pose.y}, frame.origin()) << '\n';
    }
    if (r.path.empty()) out << "NaN NaN\n";  // gnuplot refuses an empty block
    out << "\n\n";
  }
  for (const SE2Pose& q : {data.start, data.goal}) {
    out << offset_row({q.x, q.y}, frame.origin()) << ' ' << fmt("%.6g", std::cos(q.theta)) << ' '
        << fmt("%.6g", std::sin(q.theta)) << '\n';
  }
  close_output_file(out, routes);

  const std::string data_file = gnuplot_string(figure.name("_routes.dat"));
  PlotItems items{gnuplot_string(figure.name("_relief.rgb")) +
                  " using 1:2:3:4:5 with rgbimage notitle"};
  for (std::size_t r = 0; r < data.routes.size(); ++r) {
    const std::string block = data_file + " index " + std::to_string(r) + " using 1:2 with lines ";
    items.push_back(block + "lw 5 lc rgb 'black' notitle");
    items.push_back(block + "lw 3 lc rgb " + gnuplot_string(data.routes[r].colour) + " title " +
                    gnuplot_plain_text(data.routes[r].label));
  }
  const std::size_t ends = data.routes.size();
  items.push_back(frame.endpoint_items(figure.name("_routes.dat"), ends));
  items.push_back(data_file + " index " + std::to_string(ends) +
                  " using 1:2:3:4 with vectors head filled lw 2 lc rgb 'black' notitle");
  figure.canvas(1100, frame.canvas_height(1100))
      << frame.axes() << "set key outside bottom center horizontal samplen 2\n";
  figure.title(data.title).plot(items).render();
}

void render_hait_map(const std::filesystem::path& dir, const std::string& stem,
                     const HaitScenario& scenario, std::vector<HaitRoute> routes,
                     std::string title) {
  render_hait_map(
      dir, stem,
      {&scenario.grid, std::move(routes), scenario.start, scenario.goal, std::move(title)});
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
