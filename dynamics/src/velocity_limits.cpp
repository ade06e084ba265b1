#include "talus/dynamics/velocity_limits.hpp"

#include "talus/dynamics/admissible_set.hpp"

namespace talus {
std::string_view to_string(Constraint constraint) {
  switch (constraint) {
    case Constraint::kNone:
      return "none";
    case Constraint::kSliding:
      return "sliding";
    case Constraint::kTipover:
      return "tipover";
    case Constraint::kContact:
      return "contact";
    case Constraint::kMaxSpeed:
      return "max_speed";
    case Constraint::kPitchover:
      return "pitchover";
    case Constraint::kDrive:
      return "drive";
    case Constraint::kBrake:
      return "brake";
    case Constraint::kSteering:
      return "steering";
  }
  return "unknown";
}

// One-off queries: each builds the vehicle's AdmissibleSet (no allocation).
SpeedLimits speed_limits(const Vehicle& vehicle, const StationGeometry& g) {
  return AdmissibleSet(vehicle).speed_limits(g);
}

SquaredSpeedInterval admissible_squared_speeds(const Vehicle& vehicle, const StationGeometry& g) {
  return AdmissibleSet(vehicle).squared_speeds(g);
}

AccelerationBounds acceleration_bounds(const Vehicle& vehicle, const StationGeometry& g,
                                       double speed) {
  return AdmissibleSet(vehicle).acceleration_bounds(g, speed);
}

}  // namespace talus
