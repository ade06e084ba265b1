#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/terrain_quadtree.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

using terrain_test::grid_of_nodes;

RuledTerrain fractal(std::uint64_t seed, std::size_t n = 65, double height = 2.0) {
  FractalTerrainOptions o;
  o.shape = {n, n, 0.25, 0.0, 0.0};
  o.height_scale = height;
  o.seed = seed;
  return RuledTerrain(generate_fractal_terrain(o));
}

// A convex polygon with `n` vertices on an ellipse (random angles, sorted:
// counter-clockwise) lying in the plane z = z0 + g . (p - c).
std::vector<Vec3> random_face(std::mt19937_64& rng, const Vec2& c, double z0, const Vec2& g) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const int n = 3 + static_cast<int>(u01(rng) * 6.0);
  const double ra = 0.1 + 1.4 * u01(rng), rb = 0.1 + 1.4 * u01(rng);
  const double yaw = 2.0 * std::numbers::pi * u01(rng);
  std::vector<double> ang(static_cast<std::size_t>(n));
  for (double& a : ang) a = 2.0 * std::numbers::pi * u01(rng);
  std::sort(ang.begin(), ang.end());
  std::vector<Vec3> face;
  for (double a : ang) {
    const Vec2 local(ra * std::cos(a), rb * std::sin(a));
    const Vec2 p = c + Eigen::Rotation2Dd(yaw) * local;
    face.emplace_back(p.x(), p.y(), z0 + g.dot(p - c));
  }
  return face;
}

std::vector<Vec3> raised(std::vector<Vec3> face, double dz) {
  for (Vec3& v : face) v.z() += dz;
  return face;
}

