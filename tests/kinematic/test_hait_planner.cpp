#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <tuple>
#include <vector>

#include "random_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/core/graph_search.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"
#include "talus/kinematic/hait/hait_robot_validity.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using random_test::uniform;

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A synthetic world for the search: a box, forbidden discs, and a robot that
/// is a segment of half-length `half_length` along its heading. A
/// configuration is valid when the box holds the segment and its centre and
/// both ends are outside every disc; the margin grows with the clearance of
/// those three points, reaching 1 at 1 m.
struct DiscWorld {
  double x0 = -2, x1 = 12, y0 = -5, y1 = 5;
  std::vector<std::pair<Vec2, double>> discs;
  double half_length = 0.3;

  double clearance(const Vec2& p) const {
    double c = kInf;
    for (const auto& [centre, r] : discs) c = std::min(c, (p - centre).norm() - r);
    return c;
  }
  ConfigurationCheck check(const SE2Pose& q) const {
    const Vec2 d(std::cos(q.theta), std::sin(q.theta));
    double c = kInf;
    for (const Vec2& p : {q.position(), Vec2(q.position() + half_length * d),
                          Vec2(q.position() - half_length * d)}) {
      if (p.x() < x0 || p.x() > x1 || p.y() < y0 || p.y() > y1) return {false, 0.0, 1};
      c = std::min(c, clearance(p));
    }
    if (c <= 0.0) return {false, 0.0, 1};
    return {true, std::min(1.0, c), 1};
  }
  ValidityFunction validity() const {
    return [this](const SE2Pose& q) { return check(q); };
  }

  /// A potential bitmap for the tests: 8-connected wave propagation from the
  /// goal over a 0.1 m grid of the box, blocked inside the discs.
  PotentialFunction potential(const Vec2& goal) const {
    const double h = 0.1;
    const auto nx = static_cast<std::size_t>(std::round((x1 - x0) / h)) + 1;
    const auto ny = static_cast<std::size_t>(std::round((y1 - y0) / h)) + 1;
    auto node_at = [=, this](std::size_t i, std::size_t j) {
      return Vec2(x0 + static_cast<double>(i) * h, y0 + static_cast<double>(j) * h);
    };
    std::vector<unsigned char> free(nx * ny);
    for (std::size_t j = 0; j < ny; ++j) {
      for (std::size_t i = 0; i < nx; ++i) free[j * nx + i] = clearance(node_at(i, j)) > 0.0;
    }
    const auto gi = static_cast<std::size_t>(std::round((goal.x() - x0) / h));
    const auto gj = static_cast<std::size_t>(std::round((goal.y() - y0) / h));
    auto edges = [&](std::uint32_t n, auto&& emit) {
      const std::size_t i = n % nx, j = n / nx;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          if (di == 0 && dj == 0) continue;
          const auto ii = static_cast<std::ptrdiff_t>(i) + di;
          const auto jj = static_cast<std::ptrdiff_t>(j) + dj;
          if (ii < 0 || jj < 0 || ii >= static_cast<std::ptrdiff_t>(nx) ||
              jj >= static_cast<std::ptrdiff_t>(ny)) {
            continue;
          }
          const auto m = static_cast<std::uint32_t>(jj * static_cast<std::ptrdiff_t>(nx) + ii);
          if (!free[m]) continue;
          emit(m, h * std::hypot(di, dj));
        }
      }
    };
    auto field = std::make_shared<std::vector<double>>(
        shortest_paths(nx * ny, static_cast<std::uint32_t>(gj * nx + gi), edges).cost);
    const double ox = x0, oy = y0;
    return [field, nx, ny, h, ox, oy](const SE2Pose& q) {
      const auto i = static_cast<std::ptrdiff_t>(std::round((q.x - ox) / h));
      const auto j = static_cast<std::ptrdiff_t>(std::round((q.y - oy) / h));
      if (i < 0 || j < 0 || i >= static_cast<std::ptrdiff_t>(nx) ||
          j >= static_cast<std::ptrdiff_t>(ny)) {
        return kInf;
      }
      return (*field)[static_cast<std::size_t>(j) * nx + static_cast<std::size_t>(i)];
    };
  }
};

