#pragma once
/// @file
/// Small statistics of measured samples, as the experiments report them: the
/// median of a set of values and the exponent of a power law fitted to
/// (x, y) pairs (how a cost grows with a problem's size).
#include <span>
#include <vector>

namespace talus {

/// The element of rank ⌊n/2⌋ of `values` in increasing order: the median for
/// odd n, the upper of the two middle values for even n; NaN for no values.
/// NaN values are not allowed (their order is undefined).
double upper_median(std::vector<double> values);

/// The exponent p of the power law y ≈ c x^p fitted by least squares in
/// log–log space: the slope of log y against log x. Throws InputError unless
/// x and y have the same size, at least 2 pairs, and every value is positive
/// and finite; NaN when all x are equal (no slope).
double power_law_exponent(std::span<const double> x, std::span<const double> y);

}  // namespace talus
