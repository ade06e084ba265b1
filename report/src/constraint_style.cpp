#include "talus/report/constraint_style.hpp"

#include <sstream>

namespace talus {

std::string gnuplot_colour_function(const std::string& name,
                                    std::span<const ConstraintStyle> styles) {
  std::ostringstream f;
  f << name << "(b) = ";
  for (const ConstraintStyle& s : styles) {
    f << "(b eq '" << to_string(s.constraint) << "') ? 0x" << (s.colour + 1) << " : ";
  }
  f << "0x000000\n";
  return f.str();
}

}  // namespace talus
