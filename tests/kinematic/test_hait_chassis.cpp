// The articulated chassis in the Haït–Siméon–Taïx planner: the §5.2 min/max
// placement surfaces (ChassisUncertaintyTable), the §5.2.2 moved faces, and
// plan_hait with data/robots/marsokhod_chassis.yaml.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "planar_geometry_test_support.hpp"
#include "random_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"
#include "talus/kinematic/hait/chassis_uncertainty_table.hpp"
#include "talus/kinematic/hait/hait_planner.hpp"
#include "talus/kinematic/hait/hait_robot_validity.hpp"
#include "talus/kinematic/hait/robot.hpp"
#include "talus/kinematic/hait/robot_validity.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using geometry_test::convex_hull;
using geometry_test::cross;
using random_test::uniform;

constexpr double kPi = std::numbers::pi;

ArticulatedChassis marsokhod() {
  return std::get<ArticulatedChassis>(
      load_robot(std::string(TALUS_DATA_DIR) + "/robots/marsokhod_chassis.yaml"));
}

/// `width` x `depth` metres at 0.25 m (12 m x 8 m by default); z = f(x, y).
template <class F>
RuledTerrain terrain_of(F f, double width = 12.0, double depth = 8.0) {
  ElevationGrid g(static_cast<std::size_t>(std::lround(width / 0.25)) + 1,
                  static_cast<std::size_t>(std::lround(depth / 0.25)) + 1, 0.25, 0.0, 0.0, 0.0);
  for (std::size_t j = 0; j < g.nrows(); ++j) {
    for (std::size_t i = 0; i < g.ncols(); ++i) {
      const Vec2 p = g.node_position(i, j);
      g.at(i, j) = f(p.x(), p.y());
    }
  }
  return RuledTerrain(g);
}

/// A steep Gaussian hill of peak `height` at (6, 4), sigma 0.9 m (flat when 0), on 12 m x 8 m.
RuledTerrain hill(double height) {
  return terrain_of(terrain_test::gaussian_hill(Vec2(6, 4), height, 0.9));
}

/// The same hill at (8, 7) on 16 m x 14 m, room for the wider corridor of the uncertain robot.
RuledTerrain wide_hill(double height) {
  return terrain_of(terrain_test::gaussian_hill(Vec2(8, 7), height, 0.9), 16.0, 14.0);
}

/// Rolling ground: a sum of seeded random bumps, gentle enough for most placements to be valid.
RuledTerrain rolling(unsigned seed) {
  std::mt19937_64 rng(seed);
  struct Bump {
    double x, y, s, a;
  };
  std::vector<Bump> bumps;
  for (int k = 0; k < 25; ++k) {
    bumps.push_back({uniform(rng, 0, 12), uniform(rng, 0, 8), uniform(rng, 0.5, 1.2),
                     uniform(rng, -0.25, 0.25)});
  }
  return terrain_of([bumps](double x, double y) {
    double z = 0.0;
    for (const Bump& b : bumps) {
      z += b.a * std::exp(-((x - b.x) * (x - b.x) + (y - b.y) * (y - b.y)) / (2 * b.s * b.s));
    }
    return z;
  });
}

/// The configuration moved by `lateral` normal to its heading and turned by `dth` (§5.2, Fig. 25
/// b).
SE2Pose moved(const SE2Pose& q, double lateral, double dth) {
  return {q.x - lateral * std::sin(q.theta), q.y + lateral * std::cos(q.theta), q.theta + dth};
}

bool inside_convex(const Quad& face, const Vec2& p, double tol) {
  for (int k = 0; k < 4; ++k) {
    const Vec2 a = face[k].head<2>(), b = face[(k + 1) % 4].head<2>();
    const Vec2 e = b - a;
    if (e.x() * (p.y() - a.y()) - e.y() * (p.x() - a.x()) < -tol) return false;  // CCW: left
  }
  return true;
}

