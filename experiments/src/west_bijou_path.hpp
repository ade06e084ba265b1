#pragma once
/// @file
/// The fixed curved path across the West Bijou escarpment that the
/// velocity-limits and optimal-profile experiments share, so that their
/// figures can be read together.
#include <string>
#include <string_view>
#include <vector>

#include "talus/core/elevation_grid.hpp"

namespace talus::experiments {

/// The bundled DEM the path crosses (data/terrain/<stem>.asc).
inline constexpr const char* kWestBijouStem = "west_bijou_escarpment_nasadem25m";

/// data/terrain/README.md "Rover-scale use": x, y and z all scaled by 1/25
/// give 1 m cells with unchanged slopes and 25× larger curvatures, so the
/// escarpment's landforms become rover-sized obstacles.
inline constexpr double kRoverScale = 1.0 / 25.0;

/// A path interpolation point in grid cells from the south-west node, so the
/// same path serves the 25 m DEM and its 1 m rover-scale copy.
struct CellPoint {
  double u, v;
};

/// The path's interpolation points. West plateau (NW) → south along the
/// plateau → east down the escarpment face → north-east → east across the
/// lower plains → south over the knoll → south-east corner. The turns at P2,
/// P4 and P5 are the "real turns"; P3 sits below the escarpment's steepest
/// stretch, P6 on the knoll. All points are at least 6 cells inside the
/// 121 × 81-cell domain, and the cubic through them stays inside too
/// (SurfacePath checks that and would throw otherwise).
inline constexpr CellPoint kWestBijouPathCells[] = {{6.0, 74.0},  {18.0, 54.0}, {28.0, 32.0},
                                                    {46.0, 38.0}, {60.0, 60.0}, {84.0, 62.0},
                                                    {92.0, 46.0}, {114.0, 20.0}};

/// How the path runs, in a sentence, for the reports.
inline constexpr const char* kWestBijouPathRoute =
    "It runs south along the west plateau, turns east down the escarpment face, then north-east, "
    "east across the lower plains, and south over the knoll to the south-east corner.";

/// "`data/terrain/<stem>.asc` (West Bijou Creek escarpment, Colorado;
/// NASADEM, N × M nodes, cell 25 m; see `data/terrain/README.md`)", for the
/// reports' terrain line.
std::string west_bijou_terrain_text(const ElevationGrid& dem);

/// kWestBijouPathCells in `grid`'s coordinates [m]. Throws InputError, naming
/// the experiment, if a point is not 2 cells inside `grid`.
std::vector<Vec2> west_bijou_path_points(const ElevationGrid& grid, std::string_view experiment);

}  // namespace talus::experiments
