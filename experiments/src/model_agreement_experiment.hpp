#pragma once
/// @file
/// `talus experiment model-agreement` (issue #35, item 6): the canonical
/// manoeuvres of canonical_manoeuvres.hpp (flat and banked circle, crest,
/// side slope, straight drive and brake), each planned for the Iagnemma UGV
/// with evaluate_trajectory and driven by the rigid-body simulation at several
/// speed scales: the planned speed against the point mass's closed form, and
/// the simulator's own utilisation (friction envelope used, lowest total
/// normal load) against the scale, with the largest scale still driven (s*).
#include "experiment.hpp"

namespace talus::experiments {

void run_model_agreement(const ExperimentContext& context);

}  // namespace talus::experiments
