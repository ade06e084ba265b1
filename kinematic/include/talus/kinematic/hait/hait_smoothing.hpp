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
  /// configurations", §4.4); 0 = no limit. The greedy passes ignore it.
  double max_span = 5.0;
  /// How the second configuration of a random pair is drawn: true = uniformly
  /// among the configurations within max_span of the first, so every try is
  /// usable; false = both uniformly over the whole path, pairs farther apart
  /// than max_span being skipped (about 4 tries in 5 wasted on a 46 m path).
  bool draw_within_span = true;
  double check_spacing =
      0.1;                 ///< validity checks along a new curve at most this far apart [m] (> 0)
  std::uint64_t seed = 1;  ///< seed of the pair choice
  /// Throws InputError naming the field.
  void validate() const;
};

/// What the smoothing did.
struct HaitSmoothingReport {
  std::size_t control_changes_before = 0;
  std::size_t control_changes_after = 0;
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
