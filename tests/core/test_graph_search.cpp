// shortest_paths (core/graph_search.hpp) against an independent Bellman–Ford
// written here, on seeded random graphs: the oracle other suites rely on has
// to be right itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/graph_search.hpp"

namespace talus {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNone = ShortestPathTree::kNone;

struct Edge {
  std::uint32_t to;
  double cost;
};
using Graph = std::vector<std::vector<Edge>>;

/// Uniform in [0, 1) from raw mt19937_64 bits (platform-independent).
double unit(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// `n` nodes; node k < reachable_count gets random out-edges among the first
/// reachable_count nodes, the rest are isolated except for edges *into* the
/// reachable block (so they are unreachable from any source below
/// reachable_count). Weights are multiples of 1/8 in [0, 4] (exact in binary,
/// so many equal-cost paths — ties — exist and sums are exact), about 10 %
/// of them zero, plus some +inf edges that must be ignored.
Graph random_graph(std::mt19937_64& rng, std::size_t n, std::size_t reachable_count,
                   int out_degree) {
  Graph g(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t targets = reachable_count;
    for (int e = 0; e < out_degree; ++e) {
      const auto to = static_cast<std::uint32_t>(rng() % targets);
      double w = std::floor(unit(rng) * 33.0) / 8.0;
      if (unit(rng) < 0.1) w = 0.0;
      if (unit(rng) < 0.03) w = kInf;
      g[k].push_back({to, w});
    }
  }
  return g;
}

/// Plain Bellman–Ford: |V| - 1 rounds of relaxing every edge.
std::vector<double> bellman_ford(const Graph& g, std::uint32_t source) {
  std::vector<double> d(g.size(), kInf);
  d[source] = 0.0;
  for (std::size_t round = 0; round + 1 < g.size(); ++round) {
    bool changed = false;
    for (std::size_t u = 0; u < g.size(); ++u) {
      if (d[u] == kInf) continue;
      for (const Edge& e : g[u])
        if (d[u] + e.cost < d[e.to]) {
          d[e.to] = d[u] + e.cost;
          changed = true;
        }
    }
    if (!changed) break;
  }
  return d;
}

/// Cheapest edge u -> v (parallel edges exist), +inf if none.
double edge_weight(const Graph& g, std::uint32_t u, std::uint32_t v) {
  double w = kInf;
  for (const Edge& e : g[u])
    if (e.to == v) w = std::min(w, e.cost);
  return w;
}

auto edges_of(const Graph& g) {
  return [&g](std::uint32_t node, auto&& emit) {
    for (const Edge& e : g[node]) emit(e.to, e.cost);
  };
}

TEST(GraphSearch, DijkstraMatchesBellmanFordOnRandomGraphs) {
  std::mt19937_64 rng(20);
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t n = 200 + rng() % 200;
    const std::size_t reachable = n - 20 - rng() % 30;  // 20-49 nodes nothing reaches
    const Graph g = random_graph(rng, n, reachable, 3 + static_cast<int>(rng() % 4));
    const auto source = static_cast<std::uint32_t>(rng() % reachable);
    const ShortestPathTree tree = shortest_paths(n, source, edges_of(g));
    const std::vector<double> expected = bellman_ford(g, source);
    ASSERT_EQ(tree.cost.size(), n);
    ASSERT_EQ(tree.parent.size(), n);
    std::size_t reached = 0;
    for (std::uint32_t v = 0; v < n; ++v) {
      // Weights are multiples of 1/8 and paths short: every sum is exact, so
      // the two algorithms must agree bit for bit.
      ASSERT_EQ(tree.cost[v], expected[v]) << "trial " << trial << " node " << v;
      const std::vector<std::uint32_t> path = tree.path_to(v);
      if (expected[v] == kInf) {
        EXPECT_TRUE(path.empty());
        EXPECT_EQ(tree.parent[v], kNone);
        continue;
      }
      ++reached;
      ASSERT_FALSE(path.empty());
      EXPECT_EQ(path.front(), source);
      EXPECT_EQ(path.back(), v);
      // The path's cost is the sum of its own edges (each of which exists).
      double sum = 0.0;
      for (std::size_t k = 0; k + 1 < path.size(); ++k) {
        const double w = edge_weight(g, path[k], path[k + 1]);
        ASSERT_LT(w, kInf) << "path uses a missing edge";
        sum += w;
      }
      EXPECT_EQ(sum, tree.cost[v]);
    }
    EXPECT_EQ(tree.parent[source], kNone);
    EXPECT_EQ(tree.cost[source], 0.0);
    EXPECT_EQ(tree.expanded, reached);  // every reached node closed exactly once
    EXPECT_LT(reached, n);              // the isolated nodes stay unreached
    for (std::size_t v = reachable; v < n; ++v) EXPECT_EQ(tree.cost[v], kInf);
  }
}

TEST(GraphSearch, ZeroWeightEdgesAndTiesGiveConsistentTrees) {
  // 0 -> 1 -> 2 -> 3 all free; 0 -> 3 costs 0 as well (a tie at zero cost);
  // 3 -> 4 via two equal routes of cost 2 (3->4 direct, 3->5->4).
  const Graph g = {{{1, 0.0}, {3, 0.0}}, {{2, 0.0}}, {{3, 0.0}}, {{4, 2.0}, {5, 1.0}}, {},
                   {{4, 1.0}},           {{0, 1.0}}};  // 6 unreachable from 0
  const ShortestPathTree t = shortest_paths(g.size(), 0, edges_of(g));
  EXPECT_EQ(t.cost[1], 0.0);
  EXPECT_EQ(t.cost[2], 0.0);
  EXPECT_EQ(t.cost[3], 0.0);
  EXPECT_EQ(t.cost[5], 1.0);
  EXPECT_EQ(t.cost[4], 2.0);
  EXPECT_EQ(t.cost[6], kInf);
  EXPECT_TRUE(t.path_to(6).empty());
  // Whichever tie it keeps, the parent chain is a real path of the same cost.
  for (std::uint32_t v : {3u, 4u}) {
    const auto path = t.path_to(v);
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < path.size(); ++k) sum += edge_weight(g, path[k], path[k + 1]);
    EXPECT_EQ(sum, t.cost[v]) << v;
    EXPECT_EQ(path.front(), 0u);
  }
}