/// A "C" of overlapping discs opening towards the start: x = 5 from y = -3 to
/// 3, and arms back to x = 2 at y = ±3.
DiscWorld trap_world() {
  DiscWorld w;
  w.x0 = -3;
  w.x1 = 13;
  w.y0 = -7;
  w.y1 = 7;
  for (double y = -3.0; y <= 3.0 + 1e-9; y += 0.4) w.discs.push_back({Vec2(5.0, y), 0.3});
  for (double x = 2.0; x < 5.0; x += 0.4) {
    w.discs.push_back({Vec2(x, 3.0), 0.3});
    w.discs.push_back({Vec2(x, -3.0), 0.3});
  }
  return w;
}

void expect_all_valid(const std::vector<PathPoint>& path, const ValidityFunction& validity) {
  for (const PathPoint& p : path) {
    EXPECT_TRUE(validity(p.pose).valid)
        << "invalid configuration (" << p.pose.x << ", " << p.pose.y << ", " << p.pose.theta << ")";
  }
}

/// Consecutive configurations are joined by their control: straight pieces keep the heading.
void expect_consistent(const std::vector<PathPoint>& path, double radius) {
  for (std::size_t k = 1; k < path.size(); ++k) {
    const SE2Pose& a = path[k - 1].pose;
    const SE2Pose& b = path[k].pose;
    const Control u = path[k].control;
    ASSERT_NE(u.v, 0);
    const double dth = wrap_angle(b.theta - a.theta);
    const double len = u.omega == 0 ? std::hypot(b.x - a.x, b.y - a.y) : radius * std::abs(dth);
    const SE2Pose replay = apply_control(a, u, len, radius);
    EXPECT_NEAR(replay.x, b.x, 1e-9);
    EXPECT_NEAR(replay.y, b.y, 1e-9);
    EXPECT_NEAR(wrap_angle(replay.theta - b.theta), 0.0, 1e-9);
  }
}

TEST(HaitSearch, StraightPathOnFlatGround) {
  DiscWorld w;  // no discs: every configuration in the box is valid, margin 1
  HaitOptions o;
  o.heuristic = HaitHeuristic::kEuclidean;
  const HaitResult r = hait_search(w.validity(), {}, {0, 0, 0}, {10, 0, 0}, o);
  ASSERT_EQ(r.status, HaitStatus::kFound) << r.message;
  EXPECT_NEAR(r.length_m, 10.0, 1e-9);
  EXPECT_EQ(r.control_changes, 0u);
  EXPECT_TRUE(r.connected_to_goal);
  for (std::size_t k = 1; k < r.path.size(); ++k) {
    EXPECT_EQ(r.path[k].control, (Control{1, 0}));
    EXPECT_NEAR(r.path[k].pose.y, 0.0, 1e-12);
  }
  EXPECT_DOUBLE_EQ(r.path.back().pose.x, 10.0);
  EXPECT_GT(r.nodes_developed, 0u);
  EXPECT_GE(r.nodes_created, r.nodes_developed);
  EXPECT_GE(r.placements, r.path.size() - 1);
  // The straight run never needs more than its own cells plus the neighbours of each.
  EXPECT_LT(r.nodes_created, 200u);
}

TEST(HaitSearch, GoalCellWithoutFinalConnection) {
  DiscWorld w;
  HaitOptions o;
  o.heuristic = HaitHeuristic::kEuclidean;
  o.connect_goal = false;
  const HaitResult r = hait_search(w.validity(), {}, {0, 0, 0}, {8, 0, 0}, o);
  ASSERT_EQ(r.status, HaitStatus::kFound) << r.message;
  EXPECT_FALSE(r.connected_to_goal);
  EXPECT_LE(std::hypot(r.path.back().pose.x - 8, r.path.back().pose.y), o.cell_size);
  EXPECT_LE(std::abs(wrap_angle(r.path.back().pose.theta)), 2 * kPi / o.theta_bins);
  expect_consistent(r.path, o.turning_radius);
}

