#include "talus/report/plan_figures.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "talus/report/figure.hpp"
#include "talus/report/map_frame.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/relief_raster.hpp"

namespace talus {
namespace {

void write_polyline(std::ofstream& out, const std::vector<Vec2>& points, const Vec2& origin) {
  for (const Vec2& p : points) out << offset_row(p, origin) << '\n';
  out << "\n\n";  // one gnuplot `index` block per path
}

}  // namespace

void render_plan_map(const std::filesystem::path& dir, const PlanMapData& data) {
  const MapFrame frame(data.origin, data.width, data.height);
  GnuplotFigure figure(dir, "plan");
  write_relief_image(*data.surface, frame, "fitted B-patch", figure.file("_relief.rgb"));

  // Blocks: the global candidates, then the optimised paths, then start and goal.
  const std::filesystem::path routes = figure.file("_routes.dat");
  std::ofstream out = open_output_file(routes);
  out << "# x - x_min [m], y - y_min [m]; blocks: " << data.candidates.size()
      << " global candidates, " << data.optimised.size() << " optimised paths, start and goal\n";
  for (const auto& c : data.candidates) write_polyline(out, c, data.origin);
  for (const auto& o : data.optimised) write_polyline(out, o, data.origin);
  write_polyline(out, {data.start, data.goal}, data.origin);
  close_output_file(out, routes);

  const std::size_t nc = data.candidates.size(), no = data.optimised.size();
  PlotItems items{"'plan_relief.rgb' using 1:2:3:4:5 with rgbimage notitle"};
  const auto block = [](std::size_t index) {
    return "'plan_routes.dat' index " + std::to_string(index) + " using 1:2 with lines ";
  };
  for (std::size_t c = 0; c < nc; ++c) {
    items.push_back(block(c) + "lw 1.5 dt 2 lc rgb '#404040' " +
                    (c == 0 ? "title 'global candidates'" : "notitle"));
  }
  bool other_titled = false;
  for (std::size_t o = 0; o < no; ++o) {
    if (o == data.best || !std::isfinite(data.optimised_times[o])) continue;
    items.push_back(block(nc + o) + "lw 2.5 lc rgb '#2c7fb8' " +
                    (other_titled ? "notitle" : "title 'other optimised paths'"));
    other_titled = true;
  }
  if (data.best < no) {
    items.push_back(block(nc + data.best) + "lw 7 lc rgb 'black' notitle");
    items.push_back(block(nc + data.best) + "lw 5 lc rgb '#e6550d' title " +
                    gnuplot_string("best: " + fmt("%.2f", data.optimised_times[data.best]) + " s"));
  }
  items.push_back(frame.endpoint_items("plan_routes.dat", nc + no));
  figure.canvas(1100, frame.canvas_height(1100))
      << frame.axes() << "set key outside bottom center horizontal samplen 2\n";
  figure.title(data.title).plot(items).render();
}

void render_plan_profile(const std::filesystem::path& dir, const PlanProfileData& data) {
  const std::filesystem::path profile = dir / "plan_profile.dat";
  std::ofstream out = open_output_file(profile);
  out << "# s [m], v [m/s], v_max [m/s] (NaN = unlimited)\n";
  double top = 0.0;
  for (std::size_t k = 0; k < data.s.size(); ++k) {
    const bool limited = std::isfinite(data.v_max[k]);
    out << fmt("%.8g", data.s[k]) << ' ' << fmt("%.8g", data.v[k]) << ' '
        << (limited ? fmt("%.8g", data.v_max[k]) : std::string("NaN")) << '\n';
    top = std::max(top, data.v[k]);
    if (limited) top = std::max(top, data.v_max[k]);
  }
  close_output_file(out, profile);
  const std::filesystem::path switching = dir / "plan_switching.dat";
  out = open_output_file(switching);
  out << "# switching points: s [m], v [m/s]\n";
  for (std::size_t k = 0; k < data.switch_s.size(); ++k) {
    out << fmt("%.8g", data.switch_s[k]) << ' ' << fmt("%.8g", data.switch_v[k]) << '\n';
  }
  if (data.switch_s.empty()) out << "NaN NaN\n";  // gnuplot refuses an empty file
  close_output_file(out, switching);

  GnuplotFigure figure(dir, "profile");
  figure.canvas(1100, 550).title(data.title)
      << "set xlabel 's [m]'\nset ylabel 'speed [m/s]'\n"
      << "set xrange [0:" << fmt("%.10g", data.s.empty() ? 1.0 : data.s.back()) << "]\n"
      << "set yrange [0:" << fmt("%.6g", 1.1 * std::max(top, 1e-3)) << "]\n"
      << "set grid\nset key outside bottom center horizontal samplen 2\n";
  figure
      .plot({"'plan_profile.dat' using 1:3 with filledcurves y1=0 fs transparent solid 0.15 "
             "lc rgb '#d73027' notitle",
             "'' using 1:3 with lines lw 1.5 lc rgb '#d73027' title 'v_{max}(s)'",
             "'' using 1:2 with lines lw 2.5 lc rgb '#2c7fb8' title 'v(s), time-optimal'",
             "'plan_switching.dat' using 1:2 with points pt 7 ps 1.2 lc rgb 'black' "
             "title 'switching points'"})
      .render();
}

}  // namespace talus
