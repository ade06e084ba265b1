#pragma once
/// @file
/// CGspace of Eldershaw and Yim 2001 §3.1: the 3-D bitmap over (cg_x, cg_y,
/// cg_θ) of the cells where the vehicle can stand, materialised on demand in
/// blocks (the paper's "fragments").
///
/// Lattice: cell (ix, iy, it) has its centre at (x_min + ix·f, y_min + iy·f)
/// (f = the robot's foot_print, (x_min, y_min) the terrain's south-west node)
/// and heading θ_it = 2π·it / n_θ, n_θ = 1 (no rotation) or ≥ 8. A pose
/// belongs to the cell of the nearest centre and nearest heading slice.
///
/// A cell is evaluated at its centre pose (x, y, θ), body frame u along θ:
/// - MinHeight = max over the under-carriage of land + depth, taken at every
///   terrain node inside the under-carriage rectangle and at every
///   under-carriage grid node (land bilinear there); any of these off the
///   terrain's data → invalid (kOffData);
/// - rule (a) and (b): in each of the four body-frame quadrants (u ≥ 0 or
///   u < 0, v ≥ 0 or v < 0) some terrain node must be a valid footmap node
///   inside some leg's range whose height plus that leg's reach at it exceeds
///   MinHeight. No footmap-valid node in a quadrant's ranges → kNoSupport;
///   footmap-valid nodes there but none reaching → kTooShort.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/eldershaw_yim/footmap.hpp"
#include "talus/kinematic/eldershaw_yim/legged_robot.hpp"

namespace talus {

/// Indices of one CG cell.
struct CgCell {
  int ix = 0;  ///< column (from the west)
  int iy = 0;  ///< row (from the south)
  int it = 0;  ///< heading slice, 0 .. n_θ-1
  friend bool operator==(const CgCell&, const CgCell&) = default;
};

/// State of a CG cell.
enum class CgState : std::uint8_t {
  kUnknown = 0,    ///< not materialised
  kValid = 1,      ///< the vehicle can stand there
  kOffData = 2,    ///< the under-carriage leaves the terrain's data
  kNoSupport = 3,  ///< some quadrant has no valid foot position in any leg's range
  kTooShort = 4,   ///< some quadrant's valid foot positions are all out of reach of MinHeight
  kFeedback = 5,   ///< marked invalid by the foot planner (§3.3, CgSpace::mark_invalid)
};
/// "unknown", "valid", "off_data", "no_support", "too_short", "feedback".
const char* to_string(CgState state);

/// The CG lattice over a terrain (positions and headings of the cells).
class CgLattice {
 public:
  /// Throws InputError unless theta_slices is 1 or ≥ 8 (and ≤ 1024) and the
  /// lattice has at most 2^31 cells.
  CgLattice(const ElevationGrid& grid, double spacing, int theta_slices);
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int ntheta() const { return nt_; }
  double spacing() const { return f_; }
  std::size_t size() const {
    return static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) *
           static_cast<std::size_t>(nt_);
  }
  bool contains(const CgCell& c) const {
    return c.ix >= 0 && c.iy >= 0 && c.it >= 0 && c.ix < nx_ && c.iy < ny_ && c.it < nt_;
  }
  std::size_t index(const CgCell& c) const {
    return (static_cast<std::size_t>(c.it) * static_cast<std::size_t>(ny_) +
            static_cast<std::size_t>(c.iy)) *
               static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(c.ix);
  }
  CgCell cell(std::size_t index) const;
  /// The cell holding `q` (nearest centre, clamped into the lattice; nearest slice).
  CgCell cell_of(const SE2Pose& q) const;
  /// The cell's centre pose (θ in [0, 2π)).
  SE2Pose centre(const CgCell& c) const;
  double heading(int it) const;

 private:
  double x0_ = 0, y0_ = 0, f_ = 1;
  int nx_ = 0, ny_ = 0, nt_ = 1;
};

/// MinHeight at pose `q` (the file comment): the lowest height of the body's
/// zero plane [m] that keeps the under-carriage off the ground; nullopt when
/// the under-carriage leaves the terrain's data.
std::optional<double> cg_min_height(const Footmap& footmap, const LeggedRobot& robot,
                                    const SE2Pose& q);

