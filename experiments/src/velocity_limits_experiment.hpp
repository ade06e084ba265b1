#pragma once
#include "experiment.hpp"

namespace talus::experiments {

/// velocity-limits: the speed limits v_min(s), v_max(s) of each constraint
/// (sliding, lateral tip-over, contact) and the binding one, plus the
/// tangential-acceleration bounds, along a fixed curved path across the West
/// Bijou escarpment DEM, at the DEM's own 25 m scale and scaled to rover size
/// (1 m cells), for a point mass, a rigid body and a tall narrow rigid body.
void run_velocity_limits(const ExperimentContext& context);

}  // namespace talus::experiments