/// Elevation of the face's plane above p.
double plane_height(const Quad& face, const Vec2& p) {
  const Vec3 n = (face[1] - face[0]).cross(face[2] - face[0]);
  return face[0].z() - (n.x() * (p.x() - face[0].x()) + n.y() * (p.y() - face[0].y())) / n.z();
}

// ---------------------------------------------------------------- min/max surfaces

TEST(ChassisUncertaintyTable, PlaneBoundsAreAnalytic) {
  // z = a y: an axle at heading θ' rolls by atan(a cos θ') and its centre lies on the plane.
  const double a = 0.2;
  const RuledTerrain t = terrain_of([a](double, double y) { return a * y; });
  ChassisTableOptions to;
  to.theta_slices = 36;  // 10° slices
  ChassisUncertaintyOptions uo;
  uo.position_uncertainty = 0.3;
  uo.heading_uncertainty = 0.35;  // 20.05°: reach = 1 + ceil(2.005) = 4 slices
  const ChassisUncertaintyTable table(marsokhod(), t, to, uo);
  const ChassisUncertaintyDiagnostics& d = table.diagnostics();
  EXPECT_EQ(d.slice_reach, 4);
  EXPECT_NEAR(d.half_width, 0.3 + 0.6 * std::sin(0.35), 1e-12);
  EXPECT_NEAR(d.half_length, 0.6 * (1 - std::cos(0.35)), 1e-12);
  EXPECT_EQ(d.placements, 36LL * 49 * 33);
  EXPECT_GT(d.max_window_nodes, 1);
  EXPECT_GE(d.seconds, d.base_seconds);

  const double step = 2 * kPi / 36;
  // At a node and slice angle θ = 0: the roll's largest value is the heading
  // θ' = 0 itself, its smallest the farthest merged slice.
  const AxleBounds b = table.axle_bounds(6.0, 4.0, 0.0);
  ASSERT_TRUE(usable(b.status));
  const AxlePlacement nominal = table.base().axle(6.0, 4.0, 0.0);
  EXPECT_NEAR(nominal.roll, std::atan(a), 1e-6);
  EXPECT_NEAR(b.roll.hi, std::atan(a), 1e-6);
  EXPECT_NEAR(b.roll.lo, std::atan(a * std::cos(4 * step)), 1e-6);
  // z spans the window across the heading: at least ±ρ, at most the grown box.
  const double grown = d.half_width + 2 * 0.25 * std::sqrt(2.0) + 0.1;
  EXPECT_LE(b.z.lo, a * (4.0 - 0.3) + 1e-9);
  EXPECT_GE(b.z.hi, a * (4.0 + 0.3) - 1e-9);
  EXPECT_GE(b.z.lo, a * (4.0 - grown));
  EXPECT_LE(b.z.hi, a * (4.0 + grown));
  // Heading along the slope (θ = 90°): the box's long side runs along x, where the plane is flat.
  const AxleBounds along = table.axle_bounds(6.0, 4.0, kPi / 2);
  ASSERT_TRUE(usable(along.status));
  EXPECT_LT(along.z.hi - along.z.lo, b.z.hi - b.z.lo);
  // Near the map's edge part of the domain leaves the map: unusable.
  EXPECT_FALSE(usable(table.axle_bounds(0.3, 4.0, kPi / 2).status));
  EXPECT_FALSE(usable(table.axle_bounds(20.0, 4.0, 0.0).status));
}

