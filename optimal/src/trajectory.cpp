#include "talus/optimal/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {

std::size_t station_count(double length, double spacing) {
  if (!(std::isfinite(spacing) && spacing > 0.0)) {
    std::ostringstream message;
    message << "station spacing must be a positive finite number [m], got " << spacing;
    throw InputError(message.str());
  }
  if (!(std::isfinite(length) && length >= 0.0)) {
    std::ostringstream message;
    message << "path length must be a finite number >= 0 [m], got " << length;
    throw InputError(message.str());
  }
  const double n = std::ceil(length / spacing) + 1.0;
  // 2^53: beyond it doubles skip integers, and no machine holds such a table.
  if (!(n < 9007199254740992.0)) {
    std::ostringstream message;
    message << "a " << length << " m path at " << spacing << " m spacing needs too many stations";
    throw InputError(message.str());
  }
  return std::max<std::size_t>(2, static_cast<std::size_t>(n));
}

double default_station_spacing(const BPatch& surface, const Vehicle& vehicle) {
  const double b = std::isfinite(vehicle.half_track) ? std::max(vehicle.half_track, 0.0) : 0.0;
  return std::max(surface.cellsize(), b) / kStationsPerFeature;
}

double resolve_station_spacing(double requested, const BPatch& surface, const Vehicle& vehicle) {
  return requested > 0.0 ? requested : default_station_spacing(surface, vehicle);
}

void require_station_spacing(double spacing, const char* field) {
  if (spacing == 0.0 || (std::isfinite(spacing) && spacing >= kMinStationSpacing)) return;
  std::ostringstream message;
  message << field << " must be 0 (the default) or a station spacing of at least "
          << kMinStationSpacing << " m, got " << spacing;
  throw InputError(message.str());
}

void TrajectoryOptions::validate() const {
  speeds.validate();
  require_station_spacing(station_spacing, "TrajectoryOptions.station_spacing");
}

double Trajectory::travel_time() const {
  return feasible() ? profile.travel_time : std::numeric_limits<double>::infinity();
}

double Trajectory::length() const {
  return path ? path->length() : std::numeric_limits<double>::quiet_NaN();
}

Trajectory evaluate_trajectory(const BPatch& surface, const Vehicle& vehicle, const Curve2& curve,
                               const TrajectoryOptions& options,
                               TimeOptimalProfileSolver* workspace) {
  options.validate();
  vehicle.validate();
  Trajectory trajectory;
  TimeOptimalProfileSolver local_solver;
  TimeOptimalProfileSolver& solver = workspace != nullptr ? *workspace : local_solver;
  try {
    auto path = std::make_shared<const SurfacePath>(surface, curve);
    trajectory.limits = std::make_shared<const VelocityLimits>(
        vehicle, *path,
        station_count(path->length(),
                      resolve_station_spacing(options.station_spacing, surface, vehicle)));
    trajectory.path = std::move(path);
    // A start or end speed above the limit there is a property of this path
    // (the solver reports it as an InputError): the path is infeasible.
    solver.solve(*trajectory.limits, options.speeds, trajectory.profile);
    if (!trajectory.feasible()) trajectory.message = trajectory.profile.message;
  } catch (const InputError& error) {
    trajectory.profile.status = ProfileStatus::kInfeasible;
    trajectory.message = error.what();
  }
  return trajectory;
}

}  // namespace talus