TEST(HaitSearch, DetoursAroundAForbiddenDisc) {
  DiscWorld w;
  w.discs.push_back({Vec2(5, 0), 1.5});
  for (HaitHeuristic h :
       {HaitHeuristic::kEuclidean, HaitHeuristic::kPotential, HaitHeuristic::kPotentialRs}) {
    HaitOptions o;
    o.heuristic = h;
    const HaitResult r = hait_search(w.validity(), w.potential({10, 0}), {0, 0, 0}, {10, 0, 0}, o);
    ASSERT_EQ(r.status, HaitStatus::kFound) << heuristic_name(h) << ": " << r.message;
    expect_all_valid(r.path, w.validity());
    expect_consistent(r.path, o.turning_radius);
    EXPECT_GT(r.length_m, 10.5) << heuristic_name(h);  // the straight line is blocked
    double max_offset = 0.0;
    for (const PathPoint& p : r.path) max_offset = std::max(max_offset, std::abs(p.pose.y));
    EXPECT_GT(max_offset, 1.5) << heuristic_name(h);  // went round the disc
    EXPECT_NEAR(r.path.back().pose.x, 10.0, o.cell_size);
  }
}

TEST(HaitSearch, PotentialDevelopsFewerNodesThanEuclideanInATrap) {
  const DiscWorld w = trap_world();
  const SE2Pose start{0, 0, 0}, goal{10, 0, 0};
  const PotentialFunction pot = w.potential(goal.position());
  std::size_t developed[3] = {};
  int k = 0;
  for (HaitHeuristic h :
       {HaitHeuristic::kEuclidean, HaitHeuristic::kPotential, HaitHeuristic::kPotentialRs}) {
    HaitOptions o;
    o.heuristic = h;
    const HaitResult r = hait_search(w.validity(), pot, start, goal, o);
    ASSERT_EQ(r.status, HaitStatus::kFound) << heuristic_name(h) << ": " << r.message;
    expect_all_valid(r.path, w.validity());
    developed[k++] = r.nodes_developed;
  }
  EXPECT_LT(developed[1], developed[0] / 2) << developed[0] << " vs " << developed[1];
  EXPECT_LT(developed[2], developed[0] / 2) << developed[0] << " vs " << developed[2];
}

TEST(HaitSearch, PotentialRsRespectsTheGoalHeading) {
  DiscWorld w;
  HaitOptions o;
  o.heuristic = HaitHeuristic::kPotentialRs;
  o.connect_goal = false;  // the goal cell must be reached by the search itself
  const SE2Pose goal{8, 2, kPi / 2};
  const HaitResult r = hait_search(w.validity(), w.potential(goal.position()), {0, 0, 0}, goal, o);
  ASSERT_EQ(r.status, HaitStatus::kFound) << r.message;
  EXPECT_LE(std::abs(wrap_angle(r.path.back().pose.theta - goal.theta)), 2 * kPi / o.theta_bins);
}

TEST(HaitSearch, SameOptionsSameRun) {
  const DiscWorld w = trap_world();
  HaitOptions o;
  o.smooth = true;
  o.smoothing.seed = 42;
  const PotentialFunction pot = w.potential({10, 0});
  const HaitResult a = hait_search(w.validity(), pot, {0, 0, 0}, {10, 0, 0}, o);
  const HaitResult b = hait_search(w.validity(), pot, {0, 0, 0}, {10, 0, 0}, o);
  ASSERT_EQ(a.status, HaitStatus::kFound);
  EXPECT_EQ(a.nodes_created, b.nodes_created);
  EXPECT_EQ(a.nodes_developed, b.nodes_developed);
  EXPECT_EQ(a.placements, b.placements);
  ASSERT_EQ(a.path.size(), b.path.size());
  for (std::size_t k = 0; k < a.path.size(); ++k) {
    EXPECT_EQ(a.path[k].pose.x, b.path[k].pose.x);
    EXPECT_EQ(a.path[k].pose.y, b.path[k].pose.y);
    EXPECT_EQ(a.path[k].control, b.path[k].control);
  }
}

