#pragma once
/// @file
/// The two figures of `talus plan --stage full`: plan.png (the routes over
/// shaded relief) and profile.png (the best trajectory's speed under its
/// limit). Each is a gnuplot script saved beside its PNG and data files
/// (plot.hpp), so it can be re-rendered with `gnuplot plan.gp`.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// What plan.png shows. Positions are in the terrain's frame [m]; the map is
/// drawn in offsets from `origin` (the grid's south-west node).
struct PlanMapData {
  std::optional<BPatch> surface;  ///< the fitted terrain (required)
  Vec2 origin = Vec2::Zero();
  double width = 0.0, height = 0.0;           ///< the grid's extent [m]
  std::vector<std::vector<Vec2>> candidates;  ///< global candidates (lattice vertices)
  std::vector<std::vector<Vec2>> optimised;   ///< locally optimised paths (sampled)
  std::vector<double> optimised_times;        ///< their travel times [s] (inf = none)
  std::size_t best = 0;                       ///< index into `optimised`
  Vec2 start = Vec2::Zero(), goal = Vec2::Zero();
  std::string title;
};

/// Writes plan_relief.rgb, plan_routes.dat and plan.gp in `dir` and renders plan.png.
void render_plan_map(const std::filesystem::path& dir, const PlanMapData& data);

/// What profile.png shows: v(s) under v_max(s) (inf = unlimited, not drawn)
/// and the switching points.
struct PlanProfileData {
  std::vector<double> s, v, v_max;
  std::vector<double> switch_s, switch_v;
  std::string title;
};

/// Writes plan_profile.dat, plan_switching.dat and profile.gp in `dir` and renders profile.png.
void render_plan_profile(const std::filesystem::path& dir, const PlanProfileData& data);

}  // namespace talus
