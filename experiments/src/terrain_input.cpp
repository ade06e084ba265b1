#include "terrain_input.hpp"

namespace talus::experiments {

TerrainRaster load_terrain(const std::string& path, const std::string& reproject) {
  TerrainReadOptions options;
  options.reproject = parse_reprojection(reproject);
  return read_terrain(path, options);
}

}  // namespace talus::experiments