TEST(ChassisUncertaintyTable, IntervalsHoldEverySampledPlacementOfTheDomain) {
  const RuledTerrain t = rolling(11);
  const ArticulatedChassis ch = marsokhod();
  ChassisUncertaintyOptions uo;
  uo.position_uncertainty = 0.3;
  uo.heading_uncertainty = 0.7;  // the paper's 40°
  const ChassisUncertaintyTable table(ch, t, {}, uo);
  std::mt19937_64 rng(23);
  int checked = 0, wider = 0;
  for (int n = 0; n < 300; ++n) {
    const SE2Pose q{uniform(rng, 2, 10), uniform(rng, 2, 6), uniform(rng, -kPi, kPi)};
    const ChassisPlacementInterval in = table.place_interval(q.x, q.y, q.theta);
    if (!usable(in.status)) continue;
    ++checked;
    if (in.z.hi - in.z.lo > 1e-3) ++wider;
    for (int l = -4; l <= 4; ++l) {
      for (int k = -4; k <= 4; ++k) {
        const SE2Pose p = moved(q, 0.3 * l / 4, 0.7 * k / 4);
        const ChassisPlacement c = table.base().place(p.x, p.y, p.theta);
        ASSERT_TRUE(usable(c.status));  // the interval said the whole domain has placements
        const auto holds = [](const Interval& i, double v, double tol) {
          return i.lo - tol <= v && v <= i.hi + tol;
        };
        const std::string at = "q = (" + std::to_string(q.x) + ", " + std::to_string(q.y) + ", " +
                               std::to_string(q.theta) + "), l = " + std::to_string(l) +
                               ", k = " + std::to_string(k);
        // z_M and φ_M: bounds of the surfaces themselves, exact up to rounding.
        EXPECT_TRUE(holds(in.z, c.z, 1e-9)) << at;
        EXPECT_TRUE(holds(in.roll_middle, c.roll_middle, 1e-9)) << at;
        // Pitches come from iterations stopped at |G| <= 1e-6 m (d = 0.6 m).
        EXPECT_TRUE(holds(in.pitch_front, c.pitch_front, 1e-5)) << at;
        EXPECT_TRUE(holds(in.pitch_rear, c.pitch_rear, 1e-5)) << at;
        EXPECT_TRUE(holds(in.roll_front, c.roll_front, 1e-6)) << at;
        EXPECT_TRUE(holds(in.roll_rear, c.roll_rear, 1e-6)) << at;
      }
    }
  }
  EXPECT_GT(checked, 150);
  EXPECT_GT(wider, checked / 2);
}

TEST(ChassisUncertaintyTable, TerrainUncertaintyWidensTheSection51Intervals) {
  const RuledTerrain t = rolling(5);
  const ArticulatedChassis ch = marsokhod();
  ChassisTableOptions to;
  to.theta_slices = 24;
  to.terrain_uncertainty = 0.05;
  ChassisUncertaintyOptions uo;
  uo.position_uncertainty = 0.2;
  uo.heading_uncertainty = 0.3;
  const ChassisUncertaintyTable table(ch, t, to, uo);
  ASSERT_TRUE(table.base().has_uncertainty());
  std::mt19937_64 rng(3);
  int checked = 0;
  for (int n = 0; n < 200; ++n) {
    const SE2Pose q{uniform(rng, 2, 10), uniform(rng, 2, 6), uniform(rng, -kPi, kPi)};
    const ChassisPlacementInterval both = table.place_interval(q.x, q.y, q.theta);
    if (!usable(both.status)) continue;
    const ChassisPlacementInterval terrain_only = table.base().place_interval(q.x, q.y, q.theta);
    ASSERT_TRUE(usable(terrain_only.status));
    ++checked;
    // §5.2.3: S'_z_min <= S_z_min etc. at the configuration itself.
    EXPECT_LE(both.z.lo, terrain_only.z.lo + 1e-9);
    EXPECT_GE(both.z.hi, terrain_only.z.hi - 1e-9);
    EXPECT_LE(both.roll_middle.lo, terrain_only.roll_middle.lo + 1e-9);
    EXPECT_GE(both.roll_middle.hi, terrain_only.roll_middle.hi - 1e-9);
    EXPECT_LE(both.pitch_front.lo, terrain_only.pitch_front.lo + 1e-5);
    EXPECT_GE(both.pitch_front.hi, terrain_only.pitch_front.hi - 1e-5);
    // And the envelopes are ±δz apart at least.
    EXPECT_GE(both.z.hi - both.z.lo, 2 * 0.05 - 1e-9);
  }
  EXPECT_GT(checked, 100);
}

