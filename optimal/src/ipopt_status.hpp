#pragma once
// Ipopt's return codes as the lower-case text the local stage reports
// (OptimizedPath::solver_status): "success" is Ipopt's Solve_Succeeded,
// "stop_at_acceptable_point" its Solved_To_Acceptable_Level.
#include <IpAlgTypes.hpp>

#include <string>

namespace talus::detail {

std::string ipopt_status_text(Ipopt::SolverReturn status);

}  // namespace talus::detail
