#pragma once
/// @file
/// The map figure of a path over shaded relief, its line coloured by a speed
/// (velocity-limits: v_max; optimal-profile: the optimal v): the points file
/// and the gnuplot lines both experiments share. Positions are offsets [m]
/// from the surface's south-west corner; the relief image comes from
/// write_relief_image() (relief_raster.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "talus/core/types.hpp"
#include "talus/report/map_frame.hpp"

namespace talus {

/// Writes the path's interpolation points: `header` (comment lines, each
/// ending in a newline), then "x y P<i>" per point.
void write_path_points(const std::vector<Vec2>& offsets, const std::string& header,
                       const std::filesystem::path& file);

/// gnuplot settings of the map: the frame's axes, `title`, a red (slow) to
/// blue (fast) palette over [0, max_speed] labelled `speed_label`, the key
/// below the plot.
std::string path_map_settings(const MapFrame& frame, const std::string& title, double max_speed,
                              const std::string& speed_label);

/// The map's plot command: the relief image (x y r g b), the path file's
/// line (x y speed: a black casing under a line in the palette, titled
/// `path_title`), `extra_items` (complete items, each "     ITEM, \\\n"), and
/// the interpolation points file's points with their labels.
std::string path_map_plot(const std::string& relief_file, const std::string& path_file,
                          const std::string& path_title, const std::string& extra_items,
                          const std::string& points_file);

}  // namespace talus
