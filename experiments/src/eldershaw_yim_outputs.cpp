#include "eldershaw_yim_outputs.hpp"

#include <cmath>
#include <fstream>
#include <numbers>

#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"

namespace talus::experiments {

std::string eldershaw_yim_points_csv(const EldershawYimResult& result, const CgLattice& lattice) {
  std::string csv = std::string(kEldershawYimPointsCsvHeader) + "\n";
  for (std::size_t k = 0; k < result.prm_points.size(); ++k) {
    const CgCell& c = result.prm_points[k];
    const SE2Pose q = lattice.centre(c);
    csv += std::to_string(k) + "," + std::to_string(c.ix) + "," + std::to_string(c.iy) + "," +
           std::to_string(c.it) + "," + csv_number(q.x, 17) + "," + csv_number(q.y, 17) + "," +
           csv_number(q.theta, 17) + "\n";
  }
  return csv;
}

std::string eldershaw_yim_edges_csv(const EldershawYimResult& result) {
  std::string csv = std::string(kEldershawYimEdgesCsvHeader) + "\n";
  for (const auto& [a, b] : result.prm_edges)
    csv += std::to_string(a) + "," + std::to_string(b) + "\n";
  return csv;
}

std::string eldershaw_yim_steps_csv(const EldershawYimResult& result, const Footmap& footmap,
                                    std::size_t legs) {
  std::string csv = "step,move,cg_x,cg_y,cg_theta";
  for (std::size_t l = 0; l < legs; ++l) {
    for (const char* column : {",foot_x_", ",foot_y_", ",foot_z_", ",contact_"}) {
      csv.append(column);
      csv.append(std::to_string(l));
    }
  }
  csv.push_back('\n');
  if (!result.feet_planned) return csv;
  auto number = [&csv](double v) {
    csv.push_back(',');
    csv.append(csv_number(v, 17));
  };
  for (std::size_t k = 0; k < result.foot_plan.steps.size(); ++k) {
    const FootStep& st = result.foot_plan.steps[k];
    csv.append(std::to_string(k));
    csv.push_back(',');
    csv.append(to_string(st.move));
    number(st.cg.x);
    number(st.cg.y);
    number(st.cg.theta);
    for (const FootState& f : st.feet) {
      const Vec3 p = foot_position(footmap, f);
      number(p.x());
      number(p.y());
      number(p.z());
      csv.append(f.contact ? ",1" : ",0");
    }
    csv.push_back('\n');
  }
  return csv;
}

nlohmann::json cg_slice_counts(const std::vector<CgState>& slice) {
  nlohmann::json out = {{"valid", 0}, {"off_data", 0}, {"no_support", 0}, {"too_short", 0}};
  for (CgState s : slice) {
    if (s == CgState::kUnknown) continue;
    out[to_string(s)] = out[to_string(s)].get<std::size_t>() + 1;
  }
  return out;
}

void render_cg_map(const std::filesystem::path& dir, const std::string& stem,
                   const CgMapFigure& fig) {
  const Footmap& fm = *fig.footmap;
  const CgLattice& L = *fig.lattice;
  const ElevationGrid& g = fm.terrain().grid();
  const double far = g.x_min() - 1e9;  // a dummy point so that no data file is empty
  {
    const std::filesystem::path file = dir / (stem + "_foot.dat");
    std::ofstream out = open_output_file(file);
    out << fmt("%.9g", far) << " 0\n";
    for (std::size_t j = 0; j < fm.nrows(); ++j)
      for (std::size_t i = 0; i < fm.ncols(); ++i)
        if (!fm.valid(i, j)) {
          const Vec2 p = g.node_position(i, j);
          out << fmt("%.9g", p.x()) << ' ' << fmt("%.9g", p.y()) << '\n';
        }
    close_output_file(out, file);
  }
  {
    const std::filesystem::path file = dir / (stem + "_cells.dat");
    std::ofstream out = open_output_file(file);
    out << fmt("%.9g", far) << " 0 0 0\n";
    const double half = 0.5 * L.spacing();
    for (int iy = 0; iy < L.ny(); ++iy)
      for (int ix = 0; ix < L.nx(); ++ix) {
        const CgState s =
            fig.slice[static_cast<std::size_t>(iy) * static_cast<std::size_t>(L.nx()) +
                      static_cast<std::size_t>(ix)];
        if (s == CgState::kValid || s == CgState::kUnknown) continue;
        const SE2Pose q = L.centre({ix, iy, fig.it});
        out << fmt("%.9g", q.x) << ' ' << fmt("%.9g", q.y) << ' ' << fmt("%.9g", half) << ' '
            << fmt("%.9g", half) << '\n';
      }
    close_output_file(out, file);
  }
  {
    const std::filesystem::path file = dir / (stem + "_steps.dat");
    std::ofstream out = open_output_file(file);
    out << fmt("%.9g", far) << " 0\n";
    for (const Vec2& p : fig.footprints)
      out << fmt("%.9g", p.x()) << ' ' << fmt("%.9g", p.y()) << '\n';
    close_output_file(out, file);
  }
  for (const auto& [name, poses] :
       {std::pair{"_path.dat", &fig.path}, std::pair{"_prm.dat", &fig.prm_points}}) {
    const std::filesystem::path file = dir / (stem + name);
    std::ofstream out = open_output_file(file);
    out << fmt("%.9g", far) << " 0\n\n";
    for (const SE2Pose& q : *poses) out << fmt("%.9g", q.x) << ' ' << fmt("%.9g", q.y) << '\n';
    close_output_file(out, file);
  }
  std::string gp = "# " + stem +
                   ": footmap (invalid foot nodes: circles), invalid CG cells at one heading "
                   "(black), CG path and PRM points.\n# Re-render in this folder with: gnuplot " +
                   stem + ".gp\n";
  gp += png_terminal(900, 900) + "\nset output " + gnuplot_string(stem + ".png") + "\n";
  gp += "set title " +
        gnuplot_plain_text(
            fig.title + " (θ = " + fmt("%.1f", L.heading(fig.it) * 180 / std::numbers::pi) + "°)") +
        "\n";
  gp += "set size ratio -1\nset xrange [" + fmt("%.9g", g.x_min()) + ":" + fmt("%.9g", g.x_max()) +
        "]\nset yrange [" + fmt("%.9g", g.y_min()) + ":" + fmt("%.9g", g.y_max()) +
        "]\nset xlabel 'x [m]'\nset ylabel 'y [m]'\nset key below\n";
  gp += "plot " + gnuplot_string(stem + "_cells.dat") +
        " with boxxyerror fs solid 1.0 lc rgb '#000000' title 'invalid CG cell', " +
        gnuplot_string(stem + "_foot.dat") +
        " with points pt 6 ps 0.4 lc rgb '#3182bd' title 'invalid foot node', " +
        gnuplot_string(stem + "_prm.dat") +
        " with points pt 7 ps 0.5 lc rgb '#31a354' title 'PRM point', " +
        gnuplot_string(stem + "_steps.dat") +
        " with points pt 2 ps 0.6 lc rgb '#756bb1' title 'footprint', " +
        gnuplot_string(stem + "_path.dat") + " with lines lc rgb '#e6550d' lw 2 title 'CG path'\n";
  write_text_file(dir / (stem + ".gp"), gp);
  run_gnuplot(dir / (stem + ".gp"));
}

}  // namespace talus::experiments
