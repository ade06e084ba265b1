#pragma once
/// @file
/// Least-squares fit of a clamped cubic B-spline with a chosen number of
/// control points to a polyline, with the end points kept exactly: how a
/// global-search candidate becomes the initial path of the local optimiser.
#include <cstddef>
#include <vector>

#include "talus/bspline/bspline_curve.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// Clamped cubic B-spline with `control_points` (>= 4) control points and
/// uniform interior knots on [0, 1], whose first and last control points are
/// the polyline's ends, and whose other control points minimise the squared
/// distance to the polyline's vertices at their chord-length parameters.
/// Throws InputError for fewer than 2 vertices, coincident consecutive
/// vertices, or more control points than vertices + 2 allow.
Curve2 fit_clamped_cubic(const std::vector<Vec2>& polyline, std::size_t control_points);

/// The polyline resampled at `count` (>= 2) points equally spaced along it,
/// first and last kept exactly: lattice paths have long straight runs with
/// few vertices, too few to pin every control point of a fit.
std::vector<Vec2> resample_polyline(const std::vector<Vec2>& polyline, std::size_t count);

}  // namespace talus
