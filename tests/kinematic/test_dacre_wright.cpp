// Dacre-Wright and Simeon 1993: the admissibility of a configuration-space box
// (soundness, Proposition 1, against the exact placement), the average plane
// against a direct least-squares solve, closed forms on planes, a step higher
// than L_max, the octree's theta wrap-around and the planner's statuses.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "random_test_support.hpp"
#include "talus/core/error.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/dacre_wright/configuration_octree.hpp"
#include "talus/kinematic/dacre_wright/dacre_wright_planner.hpp"
#include "talus/kinematic/dacre_wright/region_admissibility.hpp"
#include "terrain_test_support.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;
using random_test::uniform;
using terrain_test::grid_from_function;
using terrain_test::HeightFunction;

const WheeledRobot& six_wheel() {
  static const WheeledRobot r =
      load_dacre_wright_robot(TALUS_DATA_DIR "/robots/dacre_wright_six_wheel.yaml");
  return r;
}

/// 13 m x 13 m at 0.25 m holding f.
RuledTerrain terrain_of(const HeightFunction& f) {
  return RuledTerrain(grid_from_function(f, 0, 0, 13, 13, 0.25));
}

// --- robot -------------------------------------------------------------------

TEST(DacreWrightRobot, SixWheelFileIsSymmetricAndValid) {
  const WheeledRobot& r = six_wheel();
  ASSERT_EQ(r.wheels.size(), 6u);
  double su = 0, sv = 0, suv = 0;
  for (const Vec2& w : r.wheels) {
    su += w.x();
    sv += w.y();
    suv += w.x() * w.y();
  }
  EXPECT_EQ(su, 0.0);
  EXPECT_EQ(sv, 0.0);
  EXPECT_EQ(suv, 0.0);
  EXPECT_NO_THROW(r.validate());
}

TEST(DacreWrightRobot, AsymmetricLayoutIsAClearError) {
  WheeledRobot r = six_wheel();
  r.wheels[0].x() += 0.1;  // sum u = 0.1
  try {
    require_symmetric_wheels(r);
    FAIL() << "an asymmetric layout was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sum u = 0.1"), std::string::npos) << e.what();
  }
  r = six_wheel();
  r.wheels = {{0.6, 0.4}, {0.6, -0.4}, {-0.6, -0.4}, {-0.6, 0.4}};  // a symmetric rectangle
  EXPECT_NO_THROW(require_symmetric_wheels(r));
  r.wheels = {{0.6, 0.5}, {0.6, -0.3}, {-0.6, -0.5}, {-0.6, 0.3}};  // sum u*v = 0.48
  EXPECT_THROW(require_symmetric_wheels(r), InputError);

  // From a file: the error names the file.
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "talus_dw_asymmetric.yaml";
  {
    std::ofstream out(file);
    out << "type: wheeled\nwheels: [[0.7, 0.4], [0.7, -0.4], [-0.6, -0.4], [-0.6, 0.4]]\n"
           "cg_height: 0.5\nmax_spring_extension: 0.1\nmax_roll: 0.3\nmax_pitch: 0.3\n"
           "body: {front: 0.8, rear: 0.8, half_width: 0.5, clearance: 0.3}\n";
  }
  try {
    load_dacre_wright_robot(file.string());
    FAIL() << "an asymmetric file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sum u"), std::string::npos) << e.what();
  }
  std::filesystem::remove(file);
  EXPECT_THROW(load_dacre_wright_robot(TALUS_DATA_DIR "/robots/marsokhod_chassis.yaml"),
               InputError);
}

// --- average plane -----------------------------------------------------------

