#include "talus/scenarios/bundled_dem.hpp"

#include <string>
#include <system_error>

#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"

namespace talus::scenarios {

std::filesystem::path bundled_dem_file(const std::filesystem::path& data_dir,
                                       std::string_view stem) {
  return data_dir / "terrain" / (std::string(stem) + ".asc");
}

ElevationGrid load_bundled_dem(const std::filesystem::path& data_dir, std::string_view stem,
                               std::string_view experiment) {
  const std::filesystem::path file = bundled_dem_file(data_dir, stem);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(std::string(experiment) + ": the bundled DEM " + file.string() +
                     " is missing");
  }
  return read_esri_ascii(file.string());
}

ElevationGrid scaled_grid(const ElevationGrid& grid, double k) {
  ElevationGrid out(grid.ncols(), grid.nrows(), grid.cellsize() * k, grid.x_min() * k,
                    grid.y_min() * k);
  for (std::size_t j = 0; j < grid.nrows(); ++j)
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      if (grid.valid(i, j)) {
        out.set(i, j, grid.at(i, j) * k);
      } else {
        out.set_void(i, j);  // the fits name it (interpolate) or leave it out (smoothing)
      }
    }
  return out;
}

}  // namespace talus::scenarios
