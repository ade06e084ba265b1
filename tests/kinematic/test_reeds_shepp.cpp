#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "talus/core/error.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/reeds_shepp.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

/// Uniform in [lo, hi) from raw mt19937_64 bits (platform-independent).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

SE2Pose random_pose(std::mt19937_64& rng) {
  return {uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -kPi, kPi)};
}

TEST(ConfigurationSpace, ApplyControlFollowsExactArcs) {
  // A quarter circle to the left of radius 2 from the origin facing east.
  const SE2Pose q = apply_control({0, 0, 0}, {1, 1}, kPi, 2.0);
  EXPECT_NEAR(q.x, 2.0, 1e-12);
  EXPECT_NEAR(q.y, 2.0, 1e-12);
  EXPECT_NEAR(q.theta, kPi / 2, 1e-12);
  // Reversing with the wheels steered left turns clockwise, backing onto the left circle.
  const SE2Pose r = apply_control({0, 0, 0}, {-1, -1}, kPi, 2.0);
  EXPECT_NEAR(r.x, -2.0, 1e-12);
  EXPECT_NEAR(r.y, 2.0, 1e-12);
  EXPECT_NEAR(r.theta, -kPi / 2, 1e-12);
  EXPECT_EQ(control_name({-1, -1}), "reverse-left");
  EXPECT_EQ(control_name({1, -1}), "forward-right");
  EXPECT_EQ(control_name({}), "none");
  // Driving forward then back the same way returns to the start.
  const SE2Pose back =
      apply_control(apply_control({1, 2, 0.3}, {1, -1}, 0.7, 1.5), {-1, 1}, 0.7, 1.5);
  EXPECT_NEAR(back.x, 1.0, 1e-12);
  EXPECT_NEAR(back.y, 2.0, 1e-12);
  EXPECT_NEAR(back.theta, 0.3, 1e-12);
}

TEST(ConfigurationSpace, ControlChangesCountSwitchesOnly) {
  std::vector<PathPoint> p{{{}, {}}, {{}, {1, 0}}, {{}, {1, 0}}, {{}, {1, 1}}, {{}, {-1, 1}}};
  EXPECT_EQ(control_changes(p), 2u);
  p.resize(3);
  EXPECT_EQ(control_changes(p), 0u);
}

TEST(ReedsShepp, StraightTranslationDistanceIsItsLength) {
  const ReedsShepp rs(1.0);
  EXPECT_NEAR(rs.distance({0, 0, 0}, {3, 0, 0}), 3.0, 1e-9);
  EXPECT_NEAR(rs.distance({1, 1, kPi / 4}, {3, 3, kPi / 4}), std::sqrt(8.0), 1e-9);
  // Straight back: reverse.
  EXPECT_NEAR(rs.distance({0, 0, 0}, {-2, 0, 0}), 2.0, 1e-9);
  const auto fwd = rs.segments({0, 0, 0}, {3, 0, 0});
  ASSERT_EQ(fwd.size(), 1u);
  EXPECT_EQ(fwd[0].control, (Control{1, 0}));
  const auto rev = rs.segments({0, 0, 0}, {-2, 0, 0});
  ASSERT_EQ(rev.size(), 1u);
  EXPECT_EQ(rev[0].control, (Control{-1, 0}));
  EXPECT_NEAR(rev[0].length, 2.0, 1e-9);
}

TEST(ReedsShepp, QuarterTurnIsOneArc) {
  const double r = 1.5;
  const ReedsShepp rs(r);
  EXPECT_NEAR(rs.distance({0, 0, 0}, {r, r, kPi / 2}), r * kPi / 2, 1e-9);
  const auto segs = rs.segments({0, 0, 0}, {r, r, kPi / 2});
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].control, (Control{1, 1}));
}

// Lower bounds used below to prove that a hand-built path is the shortest, for
// any path with curvature |κ| <= 1/r, forwards or backwards (unit speed in
// arc length s):
// (H) the heading changes at rate <= 1/r, so length >= r |wrap(θ_b - θ_a)|.
// (Y) |dy/ds| = |sin θ|. Let ψ(s) = distance of θ(s) to the nearest multiple
//     of π, so |sin θ| = sin ψ, |ψ'| <= 1/r. If θ_a and θ_b are multiples of π,
//     ψ starts and ends at 0, and ∫ sin ψ ds is largest for ψ rising at the
//     maximum rate to π/2, held, and falling again: ∫ |sin θ| ds <= 2r + (L - rπ)
//     for L >= rπ, and <= 2r (1 - cos(L / 2r)) < 2r for L < rπ. So a lateral
//     displacement |Δy| = 2r + d (d > 0) needs L >= rπ + d.

