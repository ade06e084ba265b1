#pragma once
/// @file
/// Path smoothing of Haït, Siméon, Taïx 2002 §4.4: the searched path is a
/// chain of short segments and arcs whose many control changes make the robot
/// oscillate. Repeatedly pick two random, nearby configurations on the path
/// and, if the shortest Reeds–Shepp curve between them is valid at every
/// discrete configuration, let it replace the portion between them.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/reeds_shepp.hpp"

namespace talus {

/// How smooth_path() picks the portions it tries to replace.
enum class HaitSmoothingMethod {
  /// The paper's method (§4.4): `iterations` random pairs of configurations.
  kRandomPairs,
  /// Our addition, not in the paper: the random pairs, then deterministic
  /// greedy shortcut passes. From each control switch of the path, the
  /// farthest later switch (or the goal) that a valid Reeds–Shepp curve
  /// reaches with an accepted replacement replaces everything between them;
  /// passes repeat until one changes nothing.
  kRandomPairsThenGreedy,
};

/// Options of smooth_path(); defaults in the struct.
struct HaitSmoothingOptions {
  HaitSmoothingMethod method = HaitSmoothingMethod::kRandomPairs;
  std::size_t iterations = 200;  ///< random pairs tried (>= 0)
  /// Longest portion [m] of path replaced by a random pair ("random close
  /// configurations", §4.4); 0 = no limit. The greedy passes ignore it. This
  /// metric limit is ours; the paper's hint is `max_span_controls`.
  double max_span = 5.0;
  /// The paper's hint (§4.4, "the number of change control is limited"): the
  /// portion between a random pair covers at most this many controls
  /// (segments), i.e. at most max_span_controls − 1 control changes; 0 = no
  /// limit. Applies together with max_span (set max_span = 0 for this limit
  /// alone); draw_within_span draws within both. The greedy passes ignore it.
  std::size_t max_span_controls = 0;
  /// How the second configuration of a random pair is drawn: true = uniformly
  /// among the configurations within max_span (and max_span_controls) of the
  /// first, so every try is usable; false = both uniformly over the whole
  /// path, pairs beyond the limits being skipped (with the 5 m limit, about 4
  /// tries in 5 wasted on a 46 m path).
  bool draw_within_span = true;
  double check_spacing =
      0.1;                 ///< validity checks along a new curve at most this far apart [m] (> 0)
  std::uint64_t seed = 1;  ///< seed of the pair choice
  /// Throws InputError naming the field.
  void validate() const;
};

/// What the smoothing did. The paper counts controls (Fig. 21: "the number
/// of controls decreases from 40 to 13"), the segments of constant control:
/// controls = control changes + 1 (controls()).
struct HaitSmoothingReport {
  std::size_t control_changes_before = 0;
  std::size_t control_changes_after = 0;
  /// Controls (segments) before / after, the paper's count: control changes + 1.
  std::size_t controls_before() const { return control_changes_before + 1; }
  std::size_t controls_after() const { return control_changes_after + 1; }
  std::size_t control_changes_random = 0;  ///< after the random pairs, before any greedy pass
  std::size_t replacements = 0;            ///< accepted Reeds–Shepp replacements (all stages)
  std::size_t greedy_passes = 0;           ///< greedy passes run (0 for kRandomPairs)
  std::size_t placements = 0;              ///< placements computed by its validity checks
  double length_before = 0.0;              ///< [m]
  double length_after = 0.0;               ///< [m]
};

/// Smooths `path` (dense configurations as the planner returns them, first
/// control {0, 0}). A replacement is accepted only if every configuration of
/// the new curve is valid, and it either lowers the path's control changes or
/// keeps them and shortens the path (random pairs and greedy passes alike);
/// so control changes never increase and the ends never move. Deterministic
/// for a given seed. Throws InputError for
/// a path of fewer than 2 points or invalid options.
std::vector<PathPoint> smooth_path(const std::vector<PathPoint>& path,
                                   const ValidityFunction& validity, const ReedsShepp& curves,
                                   const HaitSmoothingOptions& options,
                                   HaitSmoothingReport* report = nullptr);

}  // namespace talus
