#include "west_bijou_path.hpp"

#include <string>

#include "talus/core/error.hpp"
#include "talus/report/number_format.hpp"

namespace talus::experiments {

std::string west_bijou_terrain_text(const ElevationGrid& dem) {
  return "`data/terrain/" + std::string(kWestBijouStem) +
         ".asc` (West Bijou Creek escarpment, Colorado; NASADEM, " + std::to_string(dem.ncols()) +
         " × " + std::to_string(dem.nrows()) + " nodes, cell " + fmt("%g", dem.cellsize()) +
         " m; see `data/terrain/README.md`)";
}

std::vector<Vec2> west_bijou_path_points(const ElevationGrid& grid, std::string_view experiment) {
  std::vector<Vec2> points;
  const double h = grid.cellsize();
  for (const CellPoint& c : kWestBijouPathCells) {
    if (c.u < 2.0 || c.v < 2.0 || c.u > static_cast<double>(grid.ncols() - 1) - 2.0 ||
        c.v > static_cast<double>(grid.nrows() - 1) - 2.0) {
      throw InputError(std::string(experiment) + ": path point (" + fmt("%g", c.u) + ", " +
                       fmt("%g", c.v) + ") cells is not 2 cells inside the " +
                       std::to_string(grid.ncols()) + " × " + std::to_string(grid.nrows()) +
                       "-node grid");
    }
    points.emplace_back(grid.x_min() + c.u * h, grid.y_min() + c.v * h);
  }
  return points;
}

}  // namespace talus::experiments
