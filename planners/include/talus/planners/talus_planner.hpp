#pragma once
/// @file
/// TalusPlanner: Talus's own two-stage planner (talus::plan: the global
/// search at the velocity limit, then the B-spline optimiser) behind the
/// kinematic baselines' interface (BaselinePlanner), registered as "talus".
/// A query fits the terrain's grid (interpolating B-patch, or the smoothing
/// fit), plans the vehicle from the start to the goal with the start's and
/// the goal's headings kept, and returns the best trajectory's stations as
/// poses (heading = the path's planar tangent). Validity of a pose: the
/// vehicle can stand there and move off along its heading (a straight pass
/// through the admissible set, as the traversability map judges a node,
/// with some acceleration admissible at rest). A plan may ride a pose only
/// at speed (a flank held by the path's curvature, like a wall of death):
/// such poses fail the check although the trajectory is admissible there.
///
/// Statuses: found (a best trajectory), no_path (the goal is unreachable at
/// any speed, or no candidate has a feasible trajectory), start_invalid /
/// goal_invalid (the validity check), budget_exceeded (the work budget:
/// polls of the plan's termination, one per 1024 lattice nodes sampled or
/// expanded and one per solver iteration or evaluation — work, not time,
/// so reruns are bit-identical).
#include <cstddef>
#include <string>
#include <vector>

#include "talus/dynamics/vehicle.hpp"
#include "talus/kinematic/baseline_planner.hpp"
#include "talus/kinematic/baseline_registry.hpp"

namespace talus {

struct TalusPlannerOptions {
  /// λ of the smoothing fit of the terrain's grid (>= 0); 0 = the
  /// interpolating fit.
  double smoothing = 0.0;
  std::size_t candidates = 3;  ///< global candidates refined (>= 1)
  /// Work budget (>= 1): polls of the plan's termination (file comment).
  std::size_t budget = 1000000000;
  /// Throws InputError naming the field.
  void validate() const;
};

class TalusPlanner : public BaselinePlanner {
 public:
  /// `vehicle` needs a finite max_speed (talus::plan); `vehicle_file` is
  /// reported in settings(). InputError for invalid options or vehicle.
  TalusPlanner(Vehicle vehicle, TalusPlannerOptions options, std::string vehicle_file = "");
  std::string name() const override { return "talus"; }
  std::vector<BaselineSetting> settings() const override;
  ValidityFunction validity(const RuledTerrain& terrain) const override;

 protected:
  BaselineResult solve(const RuledTerrain& terrain, const SE2Pose& start,
                       const SE2Pose& goal) const override;

 private:
  Vehicle vehicle_;
  TalusPlannerOptions options_;
  std::string vehicle_file_;
};

/// The registry entry "talus": options robot (a vehicle file, required),
/// smoothing, candidates, budget.
BaselineEntry talus_planner_entry();

}  // namespace talus
