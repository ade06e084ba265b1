#include "talus/optimal/global_search.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/graph_search.hpp"
#include "talus/core/memory_budget.hpp"
#include "talus/core/stopwatch.hpp"
#include "talus/dynamics/admissible_set.hpp"

namespace talus {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The largest traction (W_drive) and braking (W_brake) force per unit mass
/// available at a station over its admissible speeds. Along a lifted straight
/// edge |f_q| and R are the same in both directions, so one evaluation serves
/// both: driving forwards a_max = W_drive − g k_t and a_min = −W_brake − g k_t,
/// backwards the sign of k_t flips. The forces are monotone in ṡ² (R and f_q
/// are affine in it), so the extremes sit at the ends of the admissible
/// speeds (the vehicle's traction conditions are linear in R too).
struct TangentialForces {
  double drive = -kInf, brake = -kInf;
};

TangentialForces tangential_forces(const AdmissibleSet& set, const StationGeometry& g,
                                   const SquaredSpeedInterval& window) {
  TangentialForces out;
  for (const double x : {window.lower, window.upper}) {
    const TangentialForceRange f = set.tangential_forces(g, x);
    out.drive = std::max(out.drive, f.upper);
    out.brake = std::max(out.brake, -f.lower);
  }
  return out;
}

/// `braking_rule`: GlobalSearchOptions::braking_rule (rule (c) applied).
EdgeCost edge_cost_impl(const BPatch& terrain, const AdmissibleSet& set, const Vec2& a,
                        const Vec2& b, int stations, const SurfacePoint* at_a,
                        const SurfacePoint* at_b, bool braking_rule = true) {
  const Vec2 d1 = b - a;
  EdgeCost out;
  double forward_sum = 0.0;
  bool forward_ok = true, backward_ok = true;
  for (int k = 0; k < stations; ++k) {
    const double tau = static_cast<double>(k) / (stations - 1);
    const Vec2 p = (k == stations - 1) ? b : Vec2(a + tau * d1);
    if (!terrain.on_data(p)) return {kInf, kInf, kInf};
    const SurfacePoint sp = (k == 0 && at_a)              ? *at_a
                            : (k == stations - 1 && at_b) ? *at_b
                                                          : terrain.evaluate(p);
    const PathFrame f = lift_to_surface(p, sp, d1, Vec2::Zero());
    const StationGeometry g = station_geometry(f, terrain, set.wheels());
    const SquaredSpeedInterval window = set.squared_speeds(g);
    if (window.empty() || !(window.upper > 0.0)) return {kInf, kInf, kInf};
    // Simpson weights 1, 4, 2, 4, ..., 4, 1 (stations is odd).
    const double w = (k == 0 || k == stations - 1) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    forward_sum += w * f.speed / std::sqrt(window.upper);
    out.length += w * f.speed;
    // Forwards: cannot climb if W_drive < g k_t, cannot stop if W_brake < −g k_t.
    const TangentialForces forces = tangential_forces(set, g, window);
    const double weight = set.gravity() * g.k_t;
    if (forces.drive < weight || (braking_rule && forces.brake < -weight)) forward_ok = false;
    if (forces.drive < -weight || (braking_rule && forces.brake < weight)) backward_ok = false;
  }
  const double h = 1.0 / (stations - 1) / 3.0;
  const double time = forward_sum * h;
  out.length *= h;
  out.forward = forward_ok ? time : kInf;
  out.backward = backward_ok ? time : kInf;
  return out;
}

}  // namespace

int edge_stations(double planar_length, double spacing) {
  // Simpson panels at most half a lattice spacing wide (stations a quarter
  // spacing apart): 5 stations for axial and diagonal edges, 9 for knight
  // moves. With panels a whole spacing wide the lattice stepped over an 8 m
  // stretch of Mount St. Helens (30 m cells) where a side slope steeper than
  // atan μ admits no speed, and every corridor it offered was undrivable;
  // at this density every bundled DEM plans with the rover, for about 1.7
  // times the global stage's CPU time (Big Tujunga, 512²: 1.3 → 2.2 s).
  return 2 * std::max(1, static_cast<int>(std::ceil(planar_length / (0.5 * spacing) - 1e-9))) + 1;
}

namespace {

/// Lattice nodes along an extent [m] at `spacing` [m] (the last node within
/// rounding of the far edge): the one rule for the lattice's shape.
std::size_t lattice_nodes_along(double extent, double spacing) {
  return static_cast<std::size_t>(std::floor(extent / spacing + 1e-9)) + 1;
}

/// Neighbour offsets; the first half are "positive" (dy > 0, or dy = 0 and
/// dx > 0) and offset k + half is the negation of offset k.
std::vector<std::pair<int, int>> neighbour_offsets(int connectivity) {
  std::vector<std::pair<int, int>> positive = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}};
  if (connectivity >= 16) {
    for (const auto& o : std::vector<std::pair<int, int>>{{2, 1}, {1, 2}, {-1, 2}, {-2, 1}})
      positive.push_back(o);
  }
  if (connectivity >= 32) {
    for (const auto& o : std::vector<std::pair<int, int>>{
             {3, 1}, {1, 3}, {-1, 3}, {-3, 1}, {3, 2}, {2, 3}, {-2, 3}, {-3, 2}}) {
      positive.push_back(o);
    }
  }
  std::vector<std::pair<int, int>> all = positive;
  for (const auto& [dx, dy] : positive) all.emplace_back(-dx, -dy);
  return all;
}

constexpr std::uint32_t kNoNode = ShortestPathTree::kNone;
/// Side of the corridor's tiles (multi-resolution search) [nodes].
constexpr std::size_t kTile = 16;

/// Which tiles of kTile x kTile nodes a corridor covers, over the full lattice.
struct TileMask {
  std::size_t tx = 0, ty = 0;          ///< tiles per row and column
  std::vector<unsigned char> present;  ///< tx * ty, row-major
  bool all() const {
    return std::all_of(present.begin(), present.end(), [](unsigned char p) { return p != 0; });
  }
};

/// The lattice with lazily computed, cached edge costs in both directions:
/// every node of the grid, or (with a TileMask) only the nodes of a corridor.
/// Corridor nodes are numbered row by row in the full lattice's order (so
/// the searches break ties alike); each row holds its present tiles' kTile
/// nodes, those past the grid's east edge being unused placeholders.
class Lattice {
 public:
  Lattice(const BPatch& terrain, const AdmissibleSet& set, double spacing, int connectivity,
          bool braking_rule, const TileMask* mask = nullptr)
      : terrain_(terrain),
        set_(set),
        spacing_(spacing),
        braking_rule_(braking_rule),
        offsets_(neighbour_offsets(connectivity)) {
    origin_ = Vec2(terrain.x_min(), terrain.y_min());
    nx_ = lattice_nodes_along(terrain.x_max() - terrain.x_min(), spacing);
    ny_ = lattice_nodes_along(terrain.y_max() - terrain.y_min(), spacing);
    if (nx_ < 2 || ny_ < 2) throw InputError("lattice spacing is larger than the terrain");
    if (nx_ * ny_ > 50'000'000) throw InputError("lattice too large: increase --lattice-spacing");
    half_ = offsets_.size() / 2;
    size_ = nx_ * ny_;
    if (mask != nullptr) {
      full_ = false;
      tx_ = mask->tx;
      tile_rank_.assign(mask->present.size(), -1);
      std::vector<std::size_t> per_row(mask->ty, 0);
      for (std::size_t tj = 0; tj < mask->ty; ++tj)
        for (std::size_t ti = 0; ti < mask->tx; ++ti)
          if (mask->present[tj * tx_ + ti]) {
            tile_rank_[tj * tx_ + ti] = static_cast<int>(per_row[tj]++);
          }
      row_start_.assign(ny_ + 1, 0);
      for (std::size_t j = 0; j < ny_; ++j)
        row_start_[j + 1] = row_start_[j] + kTile * per_row[j / kTile];
      size_ = row_start_[ny_];
    }
    // Per node: its surface sample and data flag, both directions' cost of
    // each of its half_ edges, and the searches' fields, labels and queues.
    const double per_node =
        static_cast<double>(sizeof(surface_[0]) + 1 + 16 * half_ + 64 + (full_ ? 0 : 4));
    bytes_ = per_node * static_cast<double>(size_);
    require_memory(bytes_,
                   "the global search's lattice of " + std::to_string(nx_) + " x " +
                       std::to_string(ny_) + " nodes" +
                       (full_ ? std::string() : " (corridor of " + std::to_string(size_) + ")"),
                   "increase the lattice spacing (--lattice-spacing; the default is the cell "
                   "size) or lower the connectivity");
    if (!full_) {
      full_index_.assign(size_, kNoNode);
      for (std::size_t j = 0; j < ny_; ++j)
        for (std::size_t ti = 0; ti < tx_; ++ti) {
          const int rank = tile_rank_[(j / kTile) * tx_ + ti];
          if (rank < 0) continue;
          for (std::size_t i = ti * kTile; i < std::min(nx_, (ti + 1) * kTile); ++i) {
            full_index_[row_start_[j] + static_cast<std::size_t>(rank) * kTile + i % kTile] =
                static_cast<std::uint32_t>(j * nx_ + i);
          }
        }
    }
    surface_.resize(size_);
    on_data_.assign(size_, 0);
    excluded_.assign(size_, 0);
    forward_.assign(size_ * half_, std::numeric_limits<double>::quiet_NaN());
    backward_.assign(size_ * half_, std::numeric_limits<double>::quiet_NaN());
  }

