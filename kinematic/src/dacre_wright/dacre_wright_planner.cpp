#include "talus/kinematic/dacre_wright/dacre_wright_planner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "talus/core/error.hpp"
#include "talus/kinematic/hait/placement.hpp"

namespace talus {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Vec3 centre(const CsBox& b) {
  return {0.5 * (b.x1 + b.x2), 0.5 * (b.y1 + b.y2), 0.5 * (b.theta1 + b.theta2)};
}

double metric(const Vec3& a, const Vec3& b, double rho) {
  const double dth = std::remainder(a.z() - b.z(), kTwoPi);
  return std::sqrt((a.x() - b.x()) * (a.x() - b.x()) + (a.y() - b.y()) * (a.y() - b.y()) +
                   rho * rho * dth * dth);
}

/// b shifted by 2πm in θ to meet `a` (closed boxes), the m whose shifted
/// interval is nearest `theta_now`; false if no shift makes them meet.
bool shifted_to_meet(const CsBox& a, CsBox b, double theta_now, CsBox& out) {
  bool any = false;
  double best = 1e300;
  const double tol = 1e-9;
  const double m0 = std::round((a.theta1 - b.theta1) / kTwoPi);
  for (double m = m0 - 2; m <= m0 + 2; m += 1.0) {
    CsBox c = b;
    c.theta1 += kTwoPi * m;
    c.theta2 += kTwoPi * m;
    if (c.theta1 > a.theta2 + tol || c.theta2 < a.theta1 - tol) continue;
    const double miss = std::abs(0.5 * (c.theta1 + c.theta2) - theta_now);
    if (miss < best) {
      best = miss;
      out = c;
      any = true;
    }
  }
  return any;
}

double clampd(double v, double lo, double hi) {
  return std::min(std::max(v, lo), hi);
}

}  // namespace

void DacreWrightOptions::validate() const {
  octree.validate();
  if (!std::isfinite(heading_weight))
    throw InputError("DacreWrightOptions.heading_weight must be finite");
  if (!(check_spacing > 0 && std::isfinite(check_spacing)))
    throw InputError("DacreWrightOptions.check_spacing must be positive and finite");
  if (!(heading_spacing > 0 && std::isfinite(heading_spacing)))
    throw InputError("DacreWrightOptions.heading_spacing must be positive and finite");
}

const char* to_string(DacreWrightStatus status) {
  switch (status) {
    case DacreWrightStatus::kFound:
      return "found";
    case DacreWrightStatus::kNoPath:
      return "no_path";
    case DacreWrightStatus::kStartInvalid:
      return "start_invalid";
    case DacreWrightStatus::kGoalInvalid:
      return "goal_invalid";
    case DacreWrightStatus::kStartUncovered:
      return "start_uncovered";
    case DacreWrightStatus::kGoalUncovered:
      return "goal_uncovered";
    case DacreWrightStatus::kBudgetExceeded:
      return "budget_exceeded";
  }
  return "unknown";
}

std::size_t DacreWrightResult::voxels_analysed() const {
  std::size_t n = 0;
  for (std::size_t c : analyses_per_level) n += c;
  return n;
}

std::string DacreWrightResult::brief_report() const {
  std::ostringstream s;
  const std::size_t n = voxels_analysed();
  s << to_string(status) << ": channel " << channel.size() << " voxels, path " << path.size()
    << " poses, " << length_m << " m, " << n << " voxels analysed (p0 = " << reference_level
    << "), " << expansions << " expansions, free volume " << free_volume_fraction
    << ", preprocessing " << preprocessing_seconds << " s, search " << search_seconds << " s; "
    << message;
  return s.str();
}

bool dacre_wright_admissible(const WheeledRobot& robot, const RuledTerrain& terrain,
                             const SE2Pose& q) {
  if (!terrain.has_data(q.position())) return false;
  return admissible(robot, place_robot(robot, terrain, q.x, q.y, q.theta));
}