TEST(ChassisUncertaintyTable, LatticeSlackOnlyWidens) {
  const RuledTerrain t = rolling(7);
  ChassisTableOptions to;
  to.theta_slices = 24;
  ChassisUncertaintyOptions uo;
  uo.position_uncertainty = 0.3;
  uo.heading_uncertainty = 0.4;
  const ChassisUncertaintyTable slack(marsokhod(), t, to, uo);
  uo.lattice_slack = false;
  const ChassisUncertaintyTable plain(marsokhod(), t, to, uo);
  EXPECT_LT(plain.diagnostics().max_window_nodes, slack.diagnostics().max_window_nodes);
  std::mt19937_64 rng(8);
  for (int n = 0; n < 200; ++n) {
    const double x = uniform(rng, 2, 10), y = uniform(rng, 2, 6), th = uniform(rng, -kPi, kPi);
    const AxleBounds a = slack.axle_bounds(x, y, th), b = plain.axle_bounds(x, y, th);
    if (!usable(a.status)) continue;
    ASSERT_TRUE(usable(b.status));
    EXPECT_LE(a.z.lo, b.z.lo + 1e-12);
    EXPECT_GE(a.z.hi, b.z.hi - 1e-12);
    EXPECT_LE(a.roll.lo, b.roll.lo + 1e-12);
    EXPECT_GE(a.roll.hi, b.roll.hi - 1e-12);
  }
}

TEST(ChassisUncertaintyTable, RejectsBadOptions) {
  const RuledTerrain t = hill(0.0);
  ChassisUncertaintyOptions uo;
  uo.position_uncertainty = -0.1;
  EXPECT_THROW(ChassisUncertaintyTable(marsokhod(), t, {}, uo), InputError);
  uo.position_uncertainty = 0.1;
  uo.heading_uncertainty = kPi / 2;
  EXPECT_THROW(ChassisUncertaintyTable(marsokhod(), t, {}, uo), InputError);
  HaitValidityOptions vo;
  vo.position_uncertainty = 0.1;
  vo.heading_uncertainty = 2.0;  // fine for the sampled rigid body, not for the chassis
  EXPECT_THROW(HaitRobotValidity(t, marsokhod(), vo), InputError);
  vo.heading_uncertainty = 0.2;
  vo.sample_spacing = 0.0;
  EXPECT_THROW(HaitRobotValidity(t, marsokhod(), vo), InputError);
}

// ---------------------------------------------------------------- moved faces (§5.2.2)

TEST(MovedLowerFaces, CoverEveryFaceOfTheDomainFromBelow) {
  // On level ground every placement of the domain is level: its faces must lie
  // inside the moved faces' outline, at or above them.
  const RuledTerrain t = hill(0.0);
  const ArticulatedChassis ch = marsokhod();
  ChassisUncertaintyOptions uo;
  uo.position_uncertainty = 0.3;
  uo.heading_uncertainty = 0.7;
  const ChassisUncertaintyTable table(ch, t, {}, uo);
  const SE2Pose q{6.0, 4.0, 0.6};
  const ChassisPlacementInterval in = table.place_interval(q.x, q.y, q.theta);
  ASSERT_TRUE(usable(in.status));
  const std::vector<Quad> faces = moved_lower_faces(ch, in, q.x, q.y, q.theta, 0.3, 0.7);
  ASSERT_EQ(faces.size(), 12u);  // per body and roll extreme, the swept 8-gon in three quads
  int corners = 0;
  for (int l = -3; l <= 3; ++l) {
    for (int k = -3; k <= 3; ++k) {
      const SE2Pose p = moved(q, 0.3 * l / 3, 0.7 * k / 3);
      for (const Quad& f : lower_faces(ch, table.base().place(p.x, p.y, p.theta))) {
        for (const Vec3& c : f) {
          bool covered = false;
          for (const Quad& m : faces) {
            covered = covered || (inside_convex(m, c.head<2>(), 1e-9) &&
                                  plane_height(m, c.head<2>()) <= c.z() + 1e-9);
          }
          EXPECT_TRUE(covered) << "corner (" << c.x() << ", " << c.y() << ") of l = " << l
                               << ", k = " << k;
          ++corners;
        }
      }
    }
  }
  EXPECT_EQ(corners, 49 * 8);
  // Without uncertainty they are the nominal faces' outline (twice).
  ChassisPlacementInterval nominal;
  const ChassisPlacement p = table.base().place(q.x, q.y, q.theta);
  nominal.status = p.status;
  nominal.z = {p.z, p.z};
  const std::vector<Quad> same = moved_lower_faces(ch, nominal, q.x, q.y, q.theta, 0.0, 0.0);
  const std::vector<Quad> exact = lower_faces(ch, p);
  ASSERT_EQ(same.size(), 4u);
  for (int b = 0; b < 2; ++b) {
    for (const Vec3& c : exact[b]) {
      double best = 1e9;
      for (const Vec3& v : same[2 * b]) best = std::min(best, (v - c).norm());
      EXPECT_LT(best, 1e-9);
    }
  }
  EXPECT_THROW(moved_lower_faces(ch, in, q.x, q.y, q.theta, -0.1, 0.1), InputError);
}

