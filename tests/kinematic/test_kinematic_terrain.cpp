#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/hait/potential_bitmap.hpp"
#include "talus/kinematic/hait/terrain_quadtree.hpp"
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

// ---------------------------------------------------------------- PotentialBitmap

constexpr double kInf = std::numeric_limits<double>::infinity();

RuledTerrain flat_terrain(std::size_t ncols, std::size_t nrows, double h = 0.25) {
  return RuledTerrain(ElevationGrid(ncols, nrows, h, 0.0, 0.0, 1.0));
}

TEST(PotentialBitmap, FlatGroundGivesTheLatticeDistanceWithinTheStencilBound) {
  const RuledTerrain t = flat_terrain(41, 41);
  for (int connectivity : {8, 16}) {
    PotentialBitmapOptions o;
    o.connectivity = connectivity;
    const PotentialBitmap pb(t, {5.0, 5.0}, o);
    // Worst case between two neighbouring stencil directions 1/cos(half their angle).
    const double bound = connectivity == 16 ? 1.0 / std::cos(0.5 * std::atan(0.5))
                                            : 1.0 / std::cos(std::numbers::pi / 8);
    double worst = 1.0;
    for (std::size_t j = 0; j < 41; ++j)
      for (std::size_t i = 0; i < 41; ++i) {
        EXPECT_DOUBLE_EQ(pb.cost_at(i, j), 1.0);
        const double di = std::abs(double(i) - 20.0), dj = std::abs(double(j) - 20.0);
        const double d = 0.25 * std::hypot(di, dj);
        const double p = pb.potential_at(i, j);
        ASSERT_GE(p, d - 1e-9);
        ASSERT_LE(p, bound * d + 1e-9);
        if (d > 0) worst = std::max(worst, p / d);
        // Exact along the stencil's own directions.
        const bool axis = di == 0 || dj == 0 || di == dj;
        const bool knight = connectivity == 16 && (di == 2 * dj || dj == 2 * di);
        if (axis || knight) {
          EXPECT_NEAR(p, d, 1e-9) << i << " " << j;
        }
      }
    EXPECT_GT(worst, 1.0 + 0.8 * (bound - 1.0));  // the bound is nearly attained
    EXPECT_EQ(pb.stats().reached, 41u * 41u);
    EXPECT_EQ(pb.stats().obstacles, 0u);
    EXPECT_DOUBLE_EQ(pb.potential({5.0, 5.0}), 0.0);
    // Between nodes on the x axis the potential is interpolated linearly.
    EXPECT_NEAR(pb.potential({5.6, 5.0}), 0.6, 1e-9);
  }
}

TEST(PotentialBitmap, UniformSlopeScalesTheCostByItsWeight) {
  const double s = 0.2;
  const RuledTerrain t(
      grid_of_nodes([s](double x, double) { return std::tan(s) * x; }, 41, 21, 0.25, 0.0, 0.0));
  PotentialBitmapOptions o;
  o.max_slope = 0.5;
  o.slope_weight = 2.0;
  const PotentialBitmap pb(t, {0.0, 2.5}, o);
  const double c = 1.0 + 2.0 * s / 0.5;
  EXPECT_NEAR(pb.cost_at(20, 10), c, 1e-12);
  EXPECT_NEAR(pb.slopes()[10 * 41 + 20], s, 1e-12);
  EXPECT_NEAR(pb.roughness()[10 * 41 + 20], 0.0, 1e-12);
  EXPECT_NEAR(pb.potential({10.0, 2.5}), 10.0 * c, 1e-9);
  // Steeper than max_slope: every node is an obstacle, only the goal is reached.
  o.max_slope = 0.1;
  const PotentialBitmap steep(t, {0.0, 2.5}, o);
  EXPECT_TRUE(steep.stats().goal_on_obstacle);
  EXPECT_EQ(steep.stats().reached, 1u);
  EXPECT_FALSE(steep.reachable({10.0, 2.5}));
}

// Flat 0.25 m grid with a 2 m high one-node wall along column `col`, absent
// for rows in [gap_lo, gap_hi].
RuledTerrain walled(std::size_t ncols, std::size_t nrows, std::size_t col, std::size_t wall_rows,
                    std::size_t gap_lo = 1, std::size_t gap_hi = 0) {
  ElevationGrid g(ncols, nrows, 0.25, 0.0, 0.0, 0.0);
  for (std::size_t j = 0; j < wall_rows; ++j)
    if (j < gap_lo || j > gap_hi) g.at(col, j) = 2.0;
  return RuledTerrain(g);
}

