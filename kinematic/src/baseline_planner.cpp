#include "talus/kinematic/baseline_planner.hpp"

#include <cmath>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {
namespace {

void require_on_data(const RuledTerrain& terrain, const SE2Pose& q, const std::string& planner,
                     const char* what) {
  if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.theta)) {
    throw InputError(planner + ": the " + what + " configuration is not finite");
  }
  if (!terrain.has_data(q.position())) {
    std::ostringstream msg;
    msg << planner << ": the " << what << " position (" << q.x << ", " << q.y << ") is "
        << (terrain.contains(q.position()) ? "on NODATA terrain" : "off the map");
    throw InputError(msg.str());
  }
}

}  // namespace

std::string to_string(BaselineStatus status) {
  switch (status) {
    case BaselineStatus::kFound:
      return "found";
    case BaselineStatus::kNoPath:
      return "no_path";
    case BaselineStatus::kStartInvalid:
      return "start_invalid";
    case BaselineStatus::kGoalInvalid:
      return "goal_invalid";
    case BaselineStatus::kBudgetExceeded:
      return "budget_exceeded";
  }
  return "unknown";
}

std::string BaselineResult::brief_report() const {
  std::ostringstream out;
  out << to_string(status);
  if (found()) out << ", " << length_m << " m over " << path.size() << " poses";
  out << ", preprocessing " << preprocessing_seconds << " s, search " << search_seconds << " s";
  for (const auto& [key, value] : counters) out << ", " << key << " " << value;
  out << ": " << message;
  return out.str();
}

BaselineResult BaselinePlanner::plan(const RuledTerrain& terrain, const SE2Pose& start,
                                     const SE2Pose& goal) const {
  const std::string who = name();
  require_on_data(terrain, start, who, "start");
  require_on_data(terrain, goal, who, "goal");
  return solve(terrain, start, goal);
}

}  // namespace talus