  /// Samples the surface at every node (once: a later call returns true at
  /// once); false if `stop` cut it short (polled every `interval` nodes).
  template <typename Stop>
  bool sample(Stop&& stop, std::size_t interval) {
    if (sampled_) return true;
    for (std::size_t n = 0; n < size_; ++n) {
      if (n % interval == 0 && stop()) return false;
      if (!exists(static_cast<std::uint32_t>(n))) continue;
      const Vec2 p = position(static_cast<std::uint32_t>(n));
      on_data_[n] = terrain_.on_data(p);
      if (on_data_[n]) surface_[n] = terrain_.evaluate(p);
    }
    sampled_ = true;
    return true;
  }

  /// Makes every edge at a node within `regions` untraversable, except at
  /// the nodes `keep_a` and `keep_b`, in place of the previous call's
  /// regions. The edge costs themselves stay cached (a mask, not a cost).
  void exclude(const std::vector<ExcludedRegion>& regions, std::uint32_t keep_a,
               std::uint32_t keep_b) {
    excluded_.assign(size_, 0);
    for (const ExcludedRegion& region : regions) {
      const Vec2 lo =
          (region.centre - origin_) / spacing_ - Vec2::Constant(region.radius / spacing_);
      const Vec2 hi =
          (region.centre - origin_) / spacing_ + Vec2::Constant(region.radius / spacing_);
      for (long j = std::max(0L, static_cast<long>(std::ceil(lo.y())));
           j <= std::min(static_cast<long>(ny_) - 1, static_cast<long>(std::floor(hi.y()))); ++j) {
        for (long i = std::max(0L, static_cast<long>(std::ceil(lo.x())));
             i <= std::min(static_cast<long>(nx_) - 1, static_cast<long>(std::floor(hi.x())));
             ++i) {
          const std::uint32_t n = node_at(i, j);
          if (n == kNoNode || n == keep_a || n == keep_b) continue;
          if ((position(n) - region.centre).norm() <= region.radius) excluded_[n] = 1;
        }
      }
    }
  }

  /// What the lattice holds [bytes] (its memory-budget estimate).
  double bytes() const { return bytes_; }
  std::size_t size() const { return size_; }
  std::size_t nx() const { return nx_; }
  std::size_t ny() const { return ny_; }
  bool full() const { return full_; }
  Vec2 origin() const { return origin_; }
  /// A real node (not a corridor row's placeholder past the grid's edge).
  bool exists(std::uint32_t n) const { return full_ || full_index_[n] != kNoNode; }
  /// Column and row of node n in the full lattice.
  std::pair<long, long> coords(std::uint32_t n) const {
    const std::size_t f = full_ ? n : full_index_[n];
    return {static_cast<long>(f % nx_), static_cast<long>(f / nx_)};
  }
  /// The node at column i, row j; kNoNode off the grid or outside the corridor.
  std::uint32_t node_at(long i, long j) const {
    if (i < 0 || j < 0 || i >= static_cast<long>(nx_) || j >= static_cast<long>(ny_)) {
      return kNoNode;
    }
    const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
    if (full_) return static_cast<std::uint32_t>(uj * nx_ + ui);
    const int rank = tile_rank_[(uj / kTile) * tx_ + ui / kTile];
    if (rank < 0) return kNoNode;
    return static_cast<std::uint32_t>(row_start_[uj] + static_cast<std::size_t>(rank) * kTile +
                                      ui % kTile);
  }
  Vec2 position(std::uint32_t n) const {
    const auto [i, j] = coords(n);
    return origin_ + spacing_ * Vec2(static_cast<double>(i), static_cast<double>(j));
  }
  /// The node nearest to p (kNoNode if it is outside the corridor).
  std::uint32_t nearest(const Vec2& p) const {
    return node_at(
        std::clamp(std::lround((p.x() - origin_.x()) / spacing_), 0L, static_cast<long>(nx_) - 1),
        std::clamp(std::lround((p.y() - origin_.y()) / spacing_), 0L, static_cast<long>(ny_) - 1));
  }
  std::size_t edges_evaluated() const { return evaluated_; }

  /// Calls emit(m, cost) for every finite-cost edge n -> m (forward) or
  /// m -> n (!forward); the node's coordinates are computed once.
  template <typename Emit>
  void for_each_edge(std::uint32_t n, bool forward, Emit&& emit) {
    const auto [i, j] = coords(n);
    for (std::size_t k = 0; k < offsets_.size(); ++k) {
      const auto [dx, dy] = offsets_[k];
      const std::uint32_t m = node_at(i + dx, j + dy);
      if (m == kNoNode) continue;
      // Offset k < half is the positive edge n -> m; else m -> n is positive.
      const std::pair<double, double> c = k < half_ ? ensure(n, m, k) : ensure(m, n, k - half_);
      const double cost = (k < half_) == forward ? c.first : c.second;
      if (cost < kInf) emit(m, cost);
    }
  }
  /// Cost of the directed edge from n along offset k (+inf if none); its end in `*to`.
  double cost(std::uint32_t n, std::size_t k, std::uint32_t* to = nullptr) {
    const std::uint32_t m = neighbour(n, k);
    if (to != nullptr) *to = m;
    if (m == kNoNode) return kInf;
    if (k < half_) return ensure(n, m, k).first;
    return ensure(m, n, k - half_).second;  // m -> n is positive: n -> m is its backward
  }
  /// Cost of the directed edge into n from its neighbour along offset k (in `*from`).
  double cost_into(std::uint32_t n, std::size_t k, std::uint32_t* from = nullptr) {
    const std::uint32_t m = neighbour(n, k);
    if (from != nullptr) *from = m;
    if (m == kNoNode) return kInf;
    if (k < half_) return ensure(n, m, k).second;  // m -> n is the backward of n -> m
    return ensure(m, n, k - half_).first;
  }
  /// The neighbour of n along offset k; kNoNode off the grid or the corridor.
  std::uint32_t neighbour(std::uint32_t n, std::size_t k) const {
    const auto [dx, dy] = offsets_[k];
    const auto [i, j] = coords(n);
    return node_at(i + dx, j + dy);
  }
  /// Some neighbour of n is on the grid but outside the corridor.
  bool on_corridor_edge(std::uint32_t n) const {
    if (full_) return false;
    const auto [i, j] = coords(n);
    for (const auto& [dx, dy] : offsets_) {
      const long a = i + dx, b = j + dy;
      if (a >= 0 && b >= 0 && a < static_cast<long>(nx_) && b < static_cast<long>(ny_) &&
          node_at(a, b) == kNoNode) {
        return true;
      }
    }
    return false;
  }
  std::size_t offsets() const { return offsets_.size(); }
  /// Offset k as a planar vector [lattice spacings].
  Vec2 offset(std::size_t k) const {
    return Vec2(static_cast<double>(offsets_[k].first), static_cast<double>(offsets_[k].second));
  }
  /// The offset opposite to k (offset k + half is the negation of offset k).
  std::size_t opposite(std::size_t k) const { return k < half_ ? k + half_ : k - half_; }
  bool on_data(std::uint32_t n) const { return on_data_[n] != 0; }