TEST(HaitSmoothing, NeverAddsControlChangesAndStaysValid) {
  DiscWorld w;
  w.discs.push_back({Vec2(5, 0), 1.5});
  w.discs.push_back({Vec2(2.5, 2.5), 0.6});
  HaitOptions o;
  o.heuristic = HaitHeuristic::kEuclidean;
  const HaitResult r = hait_search(w.validity(), {}, {0, 0, 0}, {10, 0, 0}, o);
  ASSERT_EQ(r.status, HaitStatus::kFound) << r.message;
  ASSERT_GT(r.control_changes, 0u);
  const ReedsShepp rs(o.turning_radius);
  std::size_t best = r.control_changes;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    HaitSmoothingOptions so;
    so.seed = seed;
    HaitSmoothingReport rep;
    const std::vector<PathPoint> s = smooth_path(r.path, w.validity(), rs, so, &rep);
    EXPECT_EQ(rep.control_changes_before, r.control_changes);
    EXPECT_EQ(rep.control_changes_after, control_changes(s));
    EXPECT_LE(rep.control_changes_after, rep.control_changes_before);
    expect_all_valid(s, w.validity());
    expect_consistent(s, o.turning_radius);
    EXPECT_EQ(s.front().pose.x, r.path.front().pose.x);
    EXPECT_EQ(s.back().pose.x, r.path.back().pose.x);
    EXPECT_EQ(s.back().pose.y, r.path.back().pose.y);
    EXPECT_NEAR(rep.length_after, path_length(s, o.turning_radius), 1e-9);
    best = std::min(best, rep.control_changes_after);
    // Same seed, same result.
    const std::vector<PathPoint> again = smooth_path(r.path, w.validity(), rs, so);
    ASSERT_EQ(again.size(), s.size());
    for (std::size_t k = 0; k < s.size(); ++k) EXPECT_EQ(again[k].pose.x, s[k].pose.x);
  }
  EXPECT_LT(best, r.control_changes);  // smoothing does something on this path
}

TEST(HaitSmoothing, GreedyPassesNeverAddControlChangesAndStayValid) {
  DiscWorld w;
  w.discs.push_back({Vec2(5, 0), 1.5});
  w.discs.push_back({Vec2(2.5, 2.5), 0.6});
  HaitOptions o;
  o.heuristic = HaitHeuristic::kEuclidean;
  const HaitResult r = hait_search(w.validity(), {}, {0, 0, 0}, {10, 0, 0}, o);
  ASSERT_EQ(r.status, HaitStatus::kFound) << r.message;
  const ReedsShepp rs(o.turning_radius);
  for (const std::size_t pairs : {std::size_t{0}, std::size_t{300}}) {
    HaitSmoothingOptions so;
    so.method = HaitSmoothingMethod::kRandomPairsThenGreedy;
    so.iterations = pairs;
    so.seed = 7;
    HaitSmoothingReport rep;
    const std::vector<PathPoint> s = smooth_path(r.path, w.validity(), rs, so, &rep);
    EXPECT_EQ(rep.control_changes_after, control_changes(s));
    // The greedy passes start from the random pairs' result and never undo it.
    EXPECT_LE(rep.control_changes_after, rep.control_changes_random);
    EXPECT_LE(rep.control_changes_random, rep.control_changes_before);
    EXPECT_LT(rep.control_changes_after, r.control_changes);  // it shortcuts this path
    EXPECT_GE(rep.greedy_passes, 1u);
    if (pairs == 0) {
      EXPECT_EQ(rep.control_changes_random, rep.control_changes_before);
    }
    expect_all_valid(s, w.validity());
    expect_consistent(s, o.turning_radius);
    EXPECT_EQ(s.front().pose.x, r.path.front().pose.x);
    EXPECT_EQ(s.back().pose.x, r.path.back().pose.x);
    EXPECT_EQ(s.back().pose.y, r.path.back().pose.y);
    EXPECT_NEAR(rep.length_after, path_length(s, o.turning_radius), 1e-9);
    // Same seed, same result.
    const std::vector<PathPoint> again = smooth_path(r.path, w.validity(), rs, so);
    ASSERT_EQ(again.size(), s.size());
    for (std::size_t k = 0; k < s.size(); ++k) EXPECT_EQ(again[k].pose.y, s[k].pose.y);
  }
}

