#include "talus/kinematic/eldershaw_yim/cg_local_planner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <queue>
#include <tuple>

#include "talus/core/error.hpp"
#include "talus/core/memory_budget.hpp"

namespace talus {

void CgLocalPlannerOptions::validate() const {
  if (margin < 0) throw InputError("local planner margin must be >= 0 cells");
  if (!(std::isfinite(margin_fraction) && margin_fraction >= 0))
    throw InputError("local planner margin_fraction must be a finite number >= 0");
  if (!(std::isfinite(heading_weight) && heading_weight > 0))
    throw InputError("local planner heading_weight must be > 0 m/rad");
}

CgLocalPath cg_local_plan(CgSpace& space, const CgCell& from, const CgCell& to,
                          const CgLocalPlannerOptions& o, std::size_t& work, std::size_t budget) {
  CgLocalPath out;
  const CgLattice& L = space.lattice();
  int x0, x1, y0, y1;
  if (o.whole_lattice) {
    x0 = 0, y0 = 0, x1 = L.nx() - 1, y1 = L.ny() - 1;
  } else {
    const int side = std::max(std::abs(from.ix - to.ix), std::abs(from.iy - to.iy));
    const int m = std::max(o.margin, static_cast<int>(std::ceil(o.margin_fraction * side)));
    x0 = std::max(0, std::min(from.ix, to.ix) - m);
    x1 = std::min(L.nx() - 1, std::max(from.ix, to.ix) + m);
    y0 = std::max(0, std::min(from.iy, to.iy) - m);
    y1 = std::min(L.ny() - 1, std::max(from.iy, to.iy) + m);
  }
  const int wx = x1 - x0 + 1, wy = y1 - y0 + 1, nt = L.ntheta();
  const std::size_t n =
      static_cast<std::size_t>(wx) * static_cast<std::size_t>(wy) * static_cast<std::size_t>(nt);
  // g, parent, closed per cell of the block, and about one queue entry per cell.
  require_memory(
      static_cast<double>(n) * (sizeof(double) + sizeof(std::uint32_t) + 1 + 24),
      "the CG local planner's block of " + std::to_string(n) + " cells",
      "use a larger foot_print, fewer theta slices, or the tree-PRM instead of --direct");
  auto local = [&](const CgCell& c) {
    return (static_cast<std::size_t>(c.it) * static_cast<std::size_t>(wy) +
            static_cast<std::size_t>(c.iy - y0)) *
               static_cast<std::size_t>(wx) +
           static_cast<std::size_t>(c.ix - x0);
  };
  auto cell_at = [&](std::size_t k) {
    CgCell c;
    c.ix = x0 + static_cast<int>(k % static_cast<std::size_t>(wx));
    k /= static_cast<std::size_t>(wx);
    c.iy = y0 + static_cast<int>(k % static_cast<std::size_t>(wy));
    c.it = static_cast<int>(k / static_cast<std::size_t>(wy));
    return c;
  };
  const double f = L.spacing();
  const double step_theta = o.heading_weight * 2.0 * std::numbers::pi / nt;
  auto heuristic = [&](const CgCell& c) {
    const int dt = std::abs(c.it - to.it);
    return f * (std::abs(c.ix - to.ix) + std::abs(c.iy - to.iy)) +
           step_theta * std::min(dt, nt - dt);
  };
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<double> g(n, std::numeric_limits<double>::infinity());
  std::vector<std::uint32_t> parent(n, kNone);
  std::vector<std::uint8_t> closed(n, 0);
  using Entry = std::tuple<double, double, std::size_t>;  // f, h, local index
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  const std::size_t s = local(from), t = local(to);
  g[s] = 0.0;
  open.emplace(heuristic(from), heuristic(from), s);
  while (!open.empty()) {
    const auto [fk, hk, k] = open.top();
    open.pop();
    if (closed[k]) continue;
    closed[k] = 1;
    if (space.cells_materialised() + work >= budget) {
      out.budget_exceeded = true;
      return out;
    }
    ++work;
    ++out.expansions;
    if (k == t) break;
    const CgCell c = cell_at(k);
    CgCell next[6] = {c, c, c, c, c, c};
    int count = 4;
    next[0].ix -= 1;
    next[1].ix += 1;
    next[2].iy -= 1;
    next[3].iy += 1;
    if (nt > 1) {
      next[4].it = (c.it + 1) % nt;
      next[5].it = (c.it + nt - 1) % nt;
      count = nt > 2 ? 6 : 5;
    }
    for (int d = 0; d < count; ++d) {
      const CgCell& q = next[d];
      if (q.ix < x0 || q.ix > x1 || q.iy < y0 || q.iy > y1) continue;
      const std::size_t kq = local(q);
      if (closed[kq]) continue;
      const double cost = g[k] + (d < 4 ? f : step_theta);
      if (!(cost < g[kq])) continue;
      if (!space.valid(q)) continue;
      g[kq] = cost;
      parent[kq] = static_cast<std::uint32_t>(k);
      const double hq = heuristic(q);
      open.emplace(cost + hq, hq, kq);
    }
  }
  if (!closed[t] || !(g[t] < std::numeric_limits<double>::infinity())) return out;
  out.found = true;
  out.cost = g[t];
  for (std::size_t k = t; k != kNone; k = parent[k] == kNone ? kNone : parent[k]) {
    out.cells.push_back(cell_at(k));
    if (k == s) break;
  }
  std::reverse(out.cells.begin(), out.cells.end());
  return out;
}

}  // namespace talus