TEST(GraphSearch, AStarWithAnAdmissibleHeuristicFindsTheDijkstraCost) {
  // A 30 x 30 grid with random weights >= 1 per unit step, 8-connected with
  // diagonal weights >= sqrt 2: the Euclidean distance to the target is
  // admissible (a lower bound of the remaining cost).
  std::mt19937_64 rng(21);
  const int w = 30;
  const std::size_t n = static_cast<std::size_t>(w * w);
  Graph g(n);
  for (int j = 0; j < w; ++j)
    for (int i = 0; i < w; ++i)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if ((di == 0 && dj == 0) || i + di < 0 || j + dj < 0 || i + di >= w || j + dj >= w)
            continue;
          const double step = std::hypot(di, dj);
          g[static_cast<std::size_t>(j * w + i)].push_back(
              {static_cast<std::uint32_t>((j + dj) * w + i + di), step * (1.0 + 2.0 * unit(rng))});
        }
  for (int trial = 0; trial < 10; ++trial) {
    const auto s = static_cast<std::uint32_t>(rng() % n), t = static_cast<std::uint32_t>(rng() % n);
    const double tx = t % w, ty = t / w;
    const auto h = [&](std::uint32_t v) {
      return std::hypot(static_cast<double>(v % w) - tx, static_cast<double>(v / w) - ty);
    };
    const ShortestPathTree astar = shortest_paths(n, s, edges_of(g), t, h);
    const std::vector<double> expected = bellman_ford(g, s);
    // Different summation orders: equal to rounding (a few ulps of ~50).
    EXPECT_NEAR(astar.cost[t], expected[t], 1e-12 * expected[t]) << trial;
    const auto path = astar.path_to(t);
    ASSERT_FALSE(path.empty());
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < path.size(); ++k) sum += edge_weight(g, path[k], path[k + 1]);
    EXPECT_NEAR(sum, astar.cost[t], 1e-12 * expected[t]);
    // Plain Dijkstra stopped at the target also agrees, and A* expands no more.
    const ShortestPathTree dijkstra = shortest_paths(n, s, edges_of(g), t);
    EXPECT_NEAR(dijkstra.cost[t], expected[t], 1e-12 * expected[t]);
    EXPECT_LE(astar.expanded, dijkstra.expanded);
  }
}

TEST(GraphSearch, BadNodeIndicesAreInputErrors) {
  const Graph g = {{{1, 1.0}}, {}};
  EXPECT_THROW(shortest_paths(g.size(), 2, edges_of(g)), InputError);
  EXPECT_THROW(shortest_paths(g.size(), 0, edges_of(g), 5), InputError);
  EXPECT_NO_THROW(shortest_paths(g.size(), 0, edges_of(g), 1));
  const ShortestPathTree t = shortest_paths(g.size(), 0, edges_of(g));
  EXPECT_TRUE(t.path_to(7).empty());  // out of range: no path, no crash
}

}  // namespace
}  // namespace talus
