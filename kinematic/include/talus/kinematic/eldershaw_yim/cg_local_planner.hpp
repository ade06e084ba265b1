#pragma once
/// @file
/// The local planner of Eldershaw and Yim 2001 §3.1: A* over the CGspace
/// bitmap between two cells, on a block slightly larger in x and y than the
/// two cells' bounding box and always the full θ range, with 6-adjacency
/// (one unit step along one axis per move) and θ wrapping at 2π.
///
/// Choices the paper leaves open: a step costs f (the lattice spacing) in x or
/// y and ρ·2π/n_θ in θ (ρ = heading_weight [m/rad]); the heuristic is the
/// matching L1 distance f(|Δix| + |Δiy|) + ρ·(periodic Δθ), which is exact
/// on an empty map, so A* is optimal; "slightly larger" is a margin of
/// max(margin, ⌈margin_fraction · larger side⌉) cells on each side, clipped
/// to the lattice; ties in the queue go to the smaller cost-to-go, then to the
/// smaller cell index (deterministic).
#include <cstddef>
#include <vector>

#include "talus/kinematic/eldershaw_yim/cg_space.hpp"

namespace talus {

/// Options of one local-planner call.
struct CgLocalPlannerOptions {
  int margin = 4;                 ///< least extra cells around the bounding box (>= 0)
  double margin_fraction = 0.25;  ///< extra cells as a fraction of the box's larger side (>= 0)
  double heading_weight = 1.0;    ///< ρ [m/rad] (> 0)
  bool whole_lattice = false;     ///< search the whole lattice (the direct mode)
  /// Throws InputError naming the field.
  void validate() const;
};

/// Outcome of one call.
struct CgLocalPath {
  bool found = false;
  bool budget_exceeded = false;  ///< stopped because the work budget ran out
  std::vector<CgCell> cells;     ///< from → to (inclusive) when found
  double cost = 0.0;             ///< [m] in the metric above
  std::size_t expansions = 0;
};

/// A* from `from` to `to` in `space`. `work` is the caller's running work
/// count (cell evaluations + expansions), incremented by this call's
/// expansions; the search stops with budget_exceeded once
/// space.cells_materialised() + work > budget.
/// Throws InputError when the block's search arrays exceed the memory budget
/// (memory_budget.hpp).
CgLocalPath cg_local_plan(CgSpace& space, const CgCell& from, const CgCell& to,
                          const CgLocalPlannerOptions& options, std::size_t& work,
                          std::size_t budget);

}  // namespace talus
