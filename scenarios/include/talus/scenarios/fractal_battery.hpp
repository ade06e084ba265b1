#pragma once
/// @file
/// The fractal battery of issue #12 after Iagnemma, Shimoda & Shiller (IROS
/// 2008, §V): 129 × 129 nodes at 0.24 m (two wheel diameters), fractal
/// dimension 2.05, height scale 4.2 m (35 wheel diameters), a 1 m
/// undulation over 30 m and six 1 m peaks, one terrain per seed; every case
/// runs from kBatteryStart to kBatteryGoal. Shared by the experiments
/// (closed-loop-plans, optimiser-quality, iagnemma-table1, ...), tests and
/// benchmarks.
#include <cstdint>

#include "talus/core/terrain_generators.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus::scenarios {

inline const Vec2 kBatteryStart{2.0, 2.0};   ///< [m]
inline const Vec2 kBatteryGoal{28.5, 28.5};  ///< [m]

/// The battery's terrain of `seed` (1-25 in the issue).
inline FractalTerrainOptions battery_terrain(std::uint64_t seed) {
  FractalTerrainOptions f;  // shape, D and height scale default to the study's
  f.undulation_amplitude = 1.0;
  f.undulation_wavelength = 30.0;
  f.peaks = 6;
  f.peak_height = 1.0;
  f.seed = seed;
  return f;
}

/// The point-mass UGV of the battery: μ 0.7, c.g. height 0.06 m,
/// half-track 0.124 m (the paper's), 7 m/s, drive 3 m/s², brake 5 m/s²
/// (assumed, as in data/vehicles/iagnemma_ugv.yaml).
inline Vehicle battery_point_mass_ugv() {
  Vehicle v;
  v.friction = 0.7;
  v.cg_height = 0.06;
  v.half_track = 0.124;
  v.max_speed = 7.0;
  v.max_accel = 3.0;
  v.max_decel = 5.0;
  return v;
}

}  // namespace talus::scenarios
