#pragma once
/// @file
/// Knot vectors and B-spline basis functions of any degree up to kMaxDegree.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace talus {

/// Highest B-spline degree supported; basis evaluation uses stack storage of this size.
inline constexpr int kMaxDegree = 7;

/// Non-decreasing knot sequence of a B-spline of degree p with n basis functions
/// (n + p + 1 knots). The valid parameter domain is [knots[p], knots[n]].
class KnotVector {
 public:
  /// Throws InputError unless degree is in [1, kMaxDegree], the knots are finite
  /// and non-decreasing, there are at least 2 (p + 1) knots, and the domain is non-empty.
  KnotVector(int degree, std::vector<double> knots);

  /// Clamped (open) knot vector: end breakpoints repeated p + 1 times, each
  /// interior breakpoint once. Breakpoints must be strictly increasing.
  static KnotVector clamped(int degree, const std::vector<double>& breakpoints);
  /// Uniform knots t0 + k h, k = 0 .. n + p, for n basis functions.
  static KnotVector uniform(int degree, double t0, double spacing, std::size_t num_basis);

  int degree() const { return degree_; }
  std::size_t num_basis() const { return knots_.size() - static_cast<std::size_t>(degree_) - 1; }
  const std::vector<double>& knots() const { return knots_; }
  double domain_begin() const { return knots_[static_cast<std::size_t>(degree_)]; }
  double domain_end() const { return knots_[num_basis()]; }

  /// Index k of the knot span [knots[k], knots[k+1]) holding t, with
  /// p <= k <= n - 1; t at the domain's end maps to the last non-empty span.
  /// Throws InputError if t is outside the domain or not finite.
  std::size_t find_span(double t) const;

  /// Values and derivatives of the p + 1 basis functions that are non-zero on
  /// `span` at t: out(d, j) is the d-th derivative of N_{span - p + j}, for
  /// d = 0 .. out.rows() - 1 (derivatives above p are zero). No allocation.
  void basis_derivatives(std::size_t span, double t, Eigen::Ref<Eigen::MatrixXd> out) const;

 private:
  int degree_;
  std::vector<double> knots_;
};

}  // namespace talus
