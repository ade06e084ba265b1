#pragma once
/// @file
/// Number formatting shared by the experiments' data files, reports and
/// gnuplot scripts: printf-style, without locale surprises (GCC 12 has no
/// std::format yet).
#include <string>

namespace talus {

/// `value` formatted by the printf conversion `format` (one double argument).
std::string fmt(const char* format, double value);

/// `value` to about three significant digits without an exponent and without
/// trailing zeros: 1792.53 -> "1793", 0.032829 -> "0.0328", 4.2 -> "4.2".
std::string sig3(double value);

/// A CSV number: "inf" / "-inf" / "nan" spelled out (printf may print
/// "-nan"), else `digits` significant digits. gnuplot and pandas both read
/// these spellings.
std::string csv_number(double value, int digits = 7);

}  // namespace talus
