#pragma once
/// @file
/// The time-optimal velocity profile along a fixed path: maximise progress
/// subject to v_min(s) <= v <= v_max(s), s̈ in [a_min(s, ṡ), a_max(s, ṡ)] and
/// given start and end speeds.
///
/// Method: reachability analysis in x = ṡ² (TOPP-RA, Pham & Pham 2018) on the
/// stations of a VelocityLimits table. Each step between stations i and i+1
/// has one constant s̈ = u, with x_{i+1} = x_i + 2 u Δs, and u must be
/// admissible at **both** ends of the step (TOPP-RA's "interpolation"
/// discretisation), so every constraint holds at every station whatever the
/// spacing. A backward pass computes the controllable sets K_i = [lo_i, hi_i]
/// (states from which the end state is reachable); a forward pass then takes
/// the largest admissible u that stays in K_{i+1}. Both passes solve each
/// step in closed form against the exact constraints (friction ellipse as a
/// second-order cone, see talus/dynamics/admissible_set.hpp); the admissible
/// set is convex for every vehicle model (a model only adds linear conditions
/// on the contact force), so the discrete solution is exact, not an
/// approximation of the friction ellipse. verify_profile.hpp checks a result. There is no built-in
/// cap on speed or ṡ².
#include <cstddef>
#include <string>
#include <vector>

#include "talus/dynamics/path_velocity_limits.hpp"

namespace talus {

/// Default station spacing along a path [m] for callers that choose the
/// station count (the CLI, the planner). The discretisation is conservative
/// and converges at first order: on the rover-scale West Bijou path of the
/// optimal-profile experiment the travel-time error is about 1 % per metre of
/// spacing (+0.50 % at 0.5 m, +0.11 % at 0.1 m), so 0.1 m keeps it near 0.1 %.
/// That measurement was at 1 m cells: callers that have the surface use the
/// scale-aware default_station_spacing(surface, vehicle) of trajectory.hpp
/// (max(cell size, half-track) / 10, this value at 1 m cells for the rover).
inline constexpr double kDefaultStationSpacing = 0.1;

/// Options of the time-optimal profile.
struct ProfileOptions {
  double start_speed = 0.0;  ///< ṡ at the first station [m/s] (>= 0)
  double end_speed = 0.0;    ///< ṡ at the last station [m/s] (>= 0)
  /// Throws InputError naming the field.
  void validate() const;
};

enum class ProfileStatus {
  kOk,          ///< a profile exists; `travel_time` is finite
  kInfeasible,  ///< no admissible profile: see `infeasible_station`, `message`
};

/// What changes at a switching point: the control of the steps on either side.
enum class ControlKind {
  kAccelerate,  ///< u = the largest admissible s̈
  kDecelerate,  ///< u = the smallest admissible s̈ (braking towards a later limit)
  kLimit,       ///< u in between: riding the limit curve / controllable boundary
};
std::string_view to_string(ControlKind kind);

struct SwitchingPoint {
  std::size_t station = 0;  ///< first station of the step with the new control
  double s = 0.0;           ///< its arc length [m]
  ControlKind from = ControlKind::kAccelerate;
  ControlKind to = ControlKind::kAccelerate;
};

/// The solver's result: status, diagnostics and the per-station profile.
struct TimeOptimalProfile {
  ProfileStatus status = ProfileStatus::kInfeasible;
  std::string message;  ///< human-readable reason when infeasible
  double travel_time = std::numeric_limits<double>::infinity();  ///< [s]
  std::vector<double> s;                                         ///< arc length [m]
  std::vector<double> v;                                         ///< speed ṡ [m/s]
  std::vector<double>
      a;  ///< s̈ of the step that starts at the station [m/s²] (last: previous step's)
  std::vector<double> t;             ///< time of arrival [s]
  std::vector<double> v_max;         ///< the speed limit there [m/s]
  std::vector<Constraint> binding;   ///< what sets v_max there
  std::vector<ControlKind> control;  ///< control of the step that starts at the station
  std::vector<SwitchingPoint> switching_points;
  std::size_t infeasible_station = 0;  ///< where it fails, when infeasible
  Constraint infeasible_binding = Constraint::kNone;
  std::size_t merged_stations = 0;  ///< stations closer than 1e-9 m to the previous one
};

/// Solves along `limits`. Reuse one solver for many paths: its workspace
/// (the controllable sets) is kept between calls.
class TimeOptimalProfileSolver {
 public:
  /// Throws InputError for invalid options or a start/end speed above the
  /// limit there; infeasibility of the path itself is a status, not an error.
  TimeOptimalProfile solve(const VelocityLimits& limits, const ProfileOptions& options);
  void solve(const VelocityLimits& limits, const ProfileOptions& options, TimeOptimalProfile& out);

 private:
  std::vector<double> lower_, upper_;  // controllable sets K_i in x = ṡ²
  std::vector<std::size_t> kept_;      // stations after merging near-duplicates
};

}  // namespace talus
