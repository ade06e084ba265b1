#pragma once
/// @file
/// Placement of a rigid body on sprung wheels (Haït, Siméon and Taïx 2002,
/// §3.1.1, algorithm Place_robot) and its interval version for terrain
/// uncertainty (§5.1). A configuration is (x, y, θ): the horizontal position of
/// the centre of gravity G and the heading of the body's u axis, counter-
/// clockwise from east.
///
/// Attitude convention: the body-to-world rotation is R = Rz(θ) Ry(-ψ) Rx(φ),
/// so the roll φ > 0 raises the left side and the pitch ψ > 0 raises the nose.
#include <array>

#include "talus/core/ruled_terrain.hpp"
#include "talus/core/types.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {

/// How a placement ended. Only kOffMap and kNoData make a placement unusable:
/// after kIterationLimit the last (approximate) placement is returned, as the
/// paper does.
enum class PlacementStatus {
  kConverged,       ///< the stopping rule was met
  kIterationLimit,  ///< the iteration cap was reached first; the result is the best found
  kOffMap,          ///< a wheel (or the configuration) lies off the terrain
  kNoData,          ///< a wheel lies on a patch touching a NODATA node
};

/// Lower-case name of a status ("converged", "iteration_limit", "off_map", "no_data").
const char* to_string(PlacementStatus status);
/// True unless the status is kOffMap or kNoData.
inline bool usable(PlacementStatus s) {
  return s == PlacementStatus::kConverged || s == PlacementStatus::kIterationLimit;
}

/// Options of place_robot.
struct RobotPlacementOptions {
  int max_iterations = 20;  ///< plane fits at most (> 0)
  double energy_tolerance =
      1e-12;  ///< [m^2] stop when Σ l_j² drops below this or decreases by less (> 0)
  int contact_iterations = 8;       ///< Newton steps per wheel contact L_j(p) (> 0)
  double contact_tolerance = 1e-9;  ///< [m] contact residual accepted by L_j(p) (> 0)
  /// Throws InputError naming the field.
  void validate() const;
};

/// Result of place_robot: the body pose, the spring extensions and diagnostics.
struct RobotPlacement {
  PlacementStatus status = PlacementStatus::kOffMap;
  Vec3 position = Vec3::Zero();  ///< G in the world [m]
  double theta = 0.0;            ///< heading [rad]
  double roll = 0.0;             ///< φ [rad]
  double pitch = 0.0;            ///< ψ [rad]
  int wheel_count = 0;
  std::array<double, WheeledRobot::kMaxWheels> extensions{};  ///< l_j [m], first wheel_count used
  std::array<Vec3, WheeledRobot::kMaxWheels> contacts{};  ///< contact points C_j in the world [m]
  double energy = 0.0;  ///< Σ l_j² [m²] (the paper's energy without the stiffness k)
  int iterations = 0;   ///< plane fits performed

  /// Body-to-world rotation Rz(θ) Ry(-ψ) Rx(φ).
  Mat3 rotation() const;
};

/// Place_robot (§3.1.1): the pose (z, φ, ψ) at configuration (x, y, θ) that
/// minimises Σ L_j² over the spring extensions needed to keep every wheel on
/// the terrain (eq. 1). Starts level with G at terrain(x, y) + cg_height, then
/// repeats: compute every wheel's contact C_j = L_j(p) (Newton along the body's
/// w axis), fit the least-squares plane to the C_j (orthogonal distances), and
/// put the wheels' rest plane on it. Stops when the energy falls below
/// energy_tolerance (converged) or no longer decreases by energy_tolerance
/// (the paper's "until E_i >= E_i-1", returning the better placement), or
/// after max_iterations. Off-map or NODATA wheels end it with that status.
RobotPlacement place_robot(const WheeledRobot& robot, const RuledTerrain& terrain, double x,
                           double y, double theta, const RobotPlacementOptions& options = {});

/// The same with wheel j standing on `upper` if bit j of `upper_mask` is set and
/// on `lower` otherwise (G's starting height samples wheel 0's terrain). The building block of
/// the §5.1 placement intervals.
RobotPlacement place_robot_mixed(const WheeledRobot& robot, const RuledTerrain& lower,
                                 const RuledTerrain& upper, unsigned upper_mask, double x, double y,
                                 double theta, const RobotPlacementOptions& options = {});

/// A closed interval [lo, hi].
struct Interval {
  double lo = 0.0;
  double hi = 0.0;
  /// Grows the interval to hold v.
  void include(double v) {
    lo = v < lo ? v : lo;
    hi = v > hi ? v : hi;
  }
  bool contains(double v) const { return lo <= v && v <= hi; }
};

/// Placement intervals of a wheeled robot under terrain uncertainty (§5.1).
struct RobotPlacementInterval {
  PlacementStatus status =
      PlacementStatus::kOffMap;  ///< the first unusable run's status, else the nominal one's
  Interval z, roll, pitch;       ///< of G [m] and the attitude [rad]
  int wheel_count = 0;
  std::array<Interval, WheeledRobot::kMaxWheels> extensions{};  ///< of each l_j [m]
  int placements = 0;                                           ///< place_robot runs made
};

/// §5.1.1 adapted to the sprung rigid body: the paper gives the extreme
/// placements of an axle by putting each wheel on T_min or T_max; here each
/// extreme of z, φ, ψ and of every l_j is sought by the wheel assignment that
/// the signs of the linearised least-squares fit (at the nominal wheel layout)
/// say drives it up or down (e.g. left wheels on T_max and right ones on T_min
/// for the largest roll). The intervals are the hull of those runs and of the
/// nominal placement on `terrain`; including the nominal keeps the worst-case
/// checks at least as strict as the certain ones even where the fit is far
/// from linear.
RobotPlacementInterval place_robot_interval(const WheeledRobot& robot, const RuledTerrain& terrain,
                                            const RuledTerrain& lower, const RuledTerrain& upper,
                                            double x, double y, double theta,
                                            const RobotPlacementOptions& options = {});

}  // namespace talus