  /// Stations of an edge of planar length L: at most half a spacing apart, odd count.
  int stations_for(double planar_length) const { return edge_stations(planar_length, spacing_); }

  /// Computes the costs of every positive edge of nodes [begin, end) that
  /// the searches would otherwise compute lazily, on `threads` threads
  /// (>= 1): chunks of consecutive nodes are handed out in turn, and each
  /// edge's slot is written by the one thread that owns its first node, so
  /// the costs are those of a serial run, whatever the thread count.
  void evaluate_edges(std::size_t begin, std::size_t end, std::size_t threads) {
    constexpr std::size_t kChunk = 64;  // nodes: big enough that slots seldom share cache lines
    std::atomic<std::size_t> next{begin}, evaluated{0};
    const auto work = [&] {
      std::size_t count = 0;
      for (std::size_t first = next.fetch_add(kChunk); first < end;
           first = next.fetch_add(kChunk)) {
        for (std::size_t n = first; n < std::min(end, first + kChunk); ++n) {
          const auto a = static_cast<std::uint32_t>(n);
          if (!exists(a)) continue;
          const auto [i, j] = coords(a);
          for (std::size_t k = 0; k < half_; ++k) {
            const std::uint32_t b = node_at(i + offsets_[k].first, j + offsets_[k].second);
            if (b != kNoNode && !excluded_[a] && !excluded_[b]) count += compute(a, b, k) ? 1 : 0;
          }
        }
      }
      evaluated += count;
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    evaluated_ += evaluated;
  }

 private:
  /// Computes the slot of the positive edge a -> b (offset k < half) unless
  /// it is already known; true if it computed it.
  bool compute(std::uint32_t a, std::uint32_t b, std::size_t k) {
    const std::size_t slot = static_cast<std::size_t>(a) * half_ + k;
    if (!std::isnan(forward_[slot])) return false;
    EdgeCost c{kInf, kInf, kInf};
    if (on_data_[a] && on_data_[b]) {
      const Vec2 pa = position(a), pb = position(b);
      c = edge_cost_impl(terrain_, set_, pa, pb, stations_for((pb - pa).norm()), &surface_[a],
                         &surface_[b], braking_rule_);
    }
    forward_[slot] = c.forward;
    backward_[slot] = c.backward;
    return true;
  }

  /// Forward/backward costs of the positive edge a -> b (offset k < half);
  /// +inf both ways at an excluded node.
  std::pair<double, double> ensure(std::uint32_t a, std::uint32_t b, std::size_t k) {
    if (excluded_[a] || excluded_[b]) return {kInf, kInf};  // not computed: no search needs it
    evaluated_ += compute(a, b, k) ? 1 : 0;
    const std::size_t slot = static_cast<std::size_t>(a) * half_ + k;
    return {forward_[slot], backward_[slot]};
  }

  const BPatch& terrain_;
  double bytes_ = 0.0;
  const AdmissibleSet& set_;
  double spacing_;
  bool braking_rule_;
  std::vector<std::pair<int, int>> offsets_;
  std::size_t half_ = 0, nx_ = 0, ny_ = 0, size_ = 0;
  Vec2 origin_;
  // The corridor (full_ = false): rank of each tile among its tile row's
  // present tiles (-1 absent), first node of each grid row, full-lattice
  // index of each node.
  bool full_ = true;
  std::size_t tx_ = 0;
  std::vector<int> tile_rank_;
  std::vector<std::size_t> row_start_;
  std::vector<std::uint32_t> full_index_;
  std::vector<SurfacePoint> surface_;
  bool sampled_ = false;
  std::vector<unsigned char> on_data_, excluded_;
  std::vector<double> forward_, backward_;
  std::size_t evaluated_ = 0;
};

/// The graph the searches run on. Position only: the lattice's nodes. With a
/// turn limit (GlobalSearchOptions::turn_limit): states (node, the offset it
/// was reached along), plus one free state per node that only the start (the
/// source: no arrival direction) and the goal (the target: reached from every
/// arrival direction at no cost) use; a state continues along an offset only
/// when the turn from its arrival fits the limit.
class RouteGraph {
 public:
  RouteGraph(Lattice& lattice, double max_curvature, double spacing, std::uint32_t start,
             std::uint32_t goal)
      : lattice_(lattice), start_(start), goal_(goal) {
    if (!std::isfinite(max_curvature)) return;
    const std::size_t k = lattice.offsets();
    slots_ = k + 1;
    // Two trees (cost, parent, closed flag: 13 bytes a state) and their queues.
    require_memory(32.0 * static_cast<double>(lattice.size() * slots_),
                   "the turn-limited global search (" + std::to_string(lattice.size() * slots_) +
                       " (node, arrival direction) states)",
                   "use a coarser lattice spacing, the multi resolution or no turn limit");
    allowed_.assign(k * k, 0);
    for (std::size_t in = 0; in < k; ++in) {
      for (std::size_t out = 0; out < k; ++out) {
        const Vec2 a = lattice.offset(in), b = lattice.offset(out);
        const double turn = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
        const double half_edge = 0.5 * spacing * std::min(a.norm(), b.norm());
        allowed_[in * k + out] =
            std::tan(0.5 * std::abs(turn)) <= max_curvature * half_edge * (1.0 + 1e-12);
      }
    }
  }

  std::size_t states() const { return lattice_.size() * slots_; }
  std::uint32_t node(std::uint32_t state) const {
    return static_cast<std::uint32_t>(state / slots_);
  }
  std::uint32_t start() const { return at(start_, free_slot()); }
  std::uint32_t goal() const { return at(goal_, free_slot()); }

  /// Calls emit(next, cost) for every finite-cost edge out of `state`.
  template <typename Emit>
  void forward(std::uint32_t state, Emit&& emit) const {
    const std::uint32_t n = node(state);
    if (slots_ == 1) return lattice_.for_each_edge(n, true, emit);
    const std::size_t arrival = state % slots_, k = lattice_.offsets();
    if (arrival == free_slot() && n != start_) return;  // the goal's: the search ends there
    for (std::size_t out = 0; out < k; ++out) {
      if (arrival != free_slot() && !allowed_[arrival * k + out]) continue;
      std::uint32_t m = kNoNode;
      const double c = lattice_.cost(n, out, &m);
      if (c < kInf) emit(at(m, out), c);
    }
    if (n == goal_ && arrival != free_slot()) emit(goal(), 0.0);
  }

  /// Calls emit(previous, cost) for every finite-cost edge into `state`.
  template <typename Emit>
  void reverse(std::uint32_t state, Emit&& emit) const {
    const std::uint32_t n = node(state);
    if (slots_ == 1) return lattice_.for_each_edge(n, false, emit);
    const std::size_t arrival = state % slots_, k = lattice_.offsets();
    if (arrival == free_slot()) {
      if (n == goal_)
        for (std::size_t in = 0; in < k; ++in) emit(at(n, in), 0.0);
      return;
    }
    std::uint32_t p = kNoNode;
    const double c = lattice_.cost_into(n, lattice_.opposite(arrival), &p);
    if (!(c < kInf)) return;
    for (std::size_t in = 0; in < k; ++in)
      if (allowed_[in * k + arrival]) emit(at(p, in), c);
    if (p == start_) emit(at(p, free_slot()), c);
  }