namespace {

/// r finished with `status`: every analysed voxel (the FREE ones indexed, the FREE leaves and
/// their volume marked), the channel's indices, the analysis counts and the search time.
DacreWrightResult finish_result(DacreWrightResult& r, ConfigurationOctree& oct, DacreWrightStatus s,
                                std::string message, std::chrono::steady_clock::time_point t0) {
  r.status = s;
  r.message = std::move(message);
  r.analyses_per_level = oct.analyses_per_level();
  const std::vector<AnalysedVoxel>& decided = oct.decided();
  r.voxels.reserve(decided.size());
  // Only FREE voxels are looked up (the channel's, the leaves).
  std::unordered_map<std::uint64_t, std::size_t> where;
  double volume = 0.0;
  for (const AnalysedVoxel& v : decided) {
    if (v.status == VoxelStatus::kFree) {
      where.emplace(v.key.code(), r.voxels.size());
      // A FREE leaf: no ancestor is FREE (the canonical decomposition).
      bool leaf = true;
      for (VoxelKey a = v.key; a.level > 0 && leaf;) {
        a = ConfigurationOctree::father(a);
        leaf = oct.cached(a) != VoxelStatus::kFree;
      }
      if (leaf) {
        r.free_leaf_indices.push_back(r.voxels.size());
        volume += std::ldexp(1.0, -3 * v.key.level);
      }
    }
    r.voxels.push_back({v.key, oct.box(v.key), v.status, v.from_sons});
  }
  for (const VoxelKey& v : r.channel) r.channel_indices.push_back(where.at(v.code()));
  r.free_volume_fraction = volume;
  r.search_seconds = seconds_since(t0) - r.preprocessing_seconds;
  return std::move(r);
}

/// How the search for a channel ended.
enum class ChannelSearch { kFound, kNoPath, kBudgetExceeded };

/// A* over largest FREE voxels from `vs` to `vg` (edge cost: the metric between centres);
/// r.channel and r.expansions filled.
ChannelSearch search_channel(ConfigurationOctree& oct, const VoxelKey& vs, const VoxelKey& vg,
                             double rho, DacreWrightResult& r) {
  struct Node {
    VoxelKey key;
    double g = 0.0;
    std::uint64_t parent = 0;
    bool has_parent = false;
    bool closed = false;
  };
  std::unordered_map<std::uint64_t, Node> nodes;
  using Entry = std::pair<double, std::uint64_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  const Vec3 goal_centre = centre(oct.box(vg));
  nodes[vs.code()] = {vs, 0.0, 0, false, false};
  open.push({metric(centre(oct.box(vs)), goal_centre, rho), vs.code()});
  bool reached = false;
  while (!open.empty()) {
    const auto [f, code] = open.top();
    open.pop();
    Node& cur = nodes[code];
    if (cur.closed) continue;
    cur.closed = true;
    if (cur.key == vg) {
      reached = true;
      break;
    }
    ++r.expansions;
    const VoxelKey key = cur.key;
    const double g = cur.g;
    const Vec3 c = centre(oct.box(key));
    const std::vector<VoxelKey> nbrs = oct.free_neighbours(key);
    if (oct.budget_exhausted()) return ChannelSearch::kBudgetExceeded;
    for (const VoxelKey& nb : nbrs) {
      const Vec3 cn = centre(oct.box(nb));
      const double ng = g + metric(c, cn, rho);
      auto it = nodes.find(nb.code());
      if (it == nodes.end()) {
        it = nodes.emplace(nb.code(), Node{nb, ng, code, true, false}).first;
      } else if (it->second.closed || ng >= it->second.g) {
        continue;
      } else {
        it->second.g = ng;
        it->second.parent = code;
        it->second.has_parent = true;
      }
      open.push({ng + metric(cn, goal_centre, rho), nb.code()});
    }
  }
  if (!reached) return ChannelSearch::kNoPath;
  for (std::uint64_t code = vg.code();;) {
    const Node& n = nodes.at(code);
    r.channel.push_back(n.key);
    if (!n.has_parent) break;
    code = n.parent;
  }
  std::reverse(r.channel.begin(), r.channel.end());
  return ChannelSearch::kFound;
}

/// Way points through the channel's boxes: the start, a point of each shared face (the one
/// nearest the goal), the goal; θ unwrapped along the way.
std::vector<Vec3> channel_waypoints(const std::vector<CsBox>& boxes, const SE2Pose& start,
                                    const SE2Pose& goal) {
  std::vector<Vec3> pts;
  pts.emplace_back(start.x, start.y, start.theta);
  CsBox cur = boxes.front();
  {
    CsBox shifted;
    if (shifted_to_meet({0, 0, 0, 0, start.theta, start.theta}, cur, start.theta, shifted))
      cur = shifted;
  }
  for (std::size_t k = 1; k < boxes.size(); ++k) {
    const Vec3& p = pts.back();
    CsBox next;
    if (!shifted_to_meet(cur, boxes[k], p.z(), next)) {
      throw std::logic_error("plan_dacre_wright: consecutive channel voxels do not meet");
    }
    const double gth = goal.theta + kTwoPi * std::round((p.z() - goal.theta) / kTwoPi);
    const Vec3 lo(std::max(cur.x1, next.x1), std::max(cur.y1, next.y1),
                  std::max(cur.theta1, next.theta1));
    const Vec3 hi(std::min(cur.x2, next.x2), std::min(cur.y2, next.y2),
                  std::min(cur.theta2, next.theta2));
    pts.emplace_back(clampd(goal.x, lo.x(), hi.x()), clampd(goal.y, lo.y(), hi.y()),
                     clampd(gth, std::min(lo.z(), hi.z()), std::max(lo.z(), hi.z())));
    cur = next;
  }
  const double mid = 0.5 * (cur.theta1 + cur.theta2);
  pts.emplace_back(goal.x, goal.y, goal.theta + kTwoPi * std::round((mid - goal.theta) / kTwoPi));
  return pts;
}

/// r.path: the way points joined by straight segments in (x, y, θ), sampled every
/// check_spacing in the plane and heading_spacing in θ; r.length_m their planar length.
void sample_path(const std::vector<Vec3>& pts, const DacreWrightOptions& options,
                 DacreWrightResult& r) {
  r.path.push_back({pts.front().x(), pts.front().y(), pts.front().z()});
  for (std::size_t k = 1; k < pts.size(); ++k) {
    const Vec3 d = pts[k] - pts[k - 1];
    const double xy = d.head<2>().norm();
    r.length_m += xy;
    const int steps =
        std::max(1, static_cast<int>(std::ceil(std::max(
                        xy / options.check_spacing, std::abs(d.z()) / options.heading_spacing))));
    for (int s = 1; s <= steps; ++s) {
      const Vec3 q = (s == steps) ? pts[k] : Vec3(pts[k - 1] + d * (double(s) / steps));
      r.path.push_back({q.x(), q.y(), q.z()});
    }
  }
}

}  // namespace

