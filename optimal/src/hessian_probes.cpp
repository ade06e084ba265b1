#include "talus/optimal/hessian_probes.hpp"

#include <algorithm>

#include "talus/core/error.hpp"

namespace talus {

std::vector<std::vector<std::size_t>> probe_groups(
    const std::vector<std::pair<int, int>>& lower_entries, std::size_t columns,
    std::size_t variables) {
  std::vector<std::vector<std::size_t>> rows_of(columns), columns_of(variables);
  for (const auto& [r, c] : lower_entries) {
    const auto row = static_cast<std::size_t>(r), col = static_cast<std::size_t>(c);
    if (row >= variables || col >= variables) throw InputError("probe_groups: entry out of range");
    if (col < columns) rows_of[col].push_back(row);
    if (row < columns && row != col) rows_of[row].push_back(col);
  }
  for (std::size_t c = 0; c < columns; ++c) {
    for (std::size_t r : rows_of[c]) columns_of[r].push_back(c);
  }
  // Greedy: each column takes the first group none of whose members shares
  // one of its rows.
  std::vector<std::size_t> group_of(columns, 0), taken;
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t c = 0; c < columns; ++c) {
    taken.clear();
    for (std::size_t r : rows_of[c]) {
      for (std::size_t other : columns_of[r]) {
        if (other < c) taken.push_back(group_of[other]);
      }
    }
    std::size_t g = 0;
    while (std::find(taken.begin(), taken.end(), g) != taken.end()) ++g;
    group_of[c] = g;
    if (g == groups.size()) groups.emplace_back();
    groups[g].push_back(c);
  }
  return groups;
}

}  // namespace talus
