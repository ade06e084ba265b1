#pragma once
/// @file
/// The outputs of `talus baseline dacre-wright` beyond the common ones
/// (voxels.csv, channel.csv, summary keys) and the octree figure of the
/// Dacre-Wright–Siméon baseline (the paper's figures 4 and 5), drawn by the
/// `dacre-wright-octree` experiment and by that command: one panel per heading slice θ = θ_k with
/// the FREE voxels cut by that slice (filled), the (x, y) projection of the channel's voxels
/// (outlined) and the path. A gnuplot script is saved beside the PNG (plot.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/dacre_wright/dacre_wright_planner.hpp"

namespace talus {

/// The columns of DIR/voxels.csv.
inline constexpr const char* kDacreWrightVoxelsCsvHeader =
    "level,x_min,x_max,y_min,y_max,theta_min,theta_max,status";
/// The columns of DIR/channel.csv.
inline constexpr const char* kDacreWrightChannelCsvHeader = "step,voxel";

/// voxels.csv: one row per decided voxel of `result` (DacreWrightResult::voxels,
/// in order of decision: analysed ones and, above p0, those combined from their
/// sons), status FREE or MIXED; boxes [m, m, rad] with 17 significant digits so
/// faces shared by neighbours compare equal.
std::string dacre_wright_voxels_csv(const DacreWrightResult& result);

/// channel.csv: one row per channel voxel, V_s first: step 0, 1, … and voxel =
/// its 0-based data-row index in voxels.csv. Header only unless found.
std::string dacre_wright_channel_csv(const DacreWrightResult& result);

/// Adds the octree's keys to a `talus baseline dacre-wright` summary:
/// dacre_wright_status (to_string(DacreWrightStatus)), reference_level,
/// voxels_analysed_per_level (array, index = level), voxels_decided,
/// free_leaves, free_volume_fraction (of what was built), expansions.
void add_dacre_wright_summary(nlohmann::json& summary, const DacreWrightResult& result);

/// What the figure shows; positions in the terrain's frame [m].
struct OctreeSliceFigure {
  std::vector<CsBox> free_voxels;   ///< FREE voxels (θ in [0, 2π]); drawn where a slice cuts them
  std::vector<CsBox> channel;       ///< the channel's voxels, outlined on every panel
  std::vector<SE2Pose> path;        ///< drawn as its (x, y) polyline on every panel
  std::vector<double> thetas;       ///< slice headings [rad] in [0, 2π), one panel each (1..6)
  double x_min = 0.0, x_max = 1.0;  ///< plotted x range [m]
  double y_min = 0.0, y_max = 1.0;  ///< plotted y range [m]
  std::string title;
};

/// The FREE leaves, the channel and the path of `result` (the figure's data
/// apart from the slices, ranges and title).
OctreeSliceFigure octree_slice_figure(const DacreWrightResult& result);

/// Writes `stem`_slices.dat, `stem`_channel.dat, `stem`_path.dat and
/// `stem`.gp in `dir` and renders `stem`.png (run_gnuplot; throws talus::Error
/// if gnuplot fails).
void render_octree_slices(const std::filesystem::path& dir, const std::string& stem,
                          const OctreeSliceFigure& figure);

}  // namespace talus
