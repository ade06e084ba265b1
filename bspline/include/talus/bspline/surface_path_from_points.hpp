#pragma once
/// @file
/// A path on a terrain from user way points: the interpolating cubic B-spline
/// through the points (chord-length parameters), lifted onto the grid's
/// B-patch, with every check of the user's input done first so that a bad
/// point is named (index, position, file and line) rather than failing deep
/// inside the geometry. What `talus limits` and `talus profile` build from
/// their --terrain and --path files; usable on points from anywhere.
///
/// All positions are in the terrain's frame [m]. Every check throws
/// InputError (talus/core/error.hpp) with a message meant for the user.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// Where the way points and the terrain came from, for the messages.
struct PathPointSource {
  std::string path_file = "path";        ///< named in messages about the way points
  std::string terrain_file = "terrain";  ///< named in messages about the terrain
  /// Text line of way point 0 in path_file; point k is on line k + first_line
  /// (2 for read_path_csv: a header line, then one point per line).
  std::size_t first_line = 2;
};

/// Way point k at which the polyline turns straight back on itself (the unit
/// directions in and out have a dot product below −0.9999, i.e. a turn of
/// more than about 179.2°): the interpolating spline would stop there and its
/// frame is undefined. Throws InputError naming the first such point
/// ("path point k (x, y) (FILE line L) turns the path straight back ...").
void check_no_reversal(const std::vector<Vec2>& points, const PathPointSource& source);

/// Every way point inside the grid's node rectangle; throws InputError
/// naming the first point outside and the domain.
void check_points_in_domain(const std::vector<Vec2>& points, const ElevationGrid& grid,
                            const PathPointSource& source);

/// Every way point inside `surface`'s domain and on measured data (all four
/// corners of its cell valid); throws InputError naming the first point that
/// is not, and the domain of `grid` (the grid `surface` was fitted to).
void check_points_on_data(const std::vector<Vec2>& points, const BPatch& surface,
                          const ElevationGrid& grid, const PathPointSource& source);

/// The spline `curve` through `points` (chord-length parameters normalised to
/// the curve's parameter range, as Curve2::interpolate) stays inside
/// `surface`'s domain: checked at 63 interior samples between each pair of
/// consecutive way points. Throws InputError naming the two points and the
/// first sample outside (SurfacePath's own check remains the backstop).
void check_curve_in_domain(const Curve2& curve, const std::vector<Vec2>& points,
                           const BPatch& surface, const ElevationGrid& grid,
                           const PathPointSource& source);

/// The lifted path crosses no NODATA cell anywhere, not only at a way point:
/// sampled equally in the curve parameter at max(2, ceil(L / (h/4)) + 1)
/// stations (L its 3-D length [m], h the cell size [m]), so no cell the path
/// crosses is skipped. Throws InputError naming the first station off the
/// data (its arc length s and position). The NODATA policy of `talus limits`
/// and `talus profile` (as `plan`, which treats voids as impassable).
void check_path_on_data(const SurfacePath& path, const PathPointSource& source);

/// Length of the polyline through `points` (straight segments) [m]; 0 for
/// fewer than two points.
double planar_polyline_length(const std::vector<Vec2>& points);

/// A path on a terrain. Both objects live on the heap: the path refers to
/// the surface, and a SurfacePath must not be moved or copied (its
/// arc-length table refers to its own curve).
struct TerrainPath {
  std::unique_ptr<const BPatch> surface;
  std::unique_ptr<const SurfacePath> path;  ///< lifted onto *surface
  double planar_length = 0.0;               ///< the way points' polyline (straight segments) [m]
};

/// Fits the B-patch of `grid` (BPatch::interpolate, or BPatch::fit_smoothing
/// with lambda `*smoothing`) and lifts Curve2::interpolate(points) onto it,
/// after the checks above in this order: no reversal, points in the domain,
/// (fit; a fit error is rethrown prefixed "TERRAIN_FILE: "), points on data,
/// spline in the domain, path on data. `points` as Curve2::interpolate needs
/// them (at least 2, consecutive points distinct: read_path_csv ensures it).
TerrainPath surface_path_from_points(const std::vector<Vec2>& points, const ElevationGrid& grid,
                                     const std::optional<double>& smoothing,
                                     const PathPointSource& source);

}  // namespace talus
