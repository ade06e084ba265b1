#include "baseline_command.hpp"

#include <sys/resource.h>
#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <system_error>
#include <variant>

#include "baseline_profile.hpp"
#include "cli_values.hpp"
#include "eldershaw_yim_outputs.hpp"
#include "hait_figures.hpp"
#include "limits_command.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/output_folder.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/kinematic/dacre_wright/dacre_wright_baseline.hpp"
#include "talus/kinematic/eldershaw_yim/eldershaw_yim_baseline.hpp"
#include "talus/planners/planner_registry.hpp"
#include "talus/report/dacre_wright_outputs.hpp"
#include "talus/report/number_format.hpp"
#include "talus/report/plot.hpp"
#include "talus/sweep/mpi_session.hpp"
#include "terrain_input.hpp"

namespace talus::experiments {
namespace {

nlohmann::json pose_json(const SE2Pose& q) {
  return {{"x", q.x}, {"y", q.y}, {"theta", q.theta}};
}

/// A pose the planner will reject as input (off the map or on NODATA), as
/// the one-line message of the CLI's bad-input contract.
void check_on_map(const char* option, const SE2Pose& q, const RuledTerrain& terrain,
                  const std::string& terrain_file) {
  const ElevationGrid& g = terrain.grid();
  if (!terrain.contains(q.position())) {
    throw InputError(std::string(option) + " (" + format_number(q.x) + ", " + format_number(q.y) +
                     ") is off the terrain " + terrain_file + ", whose domain is [" +
                     format_number(g.x_min()) + ", " + format_number(g.x_max()) + "] x [" +
                     format_number(g.y_min()) + ", " + format_number(g.y_max()) + "]");
  }
  if (!terrain.has_data(q.position())) {
    throw InputError(std::string(option) + " (" + format_number(q.x) + ", " + format_number(q.y) +
                     ") lies on NODATA in " + terrain_file);
  }
}

}  // namespace

std::string baseline_output_help(const std::string& name) {
  std::string help =
      "Angles in radians, counter-clockwise from east. Writes, in --out DIR (created if needed): "
      "path.csv (columns x,y,theta,control: every configuration of the path from start to goal, "
      "control = the motion reaching it as the planner names it, e.g. forward, forward-left, "
      "reverse-right, or none on the first row), summary.json (status found | no_path | "
      "start_invalid | goal_invalid | budget_exceeded, message, the planner's counters, "
      "preprocessing_seconds, search_seconds, length_m, the planner's settings such as robot and "
      "options, ...; also printed) and path.png (the path over shaded relief).";
  if (name == "dacre-wright") {
    help +=
        " Also voxels.csv (columns level,x_min,x_max,y_min,y_max,theta_min,theta_max,status: "
        "every voxel whose state was decided, analysed or combined from its sons above p0, "
        "status FREE or MIXED), channel.csv (columns step,voxel: the channel from the start's "
        "voxel to the goal's, voxel = 0-based data row of voxels.csv), octree.png (FREE voxels "
        "at four headings of the path, the channel and the path) and the summary keys "
        "voxels_analysed_per_level, free_volume_fraction, voxels_decided, free_leaves, "
        "reference_level.";
  } else if (name == "eldershaw-yim") {
    help +=
        " Also prm_points.csv (point,ix,iy,itheta,x,y,theta), prm_edges.csv "
        "(new_point,old_point), steps.csv (the foot plan: step,move,cg_x,cg_y,cg_theta then "
        "foot_x_i,foot_y_i,foot_z_i,contact_i per leg i), cgmap.png (the footmap and the CGmap "
        "of the start's heading slice, the route and its footprints) and the summary keys "
        "footmap_invalid_nodes, cgmap_cells, foot_plan_status, feedback_cells.";
  }
  return help +
         " Exit code 0 when a path is found; 2 when none exists, the start or goal configuration "
         "is invalid or the budget ran out (summary still written); 1 on bad input: malformed "
         "numbers or options, missing or bad files, a start or goal off the map or on NODATA "
         "(one line on stderr, nothing written)";
}

namespace {

/// The planner from the registry; a bad option value is named as its flag.
std::unique_ptr<BaselinePlanner> make_planner(const BaselineRequest& request) {
  try {
    return planner_registry().make(request.baseline, request.options);
  } catch (const BaselineOptionError& e) {
    throw InputError("--" + e.key() + ": " + e.reason());
  }
}

/// The octree figure's slices: four headings evenly spread over those the path
/// takes (a quarter turn apart when it keeps one heading), in [0, 2π).
std::vector<double> slice_headings(const std::vector<SE2Pose>& path) {
  double lo = path.front().theta, hi = lo;
  for (const SE2Pose& q : path) {
    lo = std::min(lo, q.theta);
    hi = std::max(hi, q.theta);
  }
  const double step = hi - lo > 1e-6 ? (hi - lo) / 3.0 : 0.5 * std::numbers::pi;
  std::vector<double> out;
  for (int k = 0; k < 4; ++k) {
    const double th = std::fmod(lo + k * step, 2.0 * std::numbers::pi);
    out.push_back(th < 0 ? th + 2.0 * std::numbers::pi : th);
  }
  return out;
}

/// The Eldershaw-Yim planner's ranks on the process's MPI session.
class MpiRanks final : public CgRankGroup {
 public:
  explicit MpiRanks(const MpiSession& mpi) : mpi_(mpi) {}
  int rank() const override { return mpi_.rank(); }
  int size() const override { return mpi_.size(); }
  void max_all(std::vector<double>& values) const override { mpi_.max_all(values); }