TEST(ReedsShepp, CscWordsHaveTheirHandDerivedLength) {
  const double r = 1.3, d = 2.1;
  const ReedsShepp rs(r);
  // L+ 90°, S d, L+ 90° from the origin facing east: the first arc (centre
  // (0, r)) ends at (r, r) facing north; the straight at (r, r + d); the
  // second arc (centre (0, r + d)) at (0, 2r + d) facing west. Length rπ + d,
  // and by (Y) (Δy = 2r + d, θ_b = π) nothing is shorter.
  const SE2Pose u_turn{0.0, 2 * r + d, kPi};
  EXPECT_NEAR(rs.distance({0, 0, 0}, u_turn), r * kPi + d, 1e-9);
  // The mirror word R- S- R- (backing round the other way) is as short, so
  // only the shape is fixed: two quarter arcs and the straight d.
  const auto lsl = rs.segments({0, 0, 0}, u_turn);
  ASSERT_EQ(lsl.size(), 3u);
  EXPECT_NE(lsl[0].control.omega, 0);
  EXPECT_EQ(lsl[1].control.omega, 0);
  EXPECT_NE(lsl[2].control.omega, 0);
  EXPECT_NEAR(lsl[0].length, r * kPi / 2, 1e-9);
  EXPECT_NEAR(lsl[1].length, d, 1e-9);
  // L+ 90°, S d, R+ 90°: the right arc (centre (2r, r + d)) ends at
  // (2r, 2r + d) facing east again. Same length, same bound (Y).
  const SE2Pose lane_change{2 * r, 2 * r + d, 0.0};
  EXPECT_NEAR(rs.distance({0, 0, 0}, lane_change), r * kPi + d, 1e-9);
  const auto lsr = rs.segments({0, 0, 0}, lane_change);
  ASSERT_EQ(lsr.size(), 3u);
  EXPECT_EQ(lsr[2].control, (Control{1, -1}));
  // The metric is invariant under a rigid motion of both poses.
  const double c = std::cos(0.9), s = std::sin(0.9);
  const SE2Pose a{4.0, -1.0, 0.9};
  const SE2Pose b{4.0 - s * (2 * r + d), -1.0 + c * (2 * r + d), 0.9 + kPi};
  EXPECT_NEAR(rs.distance(a, b), r * kPi + d, 1e-9);
}

TEST(ReedsShepp, CccWordThatOnlyTurnsOneWayIsShortestByTheHeadingBound) {
  // L+ α, R- β, L+ γ: forward-left and reverse-right both turn the heading
  // counter-clockwise at 1/r, so the heading ends at α + β + γ (lengths in
  // radians times r). By (H) no path is shorter than r (α + β + γ) when that
  // is <= π, so this word is a shortest path, whatever the end position.
  // End position by circle centres: on a left arc the vehicle is at
  // C + r (sin θ, -cos θ), on a right arc at C + r (-sin θ, cos θ); at a switch
  // the next centre is the reflection of the current one through the vehicle:
  //   C1 = (0, r),  C2 = C1 + 2r (sin α, -cos α),
  //   C3 = C2 + 2r (-sin θ2, cos θ2),  end = C3 + r (sin θ3, -cos θ3),
  // with θ2 = α + β, θ3 = α + β + γ.
  const double r = 1.3, alpha = 0.5, beta = 0.7, gamma = 0.4;
  const double t2 = alpha + beta, t3 = alpha + beta + gamma;
  const double x = 2 * r * (std::sin(alpha) - std::sin(t2)) + r * std::sin(t3);
  const double y = r + 2 * r * (std::cos(t2) - std::cos(alpha)) - r * std::cos(t3);
  const SE2Pose goal{x, y, t3};
  // Cross-check the hand formula against the exact arc integrator.
  SE2Pose q = apply_control({0, 0, 0}, {1, 1}, r * alpha, r);
  q = apply_control(q, {-1, 1}, r * beta, r);
  q = apply_control(q, {1, 1}, r * gamma, r);
  EXPECT_NEAR(q.x, goal.x, 1e-12);
  EXPECT_NEAR(q.y, goal.y, 1e-12);
  EXPECT_NEAR(q.theta, goal.theta, 1e-12);
  const ReedsShepp rs(r);
  EXPECT_NEAR(rs.distance({0, 0, 0}, goal), r * t3, 1e-9);
  const auto segs = rs.segments({0, 0, 0}, goal);
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_EQ(segs[0].control, (Control{1, 1}));
  EXPECT_EQ(segs[1].control, (Control{-1, 1}));
  EXPECT_EQ(segs[2].control, (Control{1, 1}));
  EXPECT_NEAR(segs[0].length, r * alpha, 1e-9);
  EXPECT_NEAR(segs[1].length, r * beta, 1e-9);
  EXPECT_NEAR(segs[2].length, r * gamma, 1e-9);
}

