// Candidate-corridor metrics (talus/optimal/candidate_metrics.hpp): closed forms
// on planes, hand-computed passages and overlaps, and agreement with the
// search's own cost and length on a curved terrain.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/optimal/candidate_metrics.hpp"
#include "terrain_test_support.hpp"
#include "vehicle_test_support.hpp"

namespace talus {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double degrees(double radians) {
  return radians * 180.0 / std::numbers::pi;
}

BPatch inclined_plane(double slope) {
  return BPatch::interpolate(terrain_test::grid_of_nodes(
      [slope](double x, double) { return slope * x; }, 41, 21, 1.0, 0.0, 0.0));
}

CandidatePath straight_path(double x0, double x1, double y) {
  CandidatePath path;
  for (double x = x0; x <= x1 + 1e-9; x += 1.0) path.vertices.emplace_back(x, y);
  return path;
}

TEST(CandidateMetrics, UphillOnAPlaneAtTheTopSpeed) {
  const BPatch plane = inclined_plane(0.1);
  const Vehicle rover = vehicle_test::point_mass_rover(0.7);  // 10 m/s top speed
  const CandidateMetrics m = measure_candidate(plane, rover, straight_path(2.0, 12.0, 10.0), 1.0);
  const double stretch = std::sqrt(1.0 + 0.1 * 0.1);  // 3-D length per metre of plan
  ASSERT_EQ(m.s.size(), 11u);
  ASSERT_EQ(m.edge_speed.size(), 10u);
  for (std::size_t k = 0; k < m.s.size(); ++k) {
    EXPECT_NEAR(m.s[k], stretch * static_cast<double>(k), 1e-12);
    EXPECT_NEAR(m.z[k], 0.1 * (2.0 + static_cast<double>(k)), 1e-12);
    EXPECT_NEAR(m.slope[k], degrees(std::atan(0.1)), 1e-10);
  }
  // A plane has no curvature: every edge is driven at the top speed.
  for (const double v : m.edge_speed) EXPECT_NEAR(v, rover.max_speed, 1e-12);
  EXPECT_NEAR(m.min_edge_speed, rover.max_speed, 1e-12);
  EXPECT_NEAR(m.recomputed_cost, 10.0 * stretch / rover.max_speed, 1e-12);
  EXPECT_NEAR(m.climb, 1.0, 1e-12);
  EXPECT_NEAR(m.max_z, 1.2, 1e-12);
  EXPECT_NEAR(m.max_slope, degrees(std::atan(0.1)), 1e-10);
  EXPECT_EQ(m.steep_stations, 0u);
  EXPECT_FALSE(m.revisits);
}

TEST(CandidateMetrics, SlopeSteeperThanTheFrictionAngleCountsEveryStation) {
  // tan θ = 0.5 > μ = 0.3: uphill the vehicle can hold itself nowhere. (On the
  // fitted plane κ_n is rounding, of either sign, so the concave count is not
  // asserted beyond its bound.)
  const BPatch plane = inclined_plane(0.5);
  const Vehicle rover = vehicle_test::point_mass_rover(0.3);
  const CandidateMetrics m = measure_candidate(plane, rover, straight_path(2.0, 4.0, 10.0), 1.0);
  const auto stations = static_cast<std::size_t>(edge_stations(1.0, 1.0));
  EXPECT_EQ(m.steep_stations, 2 * stations);
  EXPECT_EQ(m.speed_only_stations, 2 * stations);
  EXPECT_LE(m.concave_speed_only, m.speed_only_stations);
  EXPECT_NEAR(m.max_slope, degrees(std::atan(0.5)), 1e-10);
  EXPECT_EQ(m.recomputed_cost, kInf);  // untraversable uphill
  EXPECT_EQ(m.min_edge_speed, 0.0);
}

TEST(CandidateMetrics, ARouteThatDoublesBackRevisitsAVertex) {
  const BPatch plane = inclined_plane(0.1);
  CandidatePath path;
  path.vertices = {{2.0, 10.0}, {3.0, 10.0}, {3.0, 11.0}, {2.0, 10.0}};
  const CandidateMetrics m =
      measure_candidate(plane, vehicle_test::point_mass_rover(0.7), path, 1.0);
  EXPECT_TRUE(m.revisits);
  EXPECT_NEAR(m.climb, 0.1, 1e-12);  // rises 0.1 once, then flat, then falls
  EXPECT_THROW(measure_candidate(plane, vehicle_test::point_mass_rover(), CandidatePath{}, 1.0),
               InputError);
  EXPECT_THROW(measure_candidate(plane, vehicle_test::point_mass_rover(), path, 0.0), InputError);
}

TEST(CandidateMetrics, RecomputedCostAndLengthAgreeWithTheSearchOnACurvedTerrain) {
  const BPatch hills = BPatch::interpolate(terrain_test::grid_of_nodes(
      [](double x, double y) { return 2.0 * std::sin(x / 5.0) * std::cos(y / 7.0); }, 31, 21, 1.0,
      0.0, 0.0));
  const Vehicle rover = vehicle_test::point_mass_rover(0.7);
  GlobalSearchOptions options;
  options.candidates = 2;
  const GlobalSearchResult r = global_search(hills, rover, {3.0, 10.0}, {27.0, 10.0}, options);
  ASSERT_EQ(r.status, GlobalSearchStatus::kOk);
  for (const CandidatePath& c : r.candidates) {
    const CandidateMetrics m = measure_candidate(hills, rover, c, r.spacing);
    EXPECT_NEAR(m.recomputed_cost, c.cost_seconds, 1e-9 * c.cost_seconds);
    EXPECT_NEAR(m.s.back(), c.length_m, 1e-9 * c.length_m);
    EXPECT_FALSE(m.revisits);
    EXPECT_LE(m.max_z, 2.0 + 1e-9);
    EXPECT_GE(m.max_slope, *std::max_element(m.slope.begin(), m.slope.end()));
  }
  const LatticeCensus census = lattice_census(hills, r, rover.friction);
  EXPECT_EQ(census.unreachable_nodes, r.nodes - r.reachable_nodes);
  // The gentle hills (slopes up to atan 0.4) are nowhere steeper than atan 0.7.
  EXPECT_EQ(census.steep_nodes, 0u);
}

TEST(CandidateMetrics, LandmarkPassageOfARouteRoundASummit) {
  const std::vector<Vec2> route{{0.0, 0.0}, {5.0, -3.0}, {10.0, 0.0}};
  const LandmarkPassage south = landmark_passage(route, {0.0, 0.0}, {10.0, 0.0}, {5.0, 0.0});
  EXPECT_EQ(south.point, Vec2(5.0, -3.0));
  EXPECT_DOUBLE_EQ(south.distance, 3.0);
  EXPECT_EQ(south.side, "south");
  // Start and goal give only the axis: swapping them finds the same crossing.
  const LandmarkPassage back = landmark_passage(route, {10.0, 0.0}, {0.0, 0.0}, {5.0, 0.0});
  EXPECT_EQ(back.point, Vec2(5.0, -3.0));
  // A landmark on the axis a quarter of the way: the crossing is on the first leg.
  const LandmarkPassage quarter = landmark_passage(route, {0.0, 0.0}, {10.0, 0.0}, {2.5, 0.0});
  EXPECT_NEAR(quarter.point.x(), 2.5, 1e-15);
  EXPECT_NEAR(quarter.point.y(), -1.5, 1e-15);
  EXPECT_DOUBLE_EQ(quarter.distance, 1.5);
  // A landmark beyond the goal is never reached: the nearest vertex, (10, 0),
  // south-west of it.
  const LandmarkPassage beyond = landmark_passage(route, {0.0, 0.0}, {10.0, 0.0}, {12.0, 3.0});
  EXPECT_EQ(beyond.point, Vec2(10.0, 0.0));
  EXPECT_DOUBLE_EQ(beyond.distance, std::sqrt(13.0));
  EXPECT_EQ(beyond.side, "south-west");
  // Straight through the landmark: no side.
  const std::vector<Vec2> straight{{0.0, 0.0}, {10.0, 0.0}};
  const LandmarkPassage through = landmark_passage(straight, {0.0, 0.0}, {10.0, 0.0}, {5.0, 0.0});
  EXPECT_EQ(through.distance, 0.0);
  EXPECT_EQ(through.side, "");
  EXPECT_THROW(landmark_passage(route, {1.0, 1.0}, {1.0, 1.0}, {5.0, 0.0}), InputError);
}

TEST(CandidateMetrics, CorridorOverlapOfABulgeOffTheReference) {
  const std::vector<Vec2> reference{{0.0, 0.0}, {10.0, 0.0}};
  const std::vector<Vec2> route{{0.0, 0.0}, {2.0, 0.5}, {5.0, 4.0}, {8.0, 0.5}, {10.0, 0.0}};
  const CorridorOverlap o = corridor_overlap(route, reference, 1.0);
  EXPECT_DOUBLE_EQ(o.hausdorff, 4.0);
  EXPECT_DOUBLE_EQ(o.shared, 4.0 / 5.0);
  EXPECT_DOUBLE_EQ(corridor_overlap(route, reference, 0.5).shared, 2.0 / 5.0);
}

TEST(CandidateMetrics, DefaultSeparationAndLatticeNodes) {
  GlobalSearchResult r;
  r.start_node = {0.0, 0.0};
  r.goal_node = {60.0, 80.0};  // 100 m apart
  r.spacing = 2.0;
  EXPECT_DOUBLE_EQ(default_separation(r), 10.0);
  r.spacing = 5.0;
  EXPECT_DOUBLE_EQ(default_separation(r), 15.0);  // 3 spacings
  r.origin = {1.0, 2.0};
  r.spacing = 3.0;
  r.nx = 4;
  r.ny = 2;
  EXPECT_EQ(lattice_node_position(r, 6), Vec2(7.0, 5.0));
  EXPECT_EQ(lattice_node_position(r, 0), Vec2(1.0, 2.0));
}

TEST(CandidateMetrics, LatticeCensusOfAHandMadeField) {
  const BPatch plane = inclined_plane(0.5);  // 26.6°
  GlobalSearchResult r;
  r.nx = 3;
  r.ny = 2;
  r.origin = {5.0, 5.0};
  r.spacing = 2.0;
  r.cost_from_start = {0.0, 1.0, kInf, 2.0, kInf, 3.0};
  const LatticeCensus gentle = lattice_census(plane, r, 0.7);  // atan 0.7 = 35°
  EXPECT_EQ(gentle.steep_nodes, 0u);
  EXPECT_EQ(gentle.unreachable_nodes, 2u);
  EXPECT_EQ(lattice_census(plane, r, 0.3).steep_nodes, 6u);
  r.cost_from_start.pop_back();
  EXPECT_THROW(lattice_census(plane, r, 0.7), InputError);
}

TEST(CandidateMetrics, TerrainSlopeDegrees) {
  SurfacePoint p;
  p.gradient = {0.6, 0.8};  // |∇z| = 1
  EXPECT_DOUBLE_EQ(terrain_slope_degrees(p), 45.0);
  EXPECT_EQ(terrain_slope_degrees(SurfacePoint{}), 0.0);
}

}  // namespace
}  // namespace talus