TEST(HaitSmoothing, GreedyReachesTheGoalInOneCurveWhenNothingIsInTheWay) {
  // A zigzag on empty ground: the first greedy try, start to goal, is valid
  // and leaves the shortest Reeds–Shepp curve between the path's ends.
  DiscWorld w;
  std::vector<PathPoint> zigzag{{{0, 0, 0}, Control{}}};
  const Control turns[] = {{1, 1}, {1, -1}, {1, -1}, {1, 1}, {1, 0}, {1, 1}, {1, -1}};
  for (const Control& u : turns) {
    for (int k = 1; k <= 4; ++k) {
      zigzag.push_back({apply_control(zigzag.back().pose, u, 0.1, 1.0), u});
    }
  }
  ASSERT_GE(control_changes(zigzag), 5u);
  const ReedsShepp rs(1.0);
  HaitSmoothingOptions so;
  so.method = HaitSmoothingMethod::kRandomPairsThenGreedy;
  so.iterations = 0;
  HaitSmoothingReport rep;
  const std::vector<PathPoint> s = smooth_path(zigzag, w.validity(), rs, so, &rep);
  EXPECT_EQ(rep.replacements, 1u);
  EXPECT_NEAR(rep.length_after, rs.distance(zigzag.front().pose, zigzag.back().pose), 1e-6);
  EXPECT_EQ(rep.control_changes_after,
            rs.segments(zigzag.front().pose, zigzag.back().pose).size() - 1);
}

TEST(HaitSmoothing, DrawWithinSpanKeepsTheInvariants) {
  DiscWorld w;
  w.discs.push_back({Vec2(5, 0), 1.5});
  HaitOptions o;
  o.heuristic = HaitHeuristic::kEuclidean;
  const HaitResult r = hait_search(w.validity(), {}, {0, 0, 0}, {10, 0, 0}, o);
  ASSERT_EQ(r.status, HaitStatus::kFound) << r.message;
  const ReedsShepp rs(o.turning_radius);
  for (const bool within : {false, true}) {
    HaitSmoothingOptions so;
    so.draw_within_span = within;
    so.max_span = 2.0;
    HaitSmoothingReport rep;
    const std::vector<PathPoint> s = smooth_path(r.path, w.validity(), rs, so, &rep);
    EXPECT_LE(rep.control_changes_after, rep.control_changes_before);
    EXPECT_EQ(rep.control_changes_after, control_changes(s));
    expect_all_valid(s, w.validity());
    expect_consistent(s, o.turning_radius);
  }
}

TEST(HaitUncertainty, NeighbourhoodNeverAcceptsWhatTheCertainCheckRejects) {
  const DiscWorld w = trap_world();
  const ValidityFunction certain = w.validity();
  const ValidityFunction uncertain = neighbourhood_validity(certain, 0.3, 0.7, 0.1, 0.1);
  std::mt19937_64 rng(3);
  int strictly_tighter = 0;
  for (int k = 0; k < 3000; ++k) {
    const SE2Pose q{uniform(rng, w.x0, w.x1), uniform(rng, w.y0, w.y1), uniform(rng, -kPi, kPi)};
    const ConfigurationCheck u = uncertain(q), c = certain(q);
    if (u.valid) {
      EXPECT_TRUE(c.valid);
      EXPECT_LE(u.margin, c.margin);
    }
    if (c.valid && !u.valid) ++strictly_tighter;
  }
  EXPECT_GT(strictly_tighter, 10);
}

TEST(HaitUncertainty, UncertainPathIsValidForTheCertainPlanner) {
  DiscWorld w;
  w.discs.push_back({Vec2(5, 0.8), 1.2});
  w.discs.push_back({Vec2(5, -2.4), 1.2});  // a 0.8 m gorge between the discs, y in [-1.2, -0.4]
  const ValidityFunction certain = w.validity();
  HaitOptions o;
  o.heuristic = HaitHeuristic::kPotential;
  const PotentialFunction pot = w.potential({10, 0});
  const HaitResult base = hait_search(certain, pot, {0, 0, 0}, {10, 0, 0}, o);
  ASSERT_EQ(base.status, HaitStatus::kFound) << base.message;
  const ValidityFunction uncertain = neighbourhood_validity(certain, 0.5, 0.35, 0.1, 0.1);
  const HaitResult robust = hait_search(uncertain, pot, {0, 0, 0}, {10, 0, 0}, o);
  ASSERT_EQ(robust.status, HaitStatus::kFound) << robust.message;
  expect_all_valid(robust.path, certain);
  expect_all_valid(robust.path, uncertain);
  // The corridor: every configuration keeps the robot 0.5 m clear laterally.
  for (const PathPoint& p : robust.path) {
    EXPECT_GT(w.clearance(p.pose.position()), 0.0);
  }
  EXPECT_GT(robust.placements, base.placements);
  // The certain path takes the gorge; it is too narrow for a ±0.5 m corridor, so the
  // robust path goes round both discs.
  auto y_at_5 = [](const std::vector<PathPoint>& path) {
    double y = 0.0;
    for (const PathPoint& p : path) {
      if (std::abs(p.pose.x - 5.0) < 0.15) y = p.pose.y;
    }
    return y;
  };
  EXPECT_GT(y_at_5(base.path), -1.2);
  EXPECT_LT(y_at_5(base.path), -0.4);
  EXPECT_GT(std::abs(y_at_5(robust.path)), 2.0);
}