  /// A node's best over its states.
  std::vector<double> node_field(const std::vector<double>& state_cost) const {
    std::vector<double> out(lattice_.size(), kInf);
    for (std::size_t st = 0; st < state_cost.size(); ++st)
      out[st / slots_] = std::min(out[st / slots_], state_cost[st]);
    return out;
  }

  /// The nodes of a state path, a node repeated by the goal's free state once.
  std::vector<std::uint32_t> nodes(const std::vector<std::uint32_t>& states) const {
    std::vector<std::uint32_t> out;
    for (const std::uint32_t st : states)
      if (out.empty() || out.back() != node(st)) out.push_back(node(st));
    return out;
  }

 private:
  std::size_t free_slot() const { return slots_ - 1; }
  std::uint32_t at(std::uint32_t n, std::size_t slot) const {
    return static_cast<std::uint32_t>(n * slots_ + slot);
  }

  Lattice& lattice_;
  std::uint32_t start_, goal_;
  std::size_t slots_ = 1;
  std::vector<unsigned char> allowed_;  ///< [arrival * offsets + departure]
};

/// 3-D length on the surface of a lattice polyline, by the edges' own quadrature.
double surface_length(const BPatch& terrain, const AdmissibleSet& set,
                      const std::vector<Vec2>& vertices, double spacing) {
  double length = 0.0;
  for (std::size_t k = 0; k + 1 < vertices.size(); ++k) {
    const Vec2 a = vertices[k], b = vertices[k + 1];
    length +=
        edge_cost_impl(terrain, set, a, b, edge_stations((b - a).norm(), spacing), nullptr, nullptr)
            .length;
  }
  return length;
}

/// Distance [m] from every lattice node to the nearest of `sources`, by the
/// two-pass chamfer transform with steps h and h sqrt(2) (in a corridor:
/// through its nodes only).
std::vector<float> chamfer_distance(const std::vector<std::uint32_t>& sources,
                                    const Lattice& lattice, double spacing) {
  const float straight = static_cast<float>(spacing);
  const float diagonal = static_cast<float>(spacing * std::sqrt(2.0));
  const std::size_t n = lattice.size();
  std::vector<float> d(n, std::numeric_limits<float>::infinity());
  for (std::uint32_t s : sources) d[s] = 0.0f;
  const auto relax = [&](std::uint32_t node, long i, long j, long di, long dj, float step) {
    const std::uint32_t other = lattice.node_at(i + di, j + dj);
    if (other == kNoNode) return;
    float& here = d[node];
    here = std::min(here, d[other] + step);
  };
  for (std::uint32_t node = 0; node < n; ++node) {
    if (!lattice.exists(node)) continue;
    const auto [i, j] = lattice.coords(node);
    relax(node, i, j, -1, 0, straight);
    relax(node, i, j, 0, -1, straight);
    relax(node, i, j, -1, -1, diagonal);
    relax(node, i, j, 1, -1, diagonal);
  }
  for (std::uint32_t node = static_cast<std::uint32_t>(n); node-- > 0;) {
    if (!lattice.exists(node)) continue;
    const auto [i, j] = lattice.coords(node);
    relax(node, i, j, 1, 0, straight);
    relax(node, i, j, 0, 1, straight);
    relax(node, i, j, 1, 1, diagonal);
    relax(node, i, j, -1, 1, diagonal);
  }
  return d;
}

}  // namespace

void GlobalSearchOptions::validate() const {
  for (const ExcludedRegion& region : excluded) {
    if (!(region.centre.allFinite() && std::isfinite(region.radius) && region.radius > 0.0)) {
      throw InputError(
          "GlobalSearchOptions.excluded: every region needs a finite centre and a finite radius "
          "> 0 [m]");
    }
  }
  if (!(lattice_spacing >= 0.0) || !std::isfinite(lattice_spacing)) {
    throw InputError("GlobalSearchOptions.lattice_spacing must be >= 0 (0 = cell size), got " +
                     std::to_string(lattice_spacing));
  }
  if (connectivity != 8 && connectivity != 16 && connectivity != 32) {
    throw InputError("GlobalSearchOptions.connectivity must be 8, 16 or 32, got " +
                     std::to_string(connectivity));
  }
  if (candidates < 1) throw InputError("GlobalSearchOptions.candidates must be >= 1");
  if (!(distinctness >= 0.0)) throw InputError("GlobalSearchOptions.distinctness must be >= 0");
  if (!(max_cost_ratio >= 1.0)) throw InputError("GlobalSearchOptions.max_cost_ratio must be >= 1");
  if (resolution != GlobalSearchResolution::kFull && resolution != GlobalSearchResolution::kMulti &&
      resolution != GlobalSearchResolution::kAuto) {
    throw InputError("GlobalSearchOptions.resolution is not a GlobalSearchResolution");
  }
  if (coarse_factor < 2) {
    throw InputError("GlobalSearchOptions.coarse_factor must be >= 2, got " +
                     std::to_string(coarse_factor));
  }
  if (!(corridor_width >= 0.0) || !std::isfinite(corridor_width)) {
    throw InputError("GlobalSearchOptions.corridor_width must be a finite number >= 0 [m]");
  }
  if (stop_interval < 1) throw InputError("GlobalSearchOptions.stop_interval must be >= 1");
  if (threads > 1024) throw InputError("GlobalSearchOptions.threads must be at most 1024");
}

std::string_view to_string(GlobalSearchResolution resolution) {
  switch (resolution) {
    case GlobalSearchResolution::kFull:
      return "full";
    case GlobalSearchResolution::kMulti:
      return "multi";
    case GlobalSearchResolution::kAuto:
      return "auto";
  }
  return "unknown";
}

GlobalSearchResolution parse_global_search_resolution(std::string_view name) {
  if (name == "full") return GlobalSearchResolution::kFull;
  if (name == "multi") return GlobalSearchResolution::kMulti;
  if (name == "auto") return GlobalSearchResolution::kAuto;
  throw InputError("unknown global search resolution '" + std::string(name) +
                   "': choose auto, full or multi");
}

std::string_view to_string(GlobalSearchStatus status) {
  switch (status) {
    case GlobalSearchStatus::kOk:
      return "ok";
    case GlobalSearchStatus::kUnreachable:
      return "unreachable";
    case GlobalSearchStatus::kStopped:
      return "stopped";
  }
  return "unknown";
}

EdgeCost edge_cost(const BPatch& terrain, const Vehicle& vehicle, const Vec2& a, const Vec2& b,
                   int stations) {
  if (stations < 3 || stations % 2 == 0)
    throw InputError("edge_cost: stations must be odd and >= 3");
  if (!terrain.contains(a) || !terrain.contains(b))
    throw InputError("edge_cost: edge leaves the terrain");
  return edge_cost_impl(terrain, AdmissibleSet(vehicle), a, b, stations, nullptr, nullptr);
}

namespace {

/// One search of one lattice: its result as it grows, and the steps that grow it.
class LatticeSearch {
 public:
  LatticeSearch(const BPatch& terrain, const AdmissibleSet& set, const GlobalSearchOptions& options,
                double spacing, Lattice& lattice)
      : t0_(std::chrono::steady_clock::now()),
        terrain_(terrain),
        set_(set),
        options_(options),
        spacing_(spacing),
        lattice_(lattice),
        evaluated_before_(lattice.edges_evaluated()) {
    result_.nodes = lattice.size();
    result_.nx = lattice.nx();
    result_.ny = lattice.ny();
    result_.spacing = spacing;
    result_.origin = lattice.origin();
  }

  bool stop() const {
    reason_ = options_.termination.check();
    return reason_ != TerminationReason::kNone;
  }
  GlobalSearchResult& result() { return result_; }
  /// The graph's edges out of (forward) or into (reverse) a state, for shortest_paths.
  static auto forward(const RouteGraph& graph) {
    return [&graph](std::uint32_t state, auto&& emit) { graph.forward(state, emit); };
  }
  static auto reverse(const RouteGraph& graph) {
    return [&graph](std::uint32_t state, auto&& emit) { graph.reverse(state, emit); };
  }

