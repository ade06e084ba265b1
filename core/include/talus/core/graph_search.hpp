#pragma once
/// @file
/// Dijkstra / A* over an implicit graph with integer node ids: the graph
/// primitive under the global search. Edges come from a callback, so a
/// lattice never has to be stored as an adjacency list; the callbacks are
/// template parameters so that the compiler inlines them (std::function cost
/// 15 % of a 512 x 512 lattice search).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <queue>
#include <vector>

#include "talus/core/error.hpp"

namespace talus {

/// Distances and predecessors of a single-source search.
struct ShortestPathTree {
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<double> cost;  ///< cost from the source; +inf where unreached
  std::vector<std::uint32_t>
      parent;                ///< predecessor on a best path; kNone at the source / unreached
  std::size_t expanded = 0;  ///< nodes taken off the queue
  std::size_t relaxed = 0;   ///< edges looked at
  /// The stop check asked to stop: costs of unexpanded nodes are tentative
  /// (upper bounds, each the cost of the real path that path_to returns).
  bool stopped = false;
  /// Node ids from the source to `node` (empty if unreached).
  std::vector<std::uint32_t> path_to(std::uint32_t node) const {
    std::vector<std::uint32_t> path;
    if (node >= cost.size() || !(cost[node] < std::numeric_limits<double>::infinity())) return path;
    for (std::uint32_t n = node; n != kNone; n = parent[n]) path.push_back(n);
    std::reverse(path.begin(), path.end());
    return path;
  }
};

/// No heuristic: plain Dijkstra.
struct NoHeuristic {
  double operator()(std::uint32_t) const { return 0.0; }
};

/// No stop check: run to the end.
struct NeverStop {
  bool operator()() const { return false; }
};

/// Dijkstra from `source` over `nodes` nodes. `edges(node, emit)` calls
/// `emit(neighbour, cost)` for each out-edge (cost >= 0; +inf edges may be
/// skipped or emitted). With `target` != kNone the search stops when the
/// target is expanded; with an admissible `heuristic` (a lower bound of the
/// cost to the target) it is A*, and the tree is then complete only for the
/// expanded nodes. Without a target it computes the whole field.
/// `stop()` is polled before the first expansion and then after every
/// `stop_interval` (>= 1) expansions; when it returns true the search ends
/// there with `stopped` set, so at most one batch of `stop_interval`
/// expansions follows the moment the stop was due.
template <typename Edges, typename Heuristic = NoHeuristic, typename Stop = NeverStop>
ShortestPathTree shortest_paths(std::size_t nodes, std::uint32_t source, Edges&& edges,
                                std::uint32_t target = ShortestPathTree::kNone,
                                Heuristic heuristic = {}, Stop stop = {},
                                std::size_t stop_interval = 1024) {
  if (source >= nodes) throw InputError("shortest_paths: source node out of range");
  if (target != ShortestPathTree::kNone && target >= nodes) {
    throw InputError("shortest_paths: target node out of range");
  }
  if (stop_interval < 1) throw InputError("shortest_paths: stop_interval must be >= 1");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  ShortestPathTree tree;
  tree.cost.assign(nodes, kInf);
  tree.parent.assign(nodes, ShortestPathTree::kNone);
  std::vector<unsigned char> closed(nodes, 0);
  // Lazy deletion: stale queue entries are skipped when popped.
  using Entry = std::pair<double, std::uint32_t>;  // (priority, node)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  tree.cost[source] = 0.0;
  open.emplace(heuristic(source), source);
  while (!open.empty()) {
    const std::uint32_t node = open.top().second;
    open.pop();
    if (closed[node]) continue;
    if (tree.expanded % stop_interval == 0 && stop()) {
      tree.stopped = true;
      break;
    }
    closed[node] = 1;
    ++tree.expanded;
    if (node == target) break;
    const double base = tree.cost[node];
    edges(node, [&](std::uint32_t next, double cost) {
      ++tree.relaxed;
      if (!(cost < kInf) || closed[next]) return;
      const double candidate = base + cost;
      if (candidate < tree.cost[next]) {
        tree.cost[next] = candidate;
        tree.parent[next] = node;
        open.emplace(candidate + heuristic(next), next);
      }
    });
  }
  return tree;
}

}  // namespace talus