TEST(HaitSearch, InvalidStartOrGoalIsAStatus) {
  DiscWorld w;
  w.discs.push_back({Vec2(5, 0), 1.5});
  HaitOptions o;
  o.heuristic = HaitHeuristic::kEuclidean;
  const HaitResult s = hait_search(w.validity(), {}, {5, 0, 0}, {10, 0, 0}, o);
  EXPECT_EQ(s.status, HaitStatus::kStartInvalid);
  EXPECT_NE(s.message.find("start configuration (5, 0, 0)"), std::string::npos) << s.message;
  EXPECT_TRUE(s.path.empty());
  const HaitResult g = hait_search(w.validity(), {}, {0, 0, 0}, {5.5, 0.2, 1}, o);
  EXPECT_EQ(g.status, HaitStatus::kGoalInvalid);
  EXPECT_NE(g.message.find("goal configuration"), std::string::npos) << g.message;
  EXPECT_EQ(status_name(g.status), "goal_invalid");
}

TEST(HaitSearch, EnclosedGoalIsNoPath) {
  DiscWorld w;
  w.x0 = -2;
  w.x1 = 8;
  w.y0 = -3;
  w.y1 = 3;
  for (int k = 0; k < 40; ++k) {
    const double a = 2 * kPi * k / 40;
    w.discs.push_back({Vec2(5 + 1.5 * std::cos(a), 1.5 * std::sin(a)), 0.2});
  }
  HaitOptions o;
  o.heuristic = HaitHeuristic::kEuclidean;
  const HaitResult r = hait_search(w.validity(), {}, {0, 0, 0}, {5, 0, 0}, o);
  EXPECT_EQ(r.status, HaitStatus::kNoPath) << r.message;
  HaitOptions tight = o;
  tight.max_nodes = 50;
  EXPECT_EQ(hait_search(w.validity(), {}, {0, 0, 0}, {5, 0, 0}, tight).status,
            HaitStatus::kNodeLimit);
}

/// The planner's cell of q (§4.1: cell_size x cell_size x 2π / bins), re-derived here.
std::tuple<long, long, long> cell_of(const SE2Pose& q, double cell, int bins) {
  double t = std::fmod(q.theta, 2 * kPi);
  if (t < 0) t += 2 * kPi;
  return {
      static_cast<long>(std::floor(q.x / cell)), static_cast<long>(std::floor(q.y / cell)),
      std::min(static_cast<long>(std::floor(t / (2 * kPi) * bins)), static_cast<long>(bins - 1))};
}

TEST(HaitSearch, AChildOfInfinitePotentialIsValidatedOnce) {
  // The potential is infinite from x = 1 on: valid children there get no node,
  // but their cells are visited, so no other parent validates them again (§4.1:
  // "each new cell is marked"). One check per arc (step = check_spacing), so
  // every validity call but the start's and the goal's ends one arc.
  DiscWorld w;
  w.x0 = -2;
  w.x1 = 4;
  w.y0 = -2;
  w.y1 = 2;
  HaitOptions o;
  o.heuristic = HaitHeuristic::kPotential;
  o.connect_goal = false;
  o.check_spacing = o.step;
  const SE2Pose start{0, 0, 0}, goal{3, 0, 0};
  const PotentialFunction wall = [&](const SE2Pose& q) {
    return q.x < 1.0 ? std::hypot(goal.x - q.x, goal.y - q.y) : kInf;
  };
  std::map<std::tuple<long, long, long>, int> beyond;  // cells past the wall: validity calls
  std::size_t calls = 0, placements = 0;
  const ValidityFunction counted = [&](const SE2Pose& q) {
    const ConfigurationCheck c = w.check(q);
    ++calls;
    placements += c.placements;
    if (c.valid && q.x >= 1.0 && calls > 2) ++beyond[cell_of(q, o.cell_size, o.theta_bins)];
    return c;
  };
  const HaitResult r = hait_search(counted, wall, start, goal, o);
  EXPECT_EQ(r.status, HaitStatus::kNoPath) << r.message;
  EXPECT_EQ(r.placements, placements);
  ASSERT_GT(beyond.size(), 20u);  // the wall is reached along its whole length
  for (const auto& [cell, n] : beyond) {
    EXPECT_EQ(n, 1) << "cell (" << std::get<0>(cell) << ", " << std::get<1>(cell) << ", "
                    << std::get<2>(cell) << ") validated " << n << " times";
  }
}

