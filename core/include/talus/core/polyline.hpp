#pragma once
/// @file
/// Planar polyline geometry [m]: distance of a point to a polyline, the
/// symmetric Hausdorff distance of two polylines, the share of a polyline's
/// vertices near another, where a polyline crosses a line perpendicular to an
/// axis, and the compass point of a direction. A polyline is its vertices in
/// order, joined by straight segments; one vertex is a point.
#include <span>
#include <string>

#include "talus/core/types.hpp"

namespace talus {

/// Euclidean distance [m] from `p` to the nearest point of `line` (its
/// segments, ends included). Throws InputError if `line` is empty.
double distance_to_polyline(const Vec2& p, std::span<const Vec2> line);

/// Symmetric Hausdorff distance [m] of two polylines, taken over their
/// vertices: max(max over a's vertices of the distance to polyline b, max
/// over b's vertices of the distance to polyline a). For polylines whose
/// vertices are close together (lattice paths) this is the Hausdorff distance
/// of the curves to within the vertex spacing. Throws InputError if either
/// is empty.
double hausdorff_distance(std::span<const Vec2> a, std::span<const Vec2> b);

/// Share in [0, 1] of the vertices of `points` whose distance to polyline
/// `line` is less than `distance` [m]. Throws InputError if either is empty.
double share_within(std::span<const Vec2> points, std::span<const Vec2> line, double distance);

/// The point where `line` crosses the line through `target` perpendicular to
/// the unit vector `axis`: the first segment (from the first vertex on) along
/// which the projection (x − origin) · axis reaches (target − origin) · axis,
/// interpolated linearly. If no segment reaches it, the vertex nearest to
/// `target`. Throws InputError if `line` is empty or `axis` is not of unit
/// length (to 1e-9).
Vec2 axis_crossing(std::span<const Vec2> line, const Vec2& origin, const Vec2& axis,
                   const Vec2& target);

/// The nearest of the eight compass points to a planar direction (x east,
/// y north): "east", "north-east", "north", …, "south-east", each covering
/// the 45° sector centred on it. A direction exactly half way between two
/// goes to the one farther from east (std::lround of the angle in eighths of
/// a turn). Throws InputError for a zero or non-finite direction.
std::string compass_point(const Vec2& direction);

}  // namespace talus
