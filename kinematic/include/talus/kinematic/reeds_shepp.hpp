#pragma once
/// @file
/// Shortest Reeds–Shepp curves (J.A. Reeds, L.A. Shepp, "Optimal paths for a
/// car that goes both forwards and backwards", Pacific J. Math. 145(2), 1990),
/// used by the Haït–Siméon–Taïx planner for the goal-orientation heuristic
/// (§4.2.2), the final connection to the goal and the smoothing (§4.4).
///
/// The curve itself comes from OMPL's `ompl::base::ReedsSheppStateSpace`
/// (Debian's libompl-dev 1.5), which enumerates the 48 candidate words and
/// keeps the shortest. This wrapper keeps OMPL out of Talus's headers, turns
/// OMPL's word into Talus controls and samples it with exact arcs.
/// OMPL drops a word whose length comes out a round-off below zero, which
/// loses the straight and straight-then-arc connections about as often as
/// not; the wrapper re-solves the CSC words with a 1e-9-radius tolerance and
/// keeps them where shorter.
#include <memory>
#include <vector>

#include "talus/kinematic/configuration_space.hpp"

namespace talus {

/// One piece of a Reeds–Shepp curve: a control held over a length.
struct ReedsSheppSegment {
  Control control;  ///< {±1, ±1 or 0}
  double length;    ///< [m], > 0
};

/// Shortest Reeds–Shepp curves for one minimum turning radius.
class ReedsShepp {
 public:
  /// Throws InputError unless radius > 0 and finite.
  explicit ReedsShepp(double radius);
  ~ReedsShepp();
  ReedsShepp(ReedsShepp&&) noexcept;
  ReedsShepp& operator=(ReedsShepp&&) noexcept;

  double radius() const { return radius_; }

  /// Length [m] of the shortest Reeds–Shepp curve from a to b (a metric:
  /// symmetric, zero only for a == b).
  double distance(const SE2Pose& a, const SE2Pose& b) const;

  /// The shortest curve a → b as its non-empty segments (at most five).
  std::vector<ReedsSheppSegment> segments(const SE2Pose& a, const SE2Pose& b) const;

  /// Configurations along the shortest curve a → b, at most `spacing` [m]
  /// apart, every segment end included: the first point is a (control
  /// {0, 0}), the last is b exactly, and each point carries the control of
  /// the piece that reaches it. Throws InputError unless spacing > 0, and
  /// SolverError if the integrated curve misses b by more than 1e-6 m or rad.
  std::vector<PathPoint> sample(const SE2Pose& a, const SE2Pose& b, double spacing) const;

  /// OMPL's own interpolation at fraction t ∈ [0, 1] of the curve, for
  /// cross-checking the sampler.
  SE2Pose ompl_interpolate(const SE2Pose& a, const SE2Pose& b, double t) const;

 private:
  struct Impl;
  double radius_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace talus
