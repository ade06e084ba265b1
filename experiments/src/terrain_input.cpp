#include "terrain_input.hpp"

#include "talus/bspline/bpatch.hpp"
#include "talus/core/output_file.hpp"

namespace talus::experiments {

TerrainRaster load_terrain(const std::string& path, const std::string& reproject, int band,
                           bool fits_surface) {
  TerrainReadOptions options;
  options.reproject = parse_reprojection(reproject);
  options.band = band;
  if (fits_surface) options.bytes_per_node_after = BPatch::kInterpolationBytesPerNode;
  TerrainRaster terrain = read_terrain(path, options);
  // Every file the read reached (a VRT's sources, world files, .prj) is out of the
  // outputs' reach for the rest of the command.
  protect_from_outputs(terrain.files);
  return terrain;
}

}  // namespace talus::experiments