double polygon_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) a += cross(Vec2::Zero(), p[k], p[(k + 1) % p.size()]);
  return 0.5 * a;
}

TEST(SweptBodyOutline, HoldsEverySweptFootprintAndHugsItsHull) {
  // The body rectangle [0, L] x [-w, w] turned by phi in [-dtheta, dtheta] about the middle axle
  // and moved by t in [-rho, rho] sideways (§5.2, Fig. 25 b): every corner of every sampled
  // footprint lies in the outline, whose area is at most 6 % above the sampled hull's.
  const double L = 0.75, w = 0.3;  // marsokhod_chassis.yaml: axle_spacing + overhang, half_width
  for (const double rho : {0.0, 0.3}) {
    for (const double dtheta : {0.0, 0.1, 0.4, 40.0 * kPi / 180.0, 1.2, 1.5}) {
      const std::vector<Vec2> outline = swept_body_outline(L, w, rho, dtheta);
      ASSERT_EQ(outline.size(), dtheta == 0.0 ? 4u : 8u);
      for (std::size_t k = 0; k < outline.size(); ++k) {  // convex, counter-clockwise
        EXPECT_GT(
            cross(outline[k], outline[(k + 1) % outline.size()], outline[(k + 2) % outline.size()]),
            0.0)
            << "rho " << rho << ", dtheta " << dtheta << ", vertex " << k + 1;
      }
      std::vector<Vec2> swept;
      for (int i = -200; i <= 200; ++i) {
        const double phi = dtheta * i / 200, c = std::cos(phi), s = std::sin(phi);
        for (const double t : {-rho, rho}) {
          for (const Vec2& corner : {Vec2(0, -w), Vec2(L, -w), Vec2(L, w), Vec2(0, w)}) {
            const Vec2 p(c * corner.x() - s * corner.y(), s * corner.x() + c * corner.y() + t);
            swept.push_back(p);
            for (std::size_t k = 0; k < outline.size(); ++k) {
              EXPECT_GE(cross(outline[k], outline[(k + 1) % outline.size()], p), -1e-12)
                  << "rho " << rho << ", dtheta " << dtheta << ": (" << p.x() << ", " << p.y()
                  << ") outside edge " << k;
            }
          }
        }
      }
      const double hull = polygon_area(convex_hull(swept));
      EXPECT_LE(polygon_area(outline), 1.06 * hull) << "rho " << rho << ", dtheta " << dtheta;
      if (dtheta == 0.0) {
        EXPECT_NEAR(polygon_area(outline), L * 2 * (w + rho), 1e-12);
      }
    }
  }
  EXPECT_THROW(swept_body_outline(0.0, w, 0.1, 0.1), InputError);
  EXPECT_THROW(swept_body_outline(L, w, -0.1, 0.1), InputError);
  EXPECT_THROW(swept_body_outline(L, w, 0.1, kPi / 2), InputError);
}

