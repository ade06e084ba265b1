#pragma once
/// @file
/// The foot-level planner of Eldershaw and Yim 2001 §3.2: a depth-first search
/// over moves along a given CG path (6-connected CG cells) that yields the
/// step-by-step sequence of CG positions and foot locations.
///
/// A stance at CG pose q is feasible when every foot in contact stands on a
/// footmap-valid terrain node inside its leg's range (body frame at q), no
/// two feet share a node, each contact foot's height plus its leg's reach
/// there exceeds MinHeight(q) (cg_min_height), and it is statically stable by
/// the quadrant rule: each of the four body quadrants holds a contact foot.
///
/// Moves, in the paper's order of precedence (the search tries them in this
/// order and backtracks):
/// 1. advance the CG to the next path cell with every foot in place;
/// 2. when every contact foot stays feasible at the next cell but a quadrant
///    would be empty there, move a free foot into that quadrant;
/// 3. move a free foot that would become infeasible at the next cell;
/// 4. lift (and keep up) such a foot when it has nowhere feasible to go;
/// 5. when a foot that is not free would become infeasible, move a free foot
///    into its quadrant (at the next cell) to free it.
/// A foot is free when lifting it leaves the current stance stable. New
/// placements of a foot are ordered by how many of the following path cells
/// (up to `lookahead`) they stay feasible for, most first (the paper: "if
/// motion of the CG continued in its current direction"; we follow the
/// path's next cells), ties to the lower node index; at most
/// `placements_per_leg` of them are tried, and only placements that are
/// still feasible at the next path cell (others cannot help the next CG
/// move), so a foot "about to become infeasible" is lifted (move 4) when no
/// node feasible now and at the next cell is free for it.
///
/// Choices left open by the paper: feet stand on terrain nodes; the initial
/// stance is chosen greedily (a foot per quadrant first, by the same
/// ordering, then every other leg); at most `max_foot_moves` foot moves
/// between two CG advances; stances already visited at the same path index
/// are not searched again; the budget counts search nodes.
#include <cstddef>
#include <string>
#include <vector>

#include "talus/kinematic/eldershaw_yim/cg_space.hpp"

namespace talus {

/// Options of plan_footsteps.
struct FootPlannerOptions {
  std::size_t budget = 200000;         ///< search nodes (>= 1)
  std::size_t lookahead = 16;          ///< path cells scored ahead (>= 1)
  std::size_t placements_per_leg = 6;  ///< new positions tried per foot move (>= 1)
  std::size_t max_foot_moves = 16;     ///< foot moves between CG advances (>= 1)
  /// Throws InputError naming the field.
  void validate() const;
};

/// Kinds of step.
enum class FootMove {
  kStart,      ///< the initial stance
  kAdvanceCg,  ///< move 1: the CG to the next cell, feet in place
  kMoveFoot,   ///< moves 2, 3, 5: one foot to a new node
  kLiftFoot,   ///< move 4: one foot up
};
/// "start", "advance_cg", "move_foot", "lift_foot".
const char* to_string(FootMove move);

/// One foot of a stance.
struct FootState {
  bool contact = false;
  std::size_t i = 0, j = 0;  ///< terrain node (valid when contact, else the last one)
};

/// One step of the plan: the CG pose after it and every foot.
struct FootStep {
  FootMove move = FootMove::kStart;
  std::size_t path_index = 0;  ///< index into the CG path
  SE2Pose cg;                  ///< centre of that CG cell
  int leg = -1;                ///< the foot moved or lifted (-1 for start / advance)
  std::vector<FootState> feet;
};

/// Outcome of plan_footsteps.
enum class FootPlanStatus {
  kFound,           ///< every CG cell of the path reached
  kNoStance,        ///< no feasible initial stance
  kFailed,          ///< the search was exhausted
  kBudgetExceeded,  ///< FootPlannerOptions::budget nodes searched
};
/// "found", "no_stance", "failed", "budget_exceeded".
const char* to_string(FootPlanStatus status);

struct FootPlan {
  FootPlanStatus status = FootPlanStatus::kFailed;
  std::string message;
  std::vector<FootStep> steps;     ///< start … last CG cell (the deepest reached if not found)
  std::size_t nodes = 0;           ///< search nodes expanded
  std::size_t furthest_index = 0;  ///< furthest path index reached
  double seconds = 0.0;
  bool found() const { return status == FootPlanStatus::kFound; }
};

/// World position (x, y) and height z of terrain node (i, j).
Vec3 foot_position(const Footmap& footmap, const FootState& foot);

/// The search along `cells` (6-connected, as plan_eldershaw_yim returns).
/// `prefix`: steps already taken along these cells (an earlier plan's steps
/// up to some path index, over the same leading cells); the search then
/// starts from the last one's stance and never backtracks into the prefix,
/// and the result's steps begin with it. InputError if that stance is not
/// stable at its cell of `cells`. Empty: from an initial stance at cell 0.
FootPlan plan_footsteps(const Footmap& footmap, const LeggedRobot& robot, const CgLattice& lattice,
                        const std::vector<CgCell>& cells, const FootPlannerOptions& options = {},
                        const std::vector<FootStep>& prefix = {});

}  // namespace talus