/// The CG-cell rule at one pose (the file comment), without caching.
CgState evaluate_cg_pose(const Footmap& footmap, const LeggedRobot& robot, const SE2Pose& q);

/// One heading slice `it` of the lattice evaluated cell by cell (no cache):
/// the CGmap of the paper's figures 4 and 6, indexed iy * nx + ix. Throws
/// InputError for a slice outside 0 .. n_θ-1.
std::vector<CgState> evaluate_cg_slice(const Footmap& footmap, const LeggedRobot& robot,
                                       const CgLattice& lattice, int it);

/// CGspace of one robot on one terrain: a CgLattice whose cells are
/// evaluated a block at a time (block_side × block_side cells in x, y and
/// every heading) the first time any of them is asked for, and kept. Not
/// thread-safe (one per query); concurrent local-planner calls each use an
/// overlay (below) on one shared CgSpace that is left unchanged meanwhile.
class CgSpace {
 public:
  /// `footmap` (and its terrain) must outlive this. Throws InputError as
  /// CgLattice, or for block_side < 1.
  CgSpace(const Footmap& footmap, const LeggedRobot& robot, int theta_slices, int block_side = 16);
  /// Selects the overlay constructor below (not a copy: an overlay refers to its base).
  struct OverlayOn {};
  /// An overlay on `base`: reads base's blocks and marks, materialises the
  /// blocks base lacks itself, and counts only those (cells_materialised() is
  /// then this overlay's own evaluations, whatever other overlays do). `base`
  /// must outlive the overlay and not change while it is used; several
  /// overlays on one base may be used from different threads.
  CgSpace(OverlayOn, const CgSpace& base);
  /// Not copyable: a copy would be neither an overlay nor independent of the
  /// overlays that refer to the original.
  CgSpace(const CgSpace&) = delete;
  CgSpace& operator=(const CgSpace&) = delete;
  /// Moves `overlay`'s blocks that this lacks into this (their cells and time
  /// counted here); `overlay` must be an overlay on this. Blocks are a pure
  /// function of the cell, so the result does not depend on the order of
  /// absorption.
  void absorb(CgSpace&& overlay);
  /// The keys of the blocks this space evaluated itself (ascending).
  std::vector<std::size_t> block_keys() const;
  /// Blocks another process evaluated (keys as block_keys()): counted now
  /// unless known already, and evaluated here only if asked for, then
  /// without counting them again. Keeps the counters of ranks that share
  /// the local-planner calls equal.
  void count_blocks(const std::vector<std::size_t>& keys);

  const CgLattice& lattice() const { return lattice_; }
  const Footmap& footmap() const { return *footmap_; }
  /// The state of `c` (materialising its block); kOffData outside the lattice.
  CgState state(const CgCell& c);
  bool valid(const CgCell& c) { return state(c) == CgState::kValid; }
  /// From now on `c` is kFeedback (invalid), whatever the rule says.
  void mark_invalid(const CgCell& c);
  /// The state if its block is materialised, else kUnknown.
  CgState peek(const CgCell& c) const;
  /// Cells evaluated so far (whole blocks, clipped to the lattice).
  std::size_t cells_materialised() const { return cells_; }
  std::size_t blocks_materialised() const { return blocks_.size() + foreign_.size(); }
  /// Wall-clock time spent evaluating cells [s].
  double seconds() const { return seconds_; }

 private:
  const Footmap* footmap_;
  const LeggedRobot* robot_;
  const CgSpace* base_ = nullptr;  ///< set in an overlay
  CgLattice lattice_;
  int block_ = 16, bx_ = 1;
  std::unordered_map<std::size_t, std::vector<CgState>> blocks_;
  std::unordered_set<std::size_t> marked_;
  std::unordered_set<std::size_t> foreign_;  ///< counted, evaluated elsewhere, not here yet
  std::size_t block_cells(std::size_t key) const;
  std::size_t cells_ = 0;
  double seconds_ = 0.0;
};

}  // namespace talus
