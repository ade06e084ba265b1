#include "talus/optimal/global_search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <sstream>

#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/core/graph_search.hpp"
#include "talus/core/memory_budget.hpp"
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

EdgeCost edge_cost_impl(const BPatch& terrain, const AdmissibleSet& set, const Vec2& a,
                        const Vec2& b, int stations, const SurfacePoint* at_a,
                        const SurfacePoint* at_b) {
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
    const StationGeometry g = StationGeometry::from(f);
    const SquaredSpeedInterval window = set.squared_speeds(g);
    if (window.empty() || !(window.upper > 0.0)) return {kInf, kInf, kInf};
    // Simpson weights 1, 4, 2, 4, ..., 4, 1 (stations is odd).
    const double w = (k == 0 || k == stations - 1) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    forward_sum += w * f.speed / std::sqrt(window.upper);
    out.length += w * f.speed;
    // Forwards: cannot climb if W_drive < g k_t, cannot stop if W_brake < −g k_t.
    const TangentialForces forces = tangential_forces(set, g, window);
    const double weight = set.gravity() * g.k_t;
    if (forces.drive < weight || forces.brake < -weight) forward_ok = false;
    if (forces.drive < -weight || forces.brake < weight) backward_ok = false;
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
  // Simpson panels at most one lattice spacing wide: 3 stations for axial and
  // diagonal edges, 5 for knight moves (twice as many cost 40 % more time and
  // changed no candidate on the tests and benchmarks).
  return 2 * std::max(1, static_cast<int>(std::ceil(planar_length / (2.0 * spacing) - 1e-9))) + 1;
}

namespace {

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

/// The lattice with lazily computed, cached edge costs in both directions.
class Lattice {
 public:
  Lattice(const BPatch& terrain, const AdmissibleSet& set, double spacing, int connectivity)
      : terrain_(terrain), set_(set), spacing_(spacing), offsets_(neighbour_offsets(connectivity)) {
    origin_ = Vec2(terrain.x_min(), terrain.y_min());
    nx_ =
        static_cast<std::size_t>(std::floor((terrain.x_max() - terrain.x_min()) / spacing + 1e-9)) +
        1;
    ny_ =
        static_cast<std::size_t>(std::floor((terrain.y_max() - terrain.y_min()) / spacing + 1e-9)) +
        1;
    if (nx_ < 2 || ny_ < 2) throw InputError("lattice spacing is larger than the terrain");
    if (nx_ * ny_ > 50'000'000) throw InputError("lattice too large: increase --lattice-spacing");
    half_ = offsets_.size() / 2;
    // Per node: its surface sample and data flag, both directions' cost of
    // each of its half_ edges, and the searches' fields, labels and queues.
    const double per_node = static_cast<double>(sizeof(surface_[0]) + 1 + 16 * half_ + 64);
    require_memory(per_node * static_cast<double>(nx_ * ny_),
                   "the global search's lattice of " + std::to_string(nx_) + " x " +
                       std::to_string(ny_) + " nodes",
                   "increase the lattice spacing (--lattice-spacing; the default is the cell "
                   "size) or lower the connectivity");
    surface_.resize(nx_ * ny_);
    on_data_.resize(nx_ * ny_);
    for (std::size_t n = 0; n < nx_ * ny_; ++n) {
      const Vec2 p = position(static_cast<std::uint32_t>(n));
      on_data_[n] = terrain.on_data(p);
      if (on_data_[n]) surface_[n] = terrain.evaluate(p);
    }
    forward_.assign(nx_ * ny_ * half_, std::numeric_limits<double>::quiet_NaN());
    backward_.assign(nx_ * ny_ * half_, std::numeric_limits<double>::quiet_NaN());
  }

  std::size_t size() const { return nx_ * ny_; }
  std::size_t nx() const { return nx_; }
  std::size_t ny() const { return ny_; }
  Vec2 origin() const { return origin_; }
  Vec2 position(std::uint32_t n) const {
    return origin_ + spacing_ * Vec2(static_cast<double>(n % nx_), static_cast<double>(n / nx_));
  }
  std::uint32_t nearest(const Vec2& p) const {
    const auto i = static_cast<std::size_t>(
        std::clamp(std::lround((p.x() - origin_.x()) / spacing_), 0L, static_cast<long>(nx_) - 1));
    const auto j = static_cast<std::size_t>(
        std::clamp(std::lround((p.y() - origin_.y()) / spacing_), 0L, static_cast<long>(ny_) - 1));
    return static_cast<std::uint32_t>(j * nx_ + i);
  }
  std::size_t edges_evaluated() const { return evaluated_; }

