#pragma once
/// @file
/// `talus baseline NAME --vehicle V.yaml`: the baseline's path driven by a
/// vehicle at its time-optimal profile (talus::driven_path_time), the velocity
/// stage of a path–velocity decomposition, as summary keys.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/core/elevation_grid.hpp"
#include "talus/core/se2_pose.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus::experiments {

/// The --vehicle option's help.
inline constexpr const char* kBaselineVehicleHelp =
    "vehicle YAML (data/vehicles/README.md): also drive the path at its time-optimal profile on "
    "the terrain's interpolating B-patch: split at its cusps, each piece rest to rest along its "
    "own segments and arcs (tangent = the heading), a station at every configuration "
    "(profile_method own_arcs); a path that moves sideways (no driving direction, e.g. "
    "dacre-wright's) is driven along a clamped cubic fitted to its positions instead "
    "(fitted_cubic). Adds the summary keys vehicle, profile_method, profile_status (ok | "
    "infeasible | no_path), profile_travel_time [s] (null without one), profile_length_m (null "
    "for fitted_cubic), profile_pieces and profile_seconds";

/// Adds the keys of kBaselineVehicleHelp to `summary` for `vehicle` (read
/// from `vehicle_file`) along `path` on `grid` (`found`: the baseline found
/// it). InputError for a grid with NODATA (the interpolating B-patch needs
/// every node).
void add_baseline_profile(nlohmann::json& summary, const ElevationGrid& grid,
                          const std::vector<SE2Pose>& path, bool found, const Vehicle& vehicle,
                          const std::string& vehicle_file);

}  // namespace talus::experiments
