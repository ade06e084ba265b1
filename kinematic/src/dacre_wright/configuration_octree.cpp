#include "talus/kinematic/dacre_wright/configuration_octree.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::uint32_t cells(int level) {
  return 1u << level;
}

}  // namespace

const char* to_string(VoxelStatus status) {
  switch (status) {
    case VoxelStatus::kUnknown:
      return "unknown";
    case VoxelStatus::kFree:
      return "FREE";
    case VoxelStatus::kMixed:
      return "MIXED";
  }
  return "unknown";
}

void OctreeOptions::validate() const {
  if (max_level < 1 || max_level > 8) {
    throw InputError("OctreeOptions.max_level must be in 1..8, got " + std::to_string(max_level));
  }
  if (reference_level < -1 || reference_level > max_level) {
    throw InputError("OctreeOptions.reference_level must be -1 (auto) or in 0..max_level (" +
                     std::to_string(max_level) + "), got " + std::to_string(reference_level));
  }
  if (budget < 1) throw InputError("OctreeOptions.budget must be >= 1");
  analysis.validate();
}

ConfigurationOctree::ConfigurationOctree(const WheeledRobot& robot, const RuledTerrain& terrain,
                                         const OctreeOptions& options)
    : robot_(robot), terrain_(terrain), sums_(terrain), options_(options) {
  options_.validate();
  robot_.validate();
  require_symmetric_wheels(robot_);
  max_level_ = options_.max_level;
  const ElevationGrid& g = terrain_.grid();
  x0_ = g.x_min();
  y0_ = g.y_min();
  side_ = std::max(g.x_max() - g.x_min(), g.y_max() - g.y_min());
  if (options_.reference_level >= 0) {
    p0_ = options_.reference_level;
  } else {
    double umin = 0, umax = 0;
    for (const Vec2& w : robot_.wheels) {
      umin = std::min(umin, w.x());
      umax = std::max(umax, w.x());
    }
    const double length = std::max(umax - umin, 1e-9);
    p0_ = 0;
    double best = 1e300;
    for (int p = 0; p <= max_level_; ++p) {
      const double miss = std::abs(std::log(side_ / cells(p) / length));
      if (miss < best) {
        best = miss;
        p0_ = p;
      }
    }
  }
  cache_.resize(static_cast<std::size_t>(max_level_) + 1);
  for (int p = 0; p <= max_level_; ++p) {
    const std::size_t n = static_cast<std::size_t>(cells(p));
    cache_[static_cast<std::size_t>(p)].assign(n * n * n, VoxelStatus::kUnknown);
  }
  per_level_.assign(static_cast<std::size_t>(max_level_) + 1, 0);
}

CsBox ConfigurationOctree::box(const VoxelKey& v) const {
  const double s = side_ / cells(v.level);
  const double t = kTwoPi / cells(v.level);
  return {x0_ + s * v.i, x0_ + s * (v.i + 1), y0_ + s * v.j, y0_ + s * (v.j + 1),
          t * v.k,       t * (v.k + 1)};
}

std::optional<VoxelKey> ConfigurationOctree::locate(const SE2Pose& q, int level) const {
  const double n = cells(level);
  const double fx = (q.x - x0_) / side_ * n, fy = (q.y - y0_) / side_ * n;
  if (!(fx >= 0 && fx <= n && fy >= 0 && fy <= n)) return std::nullopt;
  double th = std::fmod(q.theta, kTwoPi);
  if (th < 0) th += kTwoPi;
  const auto clampi = [&](double f) {
    return static_cast<std::uint32_t>(std::min(std::floor(f), n - 1));
  };
  return VoxelKey{level, clampi(fx), clampi(fy), clampi(th / kTwoPi * n)};
}

std::size_t ConfigurationOctree::index(const VoxelKey& v) const {
  const std::size_t n = cells(v.level);
  return (static_cast<std::size_t>(v.k) * n + v.j) * n + v.i;
}

VoxelKey ConfigurationOctree::father(const VoxelKey& v) {
  return {v.level - 1, v.i / 2, v.j / 2, v.k / 2};
}

VoxelStatus ConfigurationOctree::state(const VoxelKey& v) {
  VoxelStatus& slot = cache_[static_cast<std::size_t>(v.level)][index(v)];
  if (slot != VoxelStatus::kUnknown) return slot;
  if (v.level < p0_) {
    // Bottom-up: FREE iff the eight sons are (short-circuit on the first MIXED).
    VoxelStatus s = VoxelStatus::kFree;
    for (std::uint32_t c = 0; c < 8 && s == VoxelStatus::kFree; ++c) {
      const VoxelKey son{v.level + 1, 2 * v.i + (c & 1u), 2 * v.j + ((c >> 1) & 1u),
                         2 * v.k + ((c >> 2) & 1u)};
      if (state(son) != VoxelStatus::kFree) s = VoxelStatus::kMixed;
    }
    // Once the budget is spent a MIXED here may only mean "not analysed": do not cache it.
    if (s == VoxelStatus::kMixed && exhausted_) return s;
    slot = s;
    decided_.push_back({v, s, true});
    return s;
  }
  if (analyses_ >= options_.budget) {
    exhausted_ = true;
    return VoxelStatus::kMixed;
  }
  const BoxAnalysis a = analyse_box(robot_, sums_, box(v), options_.analysis);
  slot = a.free() ? VoxelStatus::kFree : VoxelStatus::kMixed;
  ++per_level_[static_cast<std::size_t>(v.level)];
  ++analyses_;
  decided_.push_back({v, slot, false});
  return slot;
}