  GlobalSearchResult finish(GlobalSearchStatus status, std::string message) {
    result_.status = status;
    result_.message = std::move(message);
    result_.edges_evaluated = lattice_.edges_evaluated() - evaluated_before_;
    result_.search_seconds = seconds_since(t0_);
    return std::move(result_);
  }

  GlobalSearchResult stopped(const char* phase) {
    std::ostringstream msg;
    msg << "stopped by GlobalSearchOptions::termination (" << to_string(reason_) << ") while "
        << phase << " (" << result_.expanded << " nodes expanded); " << result_.candidates.size()
        << " candidate" << (result_.candidates.size() == 1 ? "" : "s") << " found by then";
    return finish(GlobalSearchStatus::kStopped, msg.str());
  }

  void add_candidate(const std::vector<std::uint32_t>& ids, double cost) {
    CandidatePath candidate;
    for (std::uint32_t id : ids) candidate.vertices.push_back(lattice_.position(id));
    candidate.cost_seconds = cost;
    candidate.length_m = surface_length(terrain_, set_, candidate.vertices, spacing_);
    result_.candidates.push_back(std::move(candidate));
  }

  /// The unreachable result when no edge leaves the start node or none enters
  /// the goal node (an expected outcome on steep ground, not bad input), with
  /// the reason; empty otherwise.
  std::optional<GlobalSearchResult> untraversable_end(std::uint32_t s, std::uint32_t g) {
    for (const auto& [which, node] : {std::pair{"start", s}, std::pair{"goal", g}}) {
      const bool from = std::strcmp(which, "start") == 0;
      bool any = false;
      for (std::size_t k = 0; k < lattice_.offsets() && !any; ++k)
        any = from ? lattice_.cost(node, k) < kInf : lattice_.cost_into(node, k) < kInf;
      if (any) continue;
      std::ostringstream msg;
      msg.precision(12);
      const Vec2 p = lattice_.position(node);
      msg << which << " node (" << p.x() << ", " << p.y()
          << ") is on untraversable terrain: every lattice edge " << (from ? "from" : "into")
          << " it is too steep or unstable for the vehicle";
      return finish(GlobalSearchStatus::kUnreachable, msg.str());
    }
    return std::nullopt;
  }

  /// Both cost fields reach every edge of the reachable lattice: computes
  /// them all up front on the threads, `stop` polled (on this thread only, as
  /// the searches do) between batches of stop_interval nodes per thread.
  /// False when stopped.
  bool evaluate_edges_up_front(std::size_t threads) {
    const std::size_t n = lattice_.size();
    const std::size_t batch = options_.stop_interval * threads;
    for (std::size_t begin = 0; begin < n; begin += batch) {
      if (stop()) return false;
      lattice_.evaluate_edges(begin, std::min(n, begin + batch), threads);
    }
    return true;
  }

  /// One candidate: A* from the start to the goal.
  GlobalSearchResult single_route(const RouteGraph& graph, double max_speed) {
    const std::uint32_t g = graph.goal();
    const Vec2 goal_position = lattice_.position(graph.node(g));
    const double inverse_speed = 1.0 / max_speed;
    const ShortestPathTree tree = shortest_paths(
        graph.states(), graph.start(), forward(graph), g,
        [&](std::uint32_t state) {
          return (lattice_.position(graph.node(state)) - goal_position).norm() *
                 inverse_speed;  // 3-D length >= planar
        },
        [this] { return stop(); }, options_.stop_interval);
    result_.expanded = tree.expanded;
    result_.reachable_nodes = tree.expanded;
    // A* finds no path before it expands the goal.
    if (tree.stopped) return stopped("searching (A*) from the start");
    if (!(tree.cost[g] < kInf)) {
      return finish(GlobalSearchStatus::kUnreachable,
                    "goal unreachable: the search exhausted the " + std::to_string(tree.expanded) +
                        " lattice nodes reachable from the start without finding it");
    }
    add_candidate(graph.nodes(tree.path_to(g)), tree.cost[g]);
    return finish(GlobalSearchStatus::kOk, "");
  }

  /// The cost fields from the start and to the goal, then up to `candidates`
  /// distinct routes through the nodes in increasing order of their cost.
  GlobalSearchResult cost_fields_and_candidates(const RouteGraph& graph) {
    const std::size_t n = graph.states();
    const std::uint32_t s = graph.start(), g = graph.goal();
    const auto polled = [this] { return stop(); };
    const ShortestPathTree from_start =
        shortest_paths(n, s, forward(graph), ShortestPathTree::kNone, NoHeuristic{}, polled,
                       options_.stop_interval);
    result_.expanded += from_start.expanded;
    std::vector<double> node_cost = graph.node_field(from_start.cost);
    result_.reachable_nodes = static_cast<std::size_t>(
        std::count_if(node_cost.begin(), node_cost.end(), [](double c) { return c < kInf; }));
    if (from_start.stopped) {
      // A tentative cost is that of the real path path_to returns.
      if (from_start.cost[g] < kInf)
        add_candidate(graph.nodes(from_start.path_to(g)), from_start.cost[g]);
      return stopped("computing the cost field from the start");
    }
    if (!(from_start.cost[g] < kInf)) return unreachable(std::move(node_cost));
    const ShortestPathTree to_goal = shortest_paths(n, g, reverse(graph), ShortestPathTree::kNone,
                                                    NoHeuristic{}, polled, options_.stop_interval);
    result_.expanded += to_goal.expanded;
    if (to_goal.stopped || stop()) {
      add_candidate(graph.nodes(from_start.path_to(g)), from_start.cost[g]);
      return stopped(to_goal.stopped ? "computing the cost field to the goal"
                                     : "ordering the candidate seeds");
    }
    if (!extract_candidates(graph, from_start, to_goal)) return stopped("extracting candidates");
    if (lattice_.full()) {
      result_.cost_from_start = std::move(node_cost);
      result_.cost_to_goal = graph.node_field(to_goal.cost);
    }
    // The best route touching the corridor's edge: a better one may lie outside.
    result_.corridor_width = 0.0;
    if (!lattice_.full()) {
      for (const std::uint32_t id : graph.nodes(from_start.path_to(g))) {
        if (lattice_.on_corridor_edge(id)) {
          result_.corridor_width = -1.0;  // flag for the caller
          break;
        }
      }
    }
    return finish(GlobalSearchStatus::kOk, "");
  }

 private:
  GlobalSearchResult unreachable(std::vector<double> node_cost) {
    const std::size_t n = lattice_.size();
    std::ostringstream msg;
    msg << "goal unreachable: from the start the vehicle can reach " << result_.reachable_nodes
        << " of " << n << " lattice nodes ("
        << 100.0 * static_cast<double>(result_.reachable_nodes) / static_cast<double>(n)
        << " % of the " << (lattice_.full() ? "terrain" : "corridor")
        << "), and the goal is not among them";
    if (lattice_.full()) result_.cost_from_start = std::move(node_cost);
    return finish(GlobalSearchStatus::kUnreachable, msg.str());
  }

