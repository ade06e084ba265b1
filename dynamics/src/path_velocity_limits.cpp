#include "talus/dynamics/path_velocity_limits.hpp"

#include "talus/core/error.hpp"
#include "talus/core/memory_budget.hpp"

namespace talus {

VelocityLimits::VelocityLimits(const Vehicle& vehicle) : vehicle_(vehicle), set_(vehicle_) {}

VelocityLimits::VelocityLimits(const Vehicle& vehicle, const SurfacePath& path,
                               std::size_t stations)
    : VelocityLimits(vehicle) {
  compute(path, stations);
}

void VelocityLimits::compute(const SurfacePath& path, std::size_t stations) {
  // The frames, geometry and limits here, and about as much again for a
  // profile (speeds, accelerations, times, controllable sets) built on them.
  const double per_station =
      2.0 * static_cast<double>(sizeof(PathFrame) + sizeof(StationGeometry) + sizeof(SpeedLimits));
  require_memory(per_station * static_cast<double>(stations),
                 "speed limits at " + std::to_string(stations) + " stations",
                 "use fewer stations (--stations)");
  path.sample_uniform_parameter(stations, frames_);
  compute_on(path.surface());
}

void VelocityLimits::compute(const std::vector<PathFrame>& frames, const BPatch& surface) {
  if (frames.size() < 2) throw InputError("a path needs at least 2 stations");
  frames_ = frames;
  compute_on(surface);
}

void VelocityLimits::compute(const std::vector<PathFrame>& frames) {
  if (frames.size() < 2) throw InputError("a path needs at least 2 stations");
  frames_ = frames;
  geometry_.resize(frames_.size());
  for (std::size_t k = 0; k < frames_.size(); ++k) geometry_[k] = StationGeometry::from(frames_[k]);
  compute_limits();
}

void VelocityLimits::compute_on(const BPatch& surface) {
  geometry_.resize(frames_.size());
  for (std::size_t k = 0; k < frames_.size(); ++k)
    geometry_[k] = station_geometry(frames_[k], surface, wheels());
  compute_limits();
}

void VelocityLimits::compute_limits() {
  limits_.resize(geometry_.size());
  for (std::size_t k = 0; k < geometry_.size(); ++k) limits_[k] = set_.speed_limits(geometry_[k]);
}

std::size_t VelocityLimits::first_untraversable() const {
  for (std::size_t k = 0; k < limits_.size(); ++k) {
    if (!limits_[k].traversable) return k;
  }
  return limits_.size();
}

}  // namespace talus
