// traversability_map (dynamics/traversability_map.hpp) against the closed
// forms of a straight pass on an inclined plane (test_velocity_limits.cpp's
// side-slope limits) and over a cylinder's crest (the contact limit sqrt(g R)).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/dynamics/traversability_map.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

Vehicle point_mass(double mu, double h, double b, double max_speed) {
  Vehicle v;
  v.friction = mu;
  v.cg_height = h;
  v.half_track = b;
  v.max_speed = max_speed;
  return v;
}

/// k_q and k_r of the straight pass in heading theta over a plane of slope alpha rising towards
/// `aspect`: the tangent (cos θ, sin θ, tan α cos φ)/D with φ = θ − aspect and
/// D = sqrt(1 + tan²α cos²φ), the normal (−tan α cos a, −tan α sin a, 1) cos α, q = r × t.
std::pair<double, double> plane_k_q_k_r(double alpha, double aspect, double theta) {
  const double phi = theta - aspect;
  const double d = std::sqrt(1.0 + std::pow(std::tan(alpha) * std::cos(phi), 2));
  return {-std::sin(alpha) * std::sin(phi) / d, std::cos(alpha)};
}

struct PlaneCase {
  double mu, h, b;
  Constraint side_binding;  ///< what fails on a side slope: the smaller of mu and b/h
};

class PlaneTraversability : public ::testing::TestWithParam<PlaneCase> {};

INSTANTIATE_TEST_SUITE_P(Vehicles, PlaneTraversability,
                         ::testing::Values(PlaneCase{0.7, 0.5, 0.6, Constraint::kSliding},
                                           PlaneCase{1.0, 1.0, 0.5, Constraint::kTipover}),
                         [](const ::testing::TestParamInfo<PlaneCase>& info) {
                           return std::string(to_string(info.param.side_binding));
                         });

/// tan α = 1 (45°): the straight pass is stable where min(μ, b/h) k_r >= |k_q|: up and down the
/// fall line and near it, not across. Every node of the plane sees the same limits.
TEST_P(PlaneTraversability, SpeedLimitsAreTheSideSlopeClosedForm) {
  const PlaneCase c = GetParam();
  PlaneOptions plane;
  plane.shape = {12, 10, 0.5, -3.0, 2.0};
  plane.slope = kPi / 4.0;
  plane.aspect = 0.3;
  plane.z0 = 100.0;
  const ElevationGrid grid = generate_plane(plane);
  const BPatch surface = BPatch::interpolate(grid);
  const double max_speed = 8.0;
  const Vehicle vehicle = point_mass(c.mu, c.h, c.b, max_speed);
  TraversabilityOptions options;
  options.headings = 16;
  const TraversabilityMap map = traversability_map(surface, grid, vehicle, options);
  ASSERT_EQ(map.status, TraversabilityStatus::kOk);
  ASSERT_EQ(map.headings.size(), 16u);
  ASSERT_EQ(map.speed_limit.size(), 16u);
  const double ratio = std::min(c.mu, c.b / c.h);
  std::size_t blocked_headings = 0;
  for (std::size_t k = 0; k < 16; ++k) {
    EXPECT_NEAR(map.headings[k], 2.0 * kPi * static_cast<double>(k) / 16.0, 1e-15);
    const auto [k_q, k_r] = plane_k_q_k_r(plane.slope, plane.aspect, map.headings[k]);
    const double margin = ratio * k_r - std::abs(k_q);
    ASSERT_GT(std::abs(margin), 1e-3) << "heading " << k << " too close to the threshold";
    const double expected = margin > 0.0 ? max_speed : 0.0;
    if (margin < 0.0) ++blocked_headings;
    for (std::size_t node = 0; node < grid.ncols() * grid.nrows(); ++node) {
      ASSERT_EQ(map.speed_limit[k][node], expected) << "heading " << k << ", node " << node;
    }
  }
  EXPECT_GT(blocked_headings, 0u);
  EXPECT_LT(blocked_headings, 16u);
  const std::size_t n = grid.ncols() * grid.nrows();
  for (std::size_t node = 0; node < n; ++node) {
    EXPECT_EQ(map.speed_limit_min[node], 0.0);
    EXPECT_EQ(map.binding[node], binding_code(c.side_binding));
    EXPECT_EQ(map.untraversable[node], 0.0);  // the fall line always passes
  }
  EXPECT_EQ(map.blocked_nodes, n);
  EXPECT_EQ(map.untraversable_nodes, 0u);
  EXPECT_EQ(map.nodata_nodes, 0u);
}

