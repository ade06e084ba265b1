#pragma once
/// @file
/// The Dacre-Wright–Siméon voxel channel as a guide for a finer planner (the
/// paper's stated purpose, §1 and §5): the predicate "q lies in a voxel of the
/// channel", for HaitOptions::allowed_region, which restricts the Haït search
/// to the channel.
///
/// The margins exist because the channel's finest voxels can be narrower than
/// the Haït search's own discretisation (a 0.25 m, 5.6° voxel at p_max = 6 on
/// a 16 m map against 0.25 m cells, 11.25° heading cells and 0.4 m arcs of
/// 1 m radius): the dacre-wright-octree experiment finds no Haït path inside
/// the exact channel, and one when it is grown by one search cell in x, y and
/// θ. A grown region is no longer inside the admissible set; the Haït validity
/// still checks every configuration.
#include <functional>

#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/dacre_wright/dacre_wright_planner.hpp"

namespace talus {

/// How the channel becomes a region.
struct ChannelRegionOptions {
  double xy_margin = 0.0;       ///< [m] each box grown by this in x and y (>= 0)
  double heading_margin = 0.0;  ///< [rad] and by this in θ (>= 0)
  /// Throws InputError naming the field.
  void validate() const;
};

/// True iff q lies in one of `result.channel_boxes` grown by the margins
/// (closed boxes, θ taken modulo 2π). With zero margins every configuration of
/// the region is admissible (Proposition 1). The predicate holds its own copy
/// of the boxes; it is false everywhere when the result holds no channel.
/// Throws InputError for invalid options.
std::function<bool(const SE2Pose&)> dacre_wright_channel_region(
    const DacreWrightResult& result, const ChannelRegionOptions& options = {});

}  // namespace talus
