#pragma once
#include "experiment.hpp"

namespace talus::experiments {

/// terrain-gallery: every bundled DEM and a fractal terrain as shaded relief
/// with contours, and the smoothing fit's residual map.
void run_terrain_gallery(const ExperimentContext& context);

}  // namespace talus::experiments