 private:
  const MpiSession& mpi_;
};

/// This process's peak resident memory [MiB] (getrusage; Linux reports KiB).
double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace

SE2Pose parse_pose(const std::string& option, const std::string& text) {
  if (const auto v = parse_numbers(text, 3)) return {(*v)[0], (*v)[1], (*v)[2]};
  throw InputError(option +
                   " must be X,Y,THETA: three finite numbers separated by commas (x, y [m], "
                   "heading [rad] counter-clockwise from east), got '" +
                   text + "'");
}

BaselineOutcome run_baseline(const BaselineRequest& request) {
  const auto start_time = Clock::now();
  const std::unique_ptr<BaselinePlanner> planner = make_planner(request);
  const SE2Pose start = parse_pose("--start", request.start);
  const SE2Pose goal = parse_pose("--goal", request.goal);
  if (request.output_dir.empty()) throw InputError("no output folder given (--out DIR)");
  std::error_code error;
  if (std::filesystem::exists(request.output_dir, error) &&
      !std::filesystem::is_directory(request.output_dir, error)) {
    throw InputError("--out " + request.output_dir + " exists and is not a folder");
  }
  std::optional<Vehicle> vehicle;  // --vehicle: read before the long work
  if (!request.vehicle.empty()) vehicle = load_vehicle(request.vehicle);
  // The Eldershaw-Yim baseline's full result (PRM points and edges) feeds its own outputs;
  // under mpirun its ranks share the local-planner calls and only rank 0 writes.
  const auto* ey = dynamic_cast<const EldershawYimBaseline*>(planner.get());
  std::optional<MpiSession> mpi;
  std::optional<MpiRanks> ranks;
  if (ey) {
    mpi.emplace();
    if (mpi->size() > 1) ranks.emplace(*mpi);
  }
  const bool writer = !ranks || ranks->rank() == 0;
  std::optional<OutputFolder> folder;
  std::exception_ptr folder_error;
  if (writer) {
    try {
      folder.emplace(request.output_dir);  // locked for the whole run
    } catch (...) {
      folder_error = std::current_exception();
    }
  }
  // Every rank learns whether rank 0 took the folder, so none waits for ever
  // in the planner's exchanges for a rank that has already given up.
  const bool folder_taken = ranks ? mpi->all(!folder_error) : !folder_error;
  if (folder_error) std::rethrow_exception(folder_error);
  if (!folder_taken) {
    throw InputError("--out " + request.output_dir + ": rank 0 could not take the output folder");
  }
  const RuledTerrain terrain(load_terrain(request.terrain, request.reproject, request.band,
                                          /*fits_surface=*/false)
                                 .grid);
  if (terrain.grid().ncols() < 2 || terrain.grid().nrows() < 2) {
    throw InputError(request.terrain + ": the planner needs at least 2 x 2 nodes");
  }
  check_on_map("--start", start, terrain, request.terrain);
  check_on_map("--goal", goal, terrain, request.terrain);
  // Each rank's peak memory after its planning, gathered by one collective maximum.
  auto rank_rss = [&] {
    std::vector<double> rss(static_cast<std::size_t>(ranks ? ranks->size() : 1), 0.0);
    rss[static_cast<std::size_t>(ranks ? ranks->rank() : 0)] = peak_rss_mib();
    if (ranks) mpi->max_all(rss);
    return rss;
  };
  if (!writer) {
    const bool found = ey->plan_full(terrain, start, goal, &*ranks).found();
    rank_rss();
    return {nlohmann::json(), found};
  }
  OutputFolder& out = *folder;

  // The Dacre-Wright baseline's full result (voxels, channel) feeds its own outputs.
  std::optional<DacreWrightResult> octree;
  std::optional<EldershawYimResult> legged;
  std::vector<double> rss;  // [MiB] per rank (Eldershaw-Yim)
  BaselineResult result;
  if (const auto* dw = dynamic_cast<const DacreWrightBaseline*>(planner.get())) {
    octree = dw->plan_full(terrain, start, goal);
    result = to_baseline_result(*octree, dw->options().full);
  } else if (ey) {
    legged = ey->plan_full(terrain, start, goal, ranks ? &*ranks : nullptr);
    rss = rank_rss();
    result = to_baseline_result(*legged, ey->options().direct);
  } else {
    result = planner->plan(terrain, start, goal);
  }
  const bool found = result.found();

  const std::filesystem::path& dir = out.staging();
  write_text_file(dir / "path.csv", baseline_path_csv(result.path, result.motions));
  if (octree) {
    write_text_file(dir / "voxels.csv", dacre_wright_voxels_csv(*octree));
    write_text_file(dir / "channel.csv", dacre_wright_channel_csv(*octree));
  }
  // The footmap and the CGmap of the start's heading slice (figures 4 and 6 of the paper).
  std::optional<Footmap> footmap;
  std::optional<CgLattice> lattice;
  std::vector<CgState> cg_slice;
  int cg_slice_index = 0;
  if (legged) {
    footmap.emplace(terrain, ey->robot());
    lattice.emplace(terrain.grid(), ey->robot().foot_print, ey->options().theta_slices);
    cg_slice_index = lattice->cell_of(start).it;
    // One whole slice is evaluated for the figure, up to a million cells.
    if (static_cast<double>(lattice->nx()) * lattice->ny() <= 1e6)
      cg_slice = evaluate_cg_slice(*footmap, ey->robot(), *lattice, cg_slice_index);
    write_text_file(dir / "prm_points.csv", eldershaw_yim_points_csv(*legged, *lattice));
    write_text_file(dir / "prm_edges.csv", eldershaw_yim_edges_csv(*legged));
    write_text_file(dir / "steps.csv",
                    eldershaw_yim_steps_csv(*legged, *footmap, ey->robot().legs.size()));
  }

  const auto plot_start = Clock::now();
  const bool plots = found && gnuplot_available();
  if (plots) {
    HaitMapData map;
    map.grid = &terrain.grid();
    HaitRoute route{{}, "path, " + sig3(result.length_m) + " m", "#e6550d"};
    for (const SE2Pose& q : result.path) route.path.push_back({q, {}});
    map.routes.push_back(std::move(route));
    map.start = start;
    map.goal = goal;
    map.title = "talus baseline " + planner->name() + ": " +
                std::filesystem::path(request.terrain).filename().string();
    render_hait_map(dir, "path", map);
    if (octree) {
      OctreeSliceFigure figure = octree_slice_figure(*octree);
      figure.thetas = slice_headings(octree->path);
      const ElevationGrid& g = terrain.grid();
      const double side = std::max(g.x_max() - g.x_min(), g.y_max() - g.y_min());
      figure.x_min = g.x_min();
      figure.x_max = g.x_min() + side;
      figure.y_min = g.y_min();
      figure.y_max = g.y_min() + side;
      figure.title =
          "talus baseline dacre-wright: FREE voxels at four headings of the path, the "
          "channel and the path";
      render_octree_slices(dir, "octree", figure);
    }
  }
  const bool cg_plot = legged && !cg_slice.empty() && gnuplot_available();
  if (cg_plot) {
    CgMapFigure figure;
    figure.footmap = &*footmap;
    figure.lattice = &*lattice;
    figure.slice = cg_slice;
    figure.it = cg_slice_index;
    figure.path = result.path;
    for (const CgCell& c : legged->prm_points) figure.prm_points.push_back(lattice->centre(c));
    if (legged->feet_planned) {
      std::set<std::pair<std::size_t, std::size_t>> seen;
      for (const FootStep& st : legged->foot_plan.steps)
        for (const FootState& f : st.feet)
          if (f.contact && seen.insert({f.i, f.j}).second)
            figure.footprints.push_back(foot_position(*footmap, f).head<2>());
    }
    figure.title = "talus baseline eldershaw-yim: footmap and CGmap, " + ey->robot().name;
    render_cg_map(dir, "cgmap", figure);
  }

  nlohmann::json summary;
  summary["baseline"] = planner->name();
  summary["status"] = to_string(result.status);
  summary["message"] = result.message;
  for (const auto& [key, value] : result.counters) summary[key] = value;
  for (const auto& [key, value] : result.flags) summary[key] = value;
  for (const auto& [stage, value] : result.stage_seconds) summary[stage + "_seconds"] = value;
  summary["preprocessing_seconds"] = result.preprocessing_seconds;
  summary["search_seconds"] = result.search_seconds;
  summary["length_m"] = found ? nlohmann::json(result.length_m) : nlohmann::json(nullptr);
  summary["path_points"] = result.path.size();
  if (octree) add_dacre_wright_summary(summary, *octree);
  if (vehicle)
    add_baseline_profile(summary, terrain.grid(), result.path, found, *vehicle, request.vehicle);
  if (legged) {
    summary["footmap_invalid_nodes"] = footmap->invalid_count();
    summary["footmap_nodes"] = footmap->ncols() * footmap->nrows();
    summary["cgmap_theta"] = lattice->heading(cg_slice_index);
    summary["cgmap_cells"] = cg_slice.empty() ? nlohmann::json(nullptr) : cg_slice_counts(cg_slice);
    summary["eldershaw_yim_status"] = to_string(legged->status);
    summary["foot_plan_status"] =
        legged->feet_planned ? nlohmann::json(to_string(legged->foot_plan.status)) : nullptr;
    summary["foot_plan_message"] = legged->foot_plan.message;
    summary["foot_plan_furthest_cell"] = legged->foot_plan.furthest_index;
    nlohmann::json fed = nlohmann::json::array();
    for (const CgCell& c : legged->feedback_cells) fed.push_back({c.ix, c.iy, c.it});
    summary["feedback_cells"] = fed;
    summary["workers"] = ey->options().workers;
    summary["ranks"] = ranks ? ranks->size() : 1;
    summary["peak_rss_mib"] = rss;  // per rank, after planning
    summary["peak_rss_mib_max"] = *std::max_element(rss.begin(), rss.end());
  }
  for (const BaselineSetting& s : planner->settings()) {
    std::visit([&](const auto& v) { summary[s.section][s.key] = v; }, s.value);
  }
  const ElevationGrid& g = terrain.grid();
  summary["terrain"] = {{"file", request.terrain},
                        {"ncols", g.ncols()},
                        {"nrows", g.nrows()},
                        {"cellsize", g.cellsize()}};
  summary["start"] = pose_json(start);
  summary["goal"] = pose_json(goal);
  summary["files"] = {
      {"path", out.final_path("path.csv").string()},
      {"summary", out.final_path("summary.json").string()},
      {"path_png", plots ? nlohmann::json(out.final_path("path.png").string()) : nullptr}};
  if (octree) {
    summary["files"]["voxels"] = out.final_path("voxels.csv").string();
    summary["files"]["channel"] = out.final_path("channel.csv").string();
    summary["files"]["octree_png"] =
        plots ? nlohmann::json(out.final_path("octree.png").string()) : nullptr;
  }
  if (legged) {
    summary["files"]["prm_points"] = out.final_path("prm_points.csv").string();
    summary["files"]["prm_edges"] = out.final_path("prm_edges.csv").string();
    summary["files"]["steps"] = out.final_path("steps.csv").string();
    summary["files"]["cgmap_png"] =
        cg_plot ? nlohmann::json(out.final_path("cgmap.png").string()) : nullptr;
  }
  summary["plot_seconds"] = seconds_since(plot_start);
  summary["seconds"] = seconds_since(start_time);
  write_text_file(dir / "summary.json", summary.dump(2) + "\n");
  out.commit();
  return {std::move(summary), found};
}

}  // namespace talus::experiments
