#pragma once
/// @file
/// Dijkstra / A* over an implicit graph with integer node ids: the graph
/// primitive under the global search. Edges come from a callback, so a
/// lattice never has to be stored as an adjacency list.
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <vector>

namespace talus {

/// Distances and predecessors of a single-source search.
struct ShortestPathTree {
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<double> cost;             ///< cost from the source; +inf where unreached
  std::vector<std::uint32_t> parent;    ///< predecessor on a best path; kNone at the source / unreached
  std::size_t expanded = 0;             ///< nodes taken off the queue
  std::size_t relaxed = 0;              ///< edges looked at
  /// Node ids from the source to `node` (empty if unreached).
  std::vector<std::uint32_t> path_to(std::uint32_t node) const;
};

/// Visits the out-edges of a node: call `emit(neighbour, cost)` for each (cost >= 0, +inf = none).
using EdgeVisitor =
    std::function<void(std::uint32_t node, const std::function<void(std::uint32_t, double)>& emit)>;

/// Dijkstra from `source` over `nodes` nodes. With `target` != kNone and an
/// admissible `heuristic` (a lower bound of the cost to the target), this is
/// A* and stops when the target is expanded; the tree is then complete only
/// for the expanded nodes. Without a target it computes the whole field.
ShortestPathTree shortest_paths(std::size_t nodes, std::uint32_t source, const EdgeVisitor& edges,
                                std::uint32_t target = ShortestPathTree::kNone,
                                const std::function<double(std::uint32_t)>& heuristic = {});

}  // namespace talus
