#pragma once
#include "experiment.hpp"

namespace talus::experiments {

/// optimal-profile: the time-optimal velocity profile v(s) under the limit
/// curve v_max(s), with its switching points and the tangential acceleration
/// inside the admissible [a_min, a_max], along a curved path on the West Bijou
/// DEM at rover scale (smoothing fit), for a point mass and a rigid body whose
/// braking is limited by pitch-over (the analogue of Iagnemma–Shimoda–Shiller
/// 2008, Fig. 8); plus a convergence study of the travel time in the number of
/// stations, which is the evidence behind kDefaultStationSpacing.
void run_optimal_profile(const ExperimentContext& context);

}  // namespace talus::experiments