  /// Candidates: states in increasing order of the best cost through them; each
  /// state's path (start tree + goal tree) is accepted if it is far enough, in
  /// Hausdorff distance, from every accepted one. False when stopped.
  bool extract_candidates(const RouteGraph& graph, const ShortestPathTree& from_start,
                          const ShortestPathTree& to_goal) {
    const std::size_t n = graph.states();
    const double best = from_start.cost[graph.goal()];
    const double separation =
        options_.distinctness > 0.0
            ? options_.distinctness
            : default_candidate_separation(result_.start_node, result_.goal_node, spacing_);
    // The seeds (every state within max_cost_ratio of the best: on open ground most of
    // them) and a distance map per further candidate, checked against the budget first.
    const auto seed = [&](std::uint32_t k) {
      return from_start.cost[k] + to_goal.cost[k] <= best * options_.max_cost_ratio * (1 + 1e-12);
    };
    std::size_t seed_count = 0;
    for (std::uint32_t k = 0; k < n; ++k) seed_count += seed(k) ? 1 : 0;
    // Held together with the lattice and both trees (13 bytes a state each).
    require_memory(lattice_.bytes() + 26.0 * static_cast<double>(n) +
                       4.0 * static_cast<double>(seed_count) +
                       (4.0 * static_cast<double>(options_.candidates) + 1.0) *
                           static_cast<double>(lattice_.size()),
                   "the global search's candidate extraction (" + std::to_string(seed_count) +
                       " seed states, " + std::to_string(lattice_.size()) + " lattice nodes)",
                   "increase the lattice spacing (--lattice-spacing; the default is the cell "
                   "size) or ask for fewer candidates");
    std::vector<std::uint32_t> order;
    order.reserve(seed_count);
    for (std::uint32_t k = 0; k < n; ++k)
      if (seed(k)) order.push_back(k);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      const double ca = from_start.cost[a] + to_goal.cost[a],
                   cb = from_start.cost[b] + to_goal.cost[b];
      return ca != cb ? ca < cb : a < b;  // ties by node id: deterministic
    });
    // Each accepted candidate gets a lattice distance map (chamfer transform,
    // within 8 % of the Euclidean distance), so testing a seed and its path is
    // O(path length) instead of O(path length^2).
    std::vector<std::vector<float>> distance_maps;
    // Nodes on a path already examined would mostly grow the same path again.
    std::vector<unsigned char> examined(lattice_.size(), 0);
    std::size_t seeds = 0;
    for (const std::uint32_t state : order) {
      if (result_.candidates.size() >= options_.candidates) break;
      const std::uint32_t node = graph.node(state);
      if (examined[node]) continue;
      if (++seeds % options_.stop_interval == 0 && stop()) return false;
      bool near = false;
      for (const std::vector<float>& d : distance_maps) near = near || d[node] < separation;
      if (near) continue;
      std::vector<std::uint32_t> states = from_start.path_to(state);
      for (std::uint32_t m = to_goal.parent[state]; m != ShortestPathTree::kNone;
           m = to_goal.parent[m])
        states.push_back(m);
      const std::vector<std::uint32_t> ids = graph.nodes(states);
      for (std::uint32_t id : ids) examined[id] = 1;
      if (!distinct(ids, distance_maps, separation)) continue;
      add_candidate(ids, from_start.cost[state] + to_goal.cost[state]);
      if (result_.candidates.size() < options_.candidates) {
        if (stop()) return false;
        distance_maps.push_back(chamfer_distance(ids, lattice_, spacing_));
      }
    }
    return true;
  }

  /// Distinct from an accepted candidate = somewhere at least `separation`
  /// away from it AND at most half of the path within separation / 2 of it:
  /// without the second rule the best corridor with one bulge passed as an
  /// alternative route.
  static bool distinct(const std::vector<std::uint32_t>& ids,
                       const std::vector<std::vector<float>>& distance_maps, double separation) {
    bool out = true;
    for (const std::vector<float>& d : distance_maps) {
      float farthest = 0.0f;
      std::size_t shared = 0;
      for (std::uint32_t id : ids) {
        farthest = std::max(farthest, d[id]);
        shared += d[id] < 0.5 * separation;
      }
      out = out && farthest >= separation && 2 * shared <= ids.size();
    }
    return out;
  }

  std::chrono::steady_clock::time_point t0_;
  mutable TerminationReason reason_ = TerminationReason::kNone;
  const BPatch& terrain_;
  const AdmissibleSet& set_;
  const GlobalSearchOptions& options_;
  double spacing_;
  Lattice& lattice_;
  std::size_t evaluated_before_;
  GlobalSearchResult result_;
};

/// The search of one lattice: the whole grid, or the corridor `mask`.
/// An untraversable start or goal node is an unreachable result naming it.
/// `cached`: a whole-map lattice at `spacing` whose samples and costs a
/// workspace keeps (mask is then null), or null for a lattice of this search.
GlobalSearchResult search_lattice(const BPatch& terrain, const Vehicle& vehicle,
                                  const AdmissibleSet& set, const Vec2& start, const Vec2& goal,
                                  const GlobalSearchOptions& options, double spacing,
                                  const TileMask* mask, Lattice* cached = nullptr) {
  std::optional<Lattice> own;
  Lattice& lattice = cached != nullptr ? *cached
                                       : own.emplace(terrain, set, spacing, options.connectivity,
                                                     options.braking_rule, mask);
  LatticeSearch search(terrain, set, options, spacing, lattice);
  const std::uint32_t s = lattice.nearest(start), g = lattice.nearest(goal);
  if (s == kNoNode || g == kNoNode) {
    throw InputError("global search: the corridor misses the start or goal node");  // a bug
  }
  search.result().start_node = lattice.position(s);
  search.result().goal_node = lattice.position(g);
  if (!lattice.sample([&search] { return search.stop(); }, options.stop_interval))
    return search.stopped("sampling the surface");
  lattice.exclude(options.excluded, s, g);
  if (std::optional<GlobalSearchResult> closed = search.untraversable_end(s, g))
    return std::move(*closed);
  const std::size_t threads =
      options.threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : options.threads;
  if (threads > 1 && (options.cost_fields || options.candidates > 1) &&
      !search.evaluate_edges_up_front(threads))
    return search.stopped("computing the edge costs");
  const auto route = [&](LatticeSearch& on, double max_curvature) {
    const RouteGraph graph(lattice, max_curvature, spacing, s, g);
    if (!options.cost_fields && options.candidates == 1)
      return on.single_route(graph, vehicle.max_speed);
    return on.cost_fields_and_candidates(graph);
  };
  const double max_curvature = options.turn_limit ? vehicle.max_curvature() : kInf;
  GlobalSearchResult result = route(search, max_curvature);
  if (result.status != GlobalSearchStatus::kUnreachable || !std::isfinite(max_curvature))
    return result;
  // The turn rule is only sufficient: without it the goal may be reachable by a route that
  // the local stage can still smooth within the steering limit.
  LatticeSearch position_only(terrain, set, options, spacing, lattice);
  position_only.result().start_node = result.start_node;
  position_only.result().goal_node = result.goal_node;
  GlobalSearchResult relaxed = route(position_only, kInf);
  relaxed.expanded += result.expanded;
  relaxed.edges_evaluated += result.edges_evaluated;
  relaxed.search_seconds += result.search_seconds;
  relaxed.turn_limit_relaxed = true;
  if (relaxed.status == GlobalSearchStatus::kOk) {
    relaxed.message = "no route keeps its turns within the steering limit at every lattice node (" +
                      result.message + "): the candidates are the position-only search's";
  }
  return relaxed;
}

/// The tiles within `radius` [m] of the candidates' vertices and edges, and
/// of the start and goal, on the lattice of `nx` x `ny` nodes at `spacing`.
TileMask corridor_tiles(const std::vector<CandidatePath>& candidates, const Vec2& start,
                        const Vec2& goal, const Vec2& origin, std::size_t nx, std::size_t ny,
                        double spacing, double radius) {
  TileMask mask;
  mask.tx = (nx + kTile - 1) / kTile;
  mask.ty = (ny + kTile - 1) / kTile;
  mask.present.assign(mask.tx * mask.ty, 0);
  const double tile = spacing * static_cast<double>(kTile);
  const auto mark_disc = [&](const Vec2& p) {
    // Tiles span [t * tile, (t + 1) * tile) of node coordinates from the origin.
    const Vec2 q = (p - origin) / tile;
    const double r = radius / tile;
    const long i0 = std::max(0L, static_cast<long>(std::floor(q.x() - r)));
    const long i1 =
        std::min(static_cast<long>(mask.tx) - 1, static_cast<long>(std::floor(q.x() + r)));
    const long j0 = std::max(0L, static_cast<long>(std::floor(q.y() - r)));
    const long j1 =
        std::min(static_cast<long>(mask.ty) - 1, static_cast<long>(std::floor(q.y() + r)));
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) {
        // Distance from q to the tile [i, i + 1) x [j, j + 1).
        const double dx = std::max({0.0, static_cast<double>(i) - q.x(), q.x() - (i + 1.0)});
        const double dy = std::max({0.0, static_cast<double>(j) - q.y(), q.y() - (j + 1.0)});
        if (dx * dx + dy * dy <= r * r) {
          mask.present[static_cast<std::size_t>(j) * mask.tx + static_cast<std::size_t>(i)] = 1;
        }
      }
  };
  mark_disc(start);
  mark_disc(goal);
  const double step = 0.25 * tile;
  for (const CandidatePath& c : candidates) {
    for (std::size_t k = 0; k + 1 < c.vertices.size(); ++k) {
      const Vec2 a = c.vertices[k], b = c.vertices[k + 1];
      const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
      for (int p = 0; p < pieces; ++p) mark_disc(a + (b - a) * (static_cast<double>(p) / pieces));
    }
    if (!c.vertices.empty()) mark_disc(c.vertices.back());
  }
  return mask;
}

}  // namespace