TEST(DacreWrightAveragePlane, AccumulationEqualsADirectLeastSquaresSolve) {
  std::mt19937_64 rng(14);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 5 + trial * 7;
    Eigen::MatrixXd a(n, 3);
    Eigen::VectorXd b(n);
    const Vec2 origin(uniform(rng, -50, 50), uniform(rng, -50, 50));
    AveragePlaneAccumulator acc(origin);
    for (int k = 0; k < n; ++k) {
      const double x = origin.x() + uniform(rng, -3, 3), y = origin.y() + uniform(rng, -3, 3);
      const double z = 0.3 * x - 0.2 * y + 4 + uniform(rng, -0.5, 0.5);
      a.row(k) << x, y, 1.0;
      b(k) = z;
      acc.add(x, y, z);
    }
    const Eigen::Vector3d direct = a.colPivHouseholderQr().solve(b);
    Vec3 abc;
    ASSERT_TRUE(acc.solve(abc));
    EXPECT_EQ(acc.count(), static_cast<std::size_t>(n));
    EXPECT_NEAR(abc.x(), direct.x(), 1e-10);
    EXPECT_NEAR(abc.y(), direct.y(), 1e-10);
    EXPECT_NEAR(abc.z(), direct.z(), 1e-8 * (1 + std::abs(direct.z())));
  }
  AveragePlaneAccumulator line;
  for (int k = 0; k < 10; ++k) line.add(k, 2.0 * k, 1.0);  // collinear
  Vec3 abc;
  EXPECT_FALSE(line.solve(abc));
}

TEST(DacreWrightAveragePlane, IntegralImagesEqualTheDirectSums) {
  // A rough terrain, the same 1500 m higher (conditioning), and one with NODATA.
  FractalTerrainOptions f;
  f.shape = {40, 37, 0.25, -3.0, 2.0};
  f.height_scale = 0.8;
  f.seed = 3;
  ElevationGrid rough = generate_fractal_terrain(f);
  ElevationGrid high = rough;
  for (std::size_t j = 0; j < high.nrows(); ++j)
    for (std::size_t i = 0; i < high.ncols(); ++i) high.at(i, j) += 1500.0;
  ElevationGrid holes = rough;
  holes.set_void(17, 20);
  std::mt19937_64 rng(99);
  for (const ElevationGrid& g : {rough, high, holes}) {
    const RuledTerrain t(g);
    const ElevationSums sums(t);
    for (int trial = 0; trial < 300; ++trial) {
      long i1 = static_cast<long>(uniform(rng, 0, 40)), i2 = static_cast<long>(uniform(rng, 0, 40));
      long j1 = static_cast<long>(uniform(rng, 0, 37)), j2 = static_cast<long>(uniform(rng, 0, 37));
      if (i1 > i2) std::swap(i1, i2);
      if (j1 > j2) std::swap(j1, j2);
      // Near the rectangle, as analyse_box puts it at the box's centre.
      const Vec2 origin(g.x_min() + 0.125 * static_cast<double>(i1 + i2) + uniform(rng, -1, 1),
                        g.y_min() + 0.125 * static_cast<double>(j1 + j2) + uniform(rng, -1, 1));
      AveragePlaneAccumulator direct(origin), fast(origin);
      // Two rectangles, as two wheels' regions add up.
      bool valid = true;
      for (int rep = 0; rep < 2; ++rep) {
        for (long j = j1; j <= j2; ++j)
          for (long i = i1; i <= i2; ++i) {
            const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
            valid = valid && g.valid(ui, uj);
            if (g.valid(ui, uj))
              direct.add(g.x_min() + 0.25 * static_cast<double>(i),
                         g.y_min() + 0.25 * static_cast<double>(j), g.at(ui, uj));
          }
        EXPECT_EQ(sums.accumulate(i1, i2, j1, j2, fast), valid);
      }
      if (!valid) {
        EXPECT_EQ(fast.count(), 0u);
        continue;
      }
      ASSERT_EQ(fast.count(), direct.count());
      const Mat3 da = direct.ata(), fa = fast.ata();
      const Vec3 db = direct.atb(), fb = fast.atb();
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(fb(r), db(r), 1e-9 * db.cwiseAbs().maxCoeff()) << trial << " " << r;
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(fa(r, c), da(r, c), 1e-9 * da.cwiseAbs().maxCoeff()) << trial;
      }
      Vec3 pd, pf;
      if (direct.solve(pd)) {
        ASSERT_TRUE(fast.solve(pf));
        EXPECT_NEAR(pf.x(), pd.x(), 1e-9 * (1 + std::abs(pd.x())));
        EXPECT_NEAR(pf.y(), pd.y(), 1e-9 * (1 + std::abs(pd.y())));
        EXPECT_NEAR(pf.z(), pd.z(), 1e-9 * (1 + std::abs(pd.z())));
      }
    }
  }
}