DacreWrightResult plan_dacre_wright(const RuledTerrain& terrain, const WheeledRobot& robot,
                                    const SE2Pose& start, const SE2Pose& goal,
                                    const DacreWrightOptions& options) {
  options.validate();
  for (const SE2Pose* q : {&start, &goal}) {
    if (!(std::isfinite(q->x) && std::isfinite(q->y) && std::isfinite(q->theta)))
      throw InputError("plan_dacre_wright: the start and goal must be finite");
  }
  const auto t0 = std::chrono::steady_clock::now();
  ConfigurationOctree oct(robot, terrain, options.octree);
  DacreWrightResult r;
  r.reference_level = oct.reference_level();
  double rho = options.heading_weight;
  if (rho < 0) {
    rho = 0;
    for (const Vec2& w : robot.wheels) rho = std::max(rho, w.norm());
  }
  const auto finish = [&](DacreWrightStatus s, std::string message) {
    return finish_result(r, oct, s, std::move(message), t0);
  };
  if (!dacre_wright_admissible(robot, terrain, start))
    return finish(DacreWrightStatus::kStartInvalid,
                  "the start fails the placement test (springs or attitude)");
  if (!dacre_wright_admissible(robot, terrain, goal))
    return finish(DacreWrightStatus::kGoalInvalid,
                  "the goal fails the placement test (springs or attitude)");
  if (options.full) {
    oct.build_full();
    r.preprocessing_seconds = seconds_since(t0);
  }
  const std::optional<VoxelKey> vs = oct.largest_free_containing(start);
  if (oct.budget_exhausted())
    return finish(DacreWrightStatus::kBudgetExceeded, "the voxel budget ran out");
  if (!vs)
    return finish(DacreWrightStatus::kStartUncovered,
                  "the start is admissible but lies in no FREE voxel down to p_max");
  const std::optional<VoxelKey> vg = oct.largest_free_containing(goal);
  if (oct.budget_exhausted())
    return finish(DacreWrightStatus::kBudgetExceeded, "the voxel budget ran out");
  if (!vg)
    return finish(DacreWrightStatus::kGoalUncovered,
                  "the goal is admissible but lies in no FREE voxel down to p_max");
  switch (search_channel(oct, *vs, *vg, rho, r)) {
    case ChannelSearch::kBudgetExceeded:
      r.channel.clear();
      return finish(DacreWrightStatus::kBudgetExceeded, "the voxel budget ran out");
    case ChannelSearch::kNoPath:
      return finish(DacreWrightStatus::kNoPath,
                    "no chain of FREE voxels joins the start's voxel to the goal's");
    case ChannelSearch::kFound:
      break;
  }
  for (const VoxelKey& v : r.channel) r.channel_boxes.push_back(oct.box(v));
  sample_path(channel_waypoints(r.channel_boxes, start, goal), options, r);
  return finish(DacreWrightStatus::kFound, "a channel of " + std::to_string(r.channel.size()) +
                                               " FREE voxels joins the start to the goal");
}

}  // namespace talus
