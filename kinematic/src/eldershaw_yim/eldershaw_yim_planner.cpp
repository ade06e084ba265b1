#include "talus/kinematic/eldershaw_yim/eldershaw_yim_planner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <thread>
#include <unordered_set>

#include "talus/core/error.hpp"

namespace talus {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// Uniform integer in [0, n) from 53 bits of one mt19937_64 draw (platform independent).
std::size_t uniform_index(std::mt19937_64& rng, std::size_t n) {
  const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return std::min(n - 1, static_cast<std::size_t>(u * static_cast<double>(n)));
}

/// f(0) … f(n-1) on up to `workers` threads (each index exactly once, in no
/// particular order); f must not throw.
void parallel_for(std::size_t n, int workers, const std::function<void(std::size_t)>& f) {
  const std::size_t threads = std::min(n, static_cast<std::size_t>(std::max(workers, 1)));
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  pool.reserve(threads);
  for (std::size_t k = 0; k < threads; ++k)
    pool.emplace_back([&] {
      for (std::size_t i = next++; i < n; i = next++) f(i);
    });
  for (auto& t : pool) t.join();
}

/// The rank owning the call from `a` to `b` (the header's strips in x).
int owner_of(const CgLattice& lattice, const CgCell& a, const CgCell& b, int ranks) {
  const long mid = (static_cast<long>(a.ix) + b.ix) / 2;
  return static_cast<int>(std::min<long>(ranks - 1, mid * ranks / std::max(lattice.nx(), 1)));
}

/// Every rank's results of a batch: each rank's own calls filled in, the
/// others' taken from their owners (two max_all exchanges); `keys[i]` the
/// blocks call i evaluated.
void exchange(const CgRankGroup& ranks, const CgLattice& lattice, const std::vector<int>& owner,
              std::vector<CgLocalPath>& out, std::vector<std::vector<std::size_t>>& keys,
              bool failed) {
  // Per call: found, budget exceeded, expansions, cost, cell count, block count; then one
  // "some call failed" flag. -1 (below every real value) on the ranks not owning the call.
  constexpr std::size_t kFields = 6;
  const std::size_t n = out.size();
  std::vector<double> head(n * kFields + 1, -1.0);
  head[n * kFields] = failed ? 1.0 : 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (owner[i] != ranks.rank()) continue;
    double* h = &head[i * kFields];
    h[0] = out[i].found ? 1.0 : 0.0;
    h[1] = out[i].budget_exceeded ? 1.0 : 0.0;
    h[2] = static_cast<double>(out[i].expansions);
    h[3] = out[i].cost;
    h[4] = static_cast<double>(out[i].cells.size());
    h[5] = static_cast<double>(keys[i].size());
  }
  ranks.max_all(head);
  if (head[n * kFields] > 0) {  // every rank stops here; the failing one rethrows its error
    if (failed) return;
    throw SolverError("plan_eldershaw_yim: a local-planner call failed on another rank");
  }
  std::vector<std::size_t> offset(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    offset[i + 1] = offset[i] + static_cast<std::size_t>(head[i * kFields + 4]) +
                    static_cast<std::size_t>(head[i * kFields + 5]);
  std::vector<double> body(offset[n], -1.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (owner[i] != ranks.rank()) continue;
    std::size_t k = offset[i];
    for (const CgCell& c : out[i].cells) body[k++] = static_cast<double>(lattice.index(c));
    for (std::size_t key : keys[i]) body[k++] = static_cast<double>(key);
  }
  ranks.max_all(body);
  for (std::size_t i = 0; i < n; ++i) {
    if (owner[i] == ranks.rank()) continue;
    const double* h = &head[i * kFields];
    CgLocalPath& p = out[i];
    p.found = h[0] > 0;
    p.budget_exceeded = h[1] > 0;
    p.expansions = static_cast<std::size_t>(h[2]);
    p.cost = h[3];
    const auto cells = static_cast<std::size_t>(h[4]);
    std::size_t k = offset[i];
    p.cells.clear();
    for (std::size_t j = 0; j < cells; ++j)
      p.cells.push_back(lattice.cell(static_cast<std::size_t>(body[k++])));
    keys[i].assign(body.begin() + static_cast<std::ptrdiff_t>(k),
                   body.begin() + static_cast<std::ptrdiff_t>(offset[i + 1]));
  }
}

/// One batch of local-planner calls (the header's parallel local planning):
/// each on its own overlay of `space` with the budget left at the start
/// (`work` = the caller's work so far), on this rank if it owns the call;
/// the overlays are then absorbed into `space` (the other ranks' blocks
/// counted). The first error in query order is rethrown.
std::vector<CgLocalPath> local_plan_batch(CgSpace& space,
                                          const std::vector<std::pair<CgCell, CgCell>>& queries,
                                          const CgLocalPlannerOptions& local, std::size_t work,
                                          std::size_t budget, int workers,
                                          const CgRankGroup* ranks) {
  const std::size_t n = queries.size();
  std::vector<CgLocalPath> out(n);
  std::vector<std::unique_ptr<CgSpace>> overlays(n);
  std::vector<std::exception_ptr> errors(n);
  std::vector<int> owner(n, 0);
  const bool shared = ranks != nullptr && ranks->size() > 1;
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < n; ++i) {
    if (shared)
      owner[i] = owner_of(space.lattice(), queries[i].first, queries[i].second, ranks->size());
    if (!shared || owner[i] == ranks->rank()) mine.push_back(i);
  }
  const std::size_t spent = space.cells_materialised() + work;
  parallel_for(mine.size(), workers, [&](std::size_t j) {
    const std::size_t i = mine[j];
    try {
      overlays[i] = std::make_unique<CgSpace>(CgSpace::OverlayOn{}, space);
      std::size_t w = spent;
      out[i] = cg_local_plan(*overlays[i], queries[i].first, queries[i].second, local, w, budget);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  const bool failed =
      std::any_of(errors.begin(), errors.end(), [](const auto& e) { return e != nullptr; });
  if (shared) {
    std::vector<std::vector<std::size_t>> keys(n);
    for (std::size_t i : mine)
      if (overlays[i]) keys[i] = overlays[i]->block_keys();
    exchange(*ranks, space.lattice(), owner, out, keys, failed);
    for (std::size_t i = 0; i < n; ++i)
      if (!overlays[i]) space.count_blocks(keys[i]);
  }
  for (auto& o : overlays)
    if (o) space.absorb(std::move(*o));
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return out;
}

}  // namespace

void EldershawYimPlannerOptions::validate() const {
  if (!(theta_slices == 1 || (theta_slices >= 8 && theta_slices <= 1024)))
    throw InputError("theta_slices must be 1 or 8..1024, got " + std::to_string(theta_slices));
  if (!(std::isfinite(connect_radius) && connect_radius >= 0))
    throw InputError("connect_radius must be a finite number >= 0 m (0 = automatic)");
  if (connect_attempts < 1) throw InputError("connect_attempts must be >= 1");
  if (sample_attempts < 1) throw InputError("sample_attempts must be >= 1");
  if (block_side < 1) throw InputError("block_side must be >= 1");
  if (budget < 1) throw InputError("budget must be >= 1");
  if (local.margin < 0) throw InputError("local.margin must be >= 0 cells");
  if (feedback_rounds > 1000) throw InputError("feedback_rounds must be at most 1000");
  if (workers < 1 || workers > 256)
    throw InputError("workers must be 1..256, got " + std::to_string(workers));
  feet.validate();
  if (!(std::isfinite(local.margin_fraction) && local.margin_fraction >= 0))
    throw InputError("local.margin_fraction must be a finite number >= 0");
  if (!std::isfinite(local.heading_weight))
    throw InputError("local.heading_weight must be finite (<= 0 = automatic)");
}

const char* to_string(EldershawYimStatus s) {
  switch (s) {
    case EldershawYimStatus::kFound:
      return "found";
    case EldershawYimStatus::kNoPath:
      return "no_path";
    case EldershawYimStatus::kStartInvalid:
      return "start_invalid";
    case EldershawYimStatus::kGoalInvalid:
      return "goal_invalid";
    case EldershawYimStatus::kBudgetExceeded:
      return "budget_exceeded";
  }
  return "unknown";
}

std::string EldershawYimResult::brief_report() const {
  std::ostringstream out;
  out << to_string(status);
  if (found()) out << ", " << length_m << " m over " << cells.size() << " CG cells";
  out << ", " << cells_materialised << " of " << cg_cells << " CG cells materialised, "
      << prm_points.size() << " PRM points, " << local_planner_calls << " local-planner calls, "
      << expansions << " expansions, search " << search_seconds << " s: " << message;
  return out.str();
}

std::vector<SE2Pose> cg_path_poses(const CgLattice& lattice, const std::vector<CgCell>& cells,
                                   const SE2Pose& start, const SE2Pose& goal) {
  std::vector<SE2Pose> out;
  if (cells.empty()) return out;
  out.push_back(start);
  for (std::size_t k = 1; k + 1 < cells.size(); ++k) {
    SE2Pose q = lattice.centre(cells[k]);
    q.theta = out.back().theta + std::remainder(q.theta - out.back().theta, 2 * std::numbers::pi);
    out.push_back(q);
  }
  out.push_back(goal);
  return out;
}

namespace {

/// The steps of `plan` (made along `old_cells`) that lie on the leading cells
/// `new_cells` shares with `old_cells`, up to the last step on the last shared
/// cell; empty when nothing is shared or there is no earlier plan.
std::vector<FootStep> reusable_steps(const std::vector<CgCell>& old_cells, const FootPlan& plan,
                                     const std::vector<CgCell>& new_cells) {
  std::size_t shared = 0;
  while (shared < old_cells.size() && shared < new_cells.size() &&
         old_cells[shared] == new_cells[shared])
    ++shared;
  // The last shared cell must not be the new path's end: its pose (the goal) differs.
  if (shared == 0 || shared >= new_cells.size()) return {};
  std::vector<FootStep> steps;
  for (const FootStep& step : plan.steps) {
    if (step.path_index >= shared) break;
    steps.push_back(step);
  }
  return steps;
}

}  // namespace

EldershawYimResult plan_eldershaw_yim(const RuledTerrain& terrain, const LeggedRobot& robot,
                                      const SE2Pose& start, const SE2Pose& goal,
                                      const EldershawYimPlannerOptions& options) {
  options.validate();
  robot.validate();
  for (const SE2Pose* q : {&start, &goal}) {
    if (!std::isfinite(q->x) || !std::isfinite(q->y) || !std::isfinite(q->theta))
      throw InputError("plan_eldershaw_yim: a start or goal pose is not finite");
    if (!terrain.contains(q->position()))
      throw InputError("plan_eldershaw_yim: a start or goal position is off the map");
  }
  EldershawYimResult r;
  const auto t_footmap = Clock::now();
  const Footmap footmap(terrain, robot);
  r.footmap_seconds = since(t_footmap);
  const auto t_search = Clock::now();
  CgSpace space(footmap, robot, options.theta_slices, options.block_side);
  const CgLattice& L = space.lattice();
  r.cg_cells = L.size();
  CgLocalPlannerOptions local = options.local;
  if (local.heading_weight <= 0) local.heading_weight = std::max(robot.outer_radius(), 1e-3);
  const double radius =
      options.connect_radius > 0 ? options.connect_radius : 40.0 * robot.foot_print;
  std::size_t work = 0;
  auto finish = [&](EldershawYimStatus status, std::string message) {
    r.status = status;
    r.message = std::move(message);
    r.cells_materialised = space.cells_materialised();
    r.blocks_materialised = space.blocks_materialised();
    r.materialise_seconds = space.seconds();
    r.search_seconds = since(t_search);
    if (status != EldershawYimStatus::kFound) r.cells.clear();
    return r;
  };
  auto over_budget = [&] { return space.cells_materialised() + work >= options.budget; };

  const CgCell s = L.cell_of(start), g = L.cell_of(goal);
  r.start_state = space.state(s);
  if (r.start_state != CgState::kValid)
    return finish(EldershawYimStatus::kStartInvalid,
                  std::string("the start's CG cell is invalid (") + to_string(r.start_state) + ")");
  r.goal_state = space.state(g);
  if (r.goal_state != CgState::kValid)
    return finish(EldershawYimStatus::kGoalInvalid,
                  std::string("the goal's CG cell is invalid (") + to_string(r.goal_state) + ")");
  if (over_budget())
    return finish(EldershawYimStatus::kBudgetExceeded,
                  "the work budget was spent materialising the start and goal blocks");
  auto budget_message = [&] {
    return "the work budget of " + std::to_string(options.budget) +
           " (CG cells evaluated + A* expansions) was spent";
  };

  // One CG search (the direct A* or the tree-PRM); false when it ended without a path (r
  // finished), true with r.cells set.
  auto cg_search = [&]() -> bool {
    r.cells.clear();
    r.prm_points.clear();
    r.prm_edges.clear();
    r.prm_trees = 0;
    if (s == g) {
      r.cells = {s, g};
    } else if (options.direct) {
      const auto t0 = Clock::now();
      CgLocalPlannerOptions whole = local;
      whole.whole_lattice = true;
      const CgLocalPath p = cg_local_plan(space, s, g, whole, work, options.budget);
      r.local_planner_calls += 1;
      r.expansions += p.expansions;
      r.connect_seconds += since(t0);
      if (p.budget_exceeded) {
        finish(EldershawYimStatus::kBudgetExceeded, budget_message());
        return false;
      }
      if (!p.found) {
        finish(EldershawYimStatus::kNoPath,
               "no 6-connected path of valid CG cells joins the start and the goal");
        return false;
      }
      r.local_planner_successes += 1;
      r.cells = p.cells;
    } else {
      // Trees as separate lists; tree_of[point] = its list.
      std::vector<std::vector<std::size_t>> trees;
      std::vector<std::size_t> tree_of;
      std::vector<std::vector<std::size_t>> adjacency;
      std::unordered_set<std::size_t> taken;
      double connect_time = 0.0;
      bool exhausted = false;
      auto insert = [&](const CgCell& c) {
        const std::size_t p = r.prm_points.size();
        r.prm_points.push_back(c);
        taken.insert(L.index(c));
        adjacency.emplace_back();
        tree_of.push_back(trees.size());
        trees.push_back({p});
        const auto t0 = Clock::now();
        const std::size_t existing = trees.size() - 1;
        // The members tried per tree, nearest first (fixed for the whole insertion).
        std::vector<std::vector<std::size_t>> tried(existing);
        const SE2Pose cp = L.centre(c);
        for (std::size_t t = 0; t < existing; ++t) {
          std::vector<std::pair<double, std::size_t>> near;
          for (std::size_t m : trees[t]) {
            const SE2Pose cm = L.centre(r.prm_points[m]);
            const double d = std::hypot(cp.x - cm.x, cp.y - cm.y);
            if (d <= radius) near.emplace_back(d, m);
          }
          std::sort(near.begin(), near.end());
          for (std::size_t k = 0; k < std::min(near.size(), options.connect_attempts); ++k)
            tried[t].push_back(near[k].second);
        }
        // Round k: the k-th member of every tree whose earlier ones failed, up to (and
        // including) the first tree where a call spent the budget.
        std::vector<std::vector<CgLocalPath>> results(existing);
        std::size_t stop = existing;
        for (std::size_t k = 0; k < options.connect_attempts; ++k) {
          std::vector<std::size_t> which;
          std::vector<std::pair<CgCell, CgCell>> queries;
          for (std::size_t t = 0; t < stop; ++t) {
            if (tried[t].size() <= k || results[t].size() != k) continue;
            if (k > 0 && (results[t].back().found || results[t].back().budget_exceeded)) continue;
            which.push_back(t);
            queries.emplace_back(c, r.prm_points[tried[t][k]]);
          }
          if (queries.empty()) break;
          std::vector<CgLocalPath> batch = local_plan_batch(
              space, queries, local, work, options.budget, options.workers, options.ranks);
          for (std::size_t i = 0; i < batch.size(); ++i) {
            r.local_planner_calls += 1;
            r.expansions += batch[i].expansions;
            work += batch[i].expansions;
            if (batch[i].budget_exceeded) stop = std::min(stop, which[i] + 1);
            results[which[i]].push_back(std::move(batch[i]));
          }
        }
        // Applied in the serial order: tree by tree, its members nearest first.
        for (std::size_t t = 0; t < existing && !exhausted; ++t) {
          for (std::size_t k = 0; k < results[t].size(); ++k) {
            const CgLocalPath& path = results[t][k];
            if (path.budget_exceeded) {
              exhausted = true;
              break;
            }
            if (!path.found) continue;
            const std::size_t m = tried[t][k];
            ++r.local_planner_successes;
            r.prm_edges.emplace_back(p, m);
            adjacency[p].push_back(m);
            adjacency[m].push_back(p);
            // Concatenate: the lower-numbered list absorbs the other.
            std::size_t a = tree_of[p], b = t;
            if (b < a) std::swap(a, b);
            for (std::size_t q : trees[b]) tree_of[q] = a;
            trees[a].insert(trees[a].end(), trees[b].begin(), trees[b].end());
            trees[b].clear();
            break;
          }
        }
        connect_time += since(t0);
      };
      auto joined = [&] { return r.prm_points.size() >= 2 && tree_of[0] == tree_of[1]; };
      insert(s);
      insert(g);
      const auto t_sample = Clock::now();
      double sample_connect = 0.0;
      std::mt19937_64 rng(options.seed);
      const std::size_t max_draws = options.sample_attempts * options.prm_points;
      std::size_t added = 0;
      std::size_t draws = 0;
      while (!joined() && !exhausted && added < options.prm_points && draws < max_draws) {
        if (over_budget()) {
          exhausted = true;
          break;
        }
        ++draws;
        ++r.samples_drawn;
        const CgCell c = L.cell(uniform_index(rng, L.size()));
        if (taken.count(L.index(c)) || !space.valid(c)) continue;
        ++added;
        const double before = connect_time;
        insert(c);
        sample_connect += connect_time - before;
      }
      r.sample_seconds += since(t_sample) - sample_connect;
      r.connect_seconds += connect_time;
      for (const auto& t : trees) r.prm_trees += t.empty() ? 0 : 1;
      if (!joined()) {
        if (exhausted) {
          finish(EldershawYimStatus::kBudgetExceeded, budget_message());
          return false;
        }
        {
          finish(EldershawYimStatus::kNoPath,
                 "the start's and the goal's trees were not joined by " + std::to_string(added) +
                     " PRM points (" + std::to_string(r.samples_drawn) + " draws)");
          return false;
        }
      }
      // The tree path start -> goal (breadth first; the graph is a tree).
      std::vector<std::size_t> parent(r.prm_points.size(), r.prm_points.size());
      std::vector<std::size_t> queue{0};
      parent[0] = 0;
      for (std::size_t k = 0; k < queue.size(); ++k) {
        for (std::size_t n : adjacency[queue[k]]) {
          if (parent[n] != r.prm_points.size()) continue;
          parent[n] = queue[k];
          queue.push_back(n);
        }
      }
      std::vector<std::size_t> route{1};
      while (route.back() != 0) route.push_back(parent[route.back()]);
      std::reverse(route.begin(), route.end());
      const auto t_recreate = Clock::now();
      std::vector<std::pair<CgCell, CgCell>> edges;
      for (std::size_t k = 1; k < route.size(); ++k)
        edges.emplace_back(r.prm_points[route[k - 1]], r.prm_points[route[k]]);
      const std::vector<CgLocalPath> pieces = local_plan_batch(
          space, edges, local, work, options.budget, options.workers, options.ranks);
      r.recreate_seconds += since(t_recreate);
      r.cells = {s};
      for (const CgLocalPath& piece : pieces) {
        ++r.recreate_calls;
        r.expansions += piece.expansions;
        work += piece.expansions;
      }
      for (const CgLocalPath& piece : pieces) {
        if (piece.budget_exceeded) {
          finish(EldershawYimStatus::kBudgetExceeded, budget_message());
          return false;
        }
        if (!piece.found)  // cannot happen: the same search succeeded the other way
          throw SolverError("plan_eldershaw_yim: re-running a roadmap edge failed");
        r.cells.insert(r.cells.end(), piece.cells.begin() + 1, piece.cells.end());
      }
    }
    return true;
  };

  std::vector<CgCell> failed_cells;  // the CG path whose foot plan failed last
  for (;;) {
    if (!cg_search()) return r;
    r.path = cg_path_poses(L, r.cells, start, goal);
    r.length_m = 0.0;
    for (std::size_t k = 1; k < r.path.size(); ++k)
      r.length_m += std::hypot(r.path[k].x - r.path[k - 1].x, r.path[k].y - r.path[k - 1].y);
    std::ostringstream msg;
    msg << (options.direct ? "direct A*" : "tree-PRM") << ": " << r.cells.size() << " CG cells";
    if (!options.direct) msg << " through " << r.prm_points.size() << " PRM points";
    if (r.feedback_events > 0) msg << " after " << r.feedback_events << " feedback events";
    finish(EldershawYimStatus::kFound, msg.str());
    if (!options.plan_feet) return r;
    // After feedback (§3.3) the feet keep the steps they took on the cells
    // the new CG path shares with the old one, and walk on from there; only
    // if that fails is the whole path planned afresh.
    const std::vector<FootStep> prefix = reusable_steps(failed_cells, r.foot_plan, r.cells);
    r.foot_plan = plan_footsteps(footmap, robot, L, r.cells, options.feet, prefix);
    r.foot_planner_seconds += r.foot_plan.seconds;
    r.foot_planner_nodes += r.foot_plan.nodes;
    r.foot_steps_reused = prefix.empty() ? 0 : prefix.size();
    if (!prefix.empty() && !r.foot_plan.found()) {
      FootPlan fresh = plan_footsteps(footmap, robot, L, r.cells, options.feet);
      r.foot_planner_seconds += fresh.seconds;
      r.foot_planner_nodes += fresh.nodes;
      if (fresh.found() || fresh.furthest_index > r.foot_plan.furthest_index) {
        r.foot_plan = std::move(fresh);
        r.foot_steps_reused = 0;
      }
    }
    r.feet_planned = true;
    const bool stuck = r.foot_plan.status == FootPlanStatus::kFailed ||
                       r.foot_plan.status == FootPlanStatus::kBudgetExceeded;
    const std::size_t next = r.foot_plan.furthest_index + 1;
    if (!stuck || r.feedback_events >= options.feedback_rounds || next >= r.cells.size()) {
      r.message +=
          std::string("; foot plan ") + to_string(r.foot_plan.status) + ": " + r.foot_plan.message;
      return r;
    }
    // §3.3: the CG cell the feet could not reach is marked invalid and the CG path replanned.
    failed_cells = r.cells;
    space.mark_invalid(r.cells[next]);
    r.feedback_cells.push_back(r.cells[next]);
    ++r.feedback_events;
  }
}

}  // namespace talus