// Largest height of the terrain above the face over its footprint, by
// bisection on a vertical shift of the face with the brute-force test.
double clearance_threshold(const TerrainQuadtree& tree, const std::vector<Vec3>& face) {
  double lo = -100.0, hi = 100.0;  // shift: collides at lo, free at hi
  for (int it = 0; it < 100 && hi - lo > 1e-12; ++it) {
    const double mid = 0.5 * (lo + hi);
    (tree.brute_force_collides(raised(face, mid)) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(TerrainQuadtree, FacesJustAboveAndBelowATiltedPlane) {
  const auto plane = [](double x, double y) { return 0.4 + 0.3 * x - 0.2 * y; };
  const TerrainQuadtree tree(RuledTerrain(grid_of_nodes(plane, 40, 30, 0.25, 0.0, 0.0)));
  // The plane is one slab of zero thickness: the root is a leaf.
  EXPECT_EQ(tree.cells().size(), 1u);
  const Vec2 c(5.0, 3.5);
  std::vector<Vec3> face;
  for (const Vec2& d : {Vec2(-0.7, -0.4), Vec2(0.7, -0.4), Vec2(0.7, 0.4), Vec2(-0.7, 0.4)}) {
    const Vec2 p = c + d;
    face.emplace_back(p.x(), p.y(), plane(p.x(), p.y()));
  }
  EXPECT_FALSE(tree.collides(raised(face, 1e-3)));
  EXPECT_TRUE(tree.collides(raised(face, -1e-3)));
  EXPECT_FALSE(tree.brute_force_collides(raised(face, 1e-3)));
  EXPECT_TRUE(tree.brute_force_collides(raised(face, -1e-3)));
  // A horizontal face through the plane's value at the centre cuts it: collision.
  std::vector<Vec3> flat = face;
  for (Vec3& v : flat) v.z() = plane(c.x(), c.y());
  EXPECT_TRUE(tree.collides(flat));
  // Entirely off the map: no terrain, no collision.
  std::vector<Vec3> off = raised(face, -50.0);
  for (Vec3& v : off) v.x() += 100.0;
  EXPECT_FALSE(tree.collides(off));
}

TEST(TerrainQuadtree, ExactPatchTestFindsTheSaddleMaximumInsideAnEdge) {
  // One patch z = x y / h^2 style saddle on the unit square: along the
  // diagonal edge from (1, 0) to (0, 1), z = t (1 - t) peaks at 1/4 mid-edge
  // while all three vertices of the triangle are at z = 0.
  ElevationGrid g(2, 2, 1.0, 0.0, 0.0, 0.0);
  g.at(1, 1) = 1.0;  // z = a b
  g.at(0, 0) = 0.0;
  const TerrainQuadtree tree(RuledTerrain(g), {0.0, true});
  // Triangle (1,0), (0,1), (0,0) is CW; take (0,0), (1,0), (0,1) (CCW).
  const auto tri = [](double z) {
    return std::vector<Vec3>{{0.0, 0.0, z}, {1.0, 0.0, z}, {0.0, 1.0, z}};
  };
  // The largest height over the triangle is at the hypotenuse midpoint:
  // a = b = 1/2, z = 1/4.
  EXPECT_TRUE(tree.collides(tri(0.2499)));
  EXPECT_FALSE(tree.collides(tri(0.2501)));
  EXPECT_NEAR(clearance_threshold(tree, tri(0.0)), 0.25, 1e-9);
}

TEST(TerrainQuadtree, AgreesWithBruteForceOnRandomFacesOverFractalTerrain) {
  const RuledTerrain terrain = fractal(42);
  for (double h0 : {0.0, 0.02, 0.3}) {
    const TerrainQuadtree tree(terrain, {h0, true});
    std::mt19937_64 rng(1234);
    std::uniform_real_distribution<double> ux(-1.0, 17.0), ug(-0.6, 0.6), uz(-1.0, 1.0);
    int hits = 0, misses = 0;
    std::size_t tree_tests = 0, brute_tests = 0;
    for (int k = 0; k < 2500; ++k) {
      const Vec2 c(ux(rng), ux(rng));
      const Vec2 cc = c.cwiseMax(Vec2(0.0, 0.0)).cwiseMin(Vec2(16.0, 16.0));
      const double z0 = terrain.elevation(cc) + uz(rng);
      std::vector<Vec3> face = random_face(rng, c, z0, Vec2(ug(rng), ug(rng)));
      if (k % 3 == 0) {
        // Near-tangent: shift the face to within 1e-4 .. 1e-8 m of first contact.
        const double t = clearance_threshold(tree, face);
        const double delta = std::pow(10.0, -4.0 - (k % 5));
        face = raised(face, t + ((k / 3) % 2 == 0 ? delta : -delta));
      }
      QuadtreeQueryStats st_tree, st_brute;
      const bool a = tree.collides(face, &st_tree);
      const bool b = tree.brute_force_collides(face, &st_brute);
      ASSERT_EQ(a, b) << "face " << k << " h0 " << h0;
      (a ? hits : misses) += 1;
      tree_tests += st_tree.patches_tested;
      brute_tests += st_brute.patches_tested;
    }
    // Both outcomes must be well represented, or the agreement says little.
    EXPECT_GT(hits, 500);
    EXPECT_GT(misses, 500);
    // The slabs must spare most exact patch tests.
    EXPECT_LT(tree_tests, brute_tests / 2) << "h0 " << h0;
  }
}

TEST(TerrainQuadtree, ExactTestMatchesDenseSamplingOfTheFootprint) {
  const RuledTerrain terrain = fractal(7, 33);
  const TerrainQuadtree tree(terrain);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> ux(1.5, 6.5), ug(-0.5, 0.5), u01(0.0, 1.0);
  for (int k = 0; k < 60; ++k) {
    const Vec2 c(ux(rng), ux(rng));
    const std::vector<Vec3> face =
        random_face(rng, c, terrain.elevation(c), Vec2(ug(rng), ug(rng)));
    // Sampled maximum of terrain − face over the footprint (fan triangles).
    const Vec3 f0 = face[0];
    const Vec3 normal = (face[1] - f0).cross(face[2] - f0);
    double sampled = -1e9;
    for (std::size_t t = 1; t + 1 < face.size(); ++t) {
      for (int s = 0; s < 4000; ++s) {
        double a = u01(rng), b = u01(rng);
        if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
        const Vec3 p = f0 + a * (face[t] - f0) + b * (face[t + 1] - f0);
        if (!terrain.has_data(p.head<2>())) continue;
        const double zface =
            f0.z() - (normal.x() * (p.x() - f0.x()) + normal.y() * (p.y() - f0.y())) / normal.z();
        sampled = std::max(sampled, terrain.elevation(p.head<2>()) - zface);
      }
    }
    // The maximum lies on the boundary (see the header): sample the edges densely too.
    for (std::size_t e = 0; e < face.size(); ++e) {
      const Vec3& p0 = face[e];
      const Vec3& p1 = face[(e + 1) % face.size()];
      for (int s = 0; s <= 4000; ++s) {
        const Vec3 p = p0 + (s / 4000.0) * (p1 - p0);
        if (terrain.has_data(p.head<2>())) {
          sampled = std::max(sampled, terrain.elevation(p.head<2>()) - p.z());
        }
      }
    }
    const double exact = clearance_threshold(tree, face);
    EXPECT_GE(exact, sampled - 1e-9) << k;  // the exact max is never below a sample
    EXPECT_LE(exact, sampled + 5e-3) << k;  // and dense sampling comes close to it
  }
}

TEST(TerrainQuadtree, EveryCellSlabHoldsItsNodesAndChildrenTileTheParent) {
  const RuledTerrain terrain = fractal(3, 50);  // 49 x 49 patches: uneven splits
  const TerrainQuadtreeOptions opt{0.05, true};
  const TerrainQuadtree tree(terrain, opt);
  const ElevationGrid& g = terrain.grid();
  const auto cells = tree.cells();
  ASSERT_GT(cells.size(), 1u);
  EXPECT_EQ(cells[0].i1, 49u);
  EXPECT_EQ(cells[0].j1, 49u);
  std::size_t leaves = 0, patches_in_leaves = 0;
  for (const QuadtreeCell& c : cells) {
    const double norm = std::sqrt(1.0 + c.slope.squaredNorm());
    for (std::uint32_t j = c.j0; j <= c.j1; ++j)
      for (std::uint32_t i = c.i0; i <= c.i1; ++i) {
        const double d = (g.at(i, j) - c.plane(g.node_position(i, j))) / norm;
        EXPECT_GE(d, c.d_min - 1e-12);
        EXPECT_LE(d, c.d_max + 1e-12);
      }
    if (c.child_count == 0) {
      ++leaves;
      patches_in_leaves += std::size_t{c.i1 - c.i0} * (c.j1 - c.j0);
      EXPECT_TRUE((c.i1 - c.i0 == 1 && c.j1 - c.j0 == 1) || c.thickness() < opt.h0);
      continue;
    }
    EXPECT_GE(c.thickness(), opt.h0);
    std::size_t area = 0;
    for (std::uint32_t k = 0; k < c.child_count; ++k) {
      const QuadtreeCell& ch = cells[c.first_child + k];
      EXPECT_TRUE(ch.i0 >= c.i0 && ch.i1 <= c.i1 && ch.j0 >= c.j0 && ch.j1 <= c.j1);
      EXPECT_TRUE(ch.i1 > ch.i0 && ch.j1 > ch.j0);
      area += std::size_t{ch.i1 - ch.i0} * (ch.j1 - ch.j0);
    }
    EXPECT_EQ(area, std::size_t{c.i1 - c.i0} * (c.j1 - c.j0));  // disjoint children fill it
  }
  EXPECT_EQ(leaves, tree.leaf_count());
  EXPECT_EQ(patches_in_leaves, 49u * 49u);
  // The fit is the least-squares plane: on a plane terrain it is that plane.
  const TerrainQuadtree flat(RuledTerrain(
      grid_of_nodes([](double x, double y) { return 2.0 - x + 0.5 * y; }, 9, 9, 0.5, 0.0, 0.0)));
  EXPECT_NEAR(flat.cells()[0].slope.x(), -1.0, 1e-12);
  EXPECT_NEAR(flat.cells()[0].slope.y(), 0.5, 1e-12);
  EXPECT_NEAR(flat.cells()[0].thickness(), 0.0, 1e-12);
}

TEST(TerrainQuadtree, NodataPatchesCollideOnlyWhenAsked) {
  ElevationGrid g(8, 8, 1.0, 0.0, 0.0, 0.0);
  g.set_void(4, 4);
  const std::vector<Vec3> high{{3.2, 3.2, 5.0}, {3.8, 3.2, 5.0}, {3.8, 3.8, 5.0}};
  const std::vector<Vec3> elsewhere{{0.2, 0.2, 5.0}, {0.8, 0.2, 5.0}, {0.8, 0.8, 5.0}};
  const TerrainQuadtree strict(RuledTerrain(g), {0.02, true});
  const TerrainQuadtree lenient(RuledTerrain(g), {0.02, false});
  EXPECT_TRUE(strict.collides(high));  // patch (3, 3) touches the void node
  EXPECT_TRUE(strict.brute_force_collides(high));
  EXPECT_FALSE(lenient.collides(high));
  EXPECT_FALSE(strict.collides(elsewhere));
  EXPECT_TRUE(lenient.collides(raised(elsewhere, -5.1)));
}

TEST(TerrainQuadtree, RejectsBadFacesAndOptions) {
  const TerrainQuadtree tree(fractal(1, 17));
  EXPECT_THROW(tree.collides(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}}), InputError);
  EXPECT_THROW(tree.collides(std::vector<Vec3>(9, Vec3(1, 1, 1))), InputError);
  // Clockwise seen from above.
  EXPECT_THROW(tree.collides(std::vector<Vec3>{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}), InputError);
  // Vertical.
  EXPECT_THROW(tree.collides(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}}), InputError);
  // Not planar.
  EXPECT_THROW(tree.collides(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0.3}, {0, 1, 0}}),
               InputError);
  // Not convex (a dart).
  EXPECT_THROW(tree.collides(std::vector<Vec3>{{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}}),
               InputError);
  EXPECT_THROW(tree.collides(std::vector<Vec3>{{0, 0, 0}, {1, 0, std::nan("")}, {0, 1, 0}}),
               InputError);
  EXPECT_THROW(TerrainQuadtree(fractal(1, 17), {-0.1, true}), InputError);
}

}  // namespace
}  // namespace talus
