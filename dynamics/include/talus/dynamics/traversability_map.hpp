#pragma once
/// @file
/// A traversability map: at every node of a DEM, the speed limit of a
/// straight pass over it in each of several headings (the layers a
/// `talus terrain traversability` GeoTIFF holds).
///
/// The pass in heading θ (radians counter-clockwise from east) is the planar
/// line p + s (cos θ, sin θ) lifted onto the fitted surface: its station
/// geometry at the node (lift_to_surface with d1 = (cos θ, sin θ), d2 = 0:
/// normal and geodesic curvature from the surface's Hessian, the vertical
/// unit vector from its gradient) goes through the vehicle's AdmissibleSet,
/// exactly as a station of a planned path would (velocity_limits.hpp). On a
/// plane of slope α the pass has no curvature and its limit is max_speed if
/// the side slope it sees is stable, min(μ, b/h) k_r >= |k_q|, and 0
/// otherwise (binding: sliding or tip-over).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"

namespace talus {

struct TraversabilityOptions {
  /// Headings θ_k = 2π k / headings, k = 0 .. headings - 1 [rad, CCW from
  /// east]. A straight pass's limit is the same both ways on the line only
  /// for symmetric vehicles; all headings are kept. 1 to 360.
  std::size_t headings = 16;
  /// Throws InputError if headings is outside [1, 360].
  void validate() const;
};

/// Codes of the binding-constraint layer: static_cast<std::uint8_t>(Constraint)
/// (velocity_limits.hpp): 0 none, 1 sliding, 2 tipover, 3 contact, 4 max_speed,
/// 5 pitchover, 6 drive, 7 brake.
inline std::uint8_t binding_code(Constraint constraint) {
  return static_cast<std::uint8_t>(constraint);
}

enum class TraversabilityStatus {
  kOk,      ///< at least one node has data
  kNoData,  ///< every node is NODATA (every layer NaN)
};
/// "ok" or "no_data".
std::string_view to_string(TraversabilityStatus status);

/// Layers on the DEM's nodes, each ncols × nrows values row-major from the
/// south (as ElevationGrid::values()); NaN where the DEM node is NODATA.
struct TraversabilityMap {
  TraversabilityStatus status = TraversabilityStatus::kOk;
  std::string message;  ///< empty when ok
  std::size_t ncols = 0, nrows = 0;
  std::vector<double> headings;  ///< θ_k [rad]
  /// speed_limit[k][node]: v_max of the straight pass in heading k [m/s];
  /// ∞ where nothing limits it, 0 where no speed is admissible.
  std::vector<std::vector<double>> speed_limit;
  /// Minimum over headings [m/s].
  std::vector<double> speed_limit_min;
  /// What sets speed_limit_min (binding_code of the minimising heading's
  /// upper binding; the first such heading on ties).
  std::vector<double> binding;
  /// 1 where no heading admits any speed (statically untraversable), 0 otherwise.
  std::vector<double> untraversable;
  // Diagnostics.
  std::size_t nodata_nodes = 0;         ///< DEM nodes without data
  std::size_t untraversable_nodes = 0;  ///< nodes with untraversable = 1
  std::size_t blocked_nodes = 0;        ///< nodes some heading cannot pass (speed_limit_min = 0)
  double seconds = 0.0;                 ///< wall time of the computation [s]
  /// One line: status, size, headings, counts, time.
  std::string brief_report() const;
};

/// The traversability map of `vehicle` on `surface` at the nodes of `grid`
/// (the grid the surface was fitted to, or one inside its domain): nodes
/// where `grid` is NODATA get NaN. Throws InputError for invalid options or
/// vehicle, or a grid node outside the surface's domain.
TraversabilityMap traversability_map(const BPatch& surface, const ElevationGrid& grid,
                                     const Vehicle& vehicle,
                                     const TraversabilityOptions& options = {});

}  // namespace talus
