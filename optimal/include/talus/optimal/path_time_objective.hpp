#pragma once
/// @file
/// The local stage's objective: the motion time of the exact time-optimal
/// velocity profile along a clamped cubic B-spline path on a B-patch, as a
/// function of the path's interior control points, with its exact gradient.
///
/// Parametrisation: M control points P_0 .. P_{M-1} on uniform breakpoints in
/// σ ∈ [0, 1]; P_0 = start and P_{M-1} = goal are fixed, the variables are
/// z = (x_1, y_1, ..., x_{M-2}, y_{M-2}). The profile is solved at a fixed
/// number of stations equally spaced in σ, with arc length from the
/// Hermite-corrected trapezoid rule between them, so that the travel time is
/// a piecewise-smooth function of z (a station count that followed the path
/// length would make it jump).
///
/// Gradient: adjoint sensitivity through the profile's active constraints
/// (optimal/src/profile_sensitivity.hpp) chained with the derivatives of
/// the station geometry (curvatures, slope components, arc-length rate) with
/// respect to the curve, taken by Eigen AutoDiff through the same
/// lifted_geometry() the profile uses, including the B-patch's third
/// derivatives. When the active set is not recognised cleanly (a rare
/// degenerate profile) the gradient falls back to central finite differences,
/// and `finite_difference_fallbacks` counts it.
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus {
namespace detail {
class SteeringRows;
}

/// Travel time of a clamped cubic path as a function of its interior control
/// points. A per-query workspace: not thread-safe; use one per thread.
class PathTimeObjective {
 public:
  /// Throws InputError for fewer than 4 control points, fewer than 2
  /// stations or an invalid vehicle or speeds.
  PathTimeObjective(const BPatch& terrain, const Vehicle& vehicle, const Vec2& start,
                    const Vec2& goal, std::size_t control_points, std::size_t stations,
                    const ProfileOptions& speeds);

  /// 2 (M − 2).
  std::size_t dimension() const { return 2 * (control_points_ - 2); }
  std::size_t stations() const { return sigma_.size(); }

  /// Travel time [s]; +inf when a station leaves the map or the measured data
  /// (B-patch on_data) or no admissible profile exists. When `gradient` is
  /// given and the time is finite, it receives dT/dz.
  double evaluate(const Eigen::VectorXd& z, Eigen::VectorXd* gradient = nullptr);

  /// z of a set of M control points (start and goal dropped).
  Eigen::VectorXd variables(const std::vector<Vec2>& control_points) const;
  std::vector<Vec2> control_points(const Eigen::VectorXd& z) const;
  Curve2 curve(const Eigen::VectorXd& z) const;

  /// The vehicle's steering limit as a planar curvature [1/m] (+inf: none):
  /// evaluate() is +inf wherever a station or a steering sample turns
  /// tighter, or the path kinks or nearly stops between samples.
  double max_curvature() const { return max_curvature_; }
  /// Steering samples per knot span.
  static constexpr std::size_t kCurvatureSamplesPerSpan = 16;
  /// The share of the limit the steering rows keep in reserve, so that the
  /// path stays within it between the samples.
  static constexpr double kSteeringMargin = 1e-2;
  /// With a steering limit, the least |c'| at a steering sample as a share of
  /// its mean over the samples: a near-stop of the parameter has a curvature
  /// spike too short for any sample.
  static constexpr double kMinSpeedShare = 0.02;
  /// The steering limit as smooth constraints |κ_k| <= (1 − kSteeringMargin)
  /// max_curvature() at curvature_samples() parameters, kCurvatureSamplesPerSpan
  /// per knot span evenly (both ends included), not at the stations: a path
  /// kept within the limit only at the search's stations turns tighter
  /// between them.
  std::size_t curvature_samples() const;
  /// The (row = sample, column = variable) pairs where the planar curvature
  /// κ_k depends on z (the sample's interior control points).
  const std::vector<std::pair<long, long>>& curvature_pattern() const { return pattern_; }
  /// κ_k at every sample [1/m] into `values` (curvature_samples(); may be
  /// null) and, when `jacobian` is not null, their derivatives in
  /// curvature_pattern()'s order. False (the outputs then unspecified) where a
  /// sample has a cusp (c' = 0) or z is not finite.
  bool curvatures(const Eigen::VectorXd& z, double* values, double* jacobian) const;

  /// The profile of the last evaluate() that reached the solver.
  const TimeOptimalProfile& profile() const { return profile_; }
  /// The speed limits at the stations of the last evaluation that reached the
  /// profile (empty before one).
  const VelocityLimits& limits() const { return limits_; }
  std::size_t evaluations() const { return evaluations_; }
  std::size_t gradient_evaluations() const { return gradient_evaluations_; }
  std::size_t finite_difference_fallbacks() const { return fallbacks_; }

 private:
  double travel_time(const Eigen::VectorXd& z);
  bool adjoint_gradient(Eigen::VectorXd& gradient);
  void finite_difference_gradient(const Eigen::VectorXd& z, Eigen::VectorXd& gradient);

  BPatch terrain_;  ///< a copy shares the coefficients
  Vehicle vehicle_;
  Vec2 start_, goal_;
  std::size_t control_points_;
  ProfileOptions speeds_;
  KnotVector knots_;
  std::vector<double> sigma_;                       // station parameters
  std::vector<std::size_t> first_basis_;            // index of the first non-zero basis function
  std::vector<Eigen::Matrix<double, 3, 4>> basis_;  // values, 1st, 2nd derivatives
  double max_curvature_;
  std::shared_ptr<const detail::SteeringRows> steering_;
  std::vector<std::pair<long, long>> pattern_;  // curvature_pattern()
  // Workspace of the last evaluation.
  std::vector<Vec2> control_;
  std::vector<PathFrame> frames_;
  std::vector<Eigen::Matrix<double, 2, 3>> planar_;  // position, d1, d2 per station
  VelocityLimits limits_;
  TimeOptimalProfileSolver solver_;
  TimeOptimalProfile profile_;
  std::vector<StationGeometry> geometry_;
  std::vector<double> arc_;
  std::size_t evaluations_ = 0, gradient_evaluations_ = 0, fallbacks_ = 0;
  Eigen::VectorXd last_z_;  // the point the workspace holds
  double last_time_ = 0.0;
  bool last_valid_ = false;
};

}  // namespace talus
