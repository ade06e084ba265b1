#include "talus/kinematic/dacre_wright/channel_region.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "talus/core/error.hpp"

namespace talus {

void ChannelRegionOptions::validate() const {
  if (!(xy_margin >= 0.0 && std::isfinite(xy_margin)))
    throw InputError("ChannelRegionOptions.xy_margin must be finite and >= 0");
  if (!(heading_margin >= 0.0 && std::isfinite(heading_margin)))
    throw InputError("ChannelRegionOptions.heading_margin must be finite and >= 0");
}

std::function<bool(const SE2Pose&)> dacre_wright_channel_region(
    const DacreWrightResult& result, const ChannelRegionOptions& options) {
  options.validate();
  // A relative guard of 1e-9 keeps the configurations on a shared face inside.
  const double m = options.xy_margin + 1e-9, t = options.heading_margin + 1e-9;
  auto boxes = std::make_shared<std::vector<CsBox>>(result.channel_boxes);
  for (CsBox& b : *boxes) b = {b.x1 - m, b.x2 + m, b.y1 - m, b.y2 + m, b.theta1 - t, b.theta2 + t};
  return [boxes = std::shared_ptr<const std::vector<CsBox>>(boxes)](const SE2Pose& q) {
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    double th = std::fmod(q.theta, kTwoPi);
    if (th < 0.0) th += kTwoPi;
    for (const CsBox& b : *boxes) {
      if (q.x < b.x1 || q.x > b.x2 || q.y < b.y1 || q.y > b.y2) continue;
      // θ in [θ1, θ2] up to whole turns (a grown box may reach past 0 or 2π).
      for (double s : {th, th - kTwoPi, th + kTwoPi}) {
        if (s >= b.theta1 && s <= b.theta2) return true;
      }
    }
    return false;
  };
}

}  // namespace talus
