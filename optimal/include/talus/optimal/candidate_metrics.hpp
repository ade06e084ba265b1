#pragma once
/// @file
/// Measurements of the candidate corridors of a global search
/// (global_search.hpp): along-route profiles and extremes, an independent
/// re-evaluation of the search's cost, where a route passes a landmark, how
/// much of a route runs in another's corridor, and a census of the lattice.
/// All lengths in metres, times in seconds, angles in degrees.
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/global_search.hpp"

namespace talus {

/// Terrain slope angle [deg] at a surface point: atan |∇z|, the angle of the
/// steepest descent line with the horizontal.
double terrain_slope_degrees(const SurfacePoint& point);

/// What measure_candidate() finds along one candidate path.
struct CandidateMetrics {
  std::vector<double> s;           ///< 3-D distance along the route at each vertex [m]
  std::vector<double> z;           ///< elevation at each vertex [m]
  std::vector<double> slope;       ///< terrain slope at each vertex [deg]
  std::vector<double> edge_speed;  ///< per edge: 3-D length / J, the mean speed at the limit [m/s]
  double max_slope = 0.0;          ///< steepest terrain slope at any station of any edge [deg]
  double max_z = -std::numeric_limits<double>::infinity();  ///< highest vertex [m]
  double climb = 0.0;  ///< sum of the rises between vertices [m]
  /// Σ of edge_cost().forward over the edges: an independent re-evaluation of
  /// CandidatePath::cost_seconds (they agree to rounding).
  double recomputed_cost = 0.0;
  bool revisits = false;  ///< two vertices coincide (within 1e-6 spacings): the route doubles back
  double min_edge_speed = std::numeric_limits<double>::infinity();  ///< slowest edge [m/s]
  /// Edge stations (the search's own sampling, edge_stations()) steeper than
  /// atan μ, and among them those where the vehicle could not hold itself at
  /// rest — no s̈ admissible at v = 0, or it could neither climb (a_max < 0)
  /// nor stop (a_min > 0) there — so the edge passed the search's rules only
  /// thanks to the extra normal load κ_n v² of a concave surface at a higher
  /// admissible speed.
  std::size_t steep_stations = 0, speed_only_stations = 0;
  std::size_t concave_speed_only = 0;  ///< of the latter, those with κ_n > 0
};

/// Measures `path` on `terrain` for `vehicle`, evaluating each edge with
/// edge_cost() at edge_stations(length, `spacing`) stations exactly as
/// global_search() does (`spacing` = the result's lattice spacing [m]).
/// Throws InputError if the path has no vertex or spacing is not positive.
CandidateMetrics measure_candidate(const BPatch& terrain, const Vehicle& vehicle,
                                   const CandidatePath& path, double spacing);

/// Where a route passes a landmark (a summit, a crater): the point where it
/// crosses the line through the landmark perpendicular to the start→goal
/// axis (axis_crossing() in polyline.hpp; the nearest vertex if it never
/// does), its distance from the landmark and the compass point of the
/// landmark→crossing direction ("" if the route passes through the landmark).
struct LandmarkPassage {
  Vec2 point = Vec2::Zero();  ///< [m]
  double distance = 0.0;      ///< [m]
  std::string side;           ///< e.g. "south-west"
};
/// Throws InputError if `route` is empty or start == goal.
LandmarkPassage landmark_passage(std::span<const Vec2> route, const Vec2& start, const Vec2& goal,
                                 const Vec2& landmark);

/// How far a route is from a reference route, and how much of it shares the
/// reference's corridor.
struct CorridorOverlap {
  double hausdorff = 0.0;  ///< symmetric Hausdorff distance over the vertices [m]
  double shared = 1.0;     ///< share of the route's vertices closer than `near` to the reference
};
/// Throws InputError if either route is empty.
CorridorOverlap corridor_overlap(std::span<const Vec2> route, std::span<const Vec2> reference,
                                 double near);

/// The separation global_search() uses when GlobalSearchOptions::distinctness
/// is 0: 10 % of the distance between the snapped start and goal nodes, and
/// at least 3 lattice spacings [m].
double default_separation(const GlobalSearchResult& result);

/// Position [m] of lattice node `n` (row-major, nx per row) of a search result.
Vec2 lattice_node_position(const GlobalSearchResult& result, std::size_t n);

/// Counts over the lattice of a search result. Run the search with
/// cost_fields = true: without the fields (A*), cost_from_start is +inf at
/// every node the search did not need, reachable or not.
struct LatticeCensus {
  std::size_t steep_nodes = 0;        ///< nodes where the terrain is steeper than atan μ
  std::size_t unreachable_nodes = 0;  ///< nodes with cost_from_start = +inf
};
/// Throws InputError if cost_from_start does not cover the nx × ny lattice.
LatticeCensus lattice_census(const BPatch& terrain, const GlobalSearchResult& result,
                             double friction);

}  // namespace talus
