#include "talus/report/dacre_wright_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"

namespace talus {
namespace {

/// "x_centre y_centre x_half y_half", the columns of gnuplot's boxxyerror.
void write_box(std::ofstream& out, const CsBox& b) {
  out << fmt("%.9g", 0.5 * (b.x1 + b.x2)) << ' ' << fmt("%.9g", 0.5 * (b.y1 + b.y2)) << ' '
      << fmt("%.9g", 0.5 * (b.x2 - b.x1)) << ' ' << fmt("%.9g", 0.5 * (b.y2 - b.y1)) << '\n';
}

}  // namespace

std::string dacre_wright_voxels_csv(const DacreWrightResult& result) {
  std::string csv = std::string(kDacreWrightVoxelsCsvHeader) + "\n";
  for (const DecidedVoxel& v : result.voxels) {
    const CsBox& b = v.box;
    csv += std::to_string(v.key.level);
    for (double x : {b.x1, b.x2, b.y1, b.y2, b.theta1, b.theta2}) {
      csv += ',';
      csv += csv_number(x, 17);
    }
    csv += ",";
    csv += to_string(v.status);
    csv += "\n";
  }
  return csv;
}

std::string dacre_wright_channel_csv(const DacreWrightResult& result) {
  std::string csv = std::string(kDacreWrightChannelCsvHeader) + "\n";
  for (std::size_t k = 0; k < result.channel_indices.size(); ++k) {
    csv += std::to_string(k);
    csv += ',';
    csv += std::to_string(result.channel_indices[k]);
    csv += '\n';
  }
  return csv;
}

void add_dacre_wright_summary(nlohmann::json& summary, const DacreWrightResult& result) {
  summary["dacre_wright_status"] = to_string(result.status);
  summary["reference_level"] = result.reference_level;
  summary["voxels_analysed_per_level"] = result.analyses_per_level;
  summary["voxels_decided"] = result.voxels.size();
  summary["free_leaves"] = result.free_leaf_indices.size();
  summary["free_volume_fraction"] = result.free_volume_fraction;
  summary["expansions"] = result.expansions;
}

OctreeSliceFigure octree_slice_figure(const DacreWrightResult& result) {
  OctreeSliceFigure f;
  for (std::size_t k : result.free_leaf_indices) f.free_voxels.push_back(result.voxels[k].box);
  f.channel = result.channel_boxes;
  f.path = result.path;
  return f;
}

void render_octree_slices(const std::filesystem::path& dir, const std::string& stem,
                          const OctreeSliceFigure& fig) {
  const std::filesystem::path slices = dir / (stem + "_slices.dat");
  std::ofstream out = open_output_file(slices);
  for (double th : fig.thetas) {
    // One gnuplot data block per slice (a blank-line-separated "index"), with a
    // dummy off-range point so an empty slice is still a block.
    out << fmt("%.9g", fig.x_min - 1e9) << " 0 0 0\n";
    for (const CsBox& b : fig.free_voxels) {
      if (th >= b.theta1 && th < b.theta2) write_box(out, b);
    }
    out << "\n\n";
  }
  close_output_file(out, slices);
  const std::filesystem::path channel = dir / (stem + "_channel.dat");
  std::ofstream ch = open_output_file(channel);
  ch << fmt("%.9g", fig.x_min - 1e9) << " 0 0 0\n";
  for (const CsBox& b : fig.channel) write_box(ch, b);
  close_output_file(ch, channel);
  const std::filesystem::path path = dir / (stem + "_path.dat");
  std::ofstream pa = open_output_file(path);
  pa << fmt("%.9g", fig.x_min - 1e9) << " 0\n\n";
  for (const SE2Pose& q : fig.path) pa << fmt("%.9g", q.x) << ' ' << fmt("%.9g", q.y) << '\n';
  close_output_file(pa, path);

  const std::size_t n = fig.thetas.size();
  const int cols = n <= 1 ? 1 : (n <= 4 ? 2 : 3);
  const int rows = static_cast<int>((n + static_cast<std::size_t>(cols) - 1) / cols);
  std::string gp = "# " + stem +
                   ": FREE voxels at heading slices, the channel and the path.\n"
                   "# Re-render in this folder with: gnuplot " +
                   stem + ".gp\n";
  gp += png_terminal(560 * cols + 80, 520 * rows + 80) + "\nset output " +
        gnuplot_string(stem + ".png") + "\n";
  gp += "set multiplot layout " + std::to_string(rows) + "," + std::to_string(cols) + " title " +
        gnuplot_plain_text(fig.title) + "\n";
  gp += "set size ratio -1\nset xrange [" + fmt("%.9g", fig.x_min) + ":" + fmt("%.9g", fig.x_max) +
        "]\nset yrange [" + fmt("%.9g", fig.y_min) + ":" + fmt("%.9g", fig.y_max) +
        "]\nset xlabel 'x [m]'\nset ylabel 'y [m]'\nset key off\n";
  for (std::size_t k = 0; k < n; ++k) {
    gp += "set title " +
          gnuplot_string("θ = " + fmt("%.0f", fig.thetas[k] * 180 / std::numbers::pi) + "°") + "\n";
    gp += "plot " + gnuplot_string(stem + "_slices.dat") + " index " + std::to_string(k) +
          " with boxxyerror fs solid 0.35 lc rgb '#2ca25f' lw 0.5, " +
          gnuplot_string(stem + "_channel.dat") +
          " with boxxyerror fs empty lc rgb '#e6550d' lw 1.5, " +
          gnuplot_string(stem + "_path.dat") + " with lines lc rgb '#08519c' lw 2\n";
  }
  gp += "unset multiplot\n";
  write_text_file(dir / (stem + ".gp"), gp);
  run_gnuplot(dir / (stem + ".gp"));
}

}  // namespace talus
