#pragma once
/// @file
/// navigate_potential_field: the standard potential-field navigation of
/// Iagnemma, Shimoda, Shiller (IROS 2008, §III) driving the simulated vehicle
/// (vehicle_simulation.hpp) through waypoints past disc-shaped hazards,
/// optionally with the model-based lookahead of §IV (navigation_lookahead.hpp:
/// the "near-optimal" navigation; without it the "standard" one).
///
/// Every control tick the driver:
/// 1. takes the current waypoint (the first one neither within
///    waypoint_radius nor passed — the c.g. beyond the line through it normal
///    to the leg to the next one; the last is the goal) and its desired curvature
///    κ_d = 2 sin α / D (the arc from the c.g. tangent to the heading through
///    the waypoint, α its bearing, D its distance) and speed v_d. The goal,
///    which is never passed, is captured (this library's choice; the paper
///    does not say): v_d no more than √(μ g_n / |κ_d|), the speed at which
///    its arc can be driven without sliding, and κ_d = 0 while it lies inside
///    the turning circle (|κ_d| above the steering limit), so the vehicle
///    drives on until the arc through it can be steered; without either it
///    orbited a goal it had just missed until the time limit;
/// 2. reads the gravity components g_y, g_z in the body frame (an IMU) and,
///    for each hazard ahead (a disc within sensor_radius), the curvatures
///    [κ2, κ1] of the arcs that meet it (figure 5: 2y/(x² + y²) over its rim
///    and centre, in the body frame), its distance O_d (to its rim) and the
///    waypoint's bearing A_d = |α|;
/// 3. takes one descent step of the trajectory-space field
///    (trajectory_space_field.hpp) from the last commanded (v, κ);
/// 4. with the lookahead enabled, caps the speed sent to the vehicle at the
///    safe speed where the reduced model's prediction over the horizon
///    exceeds the safe profile (navigation_lookahead.hpp); the descent's own
///    point keeps the uncapped speed, so the next step starts from it;
/// 5. steers δ = atan(L κ) (kinematic bicycle, L the wheelbase, clipped to
///    the steering limit) and drives with PD speed control,
///    F = m (kp (v − v_x) − kd a_x), a_x the measured forward acceleration
///    (finite difference of v_x over the tick) plus the weight's component
///    along the chassis.
/// The run ends at the goal (within waypoint_radius: kReachedGoal), at the
/// time limit (kTimeout) or at a failure of the simulation (its status).
#include <cstdint>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/trajectory_tracking.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/vehicle_simulation.hpp"
#include "talus/navigation/hazard_detection.hpp"
#include "talus/navigation/navigation_lookahead.hpp"
#include "talus/navigation/trajectory_space_field.hpp"

namespace talus {

struct PotentialFieldNavigationOptions {
  TrajectorySpaceGains gains;            ///< the paper's
  double velocity_unit = 0.01;           ///< TrajectorySpaceInputs::velocity_unit [m/s]
  DescentOptions descent;                ///< the per-tick step
  double max_steering = 0.6;             ///< δ limit [rad] (0, π/2); κ_MAX = tan(δ)/L
  double waypoint_radius = 0.3;          ///< a waypoint is reached within this [m] (> 0)
  double sensor_radius = 3.0;            ///< hazards farther than this are not seen [m] (> 0)
  double speed_kp = 4.0;                 ///< [1/s] (>= 0)
  double speed_kd = 0.1;                 ///< [-] (>= 0)
  double time_limit = 60.0;              ///< simulated [s] (> 0)
  std::uint64_t seed = 1;                ///< the descent's randomisation
  NavigationLookaheadOptions lookahead;  ///< §IV; off by default (the standard field)
  /// Also avoid the hazards detect_hazards() sees on the map within
  /// sensor_radius at every tick (hazard_detection.hpp), beside the given
  /// ones. min_hazard_clearance still measures the given hazards only.
  bool hazards_from_map = false;
  /// Its thresholds; its sensor_radius is replaced by the one above.
  HazardDetectionOptions hazard_detection;
  VehicleSimulationOptions simulation;  ///< end_time is replaced by time_limit
  /// Throws InputError naming the field.
  void validate() const;
};

struct PotentialFieldNavigationResult {
  TrackingStatus status = TrackingStatus::kTimeout;  ///< kReachedGoal, kTimeout or a failure
  std::string message;
  VehicleSimulationResult simulation;
  /// The commanded (v, κ) at every control tick.
  std::vector<TrajectoryPoint> commands;
  std::vector<double> command_times;  ///< the simulated time of each command [s]
  /// The lookahead's speed cap at every control tick [m/s]; +inf where the
  /// prediction stayed under the safe profile or the lookahead is off.
  std::vector<double> lookahead_caps;
  /// The safe profile's speed at the c.g. at every control tick [m/s]: the
  /// lookahead's maximum safe speed there (the paper's figure 8 limit
  /// curve); NaN where the lookahead is off or predicted no motion.
  std::vector<double> lookahead_safe_speeds;
  std::size_t lookahead_caps_applied = 0;  ///< ticks whose commanded speed the cap lowered
  std::size_t waypoints_reached = 0;
  double navigation_time = 0.0;  ///< [s]
  /// Smallest distance from the c.g. to a hazard's rim over the trace [m]
  /// (negative inside one); +inf without hazards.
  double min_hazard_clearance = 0.0;
  /// Status, time, waypoints, clearance, then the simulation's report.
  std::string brief_report() const;
};

/// Drives `vehicle` (with a body) from rest at `start` (heading `yaw`)
/// through `waypoints` (each with its desired speed, ReferenceTrajectory's
/// fields) avoiding `hazards`. InputError for invalid input.
PotentialFieldNavigationResult navigate_potential_field(
    const BPatch& surface, const Vehicle& vehicle, const Vec2& start, double yaw,
    const ReferenceTrajectory& waypoints, const std::vector<DiscHazard>& hazards,
    const PotentialFieldNavigationOptions& options = {});

}  // namespace talus