TEST(MovedLowerFaces, StayWithinTheReachOfTheSweptBody) {
  // No point of a body turned by at most Δθ about the middle axle and moved by at most ρ is
  // farther than ρ + √(L² + w²) from the axle; the outline's tangent segments overshoot that
  // circle by the factor 1/cos(β/5), β = Δθ + atan(w/L) (L = 0.75 m, w = 0.3 m here).
  const RuledTerrain t = hill(0.0);
  const ArticulatedChassis ch = marsokhod();
  const double rho = 0.3, dtheta = 40.0 * kPi / 180.0;
  ChassisUncertaintyOptions uo;
  uo.position_uncertainty = rho;
  uo.heading_uncertainty = dtheta;
  const ChassisUncertaintyTable table(ch, t, {}, uo);
  const SE2Pose q{6.0, 4.0, 0.6};
  const ChassisPlacementInterval in = table.place_interval(q.x, q.y, q.theta);
  ASSERT_TRUE(usable(in.status));
  const double L = ch.axle_spacing + ch.body.overhang, w = ch.body.half_width;
  const double reach = rho + std::hypot(L, w) / std::cos((dtheta + std::atan2(w, L)) / 5);
  for (const Quad& f : moved_lower_faces(ch, in, q.x, q.y, q.theta, rho, dtheta)) {
    for (const Vec3& v : f) EXPECT_LE(std::hypot(v.x() - q.x, v.y() - q.y), reach + 1e-9);
  }
}

// ---------------------------------------------------------------- plan_hait with the chassis

TEST(HaitChassis, StraightPathOnFlatGround) {
  const RuledTerrain flat = hill(0.0);
  for (HaitHeuristic h : {HaitHeuristic::kEuclidean, HaitHeuristic::kPotentialRs}) {
    HaitOptions o;
    o.heuristic = h;
    const HaitResult r = plan_hait(flat, marsokhod(), {2, 4, 0}, {10, 4, 0}, o);
    ASSERT_EQ(r.status, HaitStatus::kFound) << heuristic_name(h) << ": " << r.message;
    EXPECT_NEAR(r.length_m, 8.0, 1e-6) << heuristic_name(h);
    EXPECT_EQ(r.control_changes, 0u) << heuristic_name(h);
    for (const PathPoint& p : r.path) EXPECT_NEAR(p.pose.y, 4.0, 1e-9);
  }
}

TEST(HaitChassis, DetoursAroundASteepHillWithEveryConfigurationValid) {
  const RuledTerrain steep = hill(1.5);
  const ArticulatedChassis ch = marsokhod();
  const HaitRobotValidity certain(steep, ch);
  EXPECT_EQ(certain.diagnostics().method, PositionUncertaintyMethod::kNone);
  EXPECT_EQ(certain.diagnostics().table_placements, 72LL * 49 * 33);
  // Across the hill's flank the chassis rolls past its limit.
  EXPECT_FALSE(certain.check({6.0, 3.2, 0}).valid);
  for (HaitHeuristic h : {HaitHeuristic::kEuclidean, HaitHeuristic::kPotentialRs}) {
    HaitOptions o;
    o.heuristic = h;
    const HaitResult r = plan_hait(steep, ch, {1.5, 4, 0}, {10.5, 4, 0}, o);
    ASSERT_EQ(r.status, HaitStatus::kFound) << heuristic_name(h) << ": " << r.message;
    double max_offset = 0.0;
    for (const PathPoint& p : r.path) {
      EXPECT_TRUE(certain.check(p.pose).valid)
          << "(" << p.pose.x << ", " << p.pose.y << ", " << p.pose.theta << ")";
      max_offset = std::max(max_offset, std::abs(p.pose.y - 4));
    }
    EXPECT_GT(r.length_m, 9.2) << heuristic_name(h);
    EXPECT_GT(max_offset, 1.0) << heuristic_name(h);
  }
}