TEST(HaitSearch, RejectsBadOptionsAndInputs) {
  DiscWorld w;
  HaitOptions o;
  o.cell_size = 0.0;
  try {
    hait_search(w.validity(), {}, {0, 0, 0}, {1, 0, 0}, o);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cell_size"), std::string::npos) << e.what();
  }
  HaitOptions p;  // potential heuristics need a potential
  EXPECT_THROW(hait_search(w.validity(), {}, {0, 0, 0}, {1, 0, 0}, p), InputError);
  EXPECT_THROW(hait_search(w.validity(), {}, {NAN, 0, 0}, {1, 0, 0}, HaitOptions{}), InputError);
  EXPECT_EQ(parse_heuristic("potential-rs"), HaitHeuristic::kPotentialRs);
  EXPECT_THROW(parse_heuristic("dijkstra"), InputError);
}

// ---- The real robot (sprung rigid body) on ruled terrains ----

WheeledRobot small_rover() {
  WheeledRobot r;
  r.name = "test rover";
  r.wheels = {Vec2(0.4, 0.3), Vec2(0.4, -0.3), Vec2(-0.4, -0.3), Vec2(-0.4, 0.3)};
  r.cg_height = 0.3;
  r.max_spring_extension = 0.1;
  r.max_roll = 0.3;
  r.max_pitch = 0.3;
  r.body = {0.5, 0.5, 0.35, 0.2};
  return r;
}

/// 12 m x 8 m at 0.25 m; an optional steep Gaussian hill (peak `height` at (6, 4), sigma 0.9 m).
RuledTerrain hill_terrain(double height) {
  return RuledTerrain(terrain_test::grid_of_nodes(
      terrain_test::gaussian_hill(Vec2(6, 4), height, 0.9), 49, 33, 0.25, 0.0, 0.0));
}

TEST(HaitPlan, StraightPathOnFlatGround) {
  const RuledTerrain flat = hill_terrain(0.0);
  for (HaitHeuristic h :
       {HaitHeuristic::kEuclidean, HaitHeuristic::kPotential, HaitHeuristic::kPotentialRs}) {
    HaitOptions o;
    o.heuristic = h;
    const HaitResult r = plan_hait(flat, small_rover(), {2, 4, 0}, {10, 4, 0}, o);
    ASSERT_EQ(r.status, HaitStatus::kFound) << heuristic_name(h) << ": " << r.message;
    EXPECT_NEAR(r.length_m, 8.0, 1e-6) << heuristic_name(h);
    EXPECT_EQ(r.control_changes, 0u) << heuristic_name(h);
    EXPECT_GE(r.placements, r.path.size() - 1);
    EXPECT_GE(r.preprocessing_seconds, 0.0);
  }
}

TEST(HaitPlan, DetoursAroundASteepHillWithEveryConfigurationValid) {
  const RuledTerrain hill = hill_terrain(1.5);
  const WheeledRobot rover = small_rover();
  const HaitRobotValidity certain(hill, rover);
  // The top of the hill is too steep to stand on across it.
  EXPECT_FALSE(certain.check({5.2, 4, 0}).valid);
  for (HaitHeuristic h : {HaitHeuristic::kEuclidean, HaitHeuristic::kPotentialRs}) {
    HaitOptions o;
    o.heuristic = h;
    const HaitResult r = plan_hait(hill, rover, {1.5, 4, 0}, {10.5, 4, 0}, o);
    ASSERT_EQ(r.status, HaitStatus::kFound) << heuristic_name(h) << ": " << r.message;
    expect_all_valid(r.path, certain.function());
    expect_consistent(r.path, o.turning_radius);
    EXPECT_GT(r.length_m, 9.2) << heuristic_name(h);
    double max_offset = 0.0;
    for (const PathPoint& p : r.path) max_offset = std::max(max_offset, std::abs(p.pose.y - 4));
    EXPECT_GT(max_offset, 1.0) << heuristic_name(h);
  }
}

