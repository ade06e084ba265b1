#pragma once
/// @file
/// The outputs of `talus baseline eldershaw-yim` beyond the common ones: the
/// tree-PRM's points and edges (prm_points.csv, prm_edges.csv), summary keys,
/// and the CGmap figure of Eldershaw and Yim 2001 (figures 4 and 6): the
/// footmap's invalid nodes as small circles, the invalid CG cells of one
/// heading slice as black squares, the CG path and the PRM points. A gnuplot
/// script is saved beside the PNG (plot.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/kinematic/eldershaw_yim/cg_space.hpp"
#include "talus/kinematic/eldershaw_yim/eldershaw_yim_planner.hpp"

namespace talus::experiments {

/// The columns of DIR/prm_points.csv.
inline constexpr const char* kEldershawYimPointsCsvHeader = "point,ix,iy,itheta,x,y,theta";
/// The columns of DIR/prm_edges.csv.
inline constexpr const char* kEldershawYimEdgesCsvHeader = "new_point,old_point";

/// prm_points.csv: one row per PRM point (0 = the start's cell, 1 = the
/// goal's, then the random points in order of insertion), lattice indices and
/// the cell centre [m, m, rad]. Header only in the direct mode.
std::string eldershaw_yim_points_csv(const EldershawYimResult& result, const CgLattice& lattice);
/// prm_edges.csv: one row per successful local-planner connection, the new
/// point first (indices into prm_points.csv).
std::string eldershaw_yim_edges_csv(const EldershawYimResult& result);

/// steps.csv: one row per step of the foot plan: `step,move,cg_x,cg_y,cg_theta`
/// then `foot_x_i,foot_y_i,foot_z_i,contact_i` for every leg i = 0 … n-1 (the
/// robot file's order; a raised foot keeps its last node, contact 0); move is
/// to_string(FootMove). Header only when no foot plan ran.
std::string eldershaw_yim_steps_csv(const EldershawYimResult& result, const Footmap& footmap,
                                    std::size_t legs);

/// The CGmap of one heading slice and the footmap it was built from.
struct CgMapFigure {
  const Footmap* footmap = nullptr;
  const CgLattice* lattice = nullptr;
  std::vector<CgState> slice;  ///< evaluate_cg_slice of slice `it`
  int it = 0;
  std::vector<SE2Pose> path;        ///< the CG path (may be empty)
  std::vector<SE2Pose> prm_points;  ///< drawn as dots (may be empty)
  std::vector<Vec2> footprints;     ///< contact foot positions of the foot plan, drawn as crosses
  std::string title;
};

/// Counts of a slice: {"valid", "off_data", "no_support", "too_short"}.
nlohmann::json cg_slice_counts(const std::vector<CgState>& slice);

/// Writes `stem`_foot.dat, `stem`_cells.dat, `stem`_path.dat, `stem`_prm.dat, `stem`_steps.dat,
/// `stem`.gp in `dir` and renders `stem`.png (throws talus::Error if gnuplot fails).
void render_cg_map(const std::filesystem::path& dir, const std::string& stem,
                   const CgMapFigure& figure);

}  // namespace talus::experiments