TEST(HaitChassis, TerrainUncertaintyCountsEveryPlacementOnTMin) {
  // Under δz a check reads one interval from the table, then places the chassis
  // directly on T_min for the collision test: that placement is its middle
  // axle's Place_axle plus every Place_other_axle iteration (at least three).
  const RuledTerrain t = rolling(3);
  const ArticulatedChassis ch = marsokhod();
  const double dz = 0.02;
  const HaitRobotValidity uncertain(t, ch, dz);
  const RuledTerrain lower = t.lower_envelope(dz);
  std::mt19937_64 rng(23);
  int valid = 0;
  for (int n = 0; n < 200; ++n) {
    const SE2Pose q{uniform(rng, 2, 10), uniform(rng, 2, 6), uniform(rng, -kPi, kPi)};
    const ConfigurationCheck c = uncertain.check(q);
    if (!c.valid) continue;
    ++valid;
    const ChassisPlacement on_lower = place_chassis(ch, lower, q.x, q.y, q.theta);
    ASSERT_GE(on_lower.axle_placements, 3);
    EXPECT_EQ(c.placements, 1u + static_cast<std::size_t>(on_lower.axle_placements))
        << q.x << " " << q.y << " " << q.theta;
  }
  EXPECT_GT(valid, 50);
}

TEST(HaitChassis, UncertainPathIsValidForTheCertainChecks) {
  const RuledTerrain steep = wide_hill(1.5);
  const ArticulatedChassis ch = marsokhod();
  const HaitRobotValidity certain(steep, ch);
  HaitOptions o;
  o.position_uncertainty = 0.2;
  o.heading_uncertainty = 0.3;
  o.terrain_uncertainty = 0.03;
  const HaitResult r = plan_hait(steep, ch, {1.5, 7, 0}, {14.5, 7, 0}, o);
  ASSERT_EQ(r.status, HaitStatus::kFound) << r.message;
  RecordProperty("preprocessing_seconds", std::to_string(r.preprocessing_seconds));
  RecordProperty("placements", static_cast<int>(r.placements));
  // Every configuration of the uncertain path, and of its sampled corridor, is valid for the
  // certain checks.
  const ValidityFunction corridor =
      neighbourhood_validity(certain.function(), 0.2, 0.3, 0.05, 0.05);
  for (std::size_t k = 0; k < r.path.size(); ++k) {
    const SE2Pose& q = r.path[k].pose;
    EXPECT_TRUE(certain.check(q).valid) << k;
    if (k % 3 == 0) {
      EXPECT_TRUE(corridor(q).valid) << k;
    }
  }

  // The min/max-surface oracle accepts nothing whose sampled domain the certain one rejects,
  // and is stricter somewhere.
  HaitValidityOptions vo;
  vo.position_uncertainty = 0.2;
  vo.heading_uncertainty = 0.3;
  const HaitRobotValidity uncertain(steep, ch, vo);
  EXPECT_EQ(uncertain.diagnostics().method, PositionUncertaintyMethod::kMinMaxSurfaces);
  EXPECT_GT(uncertain.diagnostics().minmax_seconds, 0.0);
  std::mt19937_64 rng(17);
  int accepted = 0, tighter = 0;
  for (int n = 0; n < 400; ++n) {
    const SE2Pose q{uniform(rng, 4, 12), uniform(rng, 3, 11), uniform(rng, -kPi, kPi)};
    const bool u = uncertain.check(q).valid;
    const bool c = certain.check(q).valid;
    if (u) {
      ++accepted;
      EXPECT_TRUE(corridor(q).valid) << q.x << " " << q.y << " " << q.theta;
    }
    if (c && !u) ++tighter;
  }
  EXPECT_GT(accepted, 50);
  EXPECT_GT(tighter, 0);
}

}  // namespace
}  // namespace talus
