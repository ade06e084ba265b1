// Notebook 08 — the second kinematic baseline: the free-space structuring of
// Dacre-Wright and Siméon (ICRA 1993) through the baseline registry. Boxes of
// configuration space (x, y, θ) proven admissible from the elevation map, an
// octree of them, A* over the largest FREE voxels, and the checks that what it
// returns is what it claims.
//
//   build/notebooks_cpp/08_dacre_wright_baseline [--quick] [--out DIR] [--data DIR]
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "notebook.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/core/terrain_generators.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/kinematic/dacre_wright/dacre_wright_baseline.hpp"
#include "talus/report/dacre_wright_outputs.hpp"

using namespace talus;
using namespace talus::notebooks;

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// A uniform draw in [lo, hi) from the top 53 bits (the same on every platform).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// θ in [0, 2π).
double wrap_2pi(double theta) {
  const double t = std::fmod(theta, kTwoPi);
  return t < 0.0 ? t + kTwoPi : t;
}

/// Whether `box` (θ in [0, 2π]) holds q with its heading taken modulo 2π.
bool holds(const CsBox& box, const SE2Pose& q) {
  const double t = wrap_2pi(q.theta);
  return box.contains({q.x, q.y, t}) || box.contains({q.x, q.y, t + kTwoPi});
}

