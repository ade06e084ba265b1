#pragma once
/// @file
/// The configuration space CS = (x, y, θ) of the Haït–Siméon–Taïx planner
/// (Advanced Robotics 16(8), 2002, §2 and §4.1): a robot standing on the
/// terrain is fixed by its horizontal position and heading, everything else
/// (elevation, roll, pitch, joints) follows from the placement. Motions are
/// the elementary controls (v, ω) ∈ {−V, V} × {−Ω, 0, Ω}: straight segments
/// and arcs of minimum turning radius, forward or in reverse.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "talus/core/se2_pose.hpp"
#include "talus/core/types.hpp"

namespace talus {

// SE2Pose, the configuration (x, y, θ), is in talus/core/se2_pose.hpp.

/// An elementary control as the signs of (v, ω): v = +1 forward, −1 reverse;
/// ω = +1 heading increasing (counter-clockwise), 0 straight, −1 decreasing.
/// {0, 0} labels a path's first configuration, which no control reaches.
/// Note that reversing while steering left turns the heading clockwise, so it
/// is {−1, −1}.
struct Control {
  int v = 0;
  int omega = 0;
  friend bool operator==(const Control&, const Control&) = default;
};

/// "forward", "forward-left", "forward-right", "reverse", "reverse-left",
/// "reverse-right" (left/right = the way the wheels are steered), or "none".
std::string control_name(const Control& u);

/// One configuration of a planned path and the control that led to it from
/// the previous one.
struct PathPoint {
  SE2Pose pose;
  Control control;
};

/// θ wrapped to (−π, π].
double wrap_angle(double theta);

/// The pose reached from `q` by driving `length` >= 0 metres under control
/// `u` with turning radius `radius` [m] (exact circular arc for ω ≠ 0).
SE2Pose apply_control(const SE2Pose& q, const Control& u, double length, double radius);

/// Number of control switches along a path: consecutive points (after the
/// first) whose controls differ (Haït et al. §4.4 "control changes").
std::size_t control_changes(std::span<const PathPoint> path);

/// Length [m] driven along a path: straight pieces by their chord, turning
/// pieces by radius × |Δθ| (exact for the arcs this planner produces).
double path_length(std::span<const PathPoint> path, double radius);

/// The answer of a validity check at one configuration (paper §3.2): valid or
/// not, and how far from its limits the placement is.
struct ConfigurationCheck {
  bool valid = false;
  /// Normalised distance of the placement parameters to their limits, in
  /// [0, 1]: 0 at a limit, 1 far from every limit. Meaningful when valid.
  double margin = 0.0;
  /// Robot placements this check computed (a diagnostic the paper reports).
  std::size_t placements = 1;
};

/// The validity oracle the search and the smoothing call at each discrete
/// configuration. It must be deterministic.
using ValidityFunction = std::function<ConfigurationCheck(const SE2Pose&)>;

}  // namespace talus
