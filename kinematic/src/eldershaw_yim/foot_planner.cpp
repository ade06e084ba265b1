#include "talus/kinematic/eldershaw_yim/foot_planner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_set>

#include "talus/core/error.hpp"

namespace talus {
namespace {

struct Candidate {
  std::size_t i = 0, j = 0;
  std::size_t score = 0;  ///< following path cells it stays feasible for
};

struct Move {
  FootMove kind = FootMove::kAdvanceCg;
  int leg = -1;
  std::size_t i = 0, j = 0;
};

struct Frame {
  std::size_t k = 0;  ///< path index
  std::vector<FootState> feet;
  std::size_t foot_moves = 0;  ///< since the last CG advance
  FootStep step;
  std::vector<Move> children;
  std::size_t next_child = 0;
  bool expanded = false;
};

class Search {
 public:
  Search(const Footmap& fm, const LeggedRobot& robot, const CgLattice& L,
         const std::vector<CgCell>& cells, const FootPlannerOptions& o)
      : fm_(fm), robot_(robot), o_(o), g_(fm.terrain().grid()) {
    for (const CgCell& c : cells) {
      poses_.push_back(L.centre(c));
      const std::optional<double> mh = cg_min_height(fm, robot, poses_.back());
      min_height_.push_back(mh ? *mh : std::numeric_limits<double>::infinity());
    }
  }

  std::size_t size() const { return poses_.size(); }
  const SE2Pose& pose(std::size_t k) const { return poses_[k]; }

  Vec2 body(std::size_t i, std::size_t j, std::size_t k) const {
    const SE2Pose& q = poses_[k];
    const Vec2 d = g_.node_position(i, j) - Vec2(q.x, q.y);
    const double c = std::cos(q.theta), s = std::sin(q.theta);
    return {c * d.x() + s * d.y(), -s * d.x() + c * d.y()};
  }
  int quadrant(std::size_t i, std::size_t j, std::size_t k) const {
    const Vec2 uv = body(i, j, k);
    return (uv.x() < 0 ? 1 : 0) + (uv.y() < 0 ? 2 : 0);
  }
  bool feasible(int leg, std::size_t i, std::size_t j, std::size_t k) const {
    if (!fm_.valid(i, j)) return false;
    const Leg& l = robot_.legs[static_cast<std::size_t>(leg)];
    const Vec2 uv = body(i, j, k);
    return l.in_range(uv) && g_.at(i, j) + l.reach.at(uv) > min_height_[k];
  }
  bool stable(const std::vector<FootState>& feet, std::size_t k, int without = -1) const {
    bool q[4] = {false, false, false, false};
    for (std::size_t l = 0; l < feet.size(); ++l)
      if (feet[l].contact && static_cast<int>(l) != without)
        q[quadrant(feet[l].i, feet[l].j, k)] = true;
    return q[0] && q[1] && q[2] && q[3];
  }
  bool occupied(const std::vector<FootState>& feet, std::size_t i, std::size_t j) const {
    for (const FootState& f : feet)
      if (f.contact && f.i == i && f.j == j) return true;
    return false;
  }

