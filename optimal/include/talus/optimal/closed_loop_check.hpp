#pragma once
/// @file
/// check_closed_loop: a planned trajectory driven by the rigid-body
/// simulation (trajectory_tracking.hpp) at several multiples of its profile
/// speed, to see how much of "at the limit" a point-mass plan keeps once
/// suspension and tyres are real. The `closed-loop-plans` experiment runs it
/// on every plan of its battery.
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/dynamics/trajectory_tracking.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/trajectory.hpp"

namespace talus {

/// The stations of a feasible trajectory as a planar reference with its
/// profile speeds [m/s]; consecutive stations at one planar point (closer
/// than 1e-9 m) are merged, keeping the larger speed. InputError when the
/// trajectory is infeasible.
ReferenceTrajectory reference_trajectory(const Trajectory& trajectory);

struct ClosedLoopOptions {
  /// The multiples of the profile speed to drive at, each > 0 (at least one).
  std::vector<double> speed_scales = {0.9, 1.0, 1.1};
  /// The tracking controller and simulation; speed_scale is replaced per drive.
  TrackingOptions tracking;
  /// Throws InputError naming the field.
  void validate() const;
};

struct ClosedLoopDrive {
  double speed_scale = 1.0;
  TrackingResult result;
  bool reached() const { return result.status == TrackingStatus::kReachedGoal; }
};

struct ClosedLoopResult {
  ReferenceTrajectory reference;        ///< what was driven
  std::vector<ClosedLoopDrive> drives;  ///< one per speed scale, in order
  std::size_t reached() const;          ///< drives that reached the goal
  /// One line per drive: scale, status, progress, time against the plan, margins.
  std::string brief_report() const;
};

/// Drives `trajectory` (feasible) on `surface` with `vehicle` (which needs a
/// body) at every speed scale. InputError for an infeasible trajectory, bad
/// options or a vehicle without a body; the drives' failures are statuses.
ClosedLoopResult check_closed_loop(const BPatch& surface, const Vehicle& vehicle,
                                   const Trajectory& trajectory,
                                   const ClosedLoopOptions& options = {});

}  // namespace talus
