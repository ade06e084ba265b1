#pragma once
/// @file
/// Canonical manoeuvres: analytic terrains with a path on each whose speed
/// limit has a closed form for the point mass, to check that the planner's
/// admissible set and the simulated vehicle agree (the `model-agreement`
/// experiment, issue #35 item 6). Each is planned with evaluate_trajectory
/// (rest to rest) and driven with check_closed_loop / find_speed_scale_limit.
///
/// With g gravity, μ friction (the vehicle's):
/// - flat circle of radius R: v = sqrt(μ g R);
/// - banked circle: a horizontal circle of radius R round the apex of a cone
///   of slope tan θ: v² = g R (sin θ + μ cos θ) / (cos θ − μ sin θ)
///   (friction and the bank both hold the turn);
/// - crest: straight over the top of a Gaussian hill of height H and width
///   σ, whose crest radius is σ² / H: v = sqrt(g σ² / H) (zero normal force);
/// - side slope: straight along the contour of a plane with tan θ = 0.9 μ:
///   the friction left beside the weight's downhill component bounds the
///   tangential acceleration to g cos θ sqrt(μ² − tan² θ), both ways;
/// - straight drive and brake on flat ground: the vehicle's max_accel and
///   max_decel less its drive_reserve (when below μ g);
/// - slalom at the steering limit on flat ground: y = B (1 − cos k u) with
///   B = 0.4 m and k chosen so that the apexes' curvature B k² is 0.9 of the
///   vehicle's max_curvature(): v = sqrt(μ g / (B k²)) at every apex.
/// Every path starts and ends at rest with a straight lead-in, so the
/// manoeuvre is entered at its limit speed.
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/trajectory.hpp"

namespace talus {

enum class CanonicalManoeuvre {
  kFlatCircle,
  kBankedCircle,
  kCrest,
  kSideSlope,
  kStraightDriveBrake,
  kSlalom
};
/// "flat-circle", "banked-circle", "crest", "side-slope", "straight-drive-brake", "slalom".
std::string_view to_string(CanonicalManoeuvre manoeuvre);
/// Every manoeuvre, in declaration order.
std::vector<CanonicalManoeuvre> all_canonical_manoeuvres();

/// What limits the manoeuvre's speed, and the closed form's value.
enum class AnalyticLimitKind {
  kSpeed,         ///< a speed [m/s] at the manoeuvre's key section
  kAcceleration,  ///< a tangential acceleration bound [m/s²], both ways
};

/// One manoeuvre built for a vehicle.
struct ManoeuvreCase {
  ManoeuvreCase(CanonicalManoeuvre m, BPatch terrain, Curve2 planar_path)
      : manoeuvre(m), surface(std::move(terrain)), path(std::move(planar_path)) {}
  CanonicalManoeuvre manoeuvre;
  BPatch surface;  ///< the analytic terrain, interpolated on a 0.25 m grid
  Curve2 path;     ///< the planar path (lead-in, manoeuvre, run-out)
  AnalyticLimitKind limit_kind = AnalyticLimitKind::kSpeed;
  /// The point mass's closed form: the speed [m/s], or the drive bound [m/s²].
  double analytic_limit = 0.0;
  /// kAcceleration: the brake bound [m/s², > 0]; kSpeed: 0.
  double analytic_brake_limit = 0.0;
  /// The key section's arc-length window along the planar path [m]: where the
  /// analytic speed is reached (the circle, the crest's top, the slope's run).
  double key_from = 0.0, key_to = 0.0;
  std::string description;  ///< terrain, path and closed form in words
};

/// Builds `manoeuvre` for `vehicle` (gravity and friction; the side slope
/// needs μ > 0, the straight run finite max_accel and max_decel, the slalom a
/// steering limit of at least 0.05 1/m). The dimensions are fixed (radius 2 m
/// circles, a cone of slope 0.2, a 0.4 m hill of width 1 m, a 14 m slope)
/// except the slalom's wavelength, set by the steering limit (2.6 m for the
/// UGV's 2.53 1/m); they suit small and full-size vehicles below about
/// 6 m/s. InputError when the vehicle lacks what the manoeuvre needs.
ManoeuvreCase make_canonical_manoeuvre(CanonicalManoeuvre manoeuvre, const Vehicle& vehicle);

/// A planned profile on the manoeuvre's key section (stations with planar arc
/// length in [key_from, key_to]), to compare with the closed form.
struct ManoeuvreKeySection {
  std::size_t stations = 0;                       ///< stations on the key section
  double v_mean = 0.0, v_min = 0.0, v_max = 0.0;  ///< planned speed [m/s]
  /// Largest planned tangential acceleration and largest deceleration (>= 0) [m/s²].
  double accel_max = 0.0, decel_max = 0.0;
};
/// Measures `trajectory` (feasible, planned along `manoeuvre.path`) on the key
/// section. InputError when it is infeasible or no station lies on the section.
ManoeuvreKeySection measure_key_section(const ManoeuvreCase& manoeuvre,
                                        const Trajectory& trajectory);

}  // namespace talus
