#pragma once
/// @file
/// Hazards of the potential-field navigation (potential_field_navigation.hpp)
/// detected from the fine elevation map within a sensor radius, as the
/// on-board sensing of Iagnemma, Shimoda & Shiller (IROS 2008, §III.D). The
/// paper does not define a hazard; this library's definition (documented
/// thresholds, both derived from the vehicle unless set):
/// - too steep: the surface's slope at a node exceeds max_slope, by default
///   the static limit atan(min(μ, b / h)) of the vehicle (sliding or tipping
///   while standing on it);
/// - a step: the relief of the node's 3 × 3 neighbourhood of grid nodes
///   (highest minus lowest) exceeds max_step, by default the wheel radius
///   (a body's, else the c.g. height).
/// Hazardous nodes within sensor_radius of the vehicle are grouped by
/// 8-connectivity; each group becomes the disc round its nodes' centroid
/// that covers them all, plus half a cell. hazard_node_mask() is the same
/// node test over the whole grid, for a planner that needs the hazards of the
/// whole map (the Iagnemma baseline of kinematic/).
#include <vector>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/vehicle.hpp"

namespace talus {

/// A hazard: a disc of the plane the vehicle must not enter.
struct DiscHazard {
  Vec2 centre = Vec2::Zero();  ///< [m]
  double radius = 0.0;         ///< [m] (> 0)
};

struct HazardDetectionOptions {
  double sensor_radius = 3.0;  ///< [m] (> 0): nodes farther from the vehicle are not seen
  double max_slope = 0.0;      ///< [rad] in [0, π/2); 0 = atan(min(μ, b / h))
  double max_step = 0.0;       ///< [m] (>= 0); 0 = the wheel radius (else the c.g. height)
  /// Throws InputError naming the field.
  void validate() const;
};

/// The hazards seen from `position` (see the file comment), in the order of
/// their first node (row-major from the south-west). Throws InputError for
/// invalid options or a position that is not finite.
std::vector<DiscHazard> detect_hazards(const BPatch& surface, const Vehicle& vehicle,
                                       const Vec2& position,
                                       const HazardDetectionOptions& options = {});

/// The node test of the file comment at every node of `surface`'s grid, with
/// no sensor radius: row-major (index j · ncols + i, node (i, j) at
/// (x_min + i h, y_min + j h)), 1 where the node is a hazard, 0 elsewhere
/// and on nodes off the data. A node detect_hazards() sees is a hazard there
/// exactly when it is one here. Throws InputError for invalid options.
std::vector<unsigned char> hazard_node_mask(const BPatch& surface, const Vehicle& vehicle,
                                            const HazardDetectionOptions& options = {});

}  // namespace talus
