#pragma once
/// @file
/// navigate_layered: the layered scheme of Iagnemma, Shimoda & Shiller
/// (IROS 2008): the high-level time-optimal plan (plan(), planner.hpp) on
/// coarse map data — the fine terrain decimated, several vehicle lengths
/// per data point — its trajectory as waypoints with their profile speeds,
/// and potential-field navigation (potential_field_navigation.hpp) of the
/// simulated vehicle through them on the fine terrain, with the model-based
/// lookahead ("near-optimal") or without ("standard").
#include <cstddef>
#include <optional>
#include <string>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/navigation/potential_field_navigation.hpp"
#include "talus/optimal/planner.hpp"

namespace talus {

struct LayeredNavigationOptions {
  /// The plan's map keeps every coarse_factor-th node of the fine grid
  /// (decimate_grid; >= 1; 1 = plan on the fine data).
  std::size_t coarse_factor = 4;
  /// Waypoints every this far along the planned path [m] (> 0); 0 = four
  /// coarse cells (at two, 1.9 m apart on the tests' swell, the UGV at 4 m/s
  /// overshot them into tight circles and stalled). The last waypoint is the goal, at the speed of
  /// the one before it (the run ends within waypoint_radius of it).
  double waypoint_spacing = 0.0;
  PlannerOptions planner;  ///< the high-level layer
  /// The low-level layer; lookahead.enabled is the near-optimal navigation.
  PotentialFieldNavigationOptions navigation = [] {
    PotentialFieldNavigationOptions o;
    o.lookahead.enabled = true;
    return o;
  }();
  /// Throws InputError naming the field.
  void validate() const;
};

enum class LayeredNavigationStatus {
  kReachedGoal,  ///< the navigation reached the goal
  kFailed,       ///< the simulated vehicle failed (navigation->status says how)
  kTimeout,      ///< the navigation's time limit came first
  kNoPlan,       ///< the high-level plan found no feasible trajectory (plan_status says why)
};
/// "reached", "failed", "timeout", "no_plan".
std::string_view to_string(LayeredNavigationStatus status);

struct LayeredNavigationResult {
  LayeredNavigationStatus status = LayeredNavigationStatus::kNoPlan;
  std::string message;
  PlannerStatus plan_status = PlannerStatus::kUnreachable;
  /// The planned trajectory's travel time on the coarse surface [s] (the
  /// "optimal" time the navigation is compared with); NaN without a plan.
  double optimal_time = 0.0;
  double plan_seconds = 0.0;      ///< wall time of the high-level plan [s]
  ReferenceTrajectory waypoints;  ///< what the navigation was given
  std::optional<PotentialFieldNavigationResult> navigation;  ///< empty without a plan
  /// The navigation's time over the optimal one, minus 1 (0.096 = 9.6 %
  /// slower); NaN unless the goal was reached.
  double time_increase() const;
  /// Status, times, the navigation's report.
  std::string brief_report() const;
};

/// The waypoints of a planned trajectory's reference: a point every `spacing`
/// metres (> 0) of its planar length, and its last point, each with the
/// profile's speed there; the last (the goal) gets the speed of the one
/// before it, since a waypoint speed of 0 would stop the navigator short of
/// the goal (its run ends within waypoint_radius of it). InputError for
/// fewer than two points or a spacing <= 0.
ReferenceTrajectory plan_waypoints(const ReferenceTrajectory& reference, double spacing);

/// Plans on decimate_grid(fine, coarse_factor) and navigates on `fine`
/// (both interpolated by BPatch::interpolate) from rest at `start`, heading
/// towards the first waypoint, to `goal`. InputError for invalid input (a
/// fine grid with NODATA, a vehicle without a body or a finite max_speed,
/// start or goal off the map).
LayeredNavigationResult navigate_layered(const ElevationGrid& fine, const Vehicle& vehicle,
                                         const Vec2& start, const Vec2& goal,
                                         const LayeredNavigationOptions& options = {});

}  // namespace talus
