// End-to-end tests of `talus baseline dacre-wright`: the voxels.csv /
// channel.csv / summary.json / octree.png contract on a seeded rough terrain
// (boxes of the octree's geometry, channel rows indexing FREE voxels that hold
// the start and the goal and share a face pairwise, the free volume
// re-evaluated from voxels.csv), and the files of an invalid start.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "cli_test_support.hpp"

namespace talus::cli_test {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::string six_wheel() {
  return data_file("robots/dacre_wright_six_wheel.yaml");
}

/// 64 x 64 nodes at 0.25 m (15.75 m square), fractal, 0.6 m peak to peak.
std::string rough_map() {
  return generate_terrain("dw_rough.asc",
                          "fractal --ncols 64 --nrows 64 --cellsize 0.25 --height-scale 0.6 "
                          "--seed 1993");
}

struct Voxel {
  int level = 0;
  double x1, x2, y1, y2, t1, t2;
  bool free = false;
};

std::vector<Voxel> read_voxels(const std::string& file) {
  std::vector<Voxel> out;
  for (const auto& r : read_csv(file, "level,x_min,x_max,y_min,y_max,theta_min,theta_max,status")) {
    EXPECT_TRUE(r[7] == "FREE" || r[7] == "MIXED") << r[7];
    out.push_back({static_cast<int>(parse_number(r[0])), parse_number(r[1]), parse_number(r[2]),
                   parse_number(r[3]), parse_number(r[4]), parse_number(r[5]), parse_number(r[6]),
                   r[7] == "FREE"});
  }
  return out;
}

/// Closed intervals [a1, a2] and [b1, b2]: overlap length (negative = gap).
double overlap(double a1, double a2, double b1, double b2) {
  return std::min(a2, b2) - std::max(a1, b1);
}

/// The θ overlap of two voxels, trying the shifts by ±2π (θ is periodic).
double theta_overlap(const Voxel& a, const Voxel& b) {
  double best = -1e300;
  for (double s : {-kTwoPi, 0.0, kTwoPi})
    best = std::max(best, overlap(a.t1, a.t2, b.t1 + s, b.t2 + s));
  return best;
}

bool holds(const Voxel& v, double x, double y, double theta) {
  double th = std::fmod(theta, kTwoPi);
  if (th < 0) th += kTwoPi;
  const double e = 1e-9;
  return x >= v.x1 - e && x <= v.x2 + e && y >= v.y1 - e && y <= v.y2 + e && th >= v.t1 - e &&
         th <= v.t2 + e;
}

TEST(CliDacreWright, WritesVoxelsChannelAndSummaryOfTheOctree) {
  const std::string terrain = rough_map();
  const std::string dir = scratch_file("dw_rough_out");
  std::filesystem::remove_all(dir);
  const int p_max = 5;
  const RunResult r =
      run_talus("baseline dacre-wright --terrain " + quoted(terrain) + " --robot " +
                quoted(six_wheel()) + " --start 3,3,0 --goal 12.5,12.5,1.5 --max-level " +
                std::to_string(p_max) + " --out " + quoted(dir));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const nlohmann::json j = parse_json(r.out, "stdout");
  EXPECT_EQ(j, parse_json(read_text(dir + "/summary.json"), "summary.json"));
  EXPECT_EQ(j.value("status", ""), "found") << j.dump();
  for (const char* key : {"voxels_analysed_per_level", "free_volume_fraction", "voxels_decided",
                          "preprocessing_seconds", "search_seconds", "length_m", "reference_level",
                          "channel_voxels"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  const int p0 = j.value("reference_level", -1);
  ASSERT_GE(p0, 0);
  ASSERT_LE(p0, p_max);

  // voxels.csv: the octree's geometry (root = the 15.75 m square x [0, 2π)).
  const std::vector<Voxel> voxels = read_voxels(dir + "/voxels.csv");
  ASSERT_FALSE(voxels.empty());
  EXPECT_EQ(voxels.size(), j.value("voxels_decided", 0u));
  const double side = 63 * 0.25;
  std::vector<std::size_t> analysed(p_max + 1, 0);
  std::map<std::tuple<int, long, long, long>, bool> free_at;
  for (const Voxel& v : voxels) {
    ASSERT_GE(v.level, 0);
    ASSERT_LE(v.level, p_max);
    const double s = side / (1 << v.level), t = kTwoPi / (1 << v.level);
    EXPECT_NEAR(v.x2 - v.x1, s, 1e-12);
    EXPECT_NEAR(v.y2 - v.y1, s, 1e-12);
    EXPECT_NEAR(v.t2 - v.t1, t, 1e-12);
    const long i = std::lround(v.x1 / s), jj = std::lround(v.y1 / s), k = std::lround(v.t1 / t);
    EXPECT_NEAR(v.x1, i * s, 1e-9);
    EXPECT_NEAR(v.t1, k * t, 1e-9);
    EXPECT_TRUE(free_at.emplace(std::make_tuple(v.level, i, jj, k), v.free).second)
        << "voxel decided twice";
    if (v.level >= p0) ++analysed[static_cast<std::size_t>(v.level)];
  }
  // Per-level analyses: the rows at levels >= p0 (above p0 the voxels are combined).
  const auto per_level = j["voxels_analysed_per_level"].get<std::vector<std::size_t>>();
  EXPECT_EQ(per_level, analysed);
  std::size_t total = 0;
  for (std::size_t p = 0; p < per_level.size(); ++p) {
    total += per_level[p];
    EXPECT_EQ(j.value("voxels_analysed_level_" + std::to_string(p), 0u), per_level[p]);
  }
  EXPECT_EQ(j.value("voxels_analysed", 0u), total);
  // The free volume re-evaluated: FREE rows none of whose ancestors is a FREE row.
  double volume = 0.0;
  for (const auto& [key, is_free] : free_at) {
    if (!is_free) continue;
    auto [p, i, jj, k] = key;
    bool leaf = true;
    for (int q = p - 1; q >= 0 && leaf; --q) {
      const int sh = p - q;
      const auto a = free_at.find(std::make_tuple(q, i >> sh, jj >> sh, k >> sh));
      leaf = !(a != free_at.end() && a->second);
    }
    if (leaf) volume += std::pow(8.0, -p);
  }
  EXPECT_GT(volume, 0.0);
  EXPECT_NEAR(j.value("free_volume_fraction", -1.0), volume, 1e-12);

  // channel.csv: steps 0..n-1, FREE voxels, V_s holds the start and V_g the goal,
  // consecutive ones share a face.
  const auto channel = read_csv(dir + "/channel.csv", "step,voxel");
  ASSERT_GE(channel.size(), 2u);
  EXPECT_EQ(channel.size(), j.value("channel_voxels", 0u));
  std::vector<Voxel> chain;
  for (std::size_t k = 0; k < channel.size(); ++k) {
    EXPECT_EQ(parse_number(channel[k][0]), static_cast<double>(k));
    const double idx = parse_number(channel[k][1]);
    ASSERT_GE(idx, 0.0);
    ASSERT_LT(idx, static_cast<double>(voxels.size()));
    chain.push_back(voxels[static_cast<std::size_t>(idx)]);
    EXPECT_TRUE(chain.back().free) << "channel step " << k;
  }
  EXPECT_TRUE(holds(chain.front(), 3, 3, 0));
  EXPECT_TRUE(holds(chain.back(), 12.5, 12.5, 1.5));
  for (std::size_t k = 1; k < chain.size(); ++k) {
    const Voxel &a = chain[k - 1], &b = chain[k];
    const double o[3] = {overlap(a.x1, a.x2, b.x1, b.x2), overlap(a.y1, a.y2, b.y1, b.y2),
                         theta_overlap(a, b)};
    int touching = 0, sharing = 0;
    for (double v : o) {
      touching += std::abs(v) < 1e-9;
      sharing += v > 1e-9;
    }
    EXPECT_EQ(touching, 1) << "steps " << k - 1 << ", " << k;
    EXPECT_EQ(sharing, 2) << "steps " << k - 1 << ", " << k;
  }
  // Every path pose lies in a channel voxel.
  const auto path = read_csv(dir + "/path.csv", "x,y,theta,control");
  ASSERT_GE(path.size(), 2u);
  for (const auto& row : path) {
    const double x = parse_number(row[0]), y = parse_number(row[1]), th = parse_number(row[2]);
    EXPECT_TRUE(
        std::any_of(chain.begin(), chain.end(), [&](const Voxel& v) { return holds(v, x, y, th); }))
        << x << " " << y << " " << th;
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/octree.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/path.png"));
}

TEST(CliDacreWright, InvalidStartWritesEmptyVoxelAndChannelFiles) {
  // 12 m x 12 m flat.
  const std::string terrain =
      generate_terrain("dw_step.asc", "plane --slope 0 --ncols 49 --nrows 49 --cellsize 0.25");
  const std::string dir = scratch_file("dw_invalid_out");
  std::filesystem::remove_all(dir);
  // The start's front wheels stand on the map, its rear ones off it: no placement.
  const RunResult r =
      run_talus("baseline dacre-wright --terrain " + quoted(terrain) + " --robot " +
                quoted(six_wheel()) + " --start 0.1,6,0 --goal 6,6,0 --out " + quoted(dir));
  EXPECT_EQ(r.exit_code, 2) << r.err << r.out;
  const nlohmann::json j = parse_json(r.out, "stdout");
  EXPECT_EQ(j.value("status", ""), "start_invalid") << j.dump();
  EXPECT_TRUE(read_voxels(dir + "/voxels.csv").empty());
  EXPECT_TRUE(read_csv(dir + "/channel.csv", "step,voxel").empty());
  EXPECT_FALSE(std::filesystem::exists(dir + "/octree.png"));
}

}  // namespace
}  // namespace talus::cli_test
