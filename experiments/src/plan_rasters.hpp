#pragma once
/// @file
/// `talus plan --rasters`: the global search's cost-to-go fields as a
/// GeoTIFF in the DEM's CRS and the planned paths as GeoJSON (RFC 7946).
#include <string>

#include "talus/core/georeference.hpp"
#include "talus/core/raster_io.hpp"
#include "talus/optimal/planner.hpp"

namespace talus::experiments {

/// Band names of cost_to_go.tif, in order.
inline constexpr const char* kCostFromStartBand = "cost_from_start";
inline constexpr const char* kCostToGoalBand = "cost_to_goal";
inline constexpr const char* kUnreachableBand = "unreachable";

/// The lattice of `result` as raster layers in `crs`: cost_from_start and
/// cost_to_goal [s] (inf = not reachable, NaN = not computed: NODATA), and
/// unreachable (1 where cost_from_start is inf, 0 elsewhere).
RasterLayers cost_to_go_layers(const GlobalSearchResult& result, const GeoReference& crs);

/// A GeoJSON FeatureCollection per RFC 7946: coordinates in WGS 84
/// longitude, latitude (through GDAL's transformation from `crs`), each
/// feature's points in the DEM's CRS kept as its property
/// projected_coordinates and that CRS named by the member projected_crs; the
/// best trajectory (full stage: its stations, thinned to at most 5000 points,
/// with their z; properties kind "trajectory", travel_time) when there is
/// one, then each candidate's lattice path (kind "candidate", candidate,
/// cost_seconds, length_m). A DEM whose CRS is unknown keeps its own x, y as
/// coordinates, and the member coordinates_note says so. InputError when GDAL
/// cannot transform a point.
std::string plan_geojson(const PlannerResult& result, const GeoReference& crs);

}  // namespace talus::experiments