// --- closed forms on planes --------------------------------------------------

/// The plane's roll and pitch at heading θ (placement.hpp conventions).
double plane_roll(double a, double b, double t) {
  return std::asin((b * std::cos(t) - a * std::sin(t)) / std::sqrt(1 + a * a + b * b));
}
double plane_pitch(double a, double b, double t) {
  return std::atan(a * std::cos(t) + b * std::sin(t));
}

TEST(DacreWrightBox, OnAPlaneTheBoundsAreThePlanesAttitudeAndSmallBoxesAreFree) {
  const double a = 0.3, b = -0.12;
  const RuledTerrain t = terrain_of([&](double x, double y) { return a * x + b * y + 1.0; });
  const WheeledRobot& r = six_wheel();
  std::mt19937_64 rng(3);
  for (double width : {0.8, 0.2, 0.05, 0.01}) {
    for (int trial = 0; trial < 10; ++trial) {
      const double x = uniform(rng, 3, 9), y = uniform(rng, 3, 9), th = uniform(rng, 0, 2 * kPi);
      const CsBox box{x, x + width, y, y + width, th, th + width};
      const BoxAnalysis s = analyse_box(r, t, box);
      ASSERT_NE(s.verdict, BoxVerdict::kOffMap);
      EXPECT_NEAR(s.plane.x(), a, 1e-12);
      EXPECT_NEAR(s.plane.y(), b, 1e-12);
      EXPECT_LT(s.beta_max, 1e-7) << "the terrain is its own average plane";
      // The roll and pitch bounds are the plane's attitude over [θ1, θ2].
      double rlo = 1e9, rhi = -1e9, plo = 1e9, phi = -1e9;
      for (int k = 0; k <= 2000; ++k) {
        const double tk = th + width * k / 2000.0;
        rlo = std::min(rlo, plane_roll(a, b, tk));
        rhi = std::max(rhi, plane_roll(a, b, tk));
        plo = std::min(plo, plane_pitch(a, b, tk));
        phi = std::max(phi, plane_pitch(a, b, tk));
      }
      EXPECT_NEAR(s.roll.lo, rlo, 1e-6);
      EXPECT_NEAR(s.roll.hi, rhi, 1e-6);
      EXPECT_NEAR(s.pitch.lo, plo, 1e-6);
      EXPECT_NEAR(s.pitch.hi, phi, 1e-6);
      for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(s.extension[i].lo), 1e-6);
      // FREE exactly when the attitude range fits S (away from its edges).
      const bool fits = std::max(std::abs(rlo), std::abs(rhi)) < r.max_roll - 1e-4 &&
                        std::max(std::abs(plo), std::abs(phi)) < r.max_pitch - 1e-4;
      const bool out = std::max(std::abs(rlo), std::abs(rhi)) > r.max_roll + 1e-4 ||
                       std::max(std::abs(plo), std::abs(phi)) > r.max_pitch + 1e-4;
      if (fits) {
        EXPECT_TRUE(s.free()) << to_string(s.verdict) << " width " << width;
      }
      if (out) {
        EXPECT_FALSE(s.free()) << "width " << width;
      }
    }
  }
}

TEST(DacreWrightBox, OnLevelGroundEveryBoxOnTheMapIsFreeWithBetaZero) {
  const RuledTerrain t = terrain_of([](double, double) { return 2.0; });
  for (double width : {2.0, 1.0, 0.25}) {
    const CsBox box{5, 5 + width, 5, 5 + width, 0, 2 * kPi};
    const BoxAnalysis s = analyse_box(six_wheel(), t, box);
    EXPECT_TRUE(s.free()) << to_string(s.verdict);
    EXPECT_EQ(s.beta_max, 0.0);
  }
  // A box whose wheels reach off the map.
  EXPECT_EQ(analyse_box(six_wheel(), t, {0.1, 0.3, 5, 5.2, 0, 0.1}).verdict, BoxVerdict::kOffMap);
}

