#include "talus/kinematic/hait/hait_planner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <queue>
#include <sstream>
#include <tuple>
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

namespace {

/// One hait_search: A* over (x, y, θ) cells, one node per cell, the arcs of the controls
/// validated every check_spacing, a Reeds–Shepp connection to the exact goal near it.
class HaitSearch {
 public:
  HaitSearch(const ValidityFunction& validity, const PotentialFunction& potential,
             const SE2Pose& start, const SE2Pose& goal, const HaitOptions& options)
      : validity_(validity),
        potential_(potential),
        start_(start),
        goal_(goal),
        options_(options),
        t0_(std::chrono::steady_clock::now()),
        cell_(options.cell_size),
        bins_(options.theta_bins),
        tol_xy_(options.goal_position_tolerance > 0.0 ? options.goal_position_tolerance : cell_),
        tol_th_(options.goal_heading_tolerance > 0.0 ? options.goal_heading_tolerance
                                                     : kTwoPi / bins_),
        rs_region_(options.rs_switch_distance > 0.0 ? options.rs_switch_distance
                                                    : 3.0 * options.turning_radius),
        rs_(options.turning_radius),
        n_sub_(
            std::max(1, static_cast<int>(std::ceil(options.step / options.check_spacing - 1e-9)))),
        ds_(options.step / n_sub_) {}

  HaitResult run() {
    if (!ends_valid()) return std::move(result_);
    const double h0 = heuristic(start_);
    nodes_.push_back({start_, 0.0, -1, Control{}, false});
    marked_.insert(cell_key(start_, cell_, bins_));
    result_.nodes_created = 1;
    if (!std::isfinite(h0)) {
      return finish(HaitStatus::kNoPath, "the potential is infinite at the start " +
                                             pose_string(start_) + ": goal unreachable");
    }
    open_.push({h0, 0});
    std::int64_t goal_node = -1;
    while (!open_.empty()) {
      const std::int64_t id = open_.top().second;
      open_.pop();
      const Node node = nodes_[static_cast<std::size_t>(id)];
      if (node.via_rs || at_goal(node.q)) {
        goal_node = id;
        break;
      }
      ++result_.nodes_developed;
      if (options_.connect_goal && std::hypot(goal_.x - node.q.x, goal_.y - node.q.y) <= rs_region_)
        connect_to_goal(node, id);
      develop(node, id);
      if (result_.nodes_created >= options_.max_nodes) {
        return finish(HaitStatus::kNodeLimit,
                      "node budget of " + std::to_string(options_.max_nodes) + " nodes exhausted");
      }
    }
    if (goal_node < 0) {
      return finish(HaitStatus::kNoPath, "every reachable cell explored, the goal " +
                                             pose_string(goal_) + " was not reached");
    }
    return found(replay(goal_node));
  }

 private:
  using Entry = std::pair<double, std::int64_t>;  // (f, node id); ties: older node first

  void conclude(HaitStatus status, std::string message) {
    result_.status = status;
    result_.message = std::move(message);
    result_.search_seconds = seconds_since(t0_);
  }
  HaitResult finish(HaitStatus status, std::string message) {
    conclude(status, std::move(message));
    return std::move(result_);
  }

  /// False (result concluded) when the start or the goal is not valid for the robot.
  bool ends_valid() {
    const char* outside = " (outside the allowed region)";
    for (const auto& [which, q, status] : {std::tuple{"start", start_, HaitStatus::kStartInvalid},
                                           std::tuple{"goal", goal_, HaitStatus::kGoalInvalid}}) {
      const ConfigurationCheck check = validity_(q);
      result_.placements += check.placements;
      if (check.valid) continue;
      const bool out = options_.allowed_region && !options_.allowed_region(q);
      conclude(status, std::string(which) + " configuration " + pose_string(q) +
                           " is not valid for the robot" + (out ? outside : ""));
      return false;
    }
    return true;
  }

  double heuristic(const SE2Pose& q) const {
    const double euclid = std::hypot(goal_.x - q.x, goal_.y - q.y);
    if (options_.heuristic == HaitHeuristic::kEuclidean) return euclid;
    const double p = options_.potential_weight * potential_(q);
    if (options_.heuristic == HaitHeuristic::kPotential || euclid >= rs_region_) return p;
    // The potential ignores the goal heading; add the Reeds–Shepp curve's excess over the
    // straight line (the detour the heading costs, 0 when aligned), weighted from 1 at the
    // goal down to 0 at the region's edge. A full-weight excess switched on at the edge made
    // h jump there, and A* then developed the whole band just outside the region before
    // entering it (hait-heuristics: 1988 nodes created against the potential's 1199).
    const double weight = 1.0 - euclid / rs_region_;
    return p + weight * std::max(0.0, rs_.distance(q, goal_) - euclid);
  }

  bool at_goal(const SE2Pose& q) const {
    return std::hypot(goal_.x - q.x, goal_.y - q.y) <= tol_xy_ &&
           std::abs(wrap_angle(goal_.theta - q.theta)) <= tol_th_;
  }

