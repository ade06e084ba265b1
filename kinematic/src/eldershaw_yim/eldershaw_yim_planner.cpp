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

/// The roadmap of the tree-PRM: points (r.prm_points), their edges and the trees they form.
struct Roadmap {
  std::vector<std::vector<std::size_t>> trees;  ///< separate lists of points
  std::vector<std::size_t> tree_of;             ///< tree_of[point] = its list
  std::vector<std::vector<std::size_t>> adjacency;
  std::unordered_set<std::size_t> taken;  ///< lattice indices of the points
  double connect_time = 0.0;              ///< [s] in the local planner's calls
  bool exhausted = false;                 ///< a call spent the work budget
  bool joined() const { return tree_of.size() >= 2 && tree_of[0] == tree_of[1]; }
};

/// One call of plan_eldershaw_yim: the footmap, the CG space, the result being
/// filled and the work spent (CG cells evaluated + A* expansions).
class EldershawYimRun {
 public:
  EldershawYimRun(const RuledTerrain& terrain, const LeggedRobot& robot, const SE2Pose& start,
                  const SE2Pose& goal, const EldershawYimPlannerOptions& options)
      : robot_(robot),
        start_(start),
        goal_(goal),
        options_(options),
        t_footmap_(Clock::now()),
        footmap_(terrain, robot),
        footmap_seconds_(since(t_footmap_)),
        t_search_(Clock::now()),
        space_(footmap_, robot, options.theta_slices, options.block_side),
        lattice_(space_.lattice()),
        local_(options.local),
        radius_(options.connect_radius > 0 ? options.connect_radius : 40.0 * robot.foot_print),
        s_(lattice_.cell_of(start)),
        g_(lattice_.cell_of(goal)) {
    r_.footmap_seconds = footmap_seconds_;
    r_.cg_cells = lattice_.size();
    if (local_.heading_weight <= 0) local_.heading_weight = std::max(robot.outer_radius(), 1e-3);
  }

  /// The CG search, then the feet, replanning the CG path where they fail (§3.3).
  EldershawYimResult run() {
    if (!ends_valid()) return std::move(r_);
    std::vector<CgCell> failed_cells;  // the CG path whose foot plan failed last
    for (;;) {
      if (!cg_search()) return std::move(r_);
      found_cg_path();
      if (!options_.plan_feet) return std::move(r_);
      plan_feet(failed_cells);
      const bool stuck = r_.foot_plan.status == FootPlanStatus::kFailed ||
                         r_.foot_plan.status == FootPlanStatus::kBudgetExceeded;
      const std::size_t next = r_.foot_plan.furthest_index + 1;
      if (!stuck || r_.feedback_events >= options_.feedback_rounds || next >= r_.cells.size()) {
        r_.message += std::string("; foot plan ") + to_string(r_.foot_plan.status) + ": " +
                      r_.foot_plan.message;
        return std::move(r_);
      }
      // §3.3: the CG cell the feet could not reach is marked invalid and the CG path replanned.
      failed_cells = r_.cells;
      space_.mark_invalid(r_.cells[next]);
      r_.feedback_cells.push_back(r_.cells[next]);
      ++r_.feedback_events;
    }
  }

 private:
  void finish(EldershawYimStatus status, std::string message) {
    r_.status = status;
    r_.message = std::move(message);
    r_.cells_materialised = space_.cells_materialised();
    r_.blocks_materialised = space_.blocks_materialised();
    r_.materialise_seconds = space_.seconds();
    r_.search_seconds = since(t_search_);
    if (status != EldershawYimStatus::kFound) r_.cells.clear();
  }
  bool over_budget() const { return space_.cells_materialised() + work_ >= options_.budget; }
  std::string budget_message() const {
    return "the work budget of " + std::to_string(options_.budget) +
           " (CG cells evaluated + A* expansions) was spent";
  }

