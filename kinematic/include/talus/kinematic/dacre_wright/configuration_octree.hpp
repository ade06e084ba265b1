#pragma once
/// @file
/// The octree of Dacre-Wright and Siméon 1993 §4 over configuration space
/// (x, y, θ): the root is the square [x_min, x_min + S] × [y_min, y_min + S] ×
/// [0, 2π) with S the larger side of the map, θ periodic; a voxel of level p
/// is one of the 8^p boxes of side S / 2^p (and 2π / 2^p in θ) and is FREE
/// (analyse_box says so: every configuration in it is admissible) or MIXED
/// (no FULL voxels, footnote 7).
///
/// Construction (§4.2): voxels of the reference level p0 are analysed, MIXED
/// ones are refined top-down to p_max; a voxel of a level p < p0 is FREE iff
/// its eight sons are (bottom-up). Everything is lazy: a voxel is analysed the
/// first time the search (or build_full) needs it, then cached, so the
/// incremental search of §4.3 builds only the part of the octree it visits.
///
/// The decomposition is canonical: the FREE leaves are the FREE voxels whose
/// ancestors are all MIXED. Not thread-safe (the cache is the query's
/// workspace); results depend only on the inputs.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/dacre_wright/region_admissibility.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {

/// A voxel: level p and indices (i, j, k) in [0, 2^p) along x, y, θ.
struct VoxelKey {
  int level = 0;
  std::uint32_t i = 0, j = 0, k = 0;
  friend bool operator==(const VoxelKey&, const VoxelKey&) = default;
  /// A unique integer (level in the top bits), for maps and tie-breaking.
  std::uint64_t code() const {
    return (static_cast<std::uint64_t>(level) << 60) | (static_cast<std::uint64_t>(i) << 40) |
           (static_cast<std::uint64_t>(j) << 20) | k;
  }
};

/// State of a voxel.
enum class VoxelStatus : std::uint8_t {
  kUnknown = 0,  ///< not yet analysed
  kFree = 1,     ///< inside the admissible set ACS
  kMixed = 2,    ///< not proven admissible
};
/// "unknown", "FREE", "MIXED".
const char* to_string(VoxelStatus status);

/// Options of the octree.
struct OctreeOptions {
  int max_level = 6;             ///< p_max, the finest level, 1..8
  int reference_level = -1;      ///< p0 in 0..max_level; −1 = the level whose voxel side is
                                 ///< nearest (in ratio) the robot's wheelbase (the paper's advice)
  std::size_t budget = 1000000;  ///< most voxel analyses before budget_exhausted() (>= 1)
  BoxAnalysisOptions analysis;   ///< of each voxel's analysis
  /// Throws InputError naming the field.
  void validate() const;
};

/// One voxel whose state was decided, in the order of decision: analysed by
/// analyse_box (levels >= p0) or, above p0, combined from its eight sons.
struct AnalysedVoxel {
  VoxelKey key;
  VoxelStatus status = VoxelStatus::kUnknown;
  bool from_sons = false;  ///< decided bottom-up from the sons, not analysed
};

/// The lazily built octree of one robot on one terrain.
class ConfigurationOctree {
 public:
  /// `robot` must be valid and symmetric (require_symmetric_wheels); the
  /// references must outlive the octree. Throws InputError otherwise.
  ConfigurationOctree(const WheeledRobot& robot, const RuledTerrain& terrain,
                      const OctreeOptions& options = {});

  int max_level() const { return max_level_; }
  int reference_level() const { return p0_; }
  /// The voxel's box; θ in [2π k / 2^p, 2π (k + 1) / 2^p].
  CsBox box(const VoxelKey& v) const;
  /// The voxel of `level` holding q (θ taken modulo 2π); nullopt if (x, y) is
  /// outside the root square.
  std::optional<VoxelKey> locate(const SE2Pose& q, int level) const;

  /// The cached state of v: kUnknown if it was never decided (no analysis).
  VoxelStatus cached(const VoxelKey& v) const {
    return cache_[static_cast<std::size_t>(v.level)][index(v)];
  }
  /// FREE or MIXED, analysing (or, above p0, combining the sons) as needed.
  /// Once the budget is spent, unanalysed voxels are MIXED (conservative).
  VoxelStatus state(const VoxelKey& v);
  /// The largest FREE voxel holding q (topmost FREE on its root path), or
  /// nullopt if none down to p_max.
  std::optional<VoxelKey> largest_free_containing(const SE2Pose& q);
  /// §4.3: every largest FREE voxel sharing a face (part of one) with the FREE
  /// leaf v, over the 6 face directions with θ wrap-around; sorted by code(),
  /// no duplicates, v itself excluded.
  std::vector<VoxelKey> free_neighbours(const VoxelKey& v);
  /// The father of v (level − 1).
  static VoxelKey father(const VoxelKey& v);

  /// §4.2: every voxel of p0, MIXED ones refined to p_max, levels above p0 combined.
  void build_full();
  /// The FREE leaves of what has been built (complete after build_full()).
  std::vector<VoxelKey> free_leaves();
  /// Volume of the FREE leaves over the root's volume, in [0, 1] (after build_full()).
  double free_volume_fraction();

  bool budget_exhausted() const { return exhausted_; }
  /// analyse_box calls so far (what the budget counts).
  std::size_t analyses() const { return analyses_; }
  /// analyse_box calls per level (index = level).
  const std::vector<std::size_t>& analyses_per_level() const { return per_level_; }
  /// Every decided voxel (analysed or combined from its sons), in order.
  const std::vector<AnalysedVoxel>& decided() const { return decided_; }

 private:
  std::size_t index(const VoxelKey& v) const;
  void refine(const VoxelKey& v);
  void collect_adjacent(const VoxelKey& n, int axis, int side, std::vector<VoxelKey>& out);
  void leaves_under(const VoxelKey& v, std::vector<VoxelKey>& out);

  const WheeledRobot& robot_;
  const RuledTerrain& terrain_;
  ElevationSums sums_;  ///< the average plane's integral images, built once
  OctreeOptions options_;
  int max_level_ = 6;
  int p0_ = 3;
  double x0_ = 0.0, y0_ = 0.0, side_ = 1.0;
  std::vector<std::vector<VoxelStatus>> cache_;  ///< per level, 8^p entries
  std::vector<std::size_t> per_level_;
  std::vector<AnalysedVoxel> decided_;
  std::size_t analyses_ = 0;
  bool exhausted_ = false;
};

}  // namespace talus
