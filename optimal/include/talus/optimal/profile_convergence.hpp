#pragma once
/// @file
/// profile_convergence: a numerical study of the time-optimal profile's
/// discretisation. It solves the profile of one vehicle along one path at a
/// sequence of station counts and reports, per level, the travel time, its
/// relative error against the finest level (the reference), the observed
/// order of convergence between consecutive levels, and a Richardson
/// extrapolate of the travel time from the two finest levels.
///
/// The discretisation (time_optimal_profile.hpp) holds each step's constant
/// s̈ admissible at both of its ends, so it is conservative: where a bound
/// varies along the path a coarse profile is slower, and the error is first
/// order in the station spacing h. Where the bounds are constant between
/// switches (flat, straight ground) only the steps that straddle a switch
/// lose time, and the error is second order.
///
/// With levels whose spacing shrinks by a constant ratio r, the observed
/// order between levels i and i + 1 is
///     p_i = log(|e_i| / |e_{i+1}|) / log(h_i / h_{i+1}),
/// where e is the error against the reference and h the mean station spacing.
/// It is not computed between the reference and the level before it (the
/// reference's error is 0 by definition), and the reference's own error
/// biases the orders of the finest levels. The Richardson extrapolate for an
/// assumed order p is
///     T* = T_ref + (T_ref − T_c) / ((h_c / h_ref)^p − 1),
/// with c the sequence level just coarser than the reference.
#include <cstddef>
#include <limits>
#include <vector>

#include "talus/bspline/surface_path.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/optimal/profile_analysis.hpp"
#include "talus/optimal/time_optimal_profile.hpp"

namespace talus {

/// What profile_convergence solves and how it times the solves.
struct ProfileConvergenceOptions {
  /// The sequence of levels: station counts (each >= 2), strictly
  /// increasing, at least 2 of them. Observed orders are taken between
  /// consecutive entries; the last is the reference. Doubling counts
  /// (25, 50, 100, ...) give a spacing ratio of about 2.
  std::vector<std::size_t> station_counts = {25, 50, 100, 200, 400, 800, 1600, 3200};
  /// Further station counts (each >= 2 and below the reference) evaluated
  /// against the reference but left out of the orders and the Richardson
  /// extrapolate, e.g. the count a default spacing gives. A count that is
  /// also in station_counts is that level.
  std::vector<std::size_t> extra_station_counts;
  ProfileOptions speeds;  ///< start and end speeds [m/s]
  /// The order p assumed by the Richardson extrapolate (> 0, finite).
  double richardson_order = 1.0;
  /// Each level's VelocityLimits::compute and solve are repeated at least
  /// timing_repeats times (>= 1) and until timing_budget_seconds (>= 0,
  /// finite) have been spent on them; the fastest call is reported. A
  /// single sub-millisecond call is dominated by timer and cache noise. The
  /// results do not depend on these (every repeat computes the same).
  int timing_repeats = 1;
  double timing_budget_seconds = 0.0;
  /// Throws InputError naming the field.
  void validate() const;
};

/// One station count of the study.
struct ConvergenceLevel {
  std::size_t stations = 0;
  bool in_sequence = false;     ///< from station_counts (else only from extra_station_counts)
  double mean_spacing = 0.0;    ///< path length / (stations − 1) [m]
  double max_spacing = 0.0;     ///< largest distance between consecutive stations [m]
  double limits_seconds = 0.0;  ///< VelocityLimits::compute (path sampling and limits) [s]
  double solve_seconds = 0.0;   ///< TimeOptimalProfileSolver::solve [s]
  bool feasible = false;        ///< the solver found a profile
  double travel_time = std::numeric_limits<double>::quiet_NaN();  ///< [s]; NaN when infeasible
  /// travel_time / reference travel time − 1; NaN if either is infeasible.
  /// Positive: the level is slower than the reference.
  double error = std::numeric_limits<double>::quiet_NaN();
  /// Observed order against the next sequence level; NaN for the last two
  /// sequence levels, extra levels and where an error is 0 or NaN.
  double order = std::numeric_limits<double>::quiet_NaN();
  InfeasibilityDiagnosis failure;  ///< when infeasible (describe_infeasibility)
};

enum class ConvergenceStatus {
  kOk,                   ///< the reference level is feasible: errors are defined
  kReferenceInfeasible,  ///< no profile at the finest level: errors, orders, extrapolate NaN
};

/// Result of profile_convergence.
struct ProfileConvergence {
  ConvergenceStatus status = ConvergenceStatus::kReferenceInfeasible;
  /// All levels by increasing station count; the last is the reference.
  std::vector<ConvergenceLevel> levels;
  /// The Richardson extrapolate T* [s] (see the file comment); NaN if either
  /// of the two finest sequence levels is infeasible.
  double extrapolated_time = std::numeric_limits<double>::quiet_NaN();

  const ConvergenceLevel& reference() const { return levels.back(); }
  /// Index of the coarsest sequence level from which on every finer level
  /// (the reference excluded) has |error| <= target; levels.size() if none.
  std::size_t coarsest_within(double target) const;
  /// Index of the level with `stations` stations; levels.size() if none.
  std::size_t find(std::size_t stations) const;
};

/// Runs the study for `vehicle` along `path`. Throws InputError for invalid
/// options or vehicle; infeasible levels are results, not errors.
/// O(Σ stations × repeats).
ProfileConvergence profile_convergence(const Vehicle& vehicle, const SurfacePath& path,
                                       const ProfileConvergenceOptions& options = {});

}  // namespace talus
