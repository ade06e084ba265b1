#pragma once
/// @file
/// Colours and legend texts of the dynamic constraints in the figures, and
/// the gnuplot function that colours a curve by the binding constraint named
/// in a CSV column. Each experiment keeps its own table; one table per
/// experiment keeps its figures' colours and its colour function in step.
#include <span>
#include <string>

#include "talus/dynamics/velocity_limits.hpp"

namespace talus {

/// How one constraint is drawn.
struct ConstraintStyle {
  Constraint constraint;
  const char* colour;  ///< #rrggbb
  const char* label;
};

/// The gnuplot function `name`(b) mapping a constraint name (as the CSVs
/// spell it, to_string()) to its colour as 0xRRGGBB, black for any other
/// name; one line, newline-terminated.
std::string gnuplot_colour_function(const std::string& name,
                                    std::span<const ConstraintStyle> styles);

}  // namespace talus
