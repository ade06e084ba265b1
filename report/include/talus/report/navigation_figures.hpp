#pragma once
/// @file
/// The three figures of a navigation run, after Iagnemma, Shimoda & Shiller
/// (IROS 2008) figures 7–9, drawn by `talus navigate` and the
/// `iagnemma-table1` experiment:
/// - `<stem>_map.png` (figure 7): the terrain's shaded relief, the
///   high-level plan's waypoints and the path the simulated vehicle drove;
/// - `<stem>_speed.png` (figure 8): the vehicle's speed against time beside
///   the commanded speed, the lookahead's maximum safe speed at the c.g.
///   (its limit curve, where the lookahead ran) and the caps it applied;
/// - `<stem>_angles.png` (figure 9): the chassis roll angle and the body
///   side-slip angle against time [deg].
/// Each is a gnuplot script saved beside its PNG and data files (plot.hpp).
#include <filesystem>
#include <optional>
#include <string>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/trajectory_tracking.hpp"
#include "talus/navigation/potential_field_navigation.hpp"

namespace talus {

/// What the three figures show; the pointers must outlive the call.
struct NavigationFigureData {
  std::optional<BPatch> surface;                           ///< the terrain driven on
  const ReferenceTrajectory* waypoints = nullptr;          ///< what the navigator was given
  const PotentialFieldNavigationResult* result = nullptr;  ///< the run
  Vec2 start = Vec2::Zero(), goal = Vec2::Zero();          ///< [m]
  std::string title;  ///< the figures' common title, e.g. "seed 3, near-optimal: reached"
};

/// Writes `<stem>_map`, `<stem>_speed` and `<stem>_angles` (.gp, .dat, .png)
/// in `dir`. Throws InputError when a pointer is null.
void render_navigation_figures(const std::filesystem::path& dir, const std::string& stem,
                               const NavigationFigureData& data);

}  // namespace talus