struct GlobalSearchWorkspace::Impl {
  // The lattices' terrain (a copy shares its coefficients, so the lattices
  // never outlive it), recognised by its identity().
  std::optional<BPatch> terrain;
  std::optional<Vehicle> vehicle;
  int connectivity = 0;
  bool braking_rule = true;
  std::unique_ptr<AdmissibleSet> set;                                 // the lattices refer to it
  std::vector<std::pair<double, std::unique_ptr<Lattice>>> lattices;  // by spacing

  /// Drops the lattices unless they were made for these.
  void bind(const BPatch& t, const Vehicle& v, const GlobalSearchOptions& options) {
    if (terrain && terrain->identity() == t.identity() && vehicle && *vehicle == v &&
        connectivity == options.connectivity && braking_rule == options.braking_rule) {
      return;
    }
    lattices.clear();
    set = std::make_unique<AdmissibleSet>(v);
    terrain = t;
    vehicle = v;
    connectivity = options.connectivity;
    braking_rule = options.braking_rule;
  }
  /// The whole-map lattice at `spacing`, made on first use.
  Lattice& lattice(double spacing) {
    for (auto& [s, l] : lattices)
      if (s == spacing) return *l;
    auto made = std::make_unique<Lattice>(*terrain, *set, spacing, connectivity, braking_rule);
    lattices.emplace_back(spacing, std::move(made));
    return *lattices.back().second;
  }
};

GlobalSearchWorkspace::GlobalSearchWorkspace() : impl_(std::make_unique<Impl>()) {}
GlobalSearchWorkspace::~GlobalSearchWorkspace() = default;
GlobalSearchWorkspace::GlobalSearchWorkspace(GlobalSearchWorkspace&&) noexcept = default;
GlobalSearchWorkspace& GlobalSearchWorkspace::operator=(GlobalSearchWorkspace&&) noexcept = default;
std::size_t GlobalSearchWorkspace::lattices() const {
  return impl_ ? impl_->lattices.size() : 0;
}
void GlobalSearchWorkspace::clear() {
  if (impl_) impl_->lattices.clear();
}

