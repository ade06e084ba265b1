#pragma once
/// @file
/// The time-optimal travel time of a vehicle along a given path of
/// configurations (x, y, θ), such as a kinematic planner's: the path is split
/// at its cusps and each forward or reverse piece is driven from rest to rest
/// at its exact time-optimal velocity profile **along its own geometry** — a
/// station at every configuration, each frame lifted onto the surface from
/// the exact planar derivatives of the straight segment or circular arc that
/// joins consecutive configurations, no curve fitted. This is the velocity
/// stage of a path–velocity decomposition: the profile runs on the very
/// configurations the path planner validated.
///
/// Geometry of a step from q₀ to q₁ (Δθ = θ₁ − θ₀ wrapped to (−π, π], chord
/// c = |p₁ − p₀|): a straight segment when |Δθ| < 1e-12, else the circular
/// arc tangent to the heading at both ends, of length l = c (Δθ/2) / sin(Δθ/2)
/// and heading rate κ = Δθ / l [rad/m] per metre driven. It is driven forward
/// when the chord points along the heading (c·(cos θ₀, sin θ₀) > 0), in
/// reverse otherwise; a cusp is where that direction changes. At a station
/// the step of larger |κ| of the two it joins (within its piece) sets the
/// curvature, the outgoing one on a tie. Consecutive configurations less than
/// 1e-9 m apart count as one. A step whose chord is not along θ₀ + Δθ/2 (or the
/// opposite way) belongs to no such arc: the status says so.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/se2_pose.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus {

/// Options of driven_path_time().
struct DrivenPathOptions {
  /// Speed [m/s] at every cusp and at both ends of the path (each piece is
  /// driven from and to this speed; 0 = rest to rest, the only physical value
  /// at a cusp). >= 0.
  double cusp_speed = 0.0;
  /// Throws InputError naming the field.
  void validate() const;
};

enum class DrivenPathStatus {
  kOk,          ///< every piece has an admissible profile; `travel_time` is finite
  kInfeasible,  ///< some piece has none (see `message`, `pieces`); `travel_time` = ∞
  /// A step's chord is not that of a segment or arc along the heading (to 1e-6 rad): the path
  /// moves sideways or turns on the spot, so it has no driving direction to profile (`message`
  /// names the step; no pieces; `travel_time` = ∞). Fit a curve to it instead
  /// (polyline_travel_time).
  kNotTangent,
};
std::string_view to_string(DrivenPathStatus status);

/// One forward or reverse piece between cusps.
struct DrivenPiece {
  std::size_t first = 0, last = 0;  ///< indices of its first and last configuration in the path
  int direction = 1;                ///< +1 forward, −1 reverse
  double length = 0.0;              ///< 3-D arc length on the surface [m]
  double planar_length = 0.0;       ///< Σ of its steps' l [m]
  std::size_t stations = 0;         ///< configurations profiled (repeated ones merged)
  double travel_time = 0.0;         ///< [s]; ∞ if infeasible
  ProfileStatus status = ProfileStatus::kOk;
};

struct DrivenPathResult {
  DrivenPathStatus status = DrivenPathStatus::kOk;
  std::string message;
  double travel_time = 0.0;    ///< Σ over the pieces [s]; ∞ unless kOk
  double length = 0.0;         ///< Σ of the pieces' 3-D lengths [m]
  double planar_length = 0.0;  ///< Σ of the steps' l [m]
  std::vector<DrivenPiece> pieces;
  double seconds = 0.0;  ///< wall-clock time of the evaluation [s]
  /// One line: status, time, length, pieces, seconds.
  std::string brief_report() const;
};

/// Drives `vehicle` along `path` (at least 2 configurations; positions in the
/// surface's frame [m], headings [rad]) on `surface`. A path whose
/// configurations all coincide takes 0 s. InputError for fewer than 2
/// configurations, a non-finite value, a configuration off the surface's
/// domain or invalid options; an infeasible piece is a status. `solver`
/// (optional) is reused between calls.
DrivenPathResult driven_path_time(const BPatch& surface, const Vehicle& vehicle,
                                  std::span<const SE2Pose> path,
                                  const DrivenPathOptions& options = {},
                                  TimeOptimalProfileSolver* solver = nullptr);

}  // namespace talus