TEST(PotentialBitmap, GoesAroundAnImpassableWall) {
  // Wall x = 7.5 m for y in [0, 7] m on a 15 x 10 m map.
  const RuledTerrain t = walled(61, 41, 30, 29);
  const Vec2 goal(3.0, 2.0), start(12.0, 2.0), tip(7.5, 7.0);
  const PotentialBitmap pb(t, goal);
  EXPECT_FALSE(pb.reachable({7.5, 3.0}));  // on the wall
  EXPECT_EQ(pb.potential_at(30, 10), kInf);
  ASSERT_TRUE(pb.reachable(start));
  // Any way round passes over the wall's tip: at least the two legs to it.
  const double around = (start - tip).norm() + (tip - goal).norm();
  EXPECT_GT(pb.potential(start), around);
  EXPECT_LT(pb.potential(start), 1.2 * around);
  EXPECT_GT(pb.stats().obstacles, 29u);
  // Without the wall the potential is the straight distance.
  const PotentialBitmap free(flat_terrain(61, 41), goal);
  EXPECT_NEAR(free.potential(start), 9.0, 1e-9);
}

TEST(PotentialBitmap, GrowingByRhoClosesAGapNarrowerThanTwoRho) {
  // Full-height wall at x = 5 m with a gap of 8 nodes (rows 16..23). With a
  // 0.3 m disc the nodes next to the wall are obstacles, so the obstacles
  // across the gap are rows 16 and 23: 1.75 m apart, and the gap's middle
  // nodes are 0.75 m from the nearest one.
  const RuledTerrain t = walled(41, 41, 20, 41, 16, 23);
  PotentialBitmapOptions o;
  o.robot_radius = 0.3;
  const Vec2 goal(2.0, 5.0), start(8.0, 5.0);
  const PotentialBitmap open(t, goal, o);
  ASSERT_TRUE(open.reachable(start));
  EXPECT_EQ(open.cost_at(20, 16), kInf);
  EXPECT_EQ(open.cost_at(20, 23), kInf);
  EXPECT_LT(open.cost_at(20, 19), kInf);
  o.position_uncertainty = 0.6;  // 2 rho = 1.2 m < gap: stays open
  const PotentialBitmap grown(t, goal, o);
  ASSERT_TRUE(grown.reachable(start));
  EXPECT_GE(grown.potential(start), open.potential(start));
  EXPECT_GE(grown.stats().obstacles, open.stats().obstacles);
  o.position_uncertainty = 0.8;  // 2 rho = 1.6 m > 1.5 m between the dilated ends: closed
  const PotentialBitmap closed(t, goal, o);
  EXPECT_FALSE(closed.reachable(start));
  EXPECT_TRUE(closed.reachable({3.0, 9.0}));  // the goal's side is still connected
  // Growing is a max filter: every grown cost is at least the original one.
  for (std::size_t k = 0; k < open.costs().size(); ++k) {
    EXPECT_GE(closed.costs()[k], open.costs()[k]);
  }
}

TEST(PotentialBitmap, TerrainUncertaintyRaisesTheRoughness) {
  const RuledTerrain t = flat_terrain(21, 21);
  ElevationGrid dz(21, 21, 0.25, 0.0, 0.0, 0.05);
  const PotentialBitmap pb(t, {0.0, 0.0}, {}, &dz);
  // roughness 2 * 0.05 = 0.1 m: cost 1 + 0.1 / 0.2.
  EXPECT_NEAR(pb.cost_at(10, 10), 1.5, 1e-12);
  EXPECT_NEAR(pb.potential({5.0, 0.0}), 7.5, 1e-9);
  // An uncertain band x in [2, 3] m too wide to trust becomes an obstacle.
  for (std::size_t j = 0; j < 21; ++j)
    for (std::size_t i = 8; i <= 12; ++i) dz.at(i, j) = 0.2;
  const PotentialBitmap band(t, {0.0, 0.0}, {}, &dz);
  EXPECT_FALSE(band.reachable({5.0, 0.0}));
}

TEST(PotentialBitmap, RejectsBadInput) {
  const RuledTerrain t = flat_terrain(11, 11);
  EXPECT_THROW(PotentialBitmap(t, {-0.1, 1.0}), InputError);
  const PotentialBitmap pb(t, {1.0, 1.0});
  EXPECT_THROW(pb.potential({2.6, 1.0}), InputError);
  const auto bad = [&](auto&& edit) {
    PotentialBitmapOptions o;
    edit(o);
    EXPECT_THROW(PotentialBitmap(t, {1.0, 1.0}, o), InputError);
  };
  bad([](PotentialBitmapOptions& o) { o.robot_radius = 0.0; });
  bad([](PotentialBitmapOptions& o) { o.max_slope = 1.6; });
  bad([](PotentialBitmapOptions& o) { o.max_roughness = -1.0; });
  bad([](PotentialBitmapOptions& o) { o.slope_weight = -1.0; });
  bad([](PotentialBitmapOptions& o) { o.roughness_weight = std::nan(""); });
  bad([](PotentialBitmapOptions& o) { o.position_uncertainty = -0.1; });
  bad([](PotentialBitmapOptions& o) { o.connectivity = 4; });
  ElevationGrid wrong(10, 11, 0.25, 0.0, 0.0, 0.0);
  EXPECT_THROW(PotentialBitmap(t, {1.0, 1.0}, {}, &wrong), InputError);
  ElevationGrid negative(11, 11, 0.25, 0.0, 0.0, -0.01);
  EXPECT_THROW(PotentialBitmap(t, {1.0, 1.0}, {}, &negative), InputError);
}

}  // namespace
}  // namespace talus
