#pragma once
/// @file
/// Strict reader for planar paths given as CSV: the way points of a path in
/// metres, in the terrain's frame (x east, y north).
///
/// Format:
///
///     x,y
///     556810,4373910
///     557160.5,4374110
///
/// - Line 1 is the header and must name exactly the columns `x` and `y`, in
///   that order (spaces or tabs around a name are allowed). An optional UTF-8
///   byte-order mark before it is skipped.
/// - Every further line is one point `x,y`: two finite numbers (decimal or
///   exponent notation, optional sign) separated by one comma, spaces or tabs
///   around each allowed. Line endings may be LF or CRLF.
/// - Blank lines are allowed only at the end of the file.
/// - At least 2 points, at most kMaxPathPoints, and no two consecutive points equal.
///
/// Every deviation throws InputError naming the file and line, e.g.
/// `path.csv:4: expected 2 columns x,y, got 3`. Since blank lines can only
/// trail, point k (counted from 0) is always on line k + 2.
#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "talus/core/types.hpp"

namespace talus {

/// The most way points a path CSV may hold: a point every 10 cm over 100 km. Beyond it the
/// interpolating spline and its stations would take gigabytes (10⁷ points reached 1.6 GB
/// before running out of memory).
inline constexpr std::size_t kMaxPathPoints = 1'000'000;

/// Reads the points of a path CSV file at `path`.
std::vector<Vec2> read_path_csv(const std::string& path);
/// Reads from a stream; `source_name` is used in error messages.
std::vector<Vec2> read_path_csv(std::istream& in, const std::string& source_name);

}  // namespace talus
