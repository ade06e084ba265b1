#pragma once
/// @file
/// The trajectory-space potential field of Iagnemma, Shimoda, Shiller (IROS
/// 2008, §III; after Shimoda, Kuroda, Iagnemma, Robotica 2007): a field over
/// the vehicle's (speed v, path curvature κ) whose descent each control tick
/// picks the commanded manoeuvre. This header is the field and its descent
/// step; the navigator that feeds it waypoints and hazards is not here yet.
///
/// Terms (the paper's equation numbers), with g_y the lateral (body y, left
/// positive) and g_z the normal component of gravity in the body frame, d the
/// half-track, h the c.g. height, μ the friction, κ_MAX the steering limit:
/// - rollover (7–8): the curvature limits κ_r± = (±d g_z + h g_y) / (h v²)
///   (tip-over to the right in a left turn, κ > 0, and to the left in a right
///   turn); PF_r = K_r (1 − (κ − κ_MAX)² / (κ_r+ − κ_MAX)²) for κ_r+ <= κ <
///   κ_MAX, mirrored for κ <= κ_r− with −κ_MAX, 0 between, K_r beyond ±κ_MAX;
/// - side slip (9–10): κ_s± = (g_y ± μ g_z) / v², PF_s alike with K_s;
/// - waypoint (11): PF_g = K_g (κ − κ_d)²;
/// - velocity (12): PF_v = K_v1 |v − v_d|^K_v2;
/// - hazards (13): PF_o = K_o (K_ov v + 1) / ((K_od O_d + 1)(K_oa A_d + 1))
///   · exp(−(κ − X)² / (2σ)), X = (κ1 + κ2)/2, σ = (κ1 − κ2)/2, O_d the
///   distance to the hazard, A_d the angle from the heading to the waypoint;
/// - the net field (14) is their sum.
/// Units: the paper states none. In SI its K_v1 = 0.5e-5 would make the
/// velocity field 5e-6 at a 1 m/s error, nothing beside K_g's curvature term,
/// so v enters (12) and (13) in velocity_unit (default 0.01 m/s: cm/s, where
/// a 1 m/s error costs 500, comparable to K_r); κ is in 1/m, O_d in m, A_d in
/// rad, and the rollover and slip limits are SI throughout.
/// At v = 0 the limits are infinite (no rollover or slip field).
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace talus {

/// The paper's gains (§V).
struct TrajectorySpaceGains {
  double rollover = 800.0;        ///< K_r
  double side_slip = 800.0;       ///< K_s
  double waypoint = 0.3;          ///< K_g
  double velocity = 0.5e-5;       ///< K_v1
  double velocity_power = 4.0;    ///< K_v2
  double hazard = 1500.0;         ///< K_o
  double hazard_distance = 0.05;  ///< K_od [1/m]
  double hazard_angle = 10.0;     ///< K_oa [1/rad]
  double hazard_speed = 0.07;     ///< K_ov [1/velocity_unit]
};

/// One hazard as seen from the vehicle: the arcs of curvature in [κ2, κ1]
/// from the vehicle's pose meet it (figure 5).
struct TrajectorySpaceHazard {
  double kappa_max = 0.0;       ///< κ1 [1/m]
  double kappa_min = 0.0;       ///< κ2 [1/m] (< κ1)
  double distance = 0.0;        ///< O_d [m] (>= 0)
  double waypoint_angle = 0.0;  ///< A_d [rad] (>= 0)
};

/// Everything the field depends on at one tick.
struct TrajectorySpaceInputs {
  double gravity_lateral = 0.0;    ///< g_y [m/s²]
  double gravity_normal = 9.81;    ///< g_z [m/s²] (> 0 upright)
  double friction = 0.7;           ///< μ
  double half_track = 0.124;       ///< d [m]
  double cg_height = 0.06;         ///< h [m]
  double max_curvature = 2.0;      ///< κ_MAX [1/m] (> 0)
  double desired_curvature = 0.0;  ///< κ_d [1/m]
  double desired_speed = 1.0;      ///< v_d [m/s]
  double max_speed = 10.0;         ///< descent keeps v in [0, max_speed] [m/s]
  std::vector<TrajectorySpaceHazard> hazards;
  double velocity_unit = 0.01;  ///< see the file comment [m/s per unit]
  TrajectorySpaceGains gains;
  /// Throws InputError naming the field.
  void validate() const;
};

/// A point of the trajectory space.
struct TrajectoryPoint {
  double speed = 0.0;      ///< v [m/s]
  double curvature = 0.0;  ///< κ [1/m]
};

/// The curvature limits at speed v: rollover_limits gives (κ_r−, κ_r+),
/// slip_limits (κ_s−, κ_s+) [1/m]; ±inf at v = 0.
std::pair<double, double> rollover_limits(const TrajectorySpaceInputs& in, double v);
std::pair<double, double> slip_limits(const TrajectorySpaceInputs& in, double v);

/// Each term and the sum at (v, κ).
struct TrajectorySpaceTerms {
  double rollover = 0.0, side_slip = 0.0, waypoint = 0.0, velocity = 0.0, hazards = 0.0;
  double total() const { return rollover + side_slip + waypoint + velocity + hazards; }
};
TrajectorySpaceTerms trajectory_space_field(const TrajectorySpaceInputs& in,
                                            const TrajectoryPoint& p);

/// (∂PF/∂v, ∂PF/∂κ) by central differences (steps 1e-4 max(1, v) m/s and
/// 1e-5 κ_MAX), one-sided at the box's edges.
std::pair<double, double> trajectory_space_gradient(const TrajectorySpaceInputs& in,
                                                    const TrajectoryPoint& p);

struct DescentOptions {
  /// Step length in the scaled space (v / max_speed, κ / κ_MAX) per call (> 0).
  double step = 0.02;
  /// Below this scaled-gradient norm the point is a local extremum or plateau:
  /// a random step of the same length is taken instead (Shimoda et al.'s
  /// randomisation against local maxima and saddles) (>= 0).
  double flat_gradient = 1e-6;
  /// Throws InputError naming the field.
  void validate() const;
};

/// One descent step from `p`: a move of `step` against the scaled gradient,
/// shortened so that the field does not rise (halved up to 10 times; no move
/// if it still does), kept inside [0, max_speed] × [−κ_MAX, κ_MAX]. The random
/// step draws from `rng` (seed it for reproducible runs).
TrajectoryPoint descend(const TrajectorySpaceInputs& in, const TrajectoryPoint& p,
                        std::mt19937_64& rng, const DescentOptions& options = {});

}  // namespace talus
