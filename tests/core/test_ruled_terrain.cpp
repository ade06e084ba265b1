#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_of_nodes;

TEST(RuledTerrain, ReproducesAPlaneAndItsGradientExactly) {
  const RuledTerrain t(grid_of_nodes([](double x, double y) { return 1.5 + 0.3 * x - 0.8 * y; }, 7,
                                     5, 0.25, -1.0, 2.0));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(-1.0, 0.5), uy(2.0, 3.0);
  for (int k = 0; k < 200; ++k) {
    const Vec2 p(ux(rng), uy(rng));
    EXPECT_NEAR(t.elevation(p), 1.5 + 0.3 * p.x() - 0.8 * p.y(), 1e-12);
    EXPECT_NEAR(t.gradient(p).x(), 0.3, 1e-12);
    EXPECT_NEAR(t.gradient(p).y(), -0.8, 1e-12);
  }
}

TEST(RuledTerrain, ReproducesTheHyperbolicParaboloidXY) {
  // z = x y is bilinear, so every patch must hold it exactly, gradient (y, x) included.
  const RuledTerrain t(
      grid_of_nodes([](double x, double y) { return x * y; }, 6, 6, 0.5, -1.3, 0.4));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(-1.3, 1.2), uy(0.4, 2.9);
  for (int k = 0; k < 200; ++k) {
    const Vec2 p(ux(rng), uy(rng));
    EXPECT_NEAR(t.elevation(p), p.x() * p.y(), 1e-12);
    EXPECT_NEAR(t.gradient(p).x(), p.y(), 1e-12);
    EXPECT_NEAR(t.gradient(p).y(), p.x(), 1e-12);
  }
}

TEST(RuledTerrain, NodeValuesAreExactAndPatchesAreStraightAlongGridLines) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uz(-2.0, 2.0);
  ElevationGrid g(5, 4, 1.0, 0.0, 0.0);
  for (std::size_t j = 0; j < 4; ++j)
    for (std::size_t i = 0; i < 5; ++i) g.at(i, j) = uz(rng);
  const RuledTerrain t(g);
  for (std::size_t j = 0; j < 4; ++j)
    for (std::size_t i = 0; i < 5; ++i)
      EXPECT_DOUBLE_EQ(t.elevation(g.node_position(i, j)), g.at(i, j));
  // Ruled: along the edge y = 1 between nodes (1,1) and (2,1) z is linear.
  EXPECT_NEAR(t.elevation({1.25, 1.0}), 0.75 * g.at(1, 1) + 0.25 * g.at(2, 1), 1e-14);
  // Centre of a patch is the mean of its four nodes.
  EXPECT_NEAR(t.elevation({2.5, 0.5}), 0.25 * (g.at(2, 0) + g.at(3, 0) + g.at(2, 1) + g.at(3, 1)),
              1e-14);
}

TEST(RuledTerrain, RejectsPointsOffTheMapAndOnNodataPatches) {
  ElevationGrid g(4, 4, 1.0, 0.0, 0.0, 2.0);
  g.set_void(3, 3);
  const RuledTerrain t(g);
  EXPECT_TRUE(t.contains({3.0, 3.0}));
  EXPECT_FALSE(t.contains({3.01, 1.0}));
  EXPECT_FALSE(t.has_data({-0.01, 1.0}));
  EXPECT_THROW(t.elevation({-0.01, 1.0}), InputError);
  EXPECT_THROW(t.gradient({1.0, 3.2}), InputError);
  // Patch (2, 2) touches the void node; patch (1, 1) does not.
  EXPECT_FALSE(t.has_data({2.5, 2.5}));
  EXPECT_THROW(t.elevation({2.5, 2.5}), InputError);
  EXPECT_THROW(t.gradient({2.9, 2.1}), InputError);
  EXPECT_TRUE(t.has_data({1.5, 1.5}));
  EXPECT_DOUBLE_EQ(t.elevation({1.5, 1.5}), 2.0);
  EXPECT_THROW(RuledTerrain(ElevationGrid{}), InputError);
}

TEST(RuledTerrain, EnvelopesBracketTheTerrainByDz) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uz(-1.0, 1.0), ud(0.0, 0.3), up(0.0, 4.0);
  ElevationGrid g(5, 5, 1.0, 0.0, 0.0), dz(5, 5, 1.0, 0.0, 0.0);
  for (std::size_t j = 0; j < 5; ++j)
    for (std::size_t i = 0; i < 5; ++i) {
      g.at(i, j) = uz(rng);
      dz.at(i, j) = ud(rng);
    }
  const RuledTerrain t(g);
  const RuledTerrain lo = t.lower_envelope(0.2), hi = t.upper_envelope(0.2);
  const RuledTerrain lo_n = t.lower_envelope(dz), hi_n = t.upper_envelope(dz);
  for (int k = 0; k < 100; ++k) {
    const Vec2 p(up(rng), up(rng));
    const double z = t.elevation(p);
    // A uniform shift of every node shifts the bilinear surface by exactly dz.
    EXPECT_NEAR(lo.elevation(p), z - 0.2, 1e-12);
    EXPECT_NEAR(hi.elevation(p), z + 0.2, 1e-12);
    EXPECT_LE(lo_n.elevation(p), z);
    EXPECT_GE(hi_n.elevation(p), z);
    // The gap equals twice the interpolated per-node interval.
    const RuledTerrain dzt(dz);
    EXPECT_NEAR(hi_n.elevation(p) - lo_n.elevation(p), 2.0 * dzt.elevation(p), 1e-12);
  }
  EXPECT_THROW(t.lower_envelope(-0.1), InputError);
  EXPECT_THROW(t.upper_envelope(std::nan("")), InputError);
  EXPECT_THROW(t.upper_envelope(ElevationGrid(4, 5, 1.0, 0.0, 0.0)), InputError);
}

TEST(RuledTerrain, EnvelopesKeepNodata) {
  ElevationGrid g(3, 3, 1.0, 0.0, 0.0, 1.0);
  g.set_void(0, 0);
  const RuledTerrain hi = RuledTerrain(g).upper_envelope(0.5);
  EXPECT_FALSE(hi.grid().valid(0, 0));
  EXPECT_DOUBLE_EQ(hi.elevation({1.5, 1.5}), 1.5);
}

}  // namespace
}  // namespace talus
