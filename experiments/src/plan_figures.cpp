#include "plan_figures.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "number_format.hpp"
#include "path_map.hpp"
#include "plot.hpp"
#include "relief.hpp"
#include "relief_raster.hpp"

namespace talus::experiments {
namespace {

constexpr std::size_t kRasterMaxSamples = 500;
constexpr double kAmbient = 0.35;

void write_polyline(std::ofstream& out, const std::vector<Vec2>& points, const Vec2& origin) {
  for (const Vec2& p : points) {
    out << fmt("%.8g", p.x() - origin.x()) << ' ' << fmt("%.8g", p.y() - origin.y()) << '\n';
  }
  out << "\n\n";  // one gnuplot `index` block per path
}

}  // namespace

void render_plan_map(const std::filesystem::path& dir, const PlanMapData& data) {
  const ReliefRaster raster =
      sample_relief(*data.surface, data.origin, data.width, data.height, kRasterMaxSamples);
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (const SurfacePoint& p : raster.samples) {
    zmin = std::min(zmin, p.z);
    zmax = std::max(zmax, p.z);
  }
  const double exaggeration = hillshade_exaggeration(slope_p95(raster));
  write_relief_rgb(raster, {zmin, zmax, {315.0, 45.0}, exaggeration, kAmbient, true},
                   "# fitted B-patch: hypsometric colour x hillshade, washed towards white\n"
                   "# x - x_min [m], y - y_min [m], red, green, blue\n",
                   dir / "plan_relief.rgb");

  // Blocks: the global candidates, then the optimised paths, then start and goal.
  const std::filesystem::path routes = dir / "plan_routes.dat";
  std::ofstream out = open_output_file(routes);
  out << "# x - x_min [m], y - y_min [m]; blocks: " << data.candidates.size()
      << " global candidates, " << data.optimised.size() << " optimised paths, start and goal\n";
  for (const auto& c : data.candidates) write_polyline(out, c, data.origin);
  for (const auto& o : data.optimised) write_polyline(out, o, data.origin);
  write_polyline(out, {data.start, data.goal}, data.origin);
  close_output_file(out, routes);

  const std::size_t nc = data.candidates.size(), no = data.optimised.size();
  std::ostringstream gp;
  gp << png_terminal(1100, path_map_canvas_height(data.width, data.height))
     << "set output 'plan.png'\n"
     << "set size ratio -1\n"
     << "set xrange [0:" << fmt("%.10g", data.width)
     << "]\nset yrange [0:" << fmt("%.10g", data.height) << "]\n"
     << "set xlabel 'x − x_{min} [m]  (east)'\nset ylabel 'y − y_{min} [m]  (north)'\n"
     << "set tics out nomirror\n"
     << "set title " << gnuplot_plain_text(data.title) << " font ',10'\n"
     << "set key outside bottom center horizontal samplen 2\n"
     << "plot 'plan_relief.rgb' using 1:2:3:4:5 with rgbimage notitle";
  for (std::size_t c = 0; c < nc; ++c) {
    gp << ", \\\n     'plan_routes.dat' index " << c
       << " using 1:2 with lines lw 1.5 dt 2 lc rgb '#404040' "
       << (c == 0 ? "title 'global candidates'" : "notitle");
  }
  bool other_titled = false;
  for (std::size_t o = 0; o < no; ++o) {
    if (o == data.best || !std::isfinite(data.optimised_times[o])) continue;
    gp << ", \\\n     'plan_routes.dat' index " << nc + o
       << " using 1:2 with lines lw 2.5 lc rgb '#2c7fb8' "
       << (other_titled ? "notitle" : "title 'other optimised paths'");
    other_titled = true;
  }
  if (data.best < no) {
    gp << ", \\\n     'plan_routes.dat' index " << nc + data.best
       << " using 1:2 with lines lw 7 lc rgb 'black' notitle"
       << ", \\\n     '' index " << nc + data.best
       << " using 1:2 with lines lw 5 lc rgb '#e6550d' title "
       << gnuplot_string("best: " + fmt("%.2f", data.optimised_times[data.best]) + " s");
  }
  gp << ", \\\n     'plan_routes.dat' index " << nc + no
     << " every ::0::0 using 1:2 with points pt 7 ps 2 lc rgb '#1a9850' title 'start'"
     << ", \\\n     '' index " << nc + no
     << " every ::1::1 using 1:2 with points pt 5 ps 2 lc rgb '#d73027' title 'goal'\n";
  const std::filesystem::path script = dir / "plan.gp";
  write_text_file(script, gp.str());
  run_gnuplot(script);
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

  std::ostringstream gp;
  gp << png_terminal(1100, 550) << "set output 'profile.png'\n"
     << "set title " << gnuplot_plain_text(data.title) << " font ',10'\n"
     << "set xlabel 's [m]'\nset ylabel 'speed [m/s]'\n"
     << "set xrange [0:" << fmt("%.10g", data.s.empty() ? 1.0 : data.s.back()) << "]\n"
     << "set yrange [0:" << fmt("%.6g", 1.1 * std::max(top, 1e-3)) << "]\n"
     << "set grid\nset key outside bottom center horizontal samplen 2\n"
     << "plot 'plan_profile.dat' using 1:3 with filledcurves y1=0 fs transparent solid 0.15 "
        "lc rgb '#d73027' notitle, \\\n"
     << "     '' using 1:3 with lines lw 1.5 lc rgb '#d73027' title 'v_{max}(s)', \\\n"
     << "     '' using 1:2 with lines lw 2.5 lc rgb '#2c7fb8' title 'v(s), time-optimal', \\\n"
     << "     'plan_switching.dat' using 1:2 with points pt 7 ps 1.2 lc rgb 'black' "
        "title 'switching points'\n";
  const std::filesystem::path script = dir / "profile.gp";
  write_text_file(script, gp.str());
  run_gnuplot(script);
}

}  // namespace talus::experiments