  /// False (r finished) when the start's or goal's cell is invalid or their blocks spent the
  /// budget.
  bool ends_valid() {
    r_.start_state = space_.state(s_);
    if (r_.start_state != CgState::kValid) {
      finish(EldershawYimStatus::kStartInvalid,
             std::string("the start's CG cell is invalid (") + to_string(r_.start_state) + ")");
      return false;
    }
    r_.goal_state = space_.state(g_);
    if (r_.goal_state != CgState::kValid) {
      finish(EldershawYimStatus::kGoalInvalid,
             std::string("the goal's CG cell is invalid (") + to_string(r_.goal_state) + ")");
      return false;
    }
    if (over_budget()) {
      finish(EldershawYimStatus::kBudgetExceeded,
             "the work budget was spent materialising the start and goal blocks");
      return false;
    }
    return true;
  }

  /// One CG search (the direct A* or the tree-PRM); false when it ended without a path (r
  /// finished), true with r.cells set.
  bool cg_search() {
    r_.cells.clear();
    r_.prm_points.clear();
    r_.prm_edges.clear();
    r_.prm_trees = 0;
    if (s_ == g_) {
      r_.cells = {s_, g_};
      return true;
    }
    return options_.direct ? direct_search() : tree_prm_search();
  }

  bool direct_search() {
    const auto t0 = Clock::now();
    CgLocalPlannerOptions whole = local_;
    whole.whole_lattice = true;
    const CgLocalPath p = cg_local_plan(space_, s_, g_, whole, work_, options_.budget);
    r_.local_planner_calls += 1;
    r_.expansions += p.expansions;
    r_.connect_seconds += since(t0);
    if (p.budget_exceeded) {
      finish(EldershawYimStatus::kBudgetExceeded, budget_message());
      return false;
    }
    if (!p.found) {
      finish(EldershawYimStatus::kNoPath,
             "no 6-connected path of valid CG cells joins the start and the goal");
      return false;
    }
    r_.local_planner_successes += 1;
    r_.cells = p.cells;
    return true;
  }

  /// The tree-PRM: start and goal trees, random valid cells joined to every tree they reach,
  /// until the start's and the goal's trees meet; then the tree path's edges re-planned.
  bool tree_prm_search() {
    Roadmap map;
    insert(map, s_);
    insert(map, g_);
    const auto t_sample = Clock::now();
    double sample_connect = 0.0;
    std::mt19937_64 rng(options_.seed);
    const std::size_t max_draws = options_.sample_attempts * options_.prm_points;
    std::size_t added = 0;
    std::size_t draws = 0;
    while (!map.joined() && !map.exhausted && added < options_.prm_points && draws < max_draws) {
      if (over_budget()) {
        map.exhausted = true;
        break;
      }
      ++draws;
      ++r_.samples_drawn;
      const CgCell c = lattice_.cell(uniform_index(rng, lattice_.size()));
      if (map.taken.count(lattice_.index(c)) || !space_.valid(c)) continue;
      ++added;
      const double before = map.connect_time;
      insert(map, c);
      sample_connect += map.connect_time - before;
    }
    r_.sample_seconds += since(t_sample) - sample_connect;
    r_.connect_seconds += map.connect_time;
    for (const auto& t : map.trees) r_.prm_trees += t.empty() ? 0 : 1;
    if (!map.joined()) {
      if (map.exhausted) {
        finish(EldershawYimStatus::kBudgetExceeded, budget_message());
      } else {
        finish(EldershawYimStatus::kNoPath, "the start's and the goal's trees were not joined by " +
                                                std::to_string(added) + " PRM points (" +
                                                std::to_string(r_.samples_drawn) + " draws)");
      }
      return false;
    }
    return recreate(tree_route(map));
  }

