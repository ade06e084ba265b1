#pragma once
/// @file
/// The reproductions of Haït, Siméon, Taïx, "Algorithms for rough terrain
/// trajectory planning" (Advanced Robotics 16(8), 2002), each writing
/// `<out>/<name>/` with CSVs, PNG figures and a report.md that puts our
/// numbers beside the paper's (shared/docs/papers.md).
#include "experiment.hpp"

namespace talus::experiments {

/// hait-heuristics (§4.3 table): one problem, the three search guidances.
void run_hait_heuristics(const ExperimentContext& context);
/// hait-preprocessing (§4.3, Fig. 20): preprocessing time against terrain
/// size and resolution, with fitted exponents.
void run_hait_preprocessing(const ExperimentContext& context);
/// hait-smoothing (§4.4, Fig. 21): control changes before and after smoothing.
void run_hait_smoothing(const ExperimentContext& context);
/// hait-uncertainty (§5.4, Fig. 27): the route with and without uncertainty
/// and the preprocessing cost ratio.
void run_hait_uncertainty(const ExperimentContext& context);

}  // namespace talus::experiments