TEST(TraversabilityMap, GentlePlaneIsLimitedByMaxSpeedOnly) {
  PlaneOptions plane;
  plane.shape = {8, 8, 1.0, 0.0, 0.0};
  plane.slope = 0.1;  // tan 0.1 = 0.1 < mu
  const ElevationGrid grid = generate_plane(plane);
  const TraversabilityMap map =
      traversability_map(BPatch::interpolate(grid), grid, point_mass(0.7, 0.5, 0.6, 5.0));
  for (std::size_t node = 0; node < 64; ++node) {
    EXPECT_EQ(map.speed_limit_min[node], 5.0);
    EXPECT_EQ(map.binding[node], binding_code(Constraint::kMaxSpeed));
  }
  // Without max_speed nothing limits a straight pass on a plane.
  const TraversabilityMap free =
      traversability_map(BPatch::interpolate(grid), grid,
                         point_mass(0.7, 0.5, 0.6, std::numeric_limits<double>::infinity()));
  EXPECT_TRUE(std::isinf(free.speed_limit_min[10]));
  EXPECT_EQ(free.binding[10], binding_code(Constraint::kNone));
}

/// Across the crest of a cylinder of radius R the pass loses contact above sqrt(g R) (the
/// normal curvature is -1/R at the top); along the axis nothing limits it but max_speed. The
/// interpolating B-patch's curvature at the crest nodes is second-order accurate in h / R
/// (0.5 / 40 here): 1e-3 relative.
TEST(TraversabilityMap, CrestPassIsLimitedByContactAtSqrtGR) {
  CylinderOptions cylinder;
  cylinder.shape = {41, 41, 0.5, -10.0, -10.0};
  cylinder.radius = 40.0;
  cylinder.axis_direction = 0.0;  // axis along x through the centre (y = 0)
  const ElevationGrid grid = generate_cylinder(cylinder);
  const Vehicle vehicle = point_mass(1.5, 0.2, 1.0, 50.0);
  TraversabilityOptions options;
  options.headings = 4;  // 0, 90, 180, 270 degrees
  const TraversabilityMap map =
      traversability_map(BPatch::interpolate(grid), grid, vehicle, options);
  const std::size_t j = 20;  // y = 0
  for (std::size_t i = 10; i <= 30; ++i) {
    const std::size_t node = j * grid.ncols() + i;
    EXPECT_EQ(map.speed_limit[0][node], 50.0) << i;  // along the axis
    EXPECT_NEAR(map.speed_limit[1][node], std::sqrt(9.81 * 40.0), 1e-3 * std::sqrt(9.81 * 40.0))
        << i;
    EXPECT_NEAR(map.speed_limit[3][node], map.speed_limit[1][node], 1e-9);
    EXPECT_EQ(map.binding[node], binding_code(Constraint::kContact));
    EXPECT_EQ(map.speed_limit_min[node],
              std::min({map.speed_limit[0][node], map.speed_limit[1][node],
                        map.speed_limit[2][node], map.speed_limit[3][node]}));
  }
}

TEST(TraversabilityMap, NodataNodesAreNanAndOptionsAreChecked) {
  PlaneOptions plane;
  plane.shape = {6, 6, 1.0, 0.0, 0.0};
  ElevationGrid grid = generate_plane(plane);
  const BPatch surface = BPatch::interpolate(grid);
  grid.set_void(2, 3);
  const TraversabilityMap map = traversability_map(surface, grid, point_mass(0.7, 0.5, 0.6, 5.0));
  const std::size_t node = 3 * 6 + 2;
  EXPECT_TRUE(std::isnan(map.speed_limit_min[node]));
  EXPECT_TRUE(std::isnan(map.binding[node]));
  EXPECT_TRUE(std::isnan(map.untraversable[node]));
  EXPECT_TRUE(std::isnan(map.speed_limit[0][node]));
  EXPECT_EQ(map.nodata_nodes, 1u);
  EXPECT_EQ(map.speed_limit_min[node + 1], 5.0);
  TraversabilityOptions bad;
  bad.headings = 0;
  EXPECT_THROW(traversability_map(surface, grid, point_mass(0.7, 0.5, 0.6, 5.0), bad), InputError);
  bad.headings = 361;
  EXPECT_THROW(bad.validate(), InputError);
  EXPECT_FALSE(map.brief_report().empty());
}

}  // namespace
}  // namespace talus