TEST(DacreWrightBox, BetaMaxFormulaIsThePapers) {
  // 2 arctan[(√(K²+1) − 1)/K] = arctan K (half-angle identity).
  for (double k : {1e-6, 0.01, 0.3, 1.0, 7.0}) EXPECT_NEAR(paper_beta_max(k), std::atan(k), 1e-12);
  EXPECT_EQ(paper_beta_max(0.0), 0.0);
}

TEST(DacreWrightBox, BetaShrinksWithTheBoxOnACurvedTerrain) {
  // A gentle bowl: the analysis of ever smaller boxes around one configuration
  // gives non-increasing β_max and narrowing spring ranges.
  const RuledTerrain t = terrain_of(
      [](double x, double y) { return 0.01 * ((x - 6.5) * (x - 6.5) + (y - 6.5) * (y - 6.5)); });
  double last_beta = 1e9, last_width = 1e9;
  for (double w : {1.6, 0.8, 0.4, 0.2, 0.1}) {
    const BoxAnalysis s = analyse_box(six_wheel(), t, {6, 6 + w, 6, 6 + w, 0.3, 0.3 + w / 4});
    ASSERT_NE(s.verdict, BoxVerdict::kOffMap);
    EXPECT_LE(s.beta_max, last_beta + 1e-12);
    const double width = s.extension[0].hi - s.extension[0].lo;
    EXPECT_LT(width, last_width);
    last_beta = s.beta_max;
    last_width = width;
  }
}

// --- soundness (Proposition 1) -------------------------------------------------

struct NamedTerrain {
  std::string name;
  RuledTerrain terrain;
};

std::vector<NamedTerrain> soundness_terrains() {
  std::vector<NamedTerrain> out;
  FractalTerrainOptions f;
  f.shape = {53, 53, 0.25, 0.0, 0.0};
  f.height_scale = 0.6;
  f.seed = 7;
  out.push_back({"fractal", RuledTerrain(generate_fractal_terrain(f))});
  f.seed = 8;
  f.height_scale = 0.7;
  out.push_back({"fractal-rough", RuledTerrain(generate_fractal_terrain(f))});
  out.push_back({"hills", terrain_of([](double x, double y) {
                   return 1.2 * std::exp(-((x - 5) * (x - 5) + (y - 6) * (y - 6)) / 2.0) +
                          0.6 * std::exp(-((x - 9) * (x - 9) + (y - 8) * (y - 8)) / 0.8);
                 })});
  out.push_back({"step", terrain_of([](double x, double) { return x < 6.5 ? 0.0 : 0.3; })});
  out.push_back({"ripples", terrain_of([](double x, double y) {
                   return 0.15 * x + 0.04 * std::sin(1.7 * x) * std::cos(1.3 * y);
                 })});
  return out;
}