namespace {

/// InputError unless `vehicle` has a finite top speed and `start` and `goal` are on data.
void check_search_inputs(const BPatch& terrain, const Vehicle& vehicle, const Vec2& start,
                         const Vec2& goal) {
  if (!std::isfinite(vehicle.max_speed)) {
    throw InputError(
        "the global search needs a vehicle with a finite max_speed: its cost is the time "
        "at the speed limit, and an unlimited straight road would cost nothing");
  }
  for (const auto& [which, p] : {std::pair{"start", start}, std::pair{"goal", goal}}) {
    std::ostringstream msg;
    msg.precision(12);
    if (!p.allFinite() || !terrain.contains(p)) {
      msg << which << " (" << p.x() << ", " << p.y() << ") is off the map [" << terrain.x_min()
          << ", " << terrain.x_max() << "] x [" << terrain.y_min() << ", " << terrain.y_max()
          << "]";
      throw InputError(msg.str());
    }
    if (!terrain.on_data(p)) {
      msg << which << " (" << p.x() << ", " << p.y() << ") is on a NODATA cell";
      throw InputError(msg.str());
    }
  }
}

/// The whole-map lattice at a spacing from the workspace, or null without one.
using WholeMap = std::function<Lattice*(double spacing)>;

/// kMulti under a time budget: the route level's spacing (at most kRouteLevelNodes nodes),
/// or 0 when that is not coarser than the coarse level.
double route_level_spacing(const BPatch& terrain, double spacing, int coarse_factor) {
  const double nodes =
      static_cast<double>(lattice_nodes_along(terrain.x_max() - terrain.x_min(), spacing)) *
      static_cast<double>(lattice_nodes_along(terrain.y_max() - terrain.y_min(), spacing));
  const double factor = std::ceil(std::sqrt(nodes / static_cast<double>(kRouteLevelNodes)));
  return factor > coarse_factor ? factor * spacing : 0.0;
}

/// The multi-resolution search's counters over its levels, stamped on the result it returns.
struct MultiCounts {
  std::size_t expanded = 0, edges = 0, coarse_nodes = 0, route_nodes = 0;
  void add(const GlobalSearchResult& r) {
    expanded += r.expanded;
    edges += r.edges_evaluated;
  }
  /// `r` as the multi-resolution search's result: every level's counters, no map-sized fields.
  GlobalSearchResult stamp(GlobalSearchResult r, std::chrono::steady_clock::time_point t0) const {
    r.resolution = GlobalSearchResolution::kMulti;
    r.coarse_nodes = coarse_nodes;
    r.route_nodes = route_nodes;
    r.expanded = expanded;
    r.edges_evaluated = edges;
    r.cost_from_start.clear();
    r.cost_to_goal.clear();
    r.search_seconds = seconds_since(t0);
    return r;
  }
};

/// A finer search the budget stopped (`stopped`, `where` it was) before it had a candidate:
/// the coarser `level`'s candidates when it found some (see GlobalSearchResolution::kMulti),
/// else `stopped` without candidates (a coarse lattice path is not a fine candidate).
GlobalSearchResult stopped_search(GlobalSearchResult stopped, const char* where,
                                  std::optional<GlobalSearchResult>& level, const char* name) {
  stopped.message += where;
  if (!level || level->status != GlobalSearchStatus::kOk || level->candidates.empty()) {
    stopped.candidates.clear();
    stopped.nodes = 0;
    return stopped;
  }
  GlobalSearchResult out = std::move(*level);
  std::ostringstream text;
  text << stopped.message << "; the " << name << " level's " << out.candidates.size()
       << " candidate" << (out.candidates.size() == 1 ? "" : "s") << " (lattice spacing "
       << out.spacing << " m) " << (out.candidates.size() == 1 ? "is" : "are") << " returned";
  out.status = GlobalSearchStatus::kStopped;
  out.message = text.str();
  out.coarse_candidates = true;
  return out;
}

/// Under a time budget (and no stop request), the route level's search, run to its end (its
/// size bounds its time); empty when none applies or it fails (e.g. the start untraversable
/// at its scale).
std::optional<GlobalSearchResult> route_level(const BPatch& terrain, const Vehicle& vehicle,
                                              const AdmissibleSet& set, const Vec2& start,
                                              const Vec2& goal,
                                              const GlobalSearchOptions& coarse_options,
                                              double spacing, const WholeMap& whole_map) {
  const Termination& termination = coarse_options.termination;
  if (!std::isfinite(termination.remaining()) ||
      termination.check() == TerminationReason::kStopRequested)
    return std::nullopt;
  const double route_spacing = route_level_spacing(terrain, spacing, coarse_options.coarse_factor);
  if (route_spacing == 0.0) return std::nullopt;
  GlobalSearchOptions options = coarse_options;
  options.lattice_spacing = route_spacing;
  options.termination = Termination();
  try {
    return search_lattice(terrain, vehicle, set, start, goal, options, route_spacing, nullptr,
                          whole_map(route_spacing));
  } catch (const InputError&) {
    return std::nullopt;
  }
}

/// GlobalSearchResolution::kMulti: the coarse search, then fine corridors round its
/// candidates, doubled until the best route keeps off the corridor's edge; under a time budget
/// a route level first.
GlobalSearchResult search_coarse_to_fine(const BPatch& terrain, const Vehicle& vehicle,
                                         const AdmissibleSet& set, const Vec2& start,
                                         const Vec2& goal, const GlobalSearchOptions& options,
                                         double spacing, const WholeMap& whole_map,
                                         std::chrono::steady_clock::time_point t0) {
  const double coarse_spacing = spacing * options.coarse_factor;
  GlobalSearchOptions coarse_options = options;
  coarse_options.lattice_spacing = coarse_spacing;
  // The fine search's separation (in metres) for the coarse candidates too.
  if (coarse_options.distinctness == 0.0) {
    coarse_options.distinctness = default_candidate_separation(start, goal, spacing);
  }
  MultiCounts counts;
  std::optional<GlobalSearchResult> route =
      route_level(terrain, vehicle, set, start, goal, coarse_options, spacing, whole_map);
  if (route) {
    counts.add(*route);
    counts.route_nodes = route->nodes;
  }
  std::optional<GlobalSearchResult> coarse;
  std::string fallback;
  const bool coarse_fits = (terrain.x_max() - terrain.x_min()) >= 8.0 * coarse_spacing &&
                           (terrain.y_max() - terrain.y_min()) >= 8.0 * coarse_spacing;
  if (coarse_fits) {
    try {
      coarse.emplace(search_lattice(terrain, vehicle, set, start, goal, coarse_options,
                                    coarse_spacing, nullptr, whole_map(coarse_spacing)));
    } catch (const InputError& e) {
      fallback = std::string("the coarse search failed (") + e.what() + ")";
    }
  } else {
    fallback = "the map is under 8 coarse lattice spacings across";
  }
  if (coarse) {
    counts.add(*coarse);
    counts.coarse_nodes = coarse->nodes;
    if (coarse->status == GlobalSearchStatus::kStopped)
      return counts.stamp(
          stopped_search(std::move(*coarse), " (in the coarse search)", route, "route"), t0);
    if (coarse->status != GlobalSearchStatus::kOk) {
      fallback = "the coarse search found no route (" + coarse->message + ")";
    }
  }
  GlobalSearchResult result;
  std::size_t widenings = 0;
  double radius = options.corridor_width > 0.0 ? options.corridor_width : 4.0 * coarse_spacing;
  if (!fallback.empty()) {
    result = search_lattice(terrain, vehicle, set, start, goal, options, spacing, nullptr,
                            whole_map(spacing));
    counts.add(result);
    result.fell_back_to_full = true;
    if (result.status == GlobalSearchStatus::kOk) result.message = fallback + ": full search";
  } else {
    const std::size_t nx = lattice_nodes_along(terrain.x_max() - terrain.x_min(), spacing);
    const std::size_t ny = lattice_nodes_along(terrain.y_max() - terrain.y_min(), spacing);
    const Vec2 origin(terrain.x_min(), terrain.y_min());
    while (true) {
      const TileMask mask =
          corridor_tiles(coarse->candidates, start, goal, origin, nx, ny, spacing, radius);
      const bool whole = mask.all();
      result = search_lattice(terrain, vehicle, set, start, goal, options, spacing,
                              whole ? nullptr : &mask, whole ? whole_map(spacing) : nullptr);
      counts.add(result);
      const bool touches = result.corridor_width < 0.0;
      if (whole || result.status == GlobalSearchStatus::kStopped ||
          (result.status == GlobalSearchStatus::kOk && !touches)) {
        break;
      }
      radius *= 2.0;
      ++widenings;
    }
  }
  if (result.status == GlobalSearchStatus::kStopped && result.candidates.empty()) {
    // A coarse route beats none: the coarse level's candidates, else the route level's.
    const bool coarse_route = coarse && coarse->status == GlobalSearchStatus::kOk;
    return counts.stamp(
        stopped_search(std::move(result), " (in the fine search)", coarse_route ? coarse : route,
                       coarse_route ? "coarse" : "route"),
        t0);
  }
  result.corridor_width = result.fell_back_to_full ? 0.0 : radius;
  result.corridor_widenings = widenings;
  return counts.stamp(std::move(result), t0);
}

/// global_search() with the whole-map lattices from `workspace` when it is
/// not null (bound to this terrain, vehicle and options by the caller).
GlobalSearchResult search(const BPatch& terrain, const Vehicle& vehicle, const Vec2& start,
                          const Vec2& goal, const GlobalSearchOptions& options,
                          GlobalSearchWorkspace::Impl* workspace) {
  const auto t0 = std::chrono::steady_clock::now();
  options.validate();
  vehicle.validate();
  check_search_inputs(terrain, vehicle, start, goal);
  const double spacing =
      options.lattice_spacing > 0.0 ? options.lattice_spacing : terrain.cellsize();
  std::optional<AdmissibleSet> own_set;
  const AdmissibleSet& set = workspace != nullptr ? *workspace->set : own_set.emplace(vehicle);
  const WholeMap whole_map = [workspace](double at) {
    return workspace != nullptr ? &workspace->lattice(at) : nullptr;
  };
  // Armed once: every stage below polls the same deadlines.
  GlobalSearchOptions armed = options;
  armed.termination = options.termination.start();
  if (armed.resolution == GlobalSearchResolution::kAuto) {
    const double nodes =
        static_cast<double>(lattice_nodes_along(terrain.x_max() - terrain.x_min(), spacing)) *
        static_cast<double>(lattice_nodes_along(terrain.y_max() - terrain.y_min(), spacing));
    armed.resolution = nodes > static_cast<double>(kAutoMultiResolutionNodes)
                           ? GlobalSearchResolution::kMulti
                           : GlobalSearchResolution::kFull;
  }
  // A budget already spent still lets the coarse-to-fine search run its route level (see
  // GlobalSearchResolution::kMulti); a stop request stops everything.
  if (const TerminationReason reason = armed.termination.check();
      reason == TerminationReason::kStopRequested ||
      (reason == TerminationReason::kTimeLimit &&
       armed.resolution != GlobalSearchResolution::kMulti)) {
    GlobalSearchResult result;
    result.status = GlobalSearchStatus::kStopped;
    result.message = "stopped by GlobalSearchOptions::termination (" +
                     std::string(to_string(reason)) + ") before the search started";
    result.resolution = armed.resolution;
    return result;
  }
  if (armed.resolution == GlobalSearchResolution::kMulti) {
    return search_coarse_to_fine(terrain, vehicle, set, start, goal, armed, spacing, whole_map, t0);
  }
  GlobalSearchResult result = search_lattice(terrain, vehicle, set, start, goal, armed, spacing,
                                             nullptr, whole_map(spacing));
  result.corridor_width = 0.0;
  return result;
}

}  // namespace

GlobalSearchResult global_search(const BPatch& terrain, const Vehicle& vehicle, const Vec2& start,
                                 const Vec2& goal, const GlobalSearchOptions& options) {
  return search(terrain, vehicle, start, goal, options, nullptr);
}

GlobalSearchResult global_search(const BPatch& terrain, const Vehicle& vehicle, const Vec2& start,
                                 const Vec2& goal, const GlobalSearchOptions& options,
                                 GlobalSearchWorkspace& workspace) {
  options.validate();
  vehicle.validate();  // before the workspace's AdmissibleSet is made of it
  if (!workspace.impl_) workspace.impl_ = std::make_unique<GlobalSearchWorkspace::Impl>();
  workspace.impl_->bind(terrain, vehicle, options);
  return search(terrain, vehicle, start, goal, options, workspace.impl_.get());
}

}  // namespace talus
