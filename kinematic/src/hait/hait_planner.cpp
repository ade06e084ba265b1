#include "talus/kinematic/hait/hait_planner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <queue>
#include <sstream>
#include <unordered_set>
#include <utility>

#include "talus/core/error.hpp"
#include "talus/kinematic/reeds_shepp.hpp"

namespace talus {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The six elementary controls of §4.1, in a fixed order (ties in the open
/// list are broken by creation order, so this order makes runs reproducible).
constexpr Control kControls[6] = {{1, 0}, {1, 1}, {1, -1}, {-1, 0}, {-1, 1}, {-1, -1}};

void require(bool ok, const char* field, double value, const char* expected) {
  if (ok) return;
  std::ostringstream msg;
  msg << "HaitOptions: " << field << " = " << value << ", expected " << expected;
  throw InputError(msg.str());
}

std::string pose_string(const SE2Pose& q) {
  std::ostringstream s;
  s << "(" << q.x << ", " << q.y << ", " << q.theta << ")";
  return s.str();
}

void require_finite_pose(const SE2Pose& q, const char* what) {
  if (std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.theta)) return;
  throw InputError(std::string("hait_search: ") + what + " configuration " + pose_string(q) +
                   " is not finite");
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Sub-step cost of §4.2.1 with our weighting (file comment of the header).
double weighted(double ds, double margin, double weight) {
  return ds * (1.0 + weight * (1.0 - std::clamp(margin, 0.0, 1.0)));
}

struct Node {
  SE2Pose q;
  double g = 0.0;
  std::int64_t parent = -1;
  Control u;            ///< control from the parent
  bool via_rs = false;  ///< reached by a Reeds–Shepp curve to the exact goal
};

/// Key of the configuration-space cell holding q (21 bits per axis: enough
/// for 2 million cells per side, well beyond any terrain we load).
std::uint64_t cell_key(const SE2Pose& q, double cell, int bins) {
  const auto ix = static_cast<std::int64_t>(std::floor(q.x / cell));
  const auto iy = static_cast<std::int64_t>(std::floor(q.y / cell));
  double t = std::fmod(q.theta, kTwoPi);
  if (t < 0.0) t += kTwoPi;
  auto it = static_cast<std::int64_t>(std::floor(t / kTwoPi * bins));
  if (it >= bins) it = bins - 1;
  constexpr std::int64_t kOffset = std::int64_t{1} << 20;
  constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
  return ((static_cast<std::uint64_t>(ix + kOffset) & kMask) << 42) |
         ((static_cast<std::uint64_t>(iy + kOffset) & kMask) << 21) |
         static_cast<std::uint64_t>(it);
}

}  // namespace

std::string heuristic_name(HaitHeuristic h) {
  switch (h) {
    case HaitHeuristic::kEuclidean:
      return "euclidean";
    case HaitHeuristic::kPotential:
      return "potential";
    case HaitHeuristic::kPotentialRs:
      return "potential-rs";
  }
  return "unknown";
}

HaitHeuristic parse_heuristic(const std::string& name) {
  for (HaitHeuristic h :
       {HaitHeuristic::kEuclidean, HaitHeuristic::kPotential, HaitHeuristic::kPotentialRs}) {
    if (heuristic_name(h) == name) return h;
  }
  throw InputError("unknown heuristic '" + name +
                   "', expected one of: euclidean, potential, potential-rs");
}

std::string status_name(HaitStatus s) {
  switch (s) {
    case HaitStatus::kFound:
      return "found";
    case HaitStatus::kNoPath:
      return "no_path";
    case HaitStatus::kStartInvalid:
      return "start_invalid";
    case HaitStatus::kGoalInvalid:
      return "goal_invalid";
    case HaitStatus::kNodeLimit:
      return "node_limit";
  }
  return "unknown";
}

void HaitOptions::validate() const {
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  auto nonneg = [](double v) { return v >= 0.0 && std::isfinite(v); };
  require(positive(cell_size), "cell_size", cell_size, "> 0");
  require(theta_bins >= 4, "theta_bins", theta_bins, ">= 4");
  require(positive(step), "step", step, "> 0");
  require(positive(turning_radius), "turning_radius", turning_radius, "> 0");
  require(positive(check_spacing), "check_spacing", check_spacing, "> 0");
  require(nonneg(margin_weight), "margin_weight", margin_weight, ">= 0");
  require(max_nodes >= 1, "max_nodes", static_cast<double>(max_nodes), ">= 1");
  require(positive(potential_weight), "potential_weight", potential_weight, "> 0");
  require(nonneg(control_point_offset), "control_point_offset", control_point_offset, ">= 0");
  require(nonneg(rs_switch_distance), "rs_switch_distance", rs_switch_distance, ">= 0");
  require(nonneg(goal_position_tolerance), "goal_position_tolerance", goal_position_tolerance,
          ">= 0");
  require(nonneg(goal_heading_tolerance), "goal_heading_tolerance", goal_heading_tolerance, ">= 0");
  require(nonneg(terrain_uncertainty), "terrain_uncertainty", terrain_uncertainty, ">= 0");
  if (terrain_uncertainty_map && terrain_uncertainty > 0.0) {
    throw InputError(
        "HaitOptions: terrain_uncertainty and terrain_uncertainty_map are both set; set one");
  }
  require(nonneg(position_uncertainty), "position_uncertainty", position_uncertainty, ">= 0");
  require(nonneg(heading_uncertainty) && heading_uncertainty < std::numbers::pi,
          "heading_uncertainty", heading_uncertainty, "in [0, pi)");
  smoothing.validate();
}

ValidityFunction neighbourhood_validity(ValidityFunction base, double rho, double dtheta,
                                        double spacing, double angle_step) {
  if (!(rho >= 0.0) || !(dtheta >= 0.0) || !(spacing > 0.0) || !(angle_step > 0.0) ||
      !std::isfinite(rho) || !std::isfinite(dtheta)) {
    std::ostringstream msg;
    msg << "neighbourhood_validity: need rho >= 0, dtheta >= 0, spacing > 0, angle_step > 0; got "
        << rho << ", " << dtheta << ", " << spacing << ", " << angle_step;
    throw InputError(msg.str());
  }
  if (rho == 0.0 && dtheta == 0.0) return base;
  const int nl = static_cast<int>(std::ceil(rho / spacing - 1e-9));
  const int na = static_cast<int>(std::ceil(dtheta / angle_step - 1e-9));
  // Offsets ordered centre first, then outwards: an invalid neighbourhood is
  // usually found invalid near its centre, which saves placements.
  std::vector<std::pair<double, double>> offsets;  // (lateral [m], heading [rad])
  auto order = [](int n) {
    std::vector<int> k{0};
    for (int i = 1; i <= n; ++i) {
      k.push_back(i);
      k.push_back(-i);
    }
    return k;
  };
  for (int a : order(na)) {
    for (int l : order(nl)) {
      offsets.emplace_back(nl > 0 ? rho * l / nl : 0.0, na > 0 ? dtheta * a / na : 0.0);
    }
  }
  return [base = std::move(base), offsets = std::move(offsets)](const SE2Pose& q) {
    ConfigurationCheck out{true, 1.0, 0};
    const double s = std::sin(q.theta), c = std::cos(q.theta);
    for (const auto& [lateral, dth] : offsets) {
      // The segment normal to the heading (§5.2, Fig. 25 b).
      const ConfigurationCheck k = base({q.x - lateral * s, q.y + lateral * c, q.theta + dth});
      out.placements += k.placements;
      if (!k.valid) {
        out.valid = false;
        out.margin = 0.0;
        return out;
      }
      out.margin = std::min(out.margin, k.margin);
    }
    return out;
  };
}

HaitResult hait_search(const ValidityFunction& robot_validity, const PotentialFunction& potential,
                       const SE2Pose& start, const SE2Pose& goal, const HaitOptions& options) {
  options.validate();
  require_finite_pose(start, "start");
  require_finite_pose(goal, "goal");
  if (!robot_validity) throw InputError("hait_search: no validity function");
  // The guide region: outside it a configuration is not valid, and costs no placement.
  ValidityFunction validity = robot_validity;
  if (options.allowed_region) {
    validity = [&robot_validity, &region = options.allowed_region](const SE2Pose& q) {
      if (!region(q)) return ConfigurationCheck{false, 0.0, 0};
      return robot_validity(q);
    };
  }
  if (options.heuristic != HaitHeuristic::kEuclidean && !potential) {
    throw InputError("hait_search: heuristic '" + heuristic_name(options.heuristic) +
                     "' needs a potential function");
  }
  const auto t0 = std::chrono::steady_clock::now();
  const double cell = options.cell_size;
  const int bins = options.theta_bins;
  const double tol_xy =
      options.goal_position_tolerance > 0.0 ? options.goal_position_tolerance : cell;
  const double tol_th =
      options.goal_heading_tolerance > 0.0 ? options.goal_heading_tolerance : kTwoPi / bins;
  const double rs_region =
      options.rs_switch_distance > 0.0 ? options.rs_switch_distance : 3.0 * options.turning_radius;
  const ReedsShepp rs(options.turning_radius);

  HaitResult result;
  auto finish = [&](HaitStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    result.search_seconds = seconds_since(t0);
    return result;
  };

  const ConfigurationCheck start_check = validity(start);
  result.placements += start_check.placements;
  const char* outside = " (outside the allowed region)";
  if (!start_check.valid) {
    const bool out = options.allowed_region && !options.allowed_region(start);
    return finish(HaitStatus::kStartInvalid, "start configuration " + pose_string(start) +
                                                 " is not valid for the robot" +
                                                 (out ? outside : ""));
  }
  const ConfigurationCheck goal_check = validity(goal);
  result.placements += goal_check.placements;
  if (!goal_check.valid) {
    const bool out = options.allowed_region && !options.allowed_region(goal);
    return finish(HaitStatus::kGoalInvalid, "goal configuration " + pose_string(goal) +
                                                " is not valid for the robot" +
                                                (out ? outside : ""));
  }

  auto heuristic = [&](const SE2Pose& q) {
    const double euclid = std::hypot(goal.x - q.x, goal.y - q.y);
    if (options.heuristic == HaitHeuristic::kEuclidean) return euclid;
    const double p = options.potential_weight * potential(q);
    if (options.heuristic == HaitHeuristic::kPotential || euclid >= rs_region) return p;
    // The potential ignores the goal heading; add the Reeds–Shepp curve's excess over the
    // straight line (the detour the heading costs, 0 when aligned), weighted from 1 at the
    // goal down to 0 at the region's edge. A full-weight excess switched on at the edge made
    // h jump there, and A* then developed the whole band just outside the region before
    // entering it (hait-heuristics: 1988 nodes created against the potential's 1199).
    const double weight = 1.0 - euclid / rs_region;
    return p + weight * std::max(0.0, rs.distance(q, goal) - euclid);
  };
  auto at_goal = [&](const SE2Pose& q) {
    return std::hypot(goal.x - q.x, goal.y - q.y) <= tol_xy &&
           std::abs(wrap_angle(goal.theta - q.theta)) <= tol_th;
  };

  std::vector<Node> nodes;
  std::unordered_set<std::uint64_t> marked;
  using Entry = std::pair<double, std::int64_t>;  // (f, node id); ties: older node first
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;

  const double h0 = heuristic(start);
  nodes.push_back({start, 0.0, -1, Control{}, false});
  marked.insert(cell_key(start, cell, bins));
  result.nodes_created = 1;
  if (!std::isfinite(h0)) {
    return finish(HaitStatus::kNoPath, "the potential is infinite at the start " +
                                           pose_string(start) + ": goal unreachable");
  }
  open.push({h0, 0});

  const int n_sub =
      std::max(1, static_cast<int>(std::ceil(options.step / options.check_spacing - 1e-9)));
  const double ds = options.step / n_sub;
  std::int64_t goal_node = -1;

  while (!open.empty()) {
    const std::int64_t id = open.top().second;
    open.pop();
    const Node node = nodes[static_cast<std::size_t>(id)];
    if (node.via_rs || at_goal(node.q)) {
      goal_node = id;
      break;
    }
    ++result.nodes_developed;

    // Final connection: a valid Reeds–Shepp curve to the exact goal.
    if (options.connect_goal && std::hypot(goal.x - node.q.x, goal.y - node.q.y) <= rs_region) {
      const std::vector<PathPoint> curve = rs.sample(node.q, goal, options.check_spacing);
      double cost = 0.0;
      bool ok = true;
      for (std::size_t k = 1; k < curve.size() && ok; ++k) {
        const ConfigurationCheck c = validity(curve[k].pose);
        result.placements += c.placements;
        ok = c.valid;
        const double piece =
            curve[k].control.omega != 0
                ? options.turning_radius *
                      std::abs(wrap_angle(curve[k].pose.theta - curve[k - 1].pose.theta))
                : std::hypot(curve[k].pose.x - curve[k - 1].pose.x,
                             curve[k].pose.y - curve[k - 1].pose.y);
        cost += weighted(piece, c.margin, options.margin_weight);
      }
      if (ok) {
        nodes.push_back({goal, node.g + cost, id, Control{}, true});
        ++result.nodes_created;
        open.push({node.g + cost, static_cast<std::int64_t>(nodes.size() - 1)});
      }
    }

    for (const Control& u : kControls) {
      const SE2Pose end = apply_control(node.q, u, options.step, options.turning_radius);
      const std::uint64_t key = cell_key(end, cell, bins);
      if (marked.count(key) != 0) continue;  // at most one node per cell
      double cost = 0.0;
      bool ok = true;
      for (int k = 1; k <= n_sub && ok; ++k) {
        const SE2Pose qk =
            k == n_sub ? end : apply_control(node.q, u, ds * k, options.turning_radius);
        const ConfigurationCheck c = validity(qk);
        result.placements += c.placements;
        ok = c.valid;
        cost += weighted(ds, c.margin, options.margin_weight);
      }
      if (!ok) continue;
      // The cell is visited once its arc is valid, whatever the heuristic says: an
      // unmarked cell would be validated again from every other parent reaching it.
      marked.insert(key);
      const double h = heuristic(end);
      if (!std::isfinite(h)) continue;  // the potential says the goal is unreachable from here
      nodes.push_back({end, node.g + cost, id, u, false});
      ++result.nodes_created;
      open.push({node.g + cost + h, static_cast<std::int64_t>(nodes.size() - 1)});
    }
    if (result.nodes_created >= options.max_nodes) {
      return finish(HaitStatus::kNodeLimit,
                    "node budget of " + std::to_string(options.max_nodes) + " nodes exhausted");
    }
  }
  if (goal_node < 0) {
    return finish(HaitStatus::kNoPath, "every reachable cell explored, the goal " +
                                           pose_string(goal) + " was not reached");
  }

  // Rebuild the dense path by replaying each node's control from its parent.
  std::vector<std::int64_t> chain;
  for (std::int64_t k = goal_node; k >= 0; k = nodes[static_cast<std::size_t>(k)].parent) {
    chain.push_back(k);
  }
  std::reverse(chain.begin(), chain.end());
  std::vector<PathPoint> path{{start, Control{}}};
  for (std::size_t c = 1; c < chain.size(); ++c) {
    const Node& n = nodes[static_cast<std::size_t>(chain[c])];
    const SE2Pose from = path.back().pose;
    if (n.via_rs) {
      const std::vector<PathPoint> curve = rs.sample(from, goal, options.check_spacing);
      path.insert(path.end(), curve.begin() + 1, curve.end());
      result.connected_to_goal = true;
      continue;
    }
    for (int k = 1; k <= n_sub; ++k) {
      path.push_back(
          {k == n_sub ? n.q : apply_control(from, n.u, ds * k, options.turning_radius), n.u});
    }
  }
  result.search_seconds = seconds_since(t0);
  result.unsmoothed_path = path;
  result.control_changes_unsmoothed = control_changes(path);
  if (options.smooth && path.size() >= 2) {
    const auto ts = std::chrono::steady_clock::now();
    HaitSmoothingOptions so = options.smoothing;
    so.check_spacing = options.check_spacing;
    HaitSmoothingReport report;
    path = smooth_path(path, validity, rs, so, &report);
    result.placements += report.placements;
    result.smoothing_seconds = seconds_since(ts);
  }
  result.path = std::move(path);
  result.control_changes = control_changes(result.path);
  result.length_m = path_length(result.path, options.turning_radius);
  result.status = HaitStatus::kFound;
  std::ostringstream msg;
  msg << "path found: " << result.length_m << " m, " << result.control_changes
      << " control changes, " << result.nodes_created << " nodes created";
  result.message = msg.str();
  return result;
}

}  // namespace talus
