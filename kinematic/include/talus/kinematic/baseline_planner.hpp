#pragma once
/// @file
/// The interface every kinematic baseline planner implements (Haït–Siméon–Taïx,
/// Dacre-Wright–Siméon, Eldershaw–Yim, Iagnemma–Shimoda–Shiller):
/// one query plan(terrain, start, goal) → BaselineResult, and the planner's own
/// validity check of a configuration on a terrain, so that a shared
/// conformance test (tests/kinematic/test_baseline_conformance.cpp) can hold every
/// baseline to the same contract.
///
/// Error policy (core/error.hpp): a malformed query (a non-finite pose, a start
/// or goal off the map or on NODATA) throws InputError; the expected outcomes
/// of a query (no path, an invalid start or goal configuration, the work
/// budget spent) are statuses of the result.
///
/// Determinism: a planner's result depends only on its options, the terrain
/// and the query, never on the clock or on earlier queries (every baseline's
/// budget counts work, not time), so two runs give bit-identical paths.
#include <cstddef>
#include <map>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/configuration_space.hpp"

namespace talus {

/// Termination of a baseline query.
enum class BaselineStatus {
  kFound,           ///< a path from the start to the goal
  kNoPath,          ///< the search space was exhausted without reaching the goal
  kStartInvalid,    ///< the start configuration fails the planner's validity check
  kGoalInvalid,     ///< the goal configuration fails the planner's validity check
  kBudgetExceeded,  ///< the planner's work budget ran out before the goal was reached
};
/// "found", "no_path", "start_invalid", "goal_invalid", "budget_exceeded".
std::string to_string(BaselineStatus status);

/// Result and diagnostics of one query. The defaults mark a result no planner
/// filled in (status kNoPath, message "BaselinePlanner::plan was not called").
struct BaselineResult {
  BaselineStatus status = BaselineStatus::kNoPath;
  std::string message = "BaselinePlanner::plan was not called";  ///< human-readable outcome
  /// The path as configurations (x [m], y [m], θ [rad]), start first, goal
  /// last (within the planner's goal_tolerance()); empty unless kFound. Each
  /// pose passed the planner's validity check; consecutive poses are at most
  /// the planner's check spacing apart.
  std::vector<SE2Pose> path;
  /// Empty, or one label per pose of `path`: the motion that reached it, in
  /// the planner's own words (e.g. "forward-left"), "none" on the first.
  std::vector<std::string> motions;
  double length_m = 0.0;               ///< length driven along `path` [m]; 0 unless kFound
  double preprocessing_seconds = 0.0;  ///< wall-clock time of the per-terrain preparation [s]
  double search_seconds = 0.0;  ///< wall-clock time of the query after it (with smoothing) [s]
  /// Named work counters of the planner (snake_case keys, e.g. "nodes_created", "placements").
  std::map<std::string, std::size_t> counters;
  /// Named parts of search_seconds [s] (snake_case stage names, e.g. "smoothing").
  std::map<std::string, double> stage_seconds;
  /// Named yes/no facts about the result (snake_case, e.g. "connected_to_goal").
  std::map<std::string, bool> flags;

  bool found() const { return status == BaselineStatus::kFound; }
  /// One line: status, length, path size, times and counters, then the message.
  std::string brief_report() const;
};

/// The value of one setting of a configured planner (see BaselinePlanner::settings).
using BaselineSettingValue = std::variant<bool, long long, double, std::string>;

/// One resolved setting of a configured planner, for reports: `section`
/// groups settings ("options" for the planner's options, "robot" for its
/// robot model, ...), `key` is snake_case.
struct BaselineSetting {
  std::string section;
  std::string key;
  BaselineSettingValue value;
};

/// How close the last pose of a found path comes to the goal: its position
/// within `position` and its heading within `heading` (modulo 2π). The
/// defaults are a quarter-metre cell and one of 32 heading cells, the
/// coarsest resolution of the search-based baselines; a planner that does not
/// steer to the goal's heading says so with heading = π (any heading).
struct GoalTolerance {
  double position = 0.25;                      ///< [m] (>= 0)
  double heading = 2 * std::numbers::pi / 32;  ///< [rad] in [0, π]
};

/// A kinematic baseline planner, configured once (its options, its robot) and
/// queried any number of times. Implementations supply name(), settings(),
/// validity() and solve(); plan() checks the query and calls solve(). A
/// planner is immutable after construction: plan() and validity() are const
/// and may be called from several threads at once.
class BaselinePlanner {
 public:
  virtual ~BaselinePlanner() = default;

  /// Registry name, e.g. "hait".
  virtual std::string name() const = 0;

  /// The resolved settings (defaults filled in), in a stable order.
  virtual std::vector<BaselineSetting> settings() const = 0;

  /// The planner's own validity check on `terrain`, with whatever per-terrain
  /// preprocessing it needs done once here; `terrain` must outlive the
  /// returned function. A pose off the terrain's data is not valid.
  virtual ValidityFunction validity(const RuledTerrain& terrain) const = 0;

  /// How close a found path's last pose comes to the goal (GoalTolerance's
  /// defaults unless the planner says otherwise); the conformance suite holds
  /// each planner to its own.
  virtual GoalTolerance goal_tolerance() const { return {}; }

  /// Plans from `start` to `goal` on `terrain`. Throws InputError when a pose
  /// is not finite or its position is off the map or on NODATA; every other
  /// outcome is a status of the result.
  BaselineResult plan(const RuledTerrain& terrain, const SE2Pose& start, const SE2Pose& goal) const;

 protected:
  /// The query itself, called by plan() with finite poses on the terrain's data.
  virtual BaselineResult solve(const RuledTerrain& terrain, const SE2Pose& start,
                               const SE2Pose& goal) const = 0;
};

}  // namespace talus
