#pragma once
/// @file
/// `talus experiment closed-loop-plans` (issue #16, item 3): the planner's
/// time-optimal trajectories for the Iagnemma UGV on the fractal battery of
/// Iagnemma, Shimoda & Shiller (IROS 2008, §V) driven by the rigid-body
/// simulation (track_trajectory: curvature steering law and speed PI) at 90, 100 and
/// 110 % of their profile speed: status, failure kind, the margins kept
/// (peak lateral load ratio, minimum normal load, peak slip) and the travel
/// time against the planned one, per case and speed scale.
#include "experiment.hpp"

namespace talus::experiments {

void run_closed_loop_plans(const ExperimentContext& context);

}  // namespace talus::experiments
