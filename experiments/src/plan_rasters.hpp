#pragma once
/// @file
/// `talus plan --rasters`: the global search's cost-to-go fields as a
/// GeoTIFF and the planned paths as GeoJSON, both in the DEM's CRS.
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

/// A GeoJSON FeatureCollection (with a named "crs" member when the CRS has
/// an EPSG code): the best trajectory (full stage: its stations' x, y, z,
/// thinned to at most 5000 points; properties kind "trajectory",
/// travel_time) when there is one, then each candidate's lattice path (kind
/// "candidate", candidate, cost_seconds, length_m; x, y).
std::string plan_geojson(const PlannerResult& result, const GeoReference& crs);

}  // namespace talus::experiments
