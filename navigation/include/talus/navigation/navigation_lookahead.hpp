#pragma once
/// @file
/// The model-based lookahead of Iagnemma, Shimoda & Shiller (IROS 2008,
/// §IV) for potential-field navigation (potential_field_navigation.hpp):
/// every control tick the navigator forward-simulates a reduced model of the
/// vehicle under its own field's manoeuvres over a short horizon, computes
/// the maximum safe velocity profile along the predicted path, and where the
/// predicted speed exceeds it caps the desired speed at the safe speed there.
///
/// The reduced model (documented choice; the paper says only "low-order
/// rigid body models"): a kinematic bicycle on the surface — the heading
/// turns at the commanded curvature, the speed follows the commanded one
/// at the navigator's speed gain, clipped to the vehicle's drive and brake
/// limits, less gravity along the ground (reduced_model_speed) — with the
/// field's gravity inputs taken from the surface normal at each predicted
/// position. Gravity along the ground matters: without it the prediction
/// climbed every slope at the commanded speed and came down every descent no
/// faster, so the cap missed the speed a descent gathers and the lookahead
/// braked for crests a climb would never reach at that speed
/// (iagnemma-table1, the paper's battery: 11 of 23 terrains reached without
/// it, 15 with it; 16 with the goal capture of potential_field_navigation.hpp too).
///
/// The safe profile (safe_speed_profile) is a reduced form of the
/// time-optimal profile of Section II: the vehicle's speed limits at every
/// predicted point (VelocityLimits: sliding, tip-over, contact for its
/// model) and a backward pass with the strongest admissible deceleration at
/// each station, so a safe speed is one from which every limit ahead can
/// still be met by braking. The horizon's end is left free (its own limit).
#include <cstddef>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus {

struct NavigationLookaheadOptions {
  bool enabled = false;  ///< false: the standard field (§III) alone
  /// Horizon T [s] (> 0). The paper chooses it "empirically" and gives no
  /// value; the 1 s is several stopping distances of the UGV.
  double horizon = 1.0;
  double step = 0.05;  ///< virtual time step dt [s] (> 0, <= horizon)
  /// The cap is this fraction of the safe profile (in (0, 1]): the reduced
  /// model ignores the suspension's and the tyres' lag, and the speed loop
  /// overshoots its command. 0.9: on the tests' crest the simulated UGV left
  /// the ground at 1.00 times the point-mass contact limit √(g/κ) under a
  /// cap of 1.0. Not applied where the safe speed is the vehicle's top speed.
  double safety_factor = 0.9;
  /// Throws InputError naming the field.
  void validate() const;
};

/// sin α of the ground's slope α in the direction `heading` [rad, counter-clockwise from
/// east] where the surface's gradient is `gradient` (positive uphill).
double slope_sine_along(const Vec2& gradient, double heading);

/// One step `dt` [s] (> 0) of the reduced model's speed [m/s]: from `speed`,
/// the speed loop's acceleration gain (commanded − speed) clipped to
/// [−max_decel, max_accel], less g `slope_sine` (slope_sine_along at the
/// predicted position; 0 off the surface); never below 0 (the model does not
/// roll backwards).
double reduced_model_speed(const Vehicle& vehicle, double slope_sine, double speed,
                           double commanded, double gain, double dt);

/// The maximum safe speed [m/s] at each of `points` (a predicted path, at
/// least 2 points, consecutive ones distinct) for `vehicle` on `surface`:
/// the speed limits at each point along the interpolating cubic through
/// them, then a backward braking pass (see the file comment). Points off the
/// surface get 0, and so does every point before them once braking is taken
/// into account. Throws InputError for fewer than 2 points.
std::vector<double> safe_speed_profile(const BPatch& surface, const Vehicle& vehicle,
                                       const std::vector<Vec2>& points);

}  // namespace talus
