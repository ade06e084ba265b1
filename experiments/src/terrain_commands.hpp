#pragma once
/// @file
/// The `talus terrain` subcommands' work, separate from argument parsing.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace talus::experiments {

/// `talus terrain info FILE`: size, node-domain bounds, elevation range and
/// number of NODATA nodes of an ESRI ASCII grid.
nlohmann::json terrain_info(const std::string& path);

/// `talus terrain fit FILE [--smoothing LAMBDA] [--fill nearest]`.
struct TerrainFitRequest {
  std::string path;
  std::optional<double> smoothing;  ///< lambda of the smoothing fit; none = interpolating fit
  bool fill_nearest = false;        ///< fill NODATA by the nearest valid node before fitting
};
nlohmann::json terrain_fit(const TerrainFitRequest& request);

}  // namespace talus::experiments