  /// Adds cell c as a new tree and joins it to each existing tree it reaches (up to
  /// connect_attempts nearest members per tree within the radius), merging the trees.
  void insert(Roadmap& map, const CgCell& c) {
    const std::size_t p = r_.prm_points.size();
    r_.prm_points.push_back(c);
    map.taken.insert(lattice_.index(c));
    map.adjacency.emplace_back();
    map.tree_of.push_back(map.trees.size());
    map.trees.push_back({p});
    const auto t0 = Clock::now();
    const std::size_t existing = map.trees.size() - 1;
    const std::vector<std::vector<std::size_t>> tried = nearest_members(map, c, existing);
    const std::vector<std::vector<CgLocalPath>> results = connect_rounds(c, tried);
    // Applied in the serial order: tree by tree, its members nearest first.
    for (std::size_t t = 0; t < existing && !map.exhausted; ++t) {
      for (std::size_t k = 0; k < results[t].size(); ++k) {
        const CgLocalPath& path = results[t][k];
        if (path.budget_exceeded) {
          map.exhausted = true;
          break;
        }
        if (!path.found) continue;
        const std::size_t m = tried[t][k];
        ++r_.local_planner_successes;
        r_.prm_edges.emplace_back(p, m);
        map.adjacency[p].push_back(m);
        map.adjacency[m].push_back(p);
        // Concatenate: the lower-numbered list absorbs the other.
        std::size_t a = map.tree_of[p], b = t;
        if (b < a) std::swap(a, b);
        for (std::size_t q : map.trees[b]) map.tree_of[q] = a;
        map.trees[a].insert(map.trees[a].end(), map.trees[b].begin(), map.trees[b].end());
        map.trees[b].clear();
        break;
      }
    }
    map.connect_time += since(t0);
  }

  /// The members of each of the first `existing` trees to try joining c to, nearest first
  /// (within the radius, at most connect_attempts).
  std::vector<std::vector<std::size_t>> nearest_members(const Roadmap& map, const CgCell& c,
                                                        std::size_t existing) const {
    std::vector<std::vector<std::size_t>> tried(existing);
    const SE2Pose cp = lattice_.centre(c);
    for (std::size_t t = 0; t < existing; ++t) {
      std::vector<std::pair<double, std::size_t>> near;
      for (std::size_t m : map.trees[t]) {
        const SE2Pose cm = lattice_.centre(r_.prm_points[m]);
        const double d = std::hypot(cp.x - cm.x, cp.y - cm.y);
        if (d <= radius_) near.emplace_back(d, m);
      }
      std::sort(near.begin(), near.end());
      for (std::size_t k = 0; k < std::min(near.size(), options_.connect_attempts); ++k)
        tried[t].push_back(near[k].second);
    }
    return tried;
  }

  /// Round k: the k-th member of every tree whose earlier ones failed, up to (and including)
  /// the first tree where a call spent the budget, as one batch of local planner calls.
  std::vector<std::vector<CgLocalPath>> connect_rounds(
      const CgCell& c, const std::vector<std::vector<std::size_t>>& tried) {
    const std::size_t existing = tried.size();
    std::vector<std::vector<CgLocalPath>> results(existing);
    std::size_t stop = existing;
    for (std::size_t k = 0; k < options_.connect_attempts; ++k) {
      std::vector<std::size_t> which;
      std::vector<std::pair<CgCell, CgCell>> queries;
      for (std::size_t t = 0; t < stop; ++t) {
        if (tried[t].size() <= k || results[t].size() != k) continue;
        if (k > 0 && (results[t].back().found || results[t].back().budget_exceeded)) continue;
        which.push_back(t);
        queries.emplace_back(c, r_.prm_points[tried[t][k]]);
      }
      if (queries.empty()) break;
      std::vector<CgLocalPath> batch = local_plan_batch(
          space_, queries, local_, work_, options_.budget, options_.workers, options_.ranks);
      for (std::size_t i = 0; i < batch.size(); ++i) {
        r_.local_planner_calls += 1;
        r_.expansions += batch[i].expansions;
        work_ += batch[i].expansions;
        if (batch[i].budget_exceeded) stop = std::min(stop, which[i] + 1);
        results[which[i]].push_back(std::move(batch[i]));
      }
    }
    return results;
  }

  /// The roadmap's points from the start (0) to the goal (1), breadth first (a tree).
  std::vector<std::size_t> tree_route(const Roadmap& map) const {
    const std::size_t none = r_.prm_points.size();
    std::vector<std::size_t> parent(none, none);
    std::vector<std::size_t> queue{0};
    parent[0] = 0;
    for (std::size_t k = 0; k < queue.size(); ++k) {
      for (std::size_t n : map.adjacency[queue[k]]) {
        if (parent[n] != none) continue;
        parent[n] = queue[k];
        queue.push_back(n);
      }
    }
    std::vector<std::size_t> route{1};
    while (route.back() != 0) route.push_back(parent[route.back()]);
    std::reverse(route.begin(), route.end());
    return route;
  }