  /// Final connection: a valid Reeds–Shepp curve from the node to the exact goal.
  void connect_to_goal(const Node& node, std::int64_t id) {
    const std::vector<PathPoint> curve = rs_.sample(node.q, goal_, options_.check_spacing);
    double cost = 0.0;
    bool ok = true;
    for (std::size_t k = 1; k < curve.size() && ok; ++k) {
      const ConfigurationCheck c = validity_(curve[k].pose);
      result_.placements += c.placements;
      ok = c.valid;
      const double piece =
          curve[k].control.omega != 0
              ? options_.turning_radius *
                    std::abs(wrap_angle(curve[k].pose.theta - curve[k - 1].pose.theta))
              : std::hypot(curve[k].pose.x - curve[k - 1].pose.x,
                           curve[k].pose.y - curve[k - 1].pose.y);
      cost += weighted(piece, c.margin, options_.margin_weight);
    }
    if (ok) {
      nodes_.push_back({goal_, node.g + cost, id, Control{}, true});
      ++result_.nodes_created;
      open_.push({node.g + cost, static_cast<std::int64_t>(nodes_.size() - 1)});
    }
  }

  /// A child per control whose arc is valid and ends in a cell not yet visited.
  void develop(const Node& node, std::int64_t id) {
    for (const Control& u : kControls) {
      const SE2Pose end = apply_control(node.q, u, options_.step, options_.turning_radius);
      const std::uint64_t key = cell_key(end, cell_, bins_);
      if (marked_.count(key) != 0) continue;  // at most one node per cell
      double cost = 0.0;
      bool ok = true;
      for (int k = 1; k <= n_sub_ && ok; ++k) {
        const SE2Pose qk =
            k == n_sub_ ? end : apply_control(node.q, u, ds_ * k, options_.turning_radius);
        const ConfigurationCheck c = validity_(qk);
        result_.placements += c.placements;
        ok = c.valid;
        cost += weighted(ds_, c.margin, options_.margin_weight);
      }
      if (!ok) continue;
      // The cell is visited once its arc is valid, whatever the heuristic says: an
      // unmarked cell would be validated again from every other parent reaching it.
      marked_.insert(key);
      const double h = heuristic(end);
      if (!std::isfinite(h)) continue;  // the potential says the goal is unreachable from here
      nodes_.push_back({end, node.g + cost, id, u, false});
      ++result_.nodes_created;
      open_.push({node.g + cost + h, static_cast<std::int64_t>(nodes_.size() - 1)});
    }
  }

  /// The dense path to the goal node, each node's control replayed from its parent.
  std::vector<PathPoint> replay(std::int64_t goal_node) {
    std::vector<std::int64_t> chain;
    for (std::int64_t k = goal_node; k >= 0; k = nodes_[static_cast<std::size_t>(k)].parent) {
      chain.push_back(k);
    }
    std::reverse(chain.begin(), chain.end());
    std::vector<PathPoint> path{{start_, Control{}}};
    for (std::size_t c = 1; c < chain.size(); ++c) {
      const Node& n = nodes_[static_cast<std::size_t>(chain[c])];
      const SE2Pose from = path.back().pose;
      if (n.via_rs) {
        const std::vector<PathPoint> curve = rs_.sample(from, goal_, options_.check_spacing);
        path.insert(path.end(), curve.begin() + 1, curve.end());
        result_.connected_to_goal = true;
        continue;
      }
      for (int k = 1; k <= n_sub_; ++k) {
        path.push_back(
            {k == n_sub_ ? n.q : apply_control(from, n.u, ds_ * k, options_.turning_radius), n.u});
      }
    }
    return path;
  }

  /// The result for a path found: smoothed (HaitOptions::smooth), measured.
  HaitResult found(std::vector<PathPoint> path) {
    result_.search_seconds = seconds_since(t0_);
    result_.unsmoothed_path = path;
    result_.control_changes_unsmoothed = control_changes(path);
    if (options_.smooth && path.size() >= 2) {
      const auto ts = std::chrono::steady_clock::now();
      HaitSmoothingOptions so = options_.smoothing;
      so.check_spacing = options_.check_spacing;
      HaitSmoothingReport report;
      path = smooth_path(path, validity_, rs_, so, &report);
      result_.placements += report.placements;
      result_.smoothing_seconds = seconds_since(ts);
    }
    result_.path = std::move(path);
    result_.control_changes = control_changes(result_.path);
    result_.length_m = path_length(result_.path, options_.turning_radius);
    result_.status = HaitStatus::kFound;
    std::ostringstream msg;
    msg << "path found: " << result_.length_m << " m, " << result_.control_changes
        << " control changes, " << result_.nodes_created << " nodes created";
    result_.message = msg.str();
    return std::move(result_);
  }

  const ValidityFunction& validity_;
  const PotentialFunction& potential_;
  SE2Pose start_, goal_;
  const HaitOptions& options_;
  std::chrono::steady_clock::time_point t0_;
  double cell_;
  int bins_;
  double tol_xy_, tol_th_, rs_region_;
  ReedsShepp rs_;
  int n_sub_;
  double ds_;
  std::vector<Node> nodes_;
  std::unordered_set<std::uint64_t> marked_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open_;
  HaitResult result_;
};

}  // namespace

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
  return HaitSearch(validity, potential, start, goal, options).run();
}

}  // namespace talus
