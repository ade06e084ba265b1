#pragma once
/// @file
/// Hessian probes by column groups: which columns of a sparse symmetric
/// matrix one finite-difference probe may move together. The simultaneous
/// NLP (src/simultaneous_path_solver.cpp) probes its Lagrangian's Hessian
/// this way: about nine groups however many control points.
#include <cstddef>
#include <utility>
#include <vector>

namespace talus {

/// Groups of the first `columns` of a symmetric matrix's `variables` columns
/// (its sparsity given by `lower_entries`, (row, column) pairs with row >=
/// column) such that no row has an entry in two columns of one group: a
/// finite-difference probe moving a whole group then recovers each of its
/// columns as a probe of its own would (Curtis, Powell & Reid 1974; greedy
/// distance-2 colouring). Throws InputError for an entry out of range.
std::vector<std::vector<std::size_t>> probe_groups(
    const std::vector<std::pair<int, int>>& lower_entries, std::size_t columns,
    std::size_t variables);

}  // namespace talus
