#pragma once
/// @file
/// WheelLayout and chassis_curvatures(): how the terrain under a rigid-body
/// vehicle's four wheels loads each wheel (issue "plans a vehicle can drive",
/// item 3; Mann & Shiller 2006 judge contact at the wheels). The point mass
/// judges contact at one point, the c.g.: a crest under one wheel track, off
/// the c.g.'s line, is invisible to it, and a crest shorter than the wheelbase
/// under the c.g. is taken at the crest's own curvature although the chassis,
/// standing on both sides of it, does not follow it.
///
/// Model (dynamics/DERIVATION.md, "Contact at the wheels"). The chassis is
/// rigid and its wheels stay on the surface. At a station whose c.g. heads
/// along the planar unit vector t̂ (n̂ = t̂ turned left) and turns with planar
/// curvature κ_p, wheel j sits at the planar offset (a_j along t̂, c_j to the
/// left): front-left (l, b), front-right (l, −b), rear-left (−l, b),
/// rear-right (−l, −b). Moving rigidly with the chassis, it travels in plan
/// along d_j ∝ (1 − κ_p c_j) t̂ + κ_p a_j n̂ at a squared 3-D speed ρ_j times
/// the c.g.'s; its contact point accelerates along the surface normal at
/// a_j = κ_j ρ_j ṡ², κ_j the surface's normal curvature at the wheel in
/// direction d_j. The chassis heaves with the mean ā of the a_j, pitches
/// with (ā_front − ā_rear) / (2 l) and rolls with (ā_left − ā_right) / (2 b);
/// with its pitch and roll inertias I_p, I_r, the normal load of wheel j per
/// quarter of the mass is
///     n_j = g k_r + ā + s_j ρ_p (ā_front − ā_rear) / 2 + t_j ρ_r (ā_left − ā_right) / 2,
/// s_j = ±1 front/rear, t_j = ±1 left/right, ρ_p = I_p / (m l²),
/// ρ_r = I_r / (m b²) (ρ = 1: each wheel behaves as a point mass on its own
/// track; the UGV has 0.49 and 0.41). It is linear in ṡ²: n_j = g k_r + c_j ṡ².
/// Per station this gives two curvatures [1/m]:
///   chassis  κ_c = mean_j c_j = ā / ṡ²: the total normal load per unit mass
///            R = g k_r + κ_c ṡ², which the friction cone and the tip-over
///            conditions of the rigid body use in place of the c.g. point's κ_n;
///   wheels   κ_w = min_j c_j: contact at the wheels, g k_r + κ_w ṡ² >= 0 (the
///            least-loaded wheel keeps its load).
/// With all four wheels at the c.g. both equal the c.g. point's κ_n. Not
/// modelled: the load transfer from f_t and f_q (the pitch-over and tip-over
/// conditions carry it, at the c.g.), suspension travel, the wheel radius
/// (the wheel centre rides a crest of radius R at R + r), and the slope's
/// foreshortening of the offsets in plan.
#include <array>
#include <cmath>

#include <Eigen/Core>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/types.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"