std::optional<VoxelKey> ConfigurationOctree::largest_free_containing(const SE2Pose& q) {
  for (int p = 0; p <= max_level_; ++p) {
    const std::optional<VoxelKey> v = locate(q, p);
    if (!v) return std::nullopt;
    if (state(*v) == VoxelStatus::kFree) return v;
  }
  return std::nullopt;
}

void ConfigurationOctree::collect_adjacent(const VoxelKey& n, int axis, int side,
                                           std::vector<VoxelKey>& out) {
  // n is MIXED: its sons on the face toward the current voxel (bit `axis` of the
  // son index equal to `side`), FREE ones kept, MIXED ones opened to p_max.
  if (n.level >= max_level_) return;
  for (std::uint32_t c = 0; c < 8; ++c) {
    if (static_cast<int>((c >> axis) & 1u) != side) continue;
    const VoxelKey son{n.level + 1, 2 * n.i + (c & 1u), 2 * n.j + ((c >> 1) & 1u),
                       2 * n.k + ((c >> 2) & 1u)};
    if (state(son) == VoxelStatus::kFree) {
      out.push_back(son);
    } else {
      collect_adjacent(son, axis, side, out);
    }
  }
}

std::vector<VoxelKey> ConfigurationOctree::free_neighbours(const VoxelKey& v) {
  std::vector<VoxelKey> out;
  const std::int64_t n = cells(v.level);
  for (int axis = 0; axis < 3; ++axis) {
    for (int dir : {-1, 1}) {
      std::int64_t idx[3] = {v.i, v.j, v.k};
      idx[axis] += dir;
      if (axis == 2) {
        idx[2] = (idx[2] % n + n) % n;  // θ is periodic
      } else if (idx[axis] < 0 || idx[axis] >= n) {
        continue;
      }
      const VoxelKey nb{v.level, static_cast<std::uint32_t>(idx[0]),
                        static_cast<std::uint32_t>(idx[1]), static_cast<std::uint32_t>(idx[2])};
      if (nb == v) continue;  // level 0: the θ neighbour is the voxel itself
      // The topmost FREE voxel on nb's root path is the largest FREE voxel there
      // (the paper climbs through the fathers; descending from the root is the same).
      bool found = false;
      for (int p = 0; p <= v.level && !found; ++p) {
        const int shift = v.level - p;
        const VoxelKey a{p, nb.i >> shift, nb.j >> shift, nb.k >> shift};
        if (state(a) == VoxelStatus::kFree) {
          out.push_back(a);
          found = true;
        }
      }
      // Otherwise its sons facing v: those on the near side of the neighbour.
      if (!found) collect_adjacent(nb, axis, dir > 0 ? 0 : 1, out);
    }
  }
  std::sort(out.begin(), out.end(),
            [](const VoxelKey& a, const VoxelKey& b) { return a.code() < b.code(); });
  out.erase(std::unique(out.begin(), out.end()), out.end());
  out.erase(std::remove(out.begin(), out.end(), v), out.end());
  return out;
}

void ConfigurationOctree::refine(const VoxelKey& v) {
  if (state(v) == VoxelStatus::kFree || v.level >= max_level_ || exhausted_) return;
  for (std::uint32_t c = 0; c < 8; ++c) {
    refine({v.level + 1, 2 * v.i + (c & 1u), 2 * v.j + ((c >> 1) & 1u), 2 * v.k + ((c >> 2) & 1u)});
  }
}

void ConfigurationOctree::build_full() {
  const std::uint32_t n = cells(p0_);
  for (std::uint32_t k = 0; k < n; ++k)
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i) refine({p0_, i, j, k});
  // Bottom-up above p0 (every son is analysed now, so no short-circuit is lost).
  for (int p = p0_ - 1; p >= 0; --p) {
    const std::uint32_t m = cells(p);
    for (std::uint32_t k = 0; k < m; ++k)
      for (std::uint32_t j = 0; j < m; ++j)
        for (std::uint32_t i = 0; i < m; ++i) state({p, i, j, k});
  }
}

void ConfigurationOctree::leaves_under(const VoxelKey& v, std::vector<VoxelKey>& out) {
  const VoxelStatus s = cache_[static_cast<std::size_t>(v.level)][index(v)];
  if (s == VoxelStatus::kFree) {
    out.push_back(v);
    return;
  }
  if (v.level >= max_level_) return;
  for (std::uint32_t c = 0; c < 8; ++c) {
    leaves_under(
        {v.level + 1, 2 * v.i + (c & 1u), 2 * v.j + ((c >> 1) & 1u), 2 * v.k + ((c >> 2) & 1u)},
        out);
  }
}

std::vector<VoxelKey> ConfigurationOctree::free_leaves() {
  std::vector<VoxelKey> out;
  leaves_under({0, 0, 0, 0}, out);
  return out;
}

double ConfigurationOctree::free_volume_fraction() {
  double v = 0.0;
  for (const VoxelKey& k : free_leaves()) v += 1.0 / std::pow(8.0, k.level);
  return v;
}

}  // namespace talus
