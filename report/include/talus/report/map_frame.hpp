#pragma once
/// @file
/// The frame every map figure shares: a rectangle of the terrain drawn with
/// equal aspect in offsets from its south-west corner, in metres or
/// kilometres, on a canvas whose height follows the rectangle's aspect ratio;
/// its axes, its traced contour lines and its start and goal markers.
#include <string>
#include <string_view>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/types.hpp"

namespace talus {

/// The unit of a map's axes. Data files always hold metres; kilometre axes
/// rescale them in the plot command, because 7-digit metre tick labels are
/// hard to read.
enum class MapUnit { kMetre, kKilometre };

/// Contour levels first, first + step, ..., last (gnuplot's `levels incremental`).
struct ContourLevels {
  double first = 0.0, step = 1.0, last = 0.0;
  /// The whole multiples of `step` inside [low, high].
  static ContourLevels within(double low, double high, double step);
};

/// gnuplot lines that trace the contours of column `z_column` of `data_file`
/// (x y ... rows, a blank line after each raster row) at `levels` into the
/// table `contours_file`, leaving the settings as they were for a 2-D plot.
std::string trace_contours(std::string_view data_file, int z_column, const ContourLevels& levels,
                           std::string_view contours_file);

/// A map of the rectangle [origin, origin + (width, height)] [m].
class MapFrame {
 public:
  MapFrame(const Vec2& origin, double width, double height, MapUnit unit = MapUnit::kMetre);
  /// The patch's domain.
  static MapFrame of(const BPatch& surface, MapUnit unit = MapUnit::kMetre);
  /// The grid's node rectangle.
  static MapFrame of(const ElevationGrid& grid, MapUnit unit = MapUnit::kMetre);

  const Vec2& origin() const { return origin_; }
  double width() const { return width_; }
  double height() const { return height_; }
  /// `position` − origin [m], what the data files hold.
  Vec2 offset(const Vec2& position) const { return position - origin_; }

  /// Canvas height [px] of a map `canvas_width` px wide: the plot keeps
  /// equal aspect, so a fixed height would leave space unused. `extra` [px]
  /// makes room for a taller title or key.
  int canvas_height(int canvas_width, int extra = 0) const;

  /// The `using` columns of the map position of data rows "x y ..." in
  /// metres: "1:2", or "($1/1000):($2/1000)" on kilometre axes.
  std::string xy() const;
  /// The map position of `position` [m] as gnuplot coordinates "x,y".
  std::string at(const Vec2& position) const;

  /// Equal aspect, ranges from 0 to the extent, axis labels, outward tics.
  std::string axes() const;

  /// The plot item of a contour table traced by trace_contours().
  std::string contour_item(std::string_view contours_file, std::string_view style) const;

  /// Plot items of start (circle) and goal (square): rows 0 and 1 of block
  /// `index` of `file`, x y [m] offsets.
  std::string endpoint_items(std::string_view file, std::size_t index) const;

 private:
  Vec2 origin_;
  double width_, height_;
  MapUnit unit_;
};

/// A data row "x y" of `position` − `origin`, 8 significant digits.
std::string offset_row(const Vec2& position, const Vec2& origin);

}  // namespace talus