TEST(ReedsShepp, PureReverseTranslationCostsItsLength) {
  // Backing straight up by d at any heading: length d, and nothing is shorter
  // than the straight-line distance d.
  const ReedsShepp rs(0.7);
  for (double heading : {0.0, 0.4, 2.5, -1.9}) {
    const SE2Pose a{1.0, 2.0, heading};
    for (double d : {0.05, 1.0, 6.5}) {
      const SE2Pose b{a.x - d * std::cos(heading), a.y - d * std::sin(heading), heading};
      EXPECT_NEAR(rs.distance(a, b), d, 1e-9) << heading << " " << d;
      const auto segs = rs.segments(a, b);
      ASSERT_EQ(segs.size(), 1u);
      EXPECT_EQ(segs[0].control, (Control{-1, 0}));
    }
  }
}

TEST(ReedsShepp, NoRandomAdmissiblePathIsShorterThanTheMetric) {
  // Every sequence of exact arcs and straights is an admissible path, so the
  // shortest-path length from its start to its end is at most its length.
  // Short words keep the ends close, where the shortest word is often the
  // driven one itself (equality), so an overestimating metric would show.
  const double r = 0.9;
  const ReedsShepp rs(r);
  std::mt19937_64 rng(23);
  const Control controls[6] = {{1, 0}, {1, 1}, {1, -1}, {-1, 0}, {-1, 1}, {-1, -1}};
  int equal = 0;
  for (int k = 0; k < 2000; ++k) {
    const SE2Pose start = random_pose(rng);
    SE2Pose q = start;
    double driven = 0.0;
    const int pieces = 1 + static_cast<int>(rng() % 5);
    for (int p = 0; p < pieces; ++p) {
      const double length = uniform(rng, 0.0, 1.5);
      q = apply_control(q, controls[rng() % 6], length, r);
      driven += length;
    }
    const double metric = rs.distance(start, q);
    EXPECT_LE(metric, driven + 1e-9) << k;
    equal += metric > driven - 1e-9;
  }
  EXPECT_GT(equal, 200);  // many short words are themselves shortest
}

TEST(ReedsShepp, DistanceIsASymmetricMetric) {
  const ReedsShepp rs(0.8);
  std::mt19937_64 rng(7);
  for (int k = 0; k < 200; ++k) {
    const SE2Pose a = random_pose(rng), b = random_pose(rng), c = random_pose(rng);
    const double ab = rs.distance(a, b);
    EXPECT_NEAR(ab, rs.distance(b, a), 1e-9);
    EXPECT_GE(ab + 1e-9, std::hypot(a.x - b.x, a.y - b.y));  // never below the straight line
    EXPECT_LE(rs.distance(a, c), ab + rs.distance(b, c) + 1e-9);
  }
  EXPECT_NEAR(rs.distance({1, 2, 3}, {1, 2, 3}), 0.0, 1e-12);
}

TEST(ReedsShepp, SamplerMatchesOmplAndEndsAtTheGoal) {
  const ReedsShepp rs(1.2);
  std::mt19937_64 rng(11);
  for (int k = 0; k < 100; ++k) {
    const SE2Pose a = random_pose(rng), b = random_pose(rng);
    const double spacing = 0.1;
    const std::vector<PathPoint> pts = rs.sample(a, b, spacing);
    const double total = rs.distance(a, b);
    ASSERT_GE(pts.size(), 2u);
    EXPECT_EQ(pts.front().control, Control{});
    EXPECT_DOUBLE_EQ(pts.back().pose.x, b.x);
    EXPECT_DOUBLE_EQ(pts.back().pose.y, b.y);
    EXPECT_NEAR(path_length(pts, 1.2), total, 1e-6);
    double s = 0.0;
    for (std::size_t i = 1; i < pts.size(); ++i) {
      const std::span<const PathPoint> piece(pts.data() + i - 1, 2);
      const double ds = path_length(piece, 1.2);
      EXPECT_LE(ds, spacing + 1e-9);
      s += ds;
      // OMPL's interpolation at the same fraction of the curve lands on our sample.
      const SE2Pose o = rs.ompl_interpolate(a, b, s / total);
      EXPECT_NEAR(o.x, pts[i].pose.x, 1e-6);
      EXPECT_NEAR(o.y, pts[i].pose.y, 1e-6);
      EXPECT_NEAR(wrap_angle(o.theta - pts[i].pose.theta), 0.0, 1e-6);
    }
    EXPECT_LE(control_changes(pts), 4u);  // at most five segments
  }
}

TEST(ReedsShepp, RejectsBadInput) {
  EXPECT_THROW(ReedsShepp(0.0), InputError);
  EXPECT_THROW(ReedsShepp(-1.0), InputError);
  const ReedsShepp rs(1.0);
  EXPECT_THROW(rs.sample({0, 0, 0}, {1, 0, 0}, 0.0), InputError);
  EXPECT_THROW(rs.distance({NAN, 0, 0}, {1, 0, 0}), InputError);
}

}  // namespace
}  // namespace talus
