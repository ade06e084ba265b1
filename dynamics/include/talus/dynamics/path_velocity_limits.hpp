#pragma once
/// @file
/// VelocityLimits: a vehicle's speed limits at every station of a path on the
/// terrain, and O(1) tangential-acceleration bounds at (station, speed).
#include <cstddef>
#include <vector>

#include "talus/bspline/surface_path.hpp"
#include "talus/dynamics/admissible_set.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"
#include "talus/dynamics/wheel_contact.hpp"

namespace talus {

/// Per-station geometry and limits of one vehicle along one path. Reusable:
/// compute() overwrites the previous path's stations without reallocating
/// when the station count does not grow.
class VelocityLimits {
 public:
  explicit VelocityLimits(const Vehicle& vehicle);
  /// Validates the vehicle and computes the limits at `stations` (>= 2)
  /// stations, equally spaced in the curve parameter (SurfacePath::sample_uniform_parameter).
  VelocityLimits(const Vehicle& vehicle, const SurfacePath& path, std::size_t stations);

  void compute(const SurfacePath& path, std::size_t stations);
  /// The limits at stations the caller has sampled on `surface` (at least 2; s
  /// increasing); the surface is where a rigid body's wheels stand.
  void compute(const std::vector<PathFrame>& frames, const BPatch& surface);
  /// The limits at frames given without a surface (geometry from a user):
  /// every wheel taken at the c.g. (StationGeometry::from).
  void compute(const std::vector<PathFrame>& frames);

  const Vehicle& vehicle() const { return vehicle_; }
  /// The vehicle's admissible (ṡ², s̈) set, built once: what the optimiser asks.
  const AdmissibleSet& admissible_set() const { return set_; }
  /// The rigid body's wheels (wheel_contact.hpp); null for the point mass.
  const WheelLayout* wheels() const { return set_.wheels(); }
  std::size_t size() const { return frames_.size(); }
  const PathFrame& frame(std::size_t station) const { return frames_[station]; }
  const StationGeometry& geometry(std::size_t station) const { return geometry_[station]; }
  const SpeedLimits& limits(std::size_t station) const { return limits_[station]; }
  const std::vector<PathFrame>& frames() const { return frames_; }
  const std::vector<SpeedLimits>& all_limits() const { return limits_; }

  /// [a_min, a_max] at `station` moving at `speed` [m/s]. O(1), no allocation.
  AccelerationBounds acceleration_bounds(std::size_t station, double speed) const {
    return set_.acceleration_bounds(geometry_[station], speed);
  }

  /// Index of the first station that no speed can pass, or size() if none.
  std::size_t first_untraversable() const;

 private:
  void compute_on(const BPatch& surface);  ///< geometry_ at frames_ on it, then the limits
  void compute_limits();                   ///< limits_ from geometry_

  Vehicle vehicle_;
  AdmissibleSet set_;
  std::vector<PathFrame> frames_;
  std::vector<StationGeometry> geometry_;
  std::vector<SpeedLimits> limits_;
};

}  // namespace talus
