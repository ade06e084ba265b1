#include "talus/core/graph_search.hpp"

#include <algorithm>

#include "talus/core/error.hpp"

namespace talus {

std::vector<std::uint32_t> ShortestPathTree::path_to(std::uint32_t node) const {
  std::vector<std::uint32_t> path;
  if (node >= cost.size() || !(cost[node] < std::numeric_limits<double>::infinity())) return path;
  for (std::uint32_t n = node; n != kNone; n = parent[n]) path.push_back(n);
  std::reverse(path.begin(), path.end());
  return path;
}

ShortestPathTree shortest_paths(std::size_t nodes, std::uint32_t source, const EdgeVisitor& edges,
                                std::uint32_t target,
                                const std::function<double(std::uint32_t)>& heuristic) {
  if (source >= nodes) throw InputError("shortest_paths: source node out of range");
  if (target != ShortestPathTree::kNone && target >= nodes) {
    throw InputError("shortest_paths: target node out of range");
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  ShortestPathTree tree;
  tree.cost.assign(nodes, kInf);
  tree.parent.assign(nodes, ShortestPathTree::kNone);
  std::vector<unsigned char> closed(nodes, 0);
  // Lazy deletion: stale queue entries are skipped when popped.
  using Entry = std::pair<double, std::uint32_t>;  // (priority, node)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  const bool informed = target != ShortestPathTree::kNone && static_cast<bool>(heuristic);
  tree.cost[source] = 0.0;
  open.emplace(informed ? heuristic(source) : 0.0, source);
  std::uint32_t current = source;
  const std::function<void(std::uint32_t, double)> relax = [&](std::uint32_t next, double cost) {
    ++tree.relaxed;
    if (!(cost < kInf) || closed[next]) return;
    const double candidate = tree.cost[current] + cost;
    if (candidate < tree.cost[next]) {
      tree.cost[next] = candidate;
      tree.parent[next] = current;
      open.emplace(candidate + (informed ? heuristic(next) : 0.0), next);
    }
  };
  while (!open.empty()) {
    const auto [priority, node] = open.top();
    open.pop();
    if (closed[node]) continue;
    closed[node] = 1;
    ++tree.expanded;
    if (node == target) break;
    current = node;
    edges(node, relax);
    (void)priority;
  }
  return tree;
}

}  // namespace talus