  /// Cost of the directed edge from n along offset k (+inf if none).
  double cost(std::uint32_t n, std::size_t k) {
    const auto [dx, dy] = offsets_[k];
    const long i = static_cast<long>(n % nx_) + dx, j = static_cast<long>(n / nx_) + dy;
    if (i < 0 || j < 0 || i >= static_cast<long>(nx_) || j >= static_cast<long>(ny_)) return kInf;
    const auto m =
        static_cast<std::uint32_t>(static_cast<std::size_t>(j) * nx_ + static_cast<std::size_t>(i));
    if (k < half_) return ensure(n, m, k).first;
    return ensure(m, n, k - half_).second;  // m -> n is positive: n -> m is its backward
  }
  /// Cost of the directed edge into n from its neighbour along offset k.
  double cost_into(std::uint32_t n, std::size_t k) {
    const auto [dx, dy] = offsets_[k];
    const long i = static_cast<long>(n % nx_) + dx, j = static_cast<long>(n / nx_) + dy;
    if (i < 0 || j < 0 || i >= static_cast<long>(nx_) || j >= static_cast<long>(ny_)) return kInf;
    const auto m =
        static_cast<std::uint32_t>(static_cast<std::size_t>(j) * nx_ + static_cast<std::size_t>(i));
    if (k < half_) return ensure(n, m, k).second;  // m -> n is the backward of n -> m
    return ensure(m, n, k - half_).first;
  }
  std::uint32_t neighbour(std::uint32_t n, std::size_t k) const {
    const auto [dx, dy] = offsets_[k];
    return static_cast<std::uint32_t>(static_cast<long>(n) + dy * static_cast<long>(nx_) + dx);
  }
  std::size_t offsets() const { return offsets_.size(); }
  bool on_data(std::uint32_t n) const { return on_data_[n] != 0; }

  /// Stations of an edge of planar length L: at most half a spacing apart, odd count.
  int stations_for(double planar_length) const { return edge_stations(planar_length, spacing_); }

 private:
  /// Forward/backward costs of the positive edge a -> b (offset k < half).
  std::pair<double, double> ensure(std::uint32_t a, std::uint32_t b, std::size_t k) {
    const std::size_t slot = static_cast<std::size_t>(a) * half_ + k;
    if (std::isnan(forward_[slot])) {
      EdgeCost c{kInf, kInf, kInf};
      if (on_data_[a] && on_data_[b]) {
        const Vec2 pa = position(a), pb = position(b);
        c = edge_cost_impl(terrain_, set_, pa, pb, stations_for((pb - pa).norm()), &surface_[a],
                           &surface_[b]);
      }
      forward_[slot] = c.forward;
      backward_[slot] = c.backward;
      ++evaluated_;
    }
    return {forward_[slot], backward_[slot]};
  }

  const BPatch& terrain_;
  const AdmissibleSet& set_;
  double spacing_;
  std::vector<std::pair<int, int>> offsets_;
  std::size_t half_ = 0, nx_ = 0, ny_ = 0;
  Vec2 origin_;
  std::vector<SurfacePoint> surface_;
  std::vector<unsigned char> on_data_;
  std::vector<double> forward_, backward_;
  std::size_t evaluated_ = 0;
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
/// two-pass chamfer transform with steps h and h sqrt(2).
std::vector<float> chamfer_distance(const std::vector<std::uint32_t>& sources, std::size_t nx,
                                    std::size_t ny, double spacing) {
  const float straight = static_cast<float>(spacing);
  const float diagonal = static_cast<float>(spacing * std::sqrt(2.0));
  std::vector<float> d(nx * ny, std::numeric_limits<float>::infinity());
  for (std::uint32_t s : sources) d[s] = 0.0f;
  const auto relax = [&](std::size_t i, std::size_t j, long di, long dj, float step) {
    const long a = static_cast<long>(i) + di, b = static_cast<long>(j) + dj;
    if (a < 0 || b < 0 || a >= static_cast<long>(nx) || b >= static_cast<long>(ny)) return;
    float& here = d[j * nx + i];
    here = std::min(here, d[static_cast<std::size_t>(b) * nx + static_cast<std::size_t>(a)] + step);
  };
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      relax(i, j, -1, 0, straight);
      relax(i, j, 0, -1, straight);
      relax(i, j, -1, -1, diagonal);
      relax(i, j, 1, -1, diagonal);
    }
  for (std::size_t j = ny; j-- > 0;)
    for (std::size_t i = nx; i-- > 0;) {
      relax(i, j, 1, 0, straight);
      relax(i, j, 0, 1, straight);
      relax(i, j, 1, 1, diagonal);
      relax(i, j, -1, 1, diagonal);
    }
  return d;
}

}  // namespace