TEST(HaitPlan, UncertainPathIsValidForTheCertainRobot) {
  const RuledTerrain hill = hill_terrain(1.5);
  const WheeledRobot rover = small_rover();
  const HaitRobotValidity certain(hill, rover);
  HaitOptions o;
  o.terrain_uncertainty = 0.03;
  o.position_uncertainty = 0.1;
  o.heading_uncertainty = 0.15;
  const HaitResult r = plan_hait(hill, rover, {1.5, 4, 0}, {10.5, 4, 0}, o);
  ASSERT_EQ(r.status, HaitStatus::kFound) << r.message;
  RecordProperty("placements", static_cast<int>(r.placements));
  RecordProperty("nodes_created", static_cast<int>(r.nodes_created));
  expect_all_valid(r.path, certain.function());
  // And every configuration of the certain oracle's own corridor is valid too.
  const ValidityFunction corridor =
      neighbourhood_validity(certain.function(), 0.1, 0.15, o.check_spacing, 0.05);
  for (std::size_t k = 0; k < r.path.size(); k += 7) {
    EXPECT_TRUE(corridor(r.path[k].pose).valid) << k;
  }
  // Worst-case checks accept nothing the certain ones reject.
  const HaitRobotValidity uncertain(hill, rover, 0.03);
  std::mt19937_64 rng(5);
  int tighter = 0;
  for (int k = 0; k < 400; ++k) {
    const SE2Pose q{uniform(rng, 1, 11), uniform(rng, 1, 7), uniform(rng, -kPi, kPi)};
    const ConfigurationCheck u = uncertain.check(q), c = certain.check(q);
    if (u.valid) {
      EXPECT_TRUE(c.valid) << q.x << " " << q.y << " " << q.theta;
    }
    if (c.valid && !u.valid) ++tighter;
  }
  EXPECT_GT(tighter, 0);
}

TEST(HaitPlan, ConfigurationsWhoseControlPointLeavesTheMapGetNodes) {
  // Heading west 0.45 m from the west edge: the wheels (0.4 m ahead and behind)
  // stand on the map, the front control point (0.5 m ahead, half the body) does
  // not. The potential there is read at the map's edge, not +inf, so the
  // search starts and reverses out.
  const RuledTerrain flat = hill_terrain(0.0);
  const WheeledRobot rover = small_rover();
  const SE2Pose start{0.45, 4, kPi};
  ASSERT_TRUE(HaitRobotValidity(flat, rover).check(start).valid);
  for (HaitHeuristic h : {HaitHeuristic::kPotential, HaitHeuristic::kPotentialRs}) {
    HaitOptions o;
    o.heuristic = h;
    const HaitResult r = plan_hait(flat, rover, start, {6, 4, kPi}, o);
    ASSERT_EQ(r.status, HaitStatus::kFound) << heuristic_name(h) << ": " << r.message;
    EXPECT_GE(r.length_m, 6 - 0.45 - 1e-9) << heuristic_name(h);  // the start-goal distance
  }
}

TEST(HaitPlan, InvalidOrOffMapStartAndGoal) {
  const RuledTerrain hill = hill_terrain(1.5);
  HaitOptions o;
  const HaitResult s = plan_hait(hill, small_rover(), {5.2, 4, 0}, {10.5, 4, 0}, o);
  EXPECT_EQ(s.status, HaitStatus::kStartInvalid) << s.message;
  const HaitResult g = plan_hait(hill, small_rover(), {1.5, 4, 0}, {6.8, 4, kPi / 2}, o);
  EXPECT_EQ(g.status, HaitStatus::kGoalInvalid) << g.message;
  EXPECT_THROW(plan_hait(hill, small_rover(), {-1, 4, 0}, {10.5, 4, 0}, o), InputError);
  EXPECT_THROW(plan_hait(hill, small_rover(), {1.5, 4, 0}, {10.5, 40, 0}, o), InputError);
}

}  // namespace
}  // namespace talus
