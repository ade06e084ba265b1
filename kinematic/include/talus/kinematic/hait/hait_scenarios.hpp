#pragma once
/// @file
/// The terrains and queries of our reproductions of Haït, Siméon, Taïx,
/// "Algorithms for rough terrain trajectory planning" (Advanced Robotics
/// 16(8), 2002): the hait-* experiments, dynamic-vs-kinematic, bench_hait
/// and the tests share them. The paper's terrains are not published; ours are
/// generated with a seed at the paper's scale (0.25 m spacing, about 20000
/// nodes), so every run is reproducible and platform independent.
///
/// Frame: the south-west node at the origin, x east, y north, z up [m];
/// headings θ counter-clockwise from east [rad].
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/core/types.hpp"
#include "talus/kinematic/configuration_space.hpp"

namespace talus {

/// A planning query on a generated terrain.
struct HaitScenario {
  ElevationGrid grid;
  SE2Pose start, goal;
  std::string description;  ///< one paragraph for the reports (how the terrain was made)
  /// The Gaussian hills added to the fractal base (none for the gorge).
  std::vector<GaussianHill> hills;
  /// hait_gorge_scenario: the gorge's centre, the ridge's x–half-thickness [m],
  /// the y where the ridge ends (north) and the gorge's half-width at the top
  /// of its walls (floor half-width + wall width) [m]; unused elsewhere.
  Vec2 gorge = Vec2::Zero();
  double ridge_half_thickness = 0.0;
  double ridge_end_y = 0.0;
  double gorge_half_width = 0.0;
};

/// Adds every hill of `hills` (terrain_generators.hpp: height ·
/// exp(−|p − centre|² / (2 σ²))) to every node of `grid`, hill by hill.
void add_hills(ElevationGrid& grid, std::span<const GaussianHill> hills);

/// The fractal base of every scenario: `ncols` × `nrows` nodes at `spacing`
/// [m], a fractional Brownian surface of dimension D = 2.2 with
/// `height_scale` [m] of relief (generate_fractal_terrain, seed `seed`).
ElevationGrid hait_fractal_base(std::size_t ncols, std::size_t nrows, double spacing,
                                double height_scale, std::uint64_t seed);

/// A rough rover-scale terrain of `ncols` × `nrows` nodes at `spacing` [m]:
/// hait_fractal_base with 1.2 · (extent / 35 m)^0.8 m of relief (extent =
/// the longer side [m]; fBm with H = 0.8, so the slope statistics do not
/// depend on the map's size) plus `hills` steep Gaussian hills (1.8 m high,
/// σ = 1.4 m) at positions drawn uniformly over the map from a
/// std::mt19937_64 seeded with seed ^ 0x9e3779b97f4a7c15. The terrain of
/// hait-preprocessing.
ElevationGrid hait_rough_terrain(std::size_t ncols, std::size_t nrows, double spacing,
                                 std::size_t hills, std::uint64_t seed);

/// The hait-heuristics problem (also hait-smoothing, dynamic-vs-kinematic and
/// bench_hait): 141 × 141 nodes at 0.25 m (19881 nodes, 35 m × 35 m; `quick`:
/// 61 × 61, 15 m), a fractal base (seed 7, 1.2 m relief; quick 0.5 m) and a
/// crescent of 11 (quick 7) Gaussian hills 2 m high (σ = 1 m; quick 0.7 m),
/// evenly spaced over 216° of a circle of radius 0.22 L around (0.55 L,
/// 0.55 L) (L the side), opening south-west towards the start. It cups the
/// straight line from the start (0.12 L, 0.12 L, θ = π/4) to the goal
/// (0.88 L, 0.88 L, θ = π/2), the trap that misleads a straight-line
/// heuristic (the paper's Fig. 18 problem is of that kind).
HaitScenario hait_heuristics_scenario(bool quick);

/// The hait-uncertainty problem (the paper's Fig. 27): 141 × 141 nodes at
/// 0.25 m (quick 81 × 81), a mildly rough fractal plain (seed 11, 0.15 m
/// relief) plus a north–south ridge along x = W/2 (W the width): 2.5 m high
/// on its axis with a raised-cosine cross-section 3 m thick, from the south
/// border to y = 0.6 H (H the height), dying out north of it as
/// exp(−((y − 0.6 H)/0.6 m)²); cut at y = 0.35 H by a gorge with a flat
/// floor 1.8 m wide and raised-cosine walls 0.35 m wide. Start (0.15 W,
/// 0.35 H, θ = 0) and goal (0.85 W, 0.35 H, θ = 0) face each other through
/// the gorge; the way round is past the ridge's north end.
HaitScenario hait_gorge_scenario(bool quick);

/// The y where `path` first crosses the vertical line x = `x` (linear
/// between consecutive poses), or NaN if it never crosses.
double first_crossing_y(std::span<const PathPoint> path, double x);

/// Whether `path` crosses the ridge of a gorge scenario through the gorge:
/// its first crossing of the ridge line x = gorge.x lies in the gorge's
/// opening, |y − gorge.y| < gorge_half_width. A crossing elsewhere south of
/// the ridge's end is over the ridge, one north of it is round the ridge;
/// both are false, and so is a path that never crosses.
bool passes_through_gorge(std::span<const PathPoint> path, const HaitScenario& gorge_scenario);

/// A per-node terrain uncertainty map (HaitOptions::terrain_uncertainty_map)
/// of `grid`'s shape: `high` [m] at the nodes within `radius` [m] of `centre`
/// (inclusive), `base` [m] elsewhere. Throws InputError for a negative or
/// non-finite δz or radius.
ElevationGrid uncertainty_disc_map(const ElevationGrid& grid, double base, const Vec2& centre,
                                   double radius, double high);

/// Planar length [m] of the pieces of `path` (consecutive poses joined by
/// chords) that lie within `radius` of `centre`: each chord is clipped to the
/// disc exactly. 0 for fewer than two poses.
double length_within_disc(std::span<const PathPoint> path, const Vec2& centre, double radius);

}  // namespace talus