TEST(DacreWrightSoundness, EveryConfigurationSampledInAFreeVoxelIsAdmissible) {
  const WheeledRobot& r = six_wheel();
  OctreeOptions o;
  o.max_level = 5;
  std::mt19937_64 rng(1993);
  std::size_t total = 0;
  for (const NamedTerrain& nt : soundness_terrains()) {
    ConfigurationOctree oct(r, nt.terrain, o);
    oct.build_full();
    const std::vector<VoxelKey> leaves = oct.free_leaves();
    ASSERT_FALSE(leaves.empty()) << nt.name;
    const double fraction = oct.free_volume_fraction();
    EXPECT_GT(fraction, 0.02) << nt.name;
    EXPECT_LT(fraction, 0.98) << nt.name;
    // Volume-weighted choice of a leaf, then a uniform point in it.
    std::vector<double> cumulative;
    double acc = 0;
    for (const VoxelKey& v : leaves) cumulative.push_back(acc += std::pow(8.0, -v.level));
    std::size_t failures = 0, outside = 0;
    const int samples = 1000;
    for (int s = 0; s < samples; ++s) {
      const double pick = uniform(rng, 0, acc);
      const std::size_t idx = static_cast<std::size_t>(
          std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
      const CsBox b = oct.box(leaves[std::min(idx, leaves.size() - 1)]);
      const SE2Pose q{uniform(rng, b.x1, b.x2), uniform(rng, b.y1, b.y2),
                      uniform(rng, b.theta1, b.theta2)};
      if (!dacre_wright_admissible(r, nt.terrain, q)) {
        ++failures;
        if (failures < 4) ADD_FAILURE() << nt.name << ": " << q.x << ", " << q.y << ", " << q.theta;
      }
      // Sharper: the placement lies inside the box's computed domain Δr.
      const BoxAnalysis a = analyse_box(r, nt.terrain, b);
      const RobotPlacement p = place_robot(r, nt.terrain, q.x, q.y, q.theta);
      const double e = 1e-9;
      bool in = p.roll >= a.roll.lo - e && p.roll <= a.roll.hi + e && p.pitch >= a.pitch.lo - e &&
                p.pitch <= a.pitch.hi + e;
      for (int i = 0; i < p.wheel_count; ++i) {
        in = in && p.extensions[i] >= a.extension[i].lo - e &&
             p.extensions[i] <= a.extension[i].hi + e;
      }
      if (!in) {
        ++outside;
        if (outside < 4) {
          ADD_FAILURE() << nt.name << ": placement outside delta r at " << q.x << ", " << q.y
                        << ", " << q.theta << ": roll " << p.roll << " in [" << a.roll.lo << ", "
                        << a.roll.hi << "], pitch " << p.pitch << " in [" << a.pitch.lo << ", "
                        << a.pitch.hi << "]";
        }
      }
    }
    // The corners of every leaf too (closed boxes).
    for (const VoxelKey& v : leaves) {
      const CsBox b = oct.box(v);
      for (int c = 0; c < 8; ++c) {
        const SE2Pose q{c & 1 ? b.x2 : b.x1, c & 2 ? b.y2 : b.y1, c & 4 ? b.theta2 : b.theta1};
        if (!dacre_wright_admissible(r, nt.terrain, q)) ++failures;
      }
    }
    EXPECT_EQ(outside, 0u) << nt.name;
    EXPECT_EQ(failures, 0u) << nt.name << ": " << leaves.size() << " FREE leaves, fraction "
                            << fraction;
    total += samples + 8 * leaves.size();
  }
  EXPECT_GE(total, 5000u);
}

// --- a step higher than L_max --------------------------------------------------

TEST(DacreWrightOctree, IntegralImageAnalysisGivesTheDirectVerdicts) {
  // The octree analyses with ElevationSums; every voxel it decided, re-analysed
  // with the node-by-node sums, gets the same verdict (and nearly the same plane).
  OctreeOptions o;
  o.max_level = 5;
  const std::vector<NamedTerrain> terrains = soundness_terrains();
  std::size_t compared = 0;
  for (std::size_t t : {std::size_t{0}, std::size_t{2}}) {
    const RuledTerrain& terrain = terrains[t].terrain;
    ConfigurationOctree oct(six_wheel(), terrain, o);
    oct.build_full();
    const ElevationSums sums(terrain);
    std::size_t free = 0;
    for (const AnalysedVoxel& v : oct.decided()) {
      if (v.from_sons) continue;
      const BoxAnalysis direct = analyse_box(six_wheel(), terrain, oct.box(v.key));
      EXPECT_EQ(direct.free(), v.status == VoxelStatus::kFree) << terrains[t].name;
      free += direct.free() ? 1 : 0;
      ++compared;
      if (compared % 16 == 0) {
        const BoxAnalysis fast = analyse_box(six_wheel(), sums, oct.box(v.key));
        EXPECT_EQ(fast.verdict, direct.verdict);
        EXPECT_EQ(fast.points, direct.points);
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(fast.plane(k), direct.plane(k), 1e-9 * (1 + std::abs(direct.plane(k))));
      }
    }
    EXPECT_GT(free, 0u) << terrains[t].name;
  }
  EXPECT_GT(compared, 1000u);
}

TEST(DacreWrightOctree, VoxelsStraddlingAHighStepAreMixedDownToPmax) {
  const WheeledRobot& r = six_wheel();
  const double step_x = 6.5, height = 4 * r.max_spring_extension;
  const RuledTerrain t = terrain_of([&](double x, double) { return x < step_x ? 0.0 : height; });
  OctreeOptions o;
  o.max_level = 5;
  ConfigurationOctree oct(r, t, o);
  oct.build_full();
  std::size_t far_free = 0;
  for (const VoxelKey& v : oct.free_leaves()) {
    const CsBox b = oct.box(v);
    // No FREE voxel holds a configuration with G over the step's ramp.
    EXPECT_FALSE(b.x1 <= step_x && b.x2 >= step_x - t.spacing()) << b.x1 << " " << b.x2;
    if (b.x2 < step_x - 2 || b.x1 > step_x + 2) ++far_free;
  }
  EXPECT_GT(far_free, 0u) << "flat ground away from the step is FREE";
  for (double y : {3.0, 6.0, 9.0}) {
    for (double th : {0.0, 1.0, 2.0, 4.0}) {
      const auto v = oct.locate({step_x - 0.1, y, th}, o.max_level);
      ASSERT_TRUE(v.has_value());
      EXPECT_EQ(oct.state(*v), VoxelStatus::kMixed);
    }
  }
}

// --- octree structure ----------------------------------------------------------

TEST(DacreWrightOctree, ThetaWrapAroundConnectsVoxelsAcrossZero) {
  const RuledTerrain t = terrain_of([](double, double) { return 0.0; });
  OctreeOptions o;
  o.max_level = 4;
  ConfigurationOctree oct(six_wheel(), t, o);
  const auto top = oct.largest_free_containing({6.6, 6.6, 2 * kPi - 0.01});
  ASSERT_TRUE(top.has_value());
  const CsBox tb = oct.box(*top);
  ASSERT_EQ(tb.theta2, 2 * kPi);
  bool wraps = false;
  for (const VoxelKey& v : oct.free_neighbours(*top)) {
    const CsBox b = oct.box(v);
    wraps =
        wraps || (b.theta1 == 0.0 && b.x1 < tb.x2 && b.x2 > tb.x1 && b.y1 < tb.y2 && b.y2 > tb.y1);
  }
  EXPECT_TRUE(wraps) << "the +theta neighbour of the last theta slice is the first";

  // A path from theta = 0.1 to theta = -0.1 turns by 0.2 rad, not by 2 pi - 0.2.
  DacreWrightOptions po;
  po.octree.max_level = 4;
  const DacreWrightResult res =
      plan_dacre_wright(t, six_wheel(), {6.6, 6.6, 0.1}, {6.6, 6.6, -0.1}, po);
  ASSERT_TRUE(res.found()) << res.brief_report();
  EXPECT_NEAR(std::abs(res.path.back().theta - res.path.front().theta), 0.2, 1e-9);
}

TEST(DacreWrightOctree, NeighboursShareAFaceAndFatherMergingGivesTheLargest) {
  const RuledTerrain t = terrain_of([](double x, double) { return x < 6.5 ? 0.0 : 0.6; });
  OctreeOptions o;
  o.max_level = 5;
  ConfigurationOctree oct(six_wheel(), t, o);
  const auto v = oct.largest_free_containing({3.0, 6.0, 0.2});
  ASSERT_TRUE(v.has_value());
  const CsBox b = oct.box(*v);
  for (const VoxelKey& n : oct.free_neighbours(*v)) {
    EXPECT_EQ(oct.state(n), VoxelStatus::kFree);
    // Largest: its father is not FREE (or it is the root).
    if (n.level > 0) {
      EXPECT_NE(oct.state(ConfigurationOctree::father(n)), VoxelStatus::kFree);
    }
    // Shares part of a face with v (theta compared modulo 2 pi).
    const CsBox c = oct.box(n);
    int touching = 0, overlapping = 0;
    const auto classify = [&](double a1, double a2, double b1, double b2) {
      if (std::abs(a2 - b1) < 1e-9 || std::abs(b2 - a1) < 1e-9)
        ++touching;
      else if (std::min(a2, b2) > std::max(a1, b1))
        ++overlapping;
    };
    classify(b.x1, b.x2, c.x1, c.x2);
    classify(b.y1, b.y2, c.y1, c.y2);
    double t1 = c.theta1, t2 = c.theta2;
    if (t2 < b.theta1 - 1e-9) t1 += 2 * kPi, t2 += 2 * kPi;
    if (t1 > b.theta2 + 1e-9) t1 -= 2 * kPi, t2 -= 2 * kPi;
    classify(b.theta1, b.theta2, t1, t2);
    EXPECT_EQ(touching + overlapping, 3);
    EXPECT_GE(touching, 1);
  }
}

// --- planner ---------------------------------------------------------------------

TEST(DacreWrightPlanner, PathStaysInTheChannelAndEveryPoseIsAdmissible) {
  const RuledTerrain t = soundness_terrains()[2].terrain;  // hills
  DacreWrightOptions o;
  o.octree.max_level = 5;
  const SE2Pose start{2.5, 2.5, 0.5}, goal{10.5, 10.5, 2.0};
  const DacreWrightResult r = plan_dacre_wright(t, six_wheel(), start, goal, o);
  ASSERT_TRUE(r.found()) << r.brief_report();
  ASSERT_GE(r.path.size(), 2u);
  EXPECT_EQ(r.path.front().x, start.x);
  EXPECT_EQ(r.path.back().x, goal.x);
  EXPECT_NEAR(std::remainder(r.path.back().theta - goal.theta, 2 * kPi), 0.0, 1e-12);
  for (const SE2Pose& q : r.path) {
    EXPECT_TRUE(dacre_wright_admissible(six_wheel(), t, q)) << q.x << " " << q.y << " " << q.theta;
    bool inside = false;
    for (const CsBox& b : r.channel_boxes) {
      const double th = std::fmod(std::fmod(q.theta, 2 * kPi) + 2 * kPi, 2 * kPi);
      const double e = 1e-9;
      inside =
          inside || (q.x >= b.x1 - e && q.x <= b.x2 + e && q.y >= b.y1 - e && q.y <= b.y2 + e &&
                     ((th >= b.theta1 - e && th <= b.theta2 + e) ||
                      (th + 2 * kPi <= b.theta2 + e) || (th - 2 * kPi >= b.theta1 - e)));
    }
    EXPECT_TRUE(inside) << q.x << " " << q.y << " " << q.theta;
  }
  // Incremental search analyses fewer voxels than the whole octree.
  DacreWrightOptions full = o;
  full.full = true;
  const DacreWrightResult w = plan_dacre_wright(t, six_wheel(), start, goal, full);
  ASSERT_TRUE(w.found()) << w.brief_report();
  EXPECT_LT(r.voxels_analysed(), w.voxels_analysed());
}

TEST(DacreWrightPlanner, InvalidStartGoalAndBadOptionsAreClear) {
  const RuledTerrain t = terrain_of([](double x, double) { return x < 6.5 ? 0.0 : 0.6; });
  DacreWrightOptions o;
  o.octree.max_level = 4;
  // Sideways across the step: the roll is too large.
  const SE2Pose bad{6.5, 6, kPi / 2}, ok{3, 6, 0};
  ASSERT_FALSE(dacre_wright_admissible(six_wheel(), t, bad));
  EXPECT_EQ(plan_dacre_wright(t, six_wheel(), bad, ok, o).status, DacreWrightStatus::kStartInvalid);
  EXPECT_EQ(plan_dacre_wright(t, six_wheel(), ok, bad, o).status, DacreWrightStatus::kGoalInvalid);
  EXPECT_THROW(plan_dacre_wright(t, six_wheel(), {std::nan(""), 6, 0}, ok, o), InputError);
  DacreWrightOptions bad_options = o;
  bad_options.octree.max_level = 9;
  EXPECT_THROW(plan_dacre_wright(t, six_wheel(), ok, ok, bad_options), InputError);
  bad_options = o;
  bad_options.octree.reference_level = 5;
  EXPECT_THROW(plan_dacre_wright(t, six_wheel(), ok, ok, bad_options), InputError);
  WheeledRobot lopsided = six_wheel();
  lopsided.wheels[0].y() += 0.2;
  EXPECT_THROW(plan_dacre_wright(t, lopsided, ok, ok, o), InputError);
}

}  // namespace
}  // namespace talus