namespace talus {

/// The wheels of a rigid-body vehicle: where they are and how the terrain's
/// normal accelerations under them share into their loads. Immutable.
struct WheelLayout {
  /// (along t̂, to the left) of front-left, front-right, rear-left, rear-right [m].
  std::array<Vec2, 4> offsets{};
  /// c = loads · (κ_j ρ_j): row j gives wheel j's load curvature c_j [-].
  Eigen::Matrix4d loads = Eigen::Matrix4d::Identity();
};

/// The layout of `vehicle`'s wheels (whatever its model; the model decides
/// whether contact is judged there: VehiclePhysics::contact_at_wheels).
/// Inertias from its body, or the uniform box of default_vehicle_body() when
/// the file has none. The vehicle must be valid.
WheelLayout wheel_layout(const Vehicle& vehicle);

/// Chassis and wheel curvature of one station [1/m] (see the file comment).
template <typename Scalar>
struct ChassisCurvatures {
  Scalar chassis;  ///< κ_c: total normal load R = g k_r + κ_c ṡ²
  Scalar wheels;   ///< κ_w: the least-loaded wheel's load g k_r + κ_w ṡ²
};

/// The formulas of the file comment, once for double and for AutoDiff:
/// `heading` t̂ (unit, in plan), `kappa_planar` κ_p, the surface gradient at
/// the c.g. and the gradient and Hessian of the surface at each wheel (in the
/// order of WheelLayout::offsets).
template <typename Scalar>
ChassisCurvatures<Scalar> chassis_curvatures(
    const WheelLayout& layout, const Eigen::Matrix<Scalar, 2, 1>& heading,
    const Scalar& kappa_planar, const Eigen::Matrix<Scalar, 2, 1>& cg_gradient,
    const std::array<Eigen::Matrix<Scalar, 2, 1>, 4>& gradients,
    const std::array<Eigen::Matrix<Scalar, 2, 2>, 4>& hessians) {
  using std::sqrt;
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;
  const Vector2 left(-heading.y(), heading.x());
  const Scalar cg_slope = cg_gradient.dot(heading);
  const Scalar cg_lift = Scalar(1.0) + cg_slope * cg_slope;
  Eigen::Matrix<Scalar, 4, 1> accelerations;  // κ_j ρ_j
  for (std::size_t j = 0; j < 4; ++j) {
    const Vec2& o = layout.offsets[j];
    const Vector2 velocity = (Scalar(1.0) - kappa_planar * o.y()) * heading +
                             (kappa_planar * o.x()) * left;  // planar, per unit c.g. planar speed
    const Scalar planar_squared = velocity.squaredNorm();
    const Vector2 direction = velocity / sqrt(planar_squared);
    const Scalar slope = gradients[j].dot(direction);
    const Scalar lift = Scalar(1.0) + slope * slope;
    const Scalar normal_curvature = direction.dot(hessians[j] * direction) /
                                    (sqrt(Scalar(1.0) + gradients[j].squaredNorm()) * lift);
    accelerations[static_cast<long>(j)] = normal_curvature * (planar_squared * lift / cg_lift);
  }
  ChassisCurvatures<Scalar> out{Scalar(0.0), Scalar(0.0)};
  for (long j = 0; j < 4; ++j) {
    Scalar c = Scalar(0.0);
    for (long i = 0; i < 4; ++i) c += layout.loads(j, i) * accelerations[i];
    out.chassis += 0.25 * c;
    if (j == 0 || c < out.wheels) out.wheels = c;
  }
  return out;
}

/// The wheels' planar positions at a station with c.g. planar position
/// `position` and planar unit heading `heading`, each clamped into the
/// surface's domain (a wheel beyond the map's edge is judged at the edge).
std::array<Vec2, 4> wheel_positions(const BPatch& surface, const WheelLayout& layout,
                                    const Vec2& position, const Vec2& heading);

/// chassis_curvatures() at a station of a path on `surface`: the c.g. at
/// planar `position` with surface point `at_cg` there, planar unit `heading`,
/// planar curvature `kappa_planar`.
ChassisCurvatures<double> chassis_curvatures(const BPatch& surface, const WheelLayout& layout,
                                             const Vec2& position, const SurfacePoint& at_cg,
                                             const Vec2& heading, double kappa_planar);

/// The geometry the vehicle's limits use at a station of a path on `surface`:
/// StationGeometry::from(frame), and with `wheels` (a rigid body's layout)
/// kappa_n and kappa_wheels from chassis_curvatures(). `wheels` null: the
/// c.g. point's geometry.
StationGeometry station_geometry(const PathFrame& frame, const BPatch& surface,
                                 const WheelLayout* wheels);

}  // namespace talus
