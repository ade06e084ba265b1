#include "talus/dynamics/wheel_contact.hpp"

#include <algorithm>

namespace talus {

WheelLayout wheel_layout(const Vehicle& vehicle) {
  const double l = vehicle.half_wheelbase, b = vehicle.half_track;
  const VehicleBody body =
      vehicle.body ? *vehicle.body : default_vehicle_body(1.0, l, b, vehicle.cg_height);
  const double pitch = body.inertia_pitch / (body.mass * l * l);  // ρ_p
  const double roll = body.inertia_roll / (body.mass * b * b);    // ρ_r
  WheelLayout out;
  out.offsets = {Vec2(l, b), Vec2(l, -b), Vec2(-l, b), Vec2(-l, -b)};
  // n_j / ṡ² = ā + s_j ρ_p (ā_front − ā_rear) / 2 + t_j ρ_r (ā_left − ā_right) / 2, with
  // ā = Σ a_i / 4, ā_front = (a_0 + a_1) / 2, ā_left = (a_0 + a_2) / 2, etc.
  for (int j = 0; j < 4; ++j) {
    const double front_j = out.offsets[static_cast<std::size_t>(j)].x() > 0.0 ? 1.0 : -1.0;
    const double left_j = out.offsets[static_cast<std::size_t>(j)].y() > 0.0 ? 1.0 : -1.0;
    for (int i = 0; i < 4; ++i) {
      const double front_i = out.offsets[static_cast<std::size_t>(i)].x() > 0.0 ? 1.0 : -1.0;
      const double left_i = out.offsets[static_cast<std::size_t>(i)].y() > 0.0 ? 1.0 : -1.0;
      out.loads(j, i) = 0.25 + 0.25 * pitch * front_j * front_i + 0.25 * roll * left_j * left_i;
    }
  }
  return out;
}

std::array<Vec2, 4> wheel_positions(const BPatch& surface, const WheelLayout& layout,
                                    const Vec2& position, const Vec2& heading) {
  const Vec2 left(-heading.y(), heading.x());
  std::array<Vec2, 4> out;
  for (std::size_t j = 0; j < 4; ++j) {
    const Vec2 p = position + layout.offsets[j].x() * heading + layout.offsets[j].y() * left;
    out[j] = Vec2(std::clamp(p.x(), surface.x_min(), surface.x_max()),
                  std::clamp(p.y(), surface.y_min(), surface.y_max()));
  }
  return out;
}

ChassisCurvatures<double> chassis_curvatures(const BPatch& surface, const WheelLayout& layout,
                                             const Vec2& position, const SurfacePoint& at_cg,
                                             const Vec2& heading, double kappa_planar) {
  const std::array<Vec2, 4> wheels = wheel_positions(surface, layout, position, heading);
  std::array<Vec2, 4> gradients;
  std::array<Mat2, 4> hessians;
  for (std::size_t j = 0; j < 4; ++j) {
    const SurfacePoint sp = surface.evaluate(wheels[j]);
    gradients[j] = sp.gradient;
    hessians[j] = sp.hessian;
  }
  return chassis_curvatures<double>(layout, heading, kappa_planar, at_cg.gradient, gradients,
                                    hessians);
}

StationGeometry station_geometry(const PathFrame& frame, const BPatch& surface,
                                 const WheelLayout* wheels) {
  StationGeometry g = StationGeometry::from(frame);
  if (wheels == nullptr) return g;
  const Vec2 position = frame.point.head<2>();
  const Vec2 heading = frame.tangent.head<2>().normalized();
  // The c.g.'s surface gradient from the frame's unit normal (−z_x, −z_y, 1) / norm.
  SurfacePoint at_cg;
  at_cg.gradient = -frame.normal.head<2>() / frame.normal.z();
  const ChassisCurvatures<double> c =
      chassis_curvatures(surface, *wheels, position, at_cg, heading, frame.kappa_planar);
  g.kappa_n = c.chassis;
  g.kappa_wheels = c.wheels;
  return g;
}

}  // namespace talus
