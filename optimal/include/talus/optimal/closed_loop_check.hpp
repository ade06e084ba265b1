#pragma once
/// @file
/// check_closed_loop: a planned trajectory driven by the rigid-body
/// simulation (trajectory_tracking.hpp) at several multiples of its profile
/// speed, to see how much of "at the limit" a point-mass plan keeps once
/// suspension and tyres are real. The `closed-loop-plans` experiment runs it
/// on every plan of its battery.
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
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
  /// Simulated time to the goal over the planned time at this scale (NaN unless reached).
  double schedule_ratio() const;
  /// Reached the goal within (1 + tolerance) × the planned time at this scale.
  bool kept_schedule(double tolerance) const;
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

/// Options of find_speed_scale_limit.
struct SpeedScaleLimitOptions {
  /// The bracket of speed scales searched: 0 < lowest < highest (finite).
  double lowest = 0.5;
  double highest = 1.5;
  /// Bisection stops when the bracket is at most this wide (> 0): 0.02
  /// takes six drives on the default bracket.
  double tolerance = 0.02;
  /// A drive passes when it reaches the goal within (1 + schedule_tolerance)
  /// × its planned time at its scale (>= 0; +inf: reaching is enough). A
  /// drive that arrives later failed too, "behind schedule": the vehicle
  /// cannot drive the plan that fast (its drive, brakes or top speed
  /// saturate), so the plan is tight there although nothing slid or lifted.
  /// Without it a drive-limited plan scores s* >= 1.5 while the vehicle
  /// crawls along at its own limit. 0.1 is twice the tracker's lag on the
  /// fractal battery at 100 % (at most 6 %, closed-loop-plans).
  double schedule_tolerance = 0.1;
  /// The tracking controller and simulation; speed_scale is replaced per drive.
  TrackingOptions tracking;
  /// Throws InputError naming the field.
  void validate() const;
};

enum class SpeedScaleLimitStatus {
  kBracketed,       ///< reaches at largest_reaching_scale, fails within tolerance above it
  kReachesHighest,  ///< the drive at `highest` reached the goal: s* >= highest
  kFailsLowest,     ///< the drive at `lowest` failed: s* < lowest
};
/// "bracketed", "reaches_highest", "fails_lowest".
std::string_view to_string(SpeedScaleLimitStatus status);

/// The largest speed scale s* at which a trajectory is still driven to the
/// goal on schedule, and the failure that bounds it.
struct SpeedScaleLimit {
  SpeedScaleLimitStatus status = SpeedScaleLimitStatus::kFailsLowest;
  /// s*: the largest scale driven to the goal (NaN when kFailsLowest).
  double largest_reaching_scale = std::numeric_limits<double>::quiet_NaN();
  /// The smallest scale that failed (+inf when kReachesHighest).
  double smallest_failing_scale = std::numeric_limits<double>::infinity();
  /// Every drive in the order driven; the first is at the bracket's midpoint.
  std::vector<ClosedLoopDrive> drives;
  /// The drive at smallest_failing_scale (null when kReachesHighest): its
  /// status and message name the failure that bounds s*.
  const ClosedLoopDrive* bounding_failure() const;
  /// The drive at largest_reaching_scale (null when kFailsLowest).
  const ClosedLoopDrive* largest_reaching_drive() const;
  /// The options' schedule_tolerance the drives were judged with.
  double schedule_tolerance = 0.1;
  /// What bounds s*: the bounding failure's tracking status ("side_slip",
  /// ...), "behind_schedule" when it reached the goal too late, "" when none.
  std::string bounding_reason() const;
  /// One line: s*, the bracket and the bounding failure.
  std::string brief_report() const;
};

/// Bisection on the speed scale between options.lowest and options.highest:
/// each step drives `trajectory` at the bracket's midpoint (passing = reaching
/// the goal on schedule, see schedule_tolerance) and keeps the half
/// where reaching turns into failing, until the bracket is within tolerance;
/// the ends themselves are driven only when the bisection never left them
/// (to tell s* >= highest and s* < lowest from a bracket). Reaching is
/// assumed to fail above one scale and hold below it; where it does not (a
/// faster drive that gets past a hazard a slower one meets), s* is one
/// reach-to-fail transition, and `drives` shows every probe. InputError as
/// check_closed_loop.
SpeedScaleLimit find_speed_scale_limit(const BPatch& surface, const Vehicle& vehicle,
                                       const Trajectory& trajectory,
                                       const SpeedScaleLimitOptions& options = {});

}  // namespace talus