void GlobalSearchOptions::validate() const {
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
}

EdgeCost edge_cost(const BPatch& terrain, const Vehicle& vehicle, const Vec2& a, const Vec2& b,
                   int stations) {
  if (stations < 3 || stations % 2 == 0)
    throw InputError("edge_cost: stations must be odd and >= 3");
  if (!terrain.contains(a) || !terrain.contains(b))
    throw InputError("edge_cost: edge leaves the terrain");
  return edge_cost_impl(terrain, AdmissibleSet(vehicle), a, b, stations, nullptr, nullptr);
}

GlobalSearchResult global_search(const BPatch& terrain, const Vehicle& vehicle, const Vec2& start,
                                 const Vec2& goal, const GlobalSearchOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  options.validate();
  vehicle.validate();
  if (!std::isfinite(vehicle.max_speed)) {
    throw InputError(
        "the global search needs a vehicle with a finite max_speed: its cost is the time "
        "at the speed limit, and an unlimited straight road would cost nothing");
  }
  const auto check_point = [&terrain](const char* which, const Vec2& p) {
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
  };
  check_point("start", start);
  check_point("goal", goal);

  const double spacing =
      options.lattice_spacing > 0.0 ? options.lattice_spacing : terrain.cellsize();
  const AdmissibleSet set(vehicle);
  Lattice lattice(terrain, set, spacing, options.connectivity);
  GlobalSearchResult result;
  result.nodes = lattice.size();
  result.nx = lattice.nx();
  result.ny = lattice.ny();
  result.spacing = spacing;
  result.origin = lattice.origin();
  const std::uint32_t s = lattice.nearest(start), g = lattice.nearest(goal);
  result.start_node = lattice.position(s);
  result.goal_node = lattice.position(g);
  for (const auto& [which, node] : {std::pair{"start", s}, std::pair{"goal", g}}) {
    bool any = false;
    for (std::size_t k = 0; k < lattice.offsets() && !any; ++k) {
      any = std::strcmp(which, "start") == 0 ? lattice.cost(node, k) < kInf
                                             : lattice.cost_into(node, k) < kInf;
    }
    if (!any) {
      std::ostringstream msg;
      msg.precision(12);
      const Vec2 p = lattice.position(node);
      msg << which << " node (" << p.x() << ", " << p.y()
          << ") is on untraversable terrain: every lattice edge "
          << (std::strcmp(which, "start") == 0 ? "from" : "into")
          << " it is too steep or unstable for the vehicle";
      throw InputError(msg.str());
    }
  }

  const std::size_t n = lattice.size();
  const auto forward = [&lattice](std::uint32_t node, auto&& emit) {
    for (std::size_t k = 0; k < lattice.offsets(); ++k) {
      const double c = lattice.cost(node, k);
      if (c < kInf) emit(lattice.neighbour(node, k), c);
    }
  };
  const auto reverse = [&lattice](std::uint32_t node, auto&& emit) {
    for (std::size_t k = 0; k < lattice.offsets(); ++k) {
      const double c = lattice.cost_into(node, k);
      if (c < kInf) emit(lattice.neighbour(node, k), c);
    }
  };
  if (!options.cost_fields && options.candidates == 1) {
    const Vec2 goal_position = lattice.position(g);
    const double inverse_speed = 1.0 / vehicle.max_speed;
    const ShortestPathTree tree = shortest_paths(n, s, forward, g, [&](std::uint32_t node) {
      return (lattice.position(node) - goal_position).norm() *
             inverse_speed;  // 3-D length >= planar
    });
    result.expanded = tree.expanded;
    result.edges_evaluated = lattice.edges_evaluated();
    if (!(tree.cost[g] < kInf)) {
      result.status = GlobalSearchStatus::kUnreachable;
      result.reachable_nodes = tree.expanded;
      result.message = "goal unreachable: the search exhausted the " +
                       std::to_string(tree.expanded) +
                       " lattice nodes reachable from the start without finding it";
    } else {
      CandidatePath candidate;
      for (std::uint32_t id : tree.path_to(g)) candidate.vertices.push_back(lattice.position(id));
      candidate.cost_seconds = tree.cost[g];
      candidate.length_m = surface_length(terrain, set, candidate.vertices, spacing);
      result.candidates.push_back(std::move(candidate));
      result.status = GlobalSearchStatus::kOk;
      result.reachable_nodes = tree.expanded;
    }
    result.search_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  }
  const ShortestPathTree from_start = shortest_paths(n, s, forward);
  result.expanded += from_start.expanded;
  result.reachable_nodes = static_cast<std::size_t>(std::count_if(
      from_start.cost.begin(), from_start.cost.end(), [](double c) { return c < kInf; }));
  if (!(from_start.cost[g] < kInf)) {
    std::ostringstream msg;
    msg << "goal unreachable: from the start the vehicle can reach " << result.reachable_nodes
        << " of " << n << " lattice nodes ("
        << 100.0 * static_cast<double>(result.reachable_nodes) / static_cast<double>(n)
        << " % of the terrain), and the goal is not among them";
    result.status = GlobalSearchStatus::kUnreachable;
    result.message = msg.str();
    result.cost_from_start = from_start.cost;
    result.edges_evaluated = lattice.edges_evaluated();
    result.search_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  }
  const ShortestPathTree to_goal = shortest_paths(n, g, reverse);
  result.expanded += to_goal.expanded;

  // Candidates: nodes in increasing order of the best cost through them; each
  // node's path (start tree + goal tree) is accepted if it is far enough, in
  // Hausdorff distance, from every accepted one.
  const double best = from_start.cost[g];
  const double separation =
      options.distinctness > 0.0
          ? options.distinctness
          : default_candidate_separation(result.start_node, result.goal_node, spacing);
  std::vector<std::uint32_t> order;
  for (std::uint32_t k = 0; k < n; ++k) {
    const double through = from_start.cost[k] + to_goal.cost[k];
    if (through <= best * options.max_cost_ratio * (1 + 1e-12)) order.push_back(k);
  }
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
  std::vector<unsigned char> examined(n, 0);
  for (const std::uint32_t node : order) {
    if (result.candidates.size() >= options.candidates) break;
    if (examined[node]) continue;
    bool near = false;
    for (const std::vector<float>& d : distance_maps) near = near || d[node] < separation;
    if (near) continue;
    std::vector<std::uint32_t> ids = from_start.path_to(node);
    for (std::uint32_t m = to_goal.parent[node]; m != ShortestPathTree::kNone;
         m = to_goal.parent[m])
      ids.push_back(m);
    for (std::uint32_t id : ids) examined[id] = 1;
    // Distinct from an accepted candidate = somewhere at least `separation`
    // away from it AND at most half of the path within separation / 2 of it:
    // without the second rule the best corridor with one bulge passed as an
    // alternative route.
    bool distinct = true;
    for (const std::vector<float>& d : distance_maps) {
      float farthest = 0.0f;
      std::size_t shared = 0;
      for (std::uint32_t id : ids) {
        farthest = std::max(farthest, d[id]);
        shared += d[id] < 0.5 * separation;
      }
      distinct = distinct && farthest >= separation && 2 * shared <= ids.size();
    }
    if (!distinct) continue;
    CandidatePath candidate;
    for (std::uint32_t id : ids) candidate.vertices.push_back(lattice.position(id));
    candidate.cost_seconds = from_start.cost[node] + to_goal.cost[node];
    candidate.length_m = surface_length(terrain, set, candidate.vertices, spacing);
    result.candidates.push_back(std::move(candidate));
    if (result.candidates.size() < options.candidates) {
      distance_maps.push_back(chamfer_distance(ids, lattice.nx(), lattice.ny(), spacing));
    }
  }
  result.status = GlobalSearchStatus::kOk;
  result.cost_from_start = from_start.cost;
  result.cost_to_goal = to_goal.cost;
  result.edges_evaluated = lattice.edges_evaluated();
  result.search_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace talus
