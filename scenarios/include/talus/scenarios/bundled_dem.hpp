#pragma once
/// @file
/// The bundled DEMs (data/terrain/) by name, and a grid rescaled to another
/// size (data/terrain/README.md, "Rover-scale use").
#include <filesystem>
#include <string_view>

#include "talus/core/elevation_grid.hpp"

namespace talus::scenarios {

/// The bundled DEM `data_dir`/terrain/`stem`.asc.
std::filesystem::path bundled_dem_file(const std::filesystem::path& data_dir,
                                       std::string_view stem);

/// Reads bundled_dem_file(). Throws InputError, naming the experiment, if the
/// file is missing.
ElevationGrid load_bundled_dem(const std::filesystem::path& data_dir, std::string_view stem,
                               std::string_view experiment);

/// `grid` with x, y and z multiplied by `k`: slopes (dz/dx) unchanged,
/// curvatures (d²z/dx²) multiplied by 1/k. Voids stay voids.
ElevationGrid scaled_grid(const ElevationGrid& grid, double k);

}  // namespace talus::scenarios
