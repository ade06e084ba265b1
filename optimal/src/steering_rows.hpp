#pragma once
// The vehicle's steering limit as smooth constraints of a clamped cubic path,
// shared by both local-stage formulations (path_time_objective.cpp,
// simultaneous_path_solver.cpp): the planar curvature at samples spread
// evenly over every knot span (not at the stations: a path kept within the
// limit only at the search's stations turns tighter between them), with its
// derivatives with respect to the control points.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "talus/bspline/knot_vector.hpp"
#include "talus/core/types.hpp"
#include "talus/optimal/path_time_objective.hpp"

namespace talus::detail {

class SteeringRows {
 public:
  static constexpr std::size_t kSamplesPerSpan = PathTimeObjective::kCurvatureSamplesPerSpan;
  static constexpr double kMargin = PathTimeObjective::kSteeringMargin;
  static constexpr double kMinSpeedShare = PathTimeObjective::kMinSpeedShare;

  /// One non-zero of the rows' Jacobian: row `row` depends on interior
  /// control point `point` (1 .. M − 2: the ends are fixed) along `axis`.
  struct Entry {
    std::size_t row = 0, point = 0;
    int axis = 0;
  };

  /// The rows of a cubic with `knots` on uniform breakpoints: kSamplesPerSpan
  /// × spans + 1 samples evenly over its domain, both ends included.
  explicit SteeringRows(const KnotVector& knots);

  std::size_t size() const { return basis_.size(); }
  const std::vector<Entry>& pattern() const { return pattern_; }

  /// κ_k [1/m] at every sample into `values` (size() of them; may be null)
  /// and dκ_k/dP in pattern() order into `jacobian` (may be null). False
  /// (outputs then unspecified) where a sample has c' = 0 or a non-finite
  /// control point.
  bool evaluate(const std::vector<Vec2>& control, double* values, double* jacobian) const;

  /// The first sample where the path turns tighter than `max_curvature`:
  /// beyond it at the sample; or, from the sample before, a heading change
  /// Δθ over a chord shorter than a path within the limit needs
  /// (2 sin(|Δθ|/2) / κ_max: a kink between samples); or |c'| below
  /// kMinSpeedShare of its mean (a near-stop of the parameter, whose
  /// curvature spike is too short for any sample). size() if none.
  std::size_t first_beyond(const std::vector<Vec2>& control, double max_curvature) const;

  /// The sample's parameter in [0, 1].
  double parameter(std::size_t sample) const { return sigma_[sample]; }

 private:
  std::vector<double> sigma_;
  std::vector<std::size_t> first_;                   // first control point per sample
  std::vector<Eigen::Matrix<double, 3, 4>> basis_;  // values, 1st, 2nd derivatives
  std::vector<Entry> pattern_;
  std::size_t points_ = 0;
};

}  // namespace talus::detail