/// Two paths equal bit for bit.
bool identical(const std::vector<SE2Pose>& a, const std::vector<SE2Pose>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double u[3] = {a[k].x, a[k].y, a[k].theta}, v[3] = {b[k].x, b[k].y, b[k].theta};
    if (std::memcmp(u, v, sizeof u) != 0) return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  return run([&] {
    Notebook nb(argc, argv, "08_dacre_wright_baseline", "08 · The Dacre-Wright–Siméon baseline");
    const BaselineRegistry& registry = BaselineRegistry::builtin();

    nb.section("The idea: prove whole boxes of configurations admissible");
    nb.say(
        "Notebook 06's planner (Haït et al. 2002) places the robot at every configuration it "
        "visits. Dacre-Wright and Siméon (ICRA 1993) take the other road: they structure the "
        "free space once. A configuration q = (x, y, θ) of a robot on sprung wheels is "
        "*admissible* when its placement on the terrain keeps every spring within ±L_max and "
        "its roll and pitch inside the stability box (their Definition 2). Instead of testing "
        "points, they bound what the elevation map can do under the wheels over a whole box "
        "[x₁, x₂] × [y₁, y₂] × [θ₁, θ₂]: the regions the wheels sweep, the least-squares "
        "plane of the ground there, how far the ground departs from it, and from these the "
        "largest roll, pitch and spring travel any configuration of the box can have. If "
        "those bounds stay inside the limits, the box is FREE: every configuration in it is "
        "admissible (their Proposition 1). Otherwise it is MIXED (the analysis never proves "
        "a box wholly inadmissible).");
    nb.say(
        "The boxes are the voxels of an octree over (x, y, θ): the root is the map's square "
        "times a full turn of heading (θ periodic), a voxel of level p has side S / 2^p and "
        "2π / 2^p. Voxels of a reference level p0 (side near the robot's wheelbase) are "
        "analysed, MIXED ones split down to p_max, and a voxel above p0 is FREE when its "
        "eight sons are. The search is A* over the *largest* FREE voxels, from the one "
        "holding the start to the one holding the goal, neighbours sharing a face; the "
        "octree is built lazily, only where the search looks. The voxels it passes form a "
        "channel, and the path crosses it straight from face to face (voxels are convex, "
        "so each piece stays in one FREE voxel).");

    nb.section("A query through the registry");
    // The map of the dacre-wright-octree experiment: a seeded 64 × 64 fractal,
    // 0.25 m cells, 0.6 m peak to peak (the paper's map is 64 × 64 too).
    FractalTerrainOptions f;
    f.shape = {64, 64, 0.25, 0.0, 0.0};
    f.height_scale = 0.6;
    f.seed = 1993;
    const ElevationGrid grid = generate_fractal_terrain(f);
    const RuledTerrain ruled(grid);
    const double side = std::max(grid.x_max() - grid.x_min(), grid.y_max() - grid.y_min());
    const SE2Pose start{3.0, 3.0, 0.0}, goal{12.5, 12.5, 1.5};
    const int p_max = nb.quick() ? 5 : 6;
    const BaselineOptions options{{"robot", nb.data("robots/dacre_wright_six_wheel.yaml")},
                                  {"max-level", std::to_string(p_max)}};
    const auto planner = registry.make("dacre-wright", options);
    nb.say(
        "The terrain: a 64 × 64 fractal elevation map (seed 1993, 0.25 m cells, 0.6 m peak "
        "to peak), so the root voxel is " +
        num("%.2f", side) +
        " m on a side. The robot: the six-wheel rover "
        "`data/robots/dacre_wright_six_wheel.yaml` (wheels at ±0.6 m and 0 along, ±0.45 m "
        "across; L_max = 0.15 m, |roll| < 0.35 rad, |pitch| < 0.40 rad; the paper gives no "
        "dimensions). The octree goes down to p_max = " +
        std::to_string(p_max) + " (voxels of " + num("%.2f", side / std::pow(2.0, p_max)) +
        " m and " + num("%.1f", 360.0 / std::pow(2.0, p_max)) +
        "°). The query: from (3, 3) heading east to (12.5, 12.5) heading 1.5 rad, planned "
        "with `registry.make(\"dacre-wright\", {robot, max-level})`, as "
        "`talus baseline dacre-wright` does.");
    const BaselineResult result = planner->plan(ruled, start, goal);
    nb.say("Its result: `" + result.brief_report() + "`");
    if (!result.found()) throw Error("the Dacre-Wright planner found no path: " + result.message);

    // The full result (voxels, channel) of the same query, for the figures;
    // the registry's planner is a DacreWrightBaseline.
    const auto* dw = dynamic_cast<const DacreWrightBaseline*>(planner.get());
    if (dw == nullptr) throw Error("the registry's \"dacre-wright\" is not a DacreWrightBaseline");
    const DacreWrightResult full = dw->plan_full(ruled, start, goal);

    Table levels({"level p", "voxel side [m]", "Δθ [°]", "voxels analysed", "FREE leaves"});
    std::vector<std::size_t> free_per_level(full.analyses_per_level.size(), 0);
    for (std::size_t k : full.free_leaf_indices)
      ++free_per_level[static_cast<std::size_t>(full.voxels[k].key.level)];
    for (std::size_t p = 0; p < full.analyses_per_level.size(); ++p) {
      levels.row({std::to_string(p) + (static_cast<int>(p) == full.reference_level ? " (p0)" : ""),
                  num("%.3g", side / std::pow(2.0, static_cast<double>(p))),
                  num("%.3g", 360.0 / std::pow(2.0, static_cast<double>(p))),
                  std::to_string(full.analyses_per_level[p]), std::to_string(free_per_level[p])});
    }
    nb.table(levels);
    const double full_analyses = std::pow(8.0, p_max);
    nb.say("The search analysed " + std::to_string(full.voxels_analysed()) +
           " boxes in all and expanded " + std::to_string(full.expansions) +
           " voxels; the finest level alone has " + num("%.0f", full_analyses) +
           " voxels, so the lazy octree built only a small part of the whole. The channel "
           "has " +
           std::to_string(full.channel.size()) + " voxels and the path " +
           std::to_string(full.path.size()) + " poses over " + num("%.2f", full.length_m) +
           " m (the straight line is " + num("%.2f", (goal.position() - start.position()).norm()) +
           " m).");

    nb.section("The octree, the channel and the path");
    OctreeSliceFigure slices = octree_slice_figure(full);
    {
      // Four headings spread over those the path takes (in [0, 2π)).
      double lo = full.path.front().theta, hi = lo;
      for (const SE2Pose& q : full.path) lo = std::min(lo, q.theta), hi = std::max(hi, q.theta);
      const double step = hi - lo > 1e-6 ? (hi - lo) / 3.0 : 0.5 * std::numbers::pi;
      for (int k = 0; k < 4; ++k) slices.thetas.push_back(wrap_2pi(lo + k * step));
    }
    slices.x_min = grid.x_min(), slices.x_max = grid.x_min() + side;
    slices.y_min = grid.y_min(), slices.y_max = grid.y_min() + side;
    slices.title = "FREE voxels at four headings of the path, the channel and the path";
    render_octree_slices(nb.dir(), "octree", slices);
    nb.say(
        "Each panel cuts the octree at one heading θ: the filled squares are the FREE voxels "
        "whose θ interval holds it (large where the ground is smooth, small near the "
        "rough parts, absent where nothing was proven or nothing was built), the outlines are "
        "the channel's voxels (all θ) and the line is the path. Only the part of the octree "
        "the search needed was built, so the FREE voxels gather along the channel "
        "(the paper's figures 4 and 5 show the same kind of slices).");
    nb.figure("FREE voxels at four headings, the channel (outlined) and the path", "octree.png");

    const BPatch surface = BPatch::interpolate(grid);
    std::vector<Vec2> path_points, centres;
    for (const SE2Pose& q : result.path) path_points.push_back(q.position());
    for (const CsBox& b : full.channel_boxes)
      centres.push_back({0.5 * (b.x1 + b.x2), 0.5 * (b.y1 + b.y2)});
    nb.say(
        "Seen from above, the path turns at the voxel faces and often moves sideways: its "
        "heading only has to stay inside the channel's θ intervals, not along the motion. "
        "The method proves where the robot may *stand*, not how a car-like robot could "
        "drive between those configurations; the paper meant the channel to guide a finer "
        "planner (the dacre-wright-octree experiment restricts notebook 06's search to it).");
    nb.figure("The path over the terrain",
              nb.map("path", "Dacre-Wright–Siméon: channel voxel centres and the path", surface,
                     {{"channel voxel centres", centres, "points pt 7 ps 0.6 lc rgb '#2c7fb8'"},
                      {"path: " + num("%.2f", result.length_m) + " m", path_points,
                       "lines lw 3 lc rgb '#e6550d'"}}));

    nb.section("Checking what it claims");
    nb.say(
        "The planner's `validity()` is the placement test itself: it places the robot at one "
        "configuration (place_robot) and applies Definition 2. It shares nothing with the box "
        "analysis but the robot and the map, so it can confirm or refute the bounds.");
    const ValidityFunction valid = planner->validity(ruled);
    bool all_valid = true;
    for (const SE2Pose& q : result.path) all_valid = all_valid && valid(q).valid;
    nb.check(all_valid, "every one of the path's " + std::to_string(result.path.size()) +
                            " poses passes the planner's own validity check");
    const SE2Pose& first = result.path.front();
    const SE2Pose& last = result.path.back();
    nb.check(first.x == start.x && first.y == start.y && first.theta == start.theta,
             "the path starts exactly at the start configuration");
    nb.check((last.position() - goal.position()).norm() <= 1e-9 &&
                 std::abs(wrap_angle(last.theta - goal.theta)) <= 1e-9,
             "it ends at the goal: position within 1e-9 m, heading within 1e-9 rad (modulo "
             "2π; the path's θ is continuous, not wrapped)");
    bool in_channel = true;
    for (const SE2Pose& q : full.path) {
      bool inside = false;
      for (const CsBox& b : full.channel_boxes) inside = inside || holds(b, q);
      in_channel = in_channel && inside;
    }
    nb.check(in_channel, "every pose lies in one of the channel's " +
                             std::to_string(full.channel_boxes.size()) + " voxels");

    // Proposition 1 by sampling: configurations drawn uniformly in the FREE
    // leaves (volume-weighted, seeded), each put to the validity check.
    std::mt19937_64 rng(1993);
    std::vector<double> cumulative;
    double volume = 0.0;
    for (std::size_t k : full.free_leaf_indices) {
      const CsBox& b = full.voxels[k].box;
      cumulative.push_back(volume += (b.x2 - b.x1) * (b.y2 - b.y1) * (b.theta2 - b.theta1));
    }
    const int samples = nb.quick() ? 400 : 4000;
    int admissible = 0;
    for (int s = 0; s < samples; ++s) {
      const double pick = uniform(rng, 0.0, volume);
      const auto idx = static_cast<std::size_t>(
          std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
      const CsBox& b =
          full.voxels[full.free_leaf_indices[std::min(idx, cumulative.size() - 1)]].box;
      const SE2Pose q{uniform(rng, b.x1, b.x2), uniform(rng, b.y1, b.y2),
                      uniform(rng, b.theta1, b.theta2)};
      admissible += valid(q).valid ? 1 : 0;
    }
    // And the corners and centre of the start's voxel V_s (a closed box).
    const CsBox& vs = full.channel_boxes.front();
    int corner_valid = 0;
    for (int c = 0; c < 8; ++c) {
      const SE2Pose q{(c & 1) ? vs.x2 : vs.x1, (c & 2) ? vs.y2 : vs.y1,
                      (c & 4) ? vs.theta2 : vs.theta1};
      corner_valid += valid(q).valid ? 1 : 0;
    }
    corner_valid +=
        valid({0.5 * (vs.x1 + vs.x2), 0.5 * (vs.y1 + vs.y2), 0.5 * (vs.theta1 + vs.theta2)}).valid
            ? 1
            : 0;
    nb.check(admissible == samples, std::to_string(admissible) + " of " + std::to_string(samples) +
                                        " configurations drawn at random (seed 1993) in the " +
                                        std::to_string(full.free_leaf_indices.size()) +
                                        " FREE voxels pass the validity check (Proposition 1)");
    nb.check(corner_valid == 9, "the 8 corners and the centre of the start's voxel V_s (" +
                                    num("%.3g", vs.x2 - vs.x1) + " m × " +
                                    num("%.3g", vs.y2 - vs.y1) + " m × " +
                                    num("%.3g", vs.theta2 - vs.theta1) + " rad) are valid");

    // Determinism: a fresh planner from the registry, the same query.
    const auto again = registry.make("dacre-wright", options);
    const BaselineResult rerun = again->plan(ruled, start, goal);
    nb.check(rerun.found() && identical(rerun.path, result.path) &&
                 rerun.counters == result.counters && identical(full.path, result.path),
             "a rerun with a fresh planner gives the same path bit for bit and the same "
             "counters, and plan_full's path is the registry's");
    return nb.finish();
  });
}