  /// Feasible new nodes for `leg` at path index k, best first, at most placements_per_leg.
  std::vector<Candidate> candidates(int leg, std::size_t k, const std::vector<FootState>& feet,
                                    int want_quadrant = -1, std::size_t quadrant_index = 0) const {
    const Leg& l = robot_.legs[static_cast<std::size_t>(leg)];
    const SE2Pose& q = poses_[k];
    const double c = std::cos(q.theta), s = std::sin(q.theta);
    double xa = std::numeric_limits<double>::infinity(), xb = -xa, ya = xa, yb = -xa;
    for (const Vec2& uv : l.range) {
      const double x = q.x + c * uv.x() - s * uv.y(), y = q.y + s * uv.x() + c * uv.y();
      xa = std::min(xa, x), xb = std::max(xb, x), ya = std::min(ya, y), yb = std::max(yb, y);
    }
    const double h = g_.cellsize();
    const long i0 = std::max(0L, static_cast<long>(std::ceil((xa - g_.x_min()) / h - 1e-9)));
    const long i1 = std::min(static_cast<long>(g_.ncols()) - 1,
                             static_cast<long>(std::floor((xb - g_.x_min()) / h + 1e-9)));
    const long j0 = std::max(0L, static_cast<long>(std::ceil((ya - g_.y_min()) / h - 1e-9)));
    const long j1 = std::min(static_cast<long>(g_.nrows()) - 1,
                             static_cast<long>(std::floor((yb - g_.y_min()) / h + 1e-9)));
    std::vector<Candidate> out;
    for (long j = j0; j <= j1; ++j) {
      for (long i = i0; i <= i1; ++i) {
        const auto iu = static_cast<std::size_t>(i), ju = static_cast<std::size_t>(j);
        if (!feasible(leg, iu, ju, k) || occupied(feet, iu, ju)) continue;
        if (want_quadrant >= 0 && quadrant(iu, ju, quadrant_index) != want_quadrant) continue;
        Candidate cand{iu, ju, 0};
        for (std::size_t m = k + 1; m < poses_.size() && m <= k + o_.lookahead; ++m) {
          if (!feasible(leg, iu, ju, m)) break;
          ++cand.score;
        }
        out.push_back(cand);
      }
    }
    std::stable_sort(out.begin(), out.end(),
                     [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
    if (out.size() > o_.placements_per_leg) out.resize(o_.placements_per_leg);
    return out;
  }

  /// The ordered moves from a frame (the file comment's precedence).
  std::vector<Move> moves(const Frame& f) const {
    std::vector<Move> out;
    const std::size_t k = f.k, next = k + 1;
    const int n = static_cast<int>(f.feet.size());
    std::vector<int> failing;
    for (int l = 0; l < n; ++l) {
      const FootState& foot = f.feet[static_cast<std::size_t>(l)];
      if (foot.contact && !feasible(l, foot.i, foot.j, next)) failing.push_back(l);
    }
    const bool next_stable = stable(f.feet, next);
    if (failing.empty() && next_stable) out.push_back({FootMove::kAdvanceCg, -1, 0, 0});
    if (f.foot_moves >= o_.max_foot_moves) return out;
    auto is_free = [&](int l) {
      return !f.feet[static_cast<std::size_t>(l)].contact || stable(f.feet, k, l);
    };
    auto add_placements = [&](int l, int want_quadrant, std::size_t quadrant_index) {
      std::vector<FootState> rest = f.feet;
      rest[static_cast<std::size_t>(l)].contact = false;
      for (const Candidate& c : candidates(l, k, rest, want_quadrant, quadrant_index)) {
        if (c.score == 0 && next < poses_.size()) continue;  // useless for the next CG move
        std::vector<FootState> after = rest;
        after[static_cast<std::size_t>(l)] = {true, c.i, c.j};
        if (!stable(after, k)) continue;
        const FootState& now = f.feet[static_cast<std::size_t>(l)];
        if (now.contact && now.i == c.i && now.j == c.j) continue;
        out.push_back({FootMove::kMoveFoot, l, c.i, c.j});
      }
    };
    // 2: every foot stays in range but a quadrant empties: a free foot into it.
    if (failing.empty() && !next_stable) {
      bool q[4] = {false, false, false, false};
      for (const FootState& foot : f.feet)
        if (foot.contact) q[quadrant(foot.i, foot.j, next)] = true;
      for (int d = 0; d < 4; ++d) {
        if (q[d]) continue;
        for (int l = 0; l < n; ++l)
          if (is_free(l)) add_placements(l, d, next);
      }
    }
    // 3 and 4: a free foot about to become infeasible: a new place, else up.
    for (int l : failing) {
      if (!is_free(l)) continue;
      const std::size_t before = out.size();
      add_placements(l, -1, 0);
      if (out.size() == before) out.push_back({FootMove::kLiftFoot, l, 0, 0});
    }
    // 5: a foot that is not free is about to become infeasible: free it.
    for (int l : failing) {
      if (is_free(l)) continue;
      const FootState& foot = f.feet[static_cast<std::size_t>(l)];
      const int quad = quadrant(foot.i, foot.j, k);
      for (int m = 0; m < n; ++m)
        if (m != l && is_free(m)) add_placements(m, quad, k);
    }
    // Ours: put a raised foot back down (the best place) when nothing above applies.
    if (out.empty()) {
      for (int l = 0; l < n; ++l)
        if (!f.feet[static_cast<std::size_t>(l)].contact) add_placements(l, -1, 0);
    }
    return out;
  }

  std::string key(std::size_t k, const std::vector<FootState>& feet) const {
    std::string s = std::to_string(k);
    for (const FootState& f : feet) {
      s.push_back(':');
      if (f.contact) {
        s.append(std::to_string(f.j * g_.ncols() + f.i));
      } else {
        s.push_back('-');
      }
    }
    return s;
  }

  /// The greedy initial stance (file comment); empty if unstable.
  std::vector<FootState> initial() const {
    const std::size_t n = robot_.legs.size();
    std::vector<FootState> feet(n);
    std::vector<bool> used(n, false);
    for (int q = 0; q < 4; ++q) {
      int best_leg = -1;
      Candidate best;
      for (std::size_t l = 0; l < n; ++l) {
        if (used[l]) continue;
        const std::vector<Candidate> c = candidates(static_cast<int>(l), 0, feet, q, 0);
        if (!c.empty() && (best_leg < 0 || c.front().score > best.score)) {
          best_leg = static_cast<int>(l);
          best = c.front();
        }
      }
      if (best_leg < 0) return {};
      used[static_cast<std::size_t>(best_leg)] = true;
      feet[static_cast<std::size_t>(best_leg)] = {true, best.i, best.j};
    }
    for (std::size_t l = 0; l < n; ++l) {
      if (used[l]) continue;
      const std::vector<Candidate> c = candidates(static_cast<int>(l), 0, feet);
      if (!c.empty()) feet[l] = {true, c.front().i, c.front().j};
    }
    return stable(feet, 0) ? feet : std::vector<FootState>{};
  }

 private:
  const Footmap& fm_;
  const LeggedRobot& robot_;
  const FootPlannerOptions& o_;
  const ElevationGrid& g_;
  std::vector<SE2Pose> poses_;
  std::vector<double> min_height_;
};

}  // namespace

void FootPlannerOptions::validate() const {
  if (budget < 1) throw InputError("FootPlannerOptions.budget must be >= 1");
  if (lookahead < 1) throw InputError("FootPlannerOptions.lookahead must be >= 1");
  if (placements_per_leg < 1)
    throw InputError("FootPlannerOptions.placements_per_leg must be >= 1");
  if (max_foot_moves < 1) throw InputError("FootPlannerOptions.max_foot_moves must be >= 1");
}

const char* to_string(FootMove m) {
  switch (m) {
    case FootMove::kStart:
      return "start";
    case FootMove::kAdvanceCg:
      return "advance_cg";
    case FootMove::kMoveFoot:
      return "move_foot";
    case FootMove::kLiftFoot:
      return "lift_foot";
  }
  return "unknown";
}

const char* to_string(FootPlanStatus s) {
  switch (s) {
    case FootPlanStatus::kFound:
      return "found";
    case FootPlanStatus::kNoStance:
      return "no_stance";
    case FootPlanStatus::kFailed:
      return "failed";
    case FootPlanStatus::kBudgetExceeded:
      return "budget_exceeded";
  }
  return "unknown";
}

Vec3 foot_position(const Footmap& footmap, const FootState& foot) {
  const ElevationGrid& g = footmap.terrain().grid();
  const Vec2 p = g.node_position(foot.i, foot.j);
  return {p.x(), p.y(), g.at(foot.i, foot.j)};
}

FootPlan plan_footsteps(const Footmap& footmap, const LeggedRobot& robot, const CgLattice& lattice,
                        const std::vector<CgCell>& cells, const FootPlannerOptions& options,
                        const std::vector<FootStep>& prefix) {
  options.validate();
  robot.validate();
  const auto t0 = std::chrono::steady_clock::now();
  FootPlan plan;
  auto done = [&](FootPlanStatus status, std::string message) {
    plan.status = status;
    plan.message = std::move(message);
    plan.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return plan;
  };
  if (cells.empty()) return done(FootPlanStatus::kFailed, "the CG path is empty");
  const Search search(footmap, robot, lattice, cells, options);
  Frame first;
  if (prefix.empty()) {
    first.feet = search.initial();
    if (first.feet.empty())
      return done(FootPlanStatus::kNoStance, "no stable stance of the feet at the first CG cell");
    first.step = {FootMove::kStart, 0, search.pose(0), -1, first.feet};
  } else {
    // Resume at the prefix's last stance: it must stand on this path.
    const FootStep& last = prefix.back();
    if (last.path_index >= search.size() || last.feet.size() != robot.legs.size() ||
        !search.stable(last.feet, last.path_index)) {
      throw InputError(
          "plan_footsteps: the prefix's last stance is not a stable stance on this "
          "path at its CG cell " +
          std::to_string(last.path_index));
    }
    first.k = last.path_index;
    first.feet = last.feet;
    first.step = last;
  }
  std::vector<Frame> stack;
  std::unordered_set<std::string> visited;
  visited.insert(search.key(first.k, first.feet));
  plan.furthest_index = first.k;
  stack.push_back(std::move(first));
  plan.nodes = 1;
  // The steps taken: the prefix (its last step is the first frame's), then the stack's.
  auto record = [&] {
    plan.steps.assign(prefix.begin(), prefix.empty() ? prefix.end() : prefix.end() - 1);
    for (const Frame& f : stack) plan.steps.push_back(f.step);
  };
  record();
  while (!stack.empty()) {
    Frame& top = stack.back();
    if (top.k + 1 == search.size()) {
      record();
      plan.furthest_index = top.k;
      return done(FootPlanStatus::kFound, "every CG cell of the path reached in " +
                                              std::to_string(plan.steps.size()) + " steps");
    }
    if (!top.expanded) {
      top.children = search.moves(top);
      top.expanded = true;
    }
    if (top.next_child >= top.children.size()) {
      stack.pop_back();
      continue;
    }
    const Move m = top.children[top.next_child++];
    Frame child;
    child.feet = top.feet;
    child.k = top.k;
    child.foot_moves = top.foot_moves + 1;
    if (m.kind == FootMove::kAdvanceCg) {
      child.k = top.k + 1;
      child.foot_moves = 0;
    } else if (m.kind == FootMove::kMoveFoot) {
      child.feet[static_cast<std::size_t>(m.leg)] = {true, m.i, m.j};
    } else {
      child.feet[static_cast<std::size_t>(m.leg)].contact = false;
    }
    if (!visited.insert(search.key(child.k, child.feet)).second) continue;
    if (plan.nodes >= options.budget) {
      return done(FootPlanStatus::kBudgetExceeded,
                  "the foot planner's budget of " + std::to_string(options.budget) +
                      " nodes was spent at CG cell " + std::to_string(plan.furthest_index) +
                      " of " + std::to_string(search.size()));
    }
    ++plan.nodes;
    child.step = {m.kind, child.k, search.pose(child.k), m.leg, child.feet};
    stack.push_back(std::move(child));
    if (stack.back().k > plan.furthest_index) {
      plan.furthest_index = stack.back().k;
      record();
    }
  }
  return done(FootPlanStatus::kFailed, "the foot planner's search was exhausted at CG cell " +
                                           std::to_string(plan.furthest_index) + " of " +
                                           std::to_string(search.size()));
}

}  // namespace talus
