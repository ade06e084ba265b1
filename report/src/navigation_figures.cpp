#include "talus/report/navigation_figures.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include "talus/core/error.hpp"
#include "talus/report/figure.hpp"
#include "talus/report/map_frame.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/report/relief_raster.hpp"

namespace talus {
namespace {

/// "NaN" for a value gnuplot should skip (an infinite cap, no safe speed).
std::string number_or_nan(double value) {
  return std::isfinite(value) ? fmt("%.8g", value) : std::string("NaN");
}

double degrees(double radians) {
  return radians * 180.0 / std::numbers::pi;
}

/// Figure 7: relief, waypoints, driven path, start and goal.
void render_map(const std::filesystem::path& dir, const std::string& stem,
                const NavigationFigureData& data) {
  const MapFrame frame = MapFrame::of(*data.surface);
  GnuplotFigure figure(dir, stem + "_map");
  write_relief_image(*data.surface, frame, "fitted B-patch", figure.file("_relief.rgb"));
  const std::filesystem::path routes = figure.file(".dat");
  std::ofstream out = open_output_file(routes);
  out << "# x - x_min [m], y - y_min [m]; blocks: waypoints, driven path, start and goal\n";
  for (const Vec2& p : data.waypoints->points) out << offset_row(p, frame.origin()) << '\n';
  out << "\n\n";
  for (const VehicleSample& s : data.result->simulation.trace)
    out << offset_row(Vec2(s.state.position.x(), s.state.position.y()), frame.origin()) << '\n';
  out << "\n\n";
  out << offset_row(data.start, frame.origin()) << '\n'
      << offset_row(data.goal, frame.origin()) << '\n';
  close_output_file(out, routes);

  const std::string file = gnuplot_string(figure.name(".dat"));
  figure.describe("terrain relief, high-level waypoints and the driven path (IROS 2008 fig. 7)",
                  figure.name(".dat") + ", " + figure.name("_relief.rgb"))
          .canvas(1000, frame.canvas_height(1000))
      << frame.axes() << "set key outside bottom center horizontal samplen 2\n";
  figure.title(data.title)
      .plot({gnuplot_string(figure.name("_relief.rgb")) + " using 1:2:3:4:5 with rgbimage notitle",
             file + " index 1 using " + frame.xy() + " with lines lw 5 lc rgb 'black' notitle",
             file + " index 1 using " + frame.xy() +
                 " with lines lw 3 lc rgb '#e6550d' title 'driven path'",
             file + " index 0 using " + frame.xy() +
                 " with points pt 9 ps 1.4 lc rgb '#2c7fb8' title 'waypoints (high-level plan)'",
             frame.endpoint_items(figure.name(".dat"), 2)})
      .render();
}

/// Figure 8: speed, command, the lookahead's safe speed and its caps against time.
void render_speed(const std::filesystem::path& dir, const std::string& stem,
                  const NavigationFigureData& data) {
  const PotentialFieldNavigationResult& r = *data.result;
  GnuplotFigure figure(dir, stem + "_speed");
  const std::filesystem::path path = figure.file(".dat");
  std::ofstream out = open_output_file(path);
  out << "# block 0, every trace sample: t [s], speed [m/s]\n";
  for (const VehicleSample& s : r.simulation.trace)
    out << fmt("%.8g", s.t) << ' ' << fmt("%.8g", s.speed) << '\n';
  out << "\n\n# block 1, every control tick: t [s], commanded speed, safe speed at the c.g., "
         "applied cap [m/s] (NaN = none)\n";
  for (std::size_t k = 0; k < r.commands.size(); ++k) {
    const double safe = k < r.lookahead_safe_speeds.size()
                            ? r.lookahead_safe_speeds[k]
                            : std::numeric_limits<double>::quiet_NaN();
    out << fmt("%.8g", r.command_times[k]) << ' ' << fmt("%.8g", r.commands[k].speed) << ' '
        << number_or_nan(safe) << ' ' << number_or_nan(r.lookahead_caps[k]) << '\n';
  }
  if (r.commands.empty()) out << "NaN NaN NaN NaN\n";  // gnuplot refuses an empty block
  close_output_file(out, path);

  const std::string file = gnuplot_string(figure.name(".dat"));
  figure.describe("speed against the lookahead's safe speed (IROS 2008 fig. 8)",
                  figure.name(".dat"))
          .canvas(1100, 550)
          .title(data.title)
      << "set xlabel 'time [s]'\nset ylabel 'speed [m/s]'\nset grid\nset yrange [0:*]\n"
      << "set key outside bottom center horizontal samplen 2\n";
  figure
      .plot({file + " index 1 using 1:3 with lines lw 1.5 lc rgb '#d73027' "
                    "title 'maximum safe speed (lookahead)'",
             file + " index 1 using 1:2 with lines lw 1 dt 2 lc rgb '#404040' "
                    "title 'commanded speed'",
             file + " index 1 using 1:4 with points pt 7 ps 0.3 lc rgb '#984ea3' "
                    "title 'lookahead cap applied'",
             file + " index 0 using 1:2 with lines lw 2.5 lc rgb '#2c7fb8' title 'UGV speed'"})
      .render();
}

/// Figure 9: roll and side-slip angles against time.
void render_angles(const std::filesystem::path& dir, const std::string& stem,
                   const NavigationFigureData& data) {
  GnuplotFigure figure(dir, stem + "_angles");
  const std::filesystem::path path = figure.file(".dat");
  std::ofstream out = open_output_file(path);
  out << "# t [s], roll [deg], body side-slip angle [deg]\n";
  for (const VehicleSample& s : data.result->simulation.trace)
    out << fmt("%.8g", s.t) << ' ' << fmt("%.6g", degrees(s.state.roll)) << ' '
        << fmt("%.6g", degrees(s.side_slip)) << '\n';
  close_output_file(out, path);
  const std::string file = gnuplot_string(figure.name(".dat"));
  figure.describe("roll and side-slip angles (IROS 2008 fig. 9)", figure.name(".dat"))
          .canvas(1100, 550)
          .title(data.title)
      << "set xlabel 'time [s]'\nset ylabel 'angle [deg]'\nset grid\n"
      << "set key outside bottom center horizontal samplen 2\n";
  figure
      .plot({file + " using 1:2 with lines lw 2 lc rgb '#2c7fb8' title 'roll angle'",
             file + " using 1:3 with lines lw 2 lc rgb '#e6550d' title 'side-slip angle'"})
      .render();
}

}  // namespace

void render_navigation_figures(const std::filesystem::path& dir, const std::string& stem,
                               const NavigationFigureData& data) {
  if (!data.surface || data.waypoints == nullptr || data.result == nullptr)
    throw InputError("render_navigation_figures: surface, waypoints and result are required");
  render_map(dir, stem, data);
  render_speed(dir, stem, data);
  render_angles(dir, stem, data);
}

}  // namespace talus