  /// r.cells along the route: each roadmap edge's local path planned again.
  bool recreate(const std::vector<std::size_t>& route) {
    const auto t_recreate = Clock::now();
    std::vector<std::pair<CgCell, CgCell>> edges;
    for (std::size_t k = 1; k < route.size(); ++k)
      edges.emplace_back(r_.prm_points[route[k - 1]], r_.prm_points[route[k]]);
    const std::vector<CgLocalPath> pieces = local_plan_batch(
        space_, edges, local_, work_, options_.budget, options_.workers, options_.ranks);
    r_.recreate_seconds += since(t_recreate);
    r_.cells = {s_};
    for (const CgLocalPath& piece : pieces) {
      ++r_.recreate_calls;
      r_.expansions += piece.expansions;
      work_ += piece.expansions;
    }
    for (const CgLocalPath& piece : pieces) {
      if (piece.budget_exceeded) {
        finish(EldershawYimStatus::kBudgetExceeded, budget_message());
        return false;
      }
      if (!piece.found)  // cannot happen: the same search succeeded the other way
        throw SolverError("plan_eldershaw_yim: re-running a roadmap edge failed");
      r_.cells.insert(r_.cells.end(), piece.cells.begin() + 1, piece.cells.end());
    }
    return true;
  }

  /// r finished as found: the CG path's poses, length and message.
  void found_cg_path() {
    r_.path = cg_path_poses(lattice_, r_.cells, start_, goal_);
    r_.length_m = 0.0;
    for (std::size_t k = 1; k < r_.path.size(); ++k)
      r_.length_m += std::hypot(r_.path[k].x - r_.path[k - 1].x, r_.path[k].y - r_.path[k - 1].y);
    std::ostringstream msg;
    msg << (options_.direct ? "direct A*" : "tree-PRM") << ": " << r_.cells.size() << " CG cells";
    if (!options_.direct) msg << " through " << r_.prm_points.size() << " PRM points";
    if (r_.feedback_events > 0) msg << " after " << r_.feedback_events << " feedback events";
    finish(EldershawYimStatus::kFound, msg.str());
  }

  /// The foot plan along r.cells. After feedback (§3.3) the feet keep the steps they took on
  /// the cells the new CG path shares with the old one (`failed_cells`), and walk on from
  /// there; only if that fails is the whole path planned afresh.
  void plan_feet(const std::vector<CgCell>& failed_cells) {
    const std::vector<FootStep> prefix = reusable_steps(failed_cells, r_.foot_plan, r_.cells);
    r_.foot_plan = plan_footsteps(footmap_, robot_, lattice_, r_.cells, options_.feet, prefix);
    r_.foot_planner_seconds += r_.foot_plan.seconds;
    r_.foot_planner_nodes += r_.foot_plan.nodes;
    r_.foot_steps_reused = prefix.empty() ? 0 : prefix.size();
    if (!prefix.empty() && !r_.foot_plan.found()) {
      FootPlan fresh = plan_footsteps(footmap_, robot_, lattice_, r_.cells, options_.feet);
      r_.foot_planner_seconds += fresh.seconds;
      r_.foot_planner_nodes += fresh.nodes;
      if (fresh.found() || fresh.furthest_index > r_.foot_plan.furthest_index) {
        r_.foot_plan = std::move(fresh);
        r_.foot_steps_reused = 0;
      }
    }
    r_.feet_planned = true;
  }

  const LeggedRobot& robot_;
  SE2Pose start_, goal_;
  const EldershawYimPlannerOptions& options_;
  Clock::time_point t_footmap_;
  Footmap footmap_;  // before space_, which refers to it
  double footmap_seconds_;
  Clock::time_point t_search_;
  CgSpace space_;
  const CgLattice& lattice_;
  CgLocalPlannerOptions local_;
  double radius_;
  CgCell s_, g_;
  std::size_t work_ = 0;
  EldershawYimResult r_;
};

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
  return EldershawYimRun(terrain, robot, start, goal, options).run();
}

}  // namespace talus
