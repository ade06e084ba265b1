#include "talus/kinematic/dacre_wright/dacre_wright_baseline.hpp"

#include <memory>
#include <utility>

#include "talus/core/error.hpp"

namespace talus {
namespace {

BaselineStatus baseline_status(DacreWrightStatus s) {
  switch (s) {
    case DacreWrightStatus::kFound:
      return BaselineStatus::kFound;
    case DacreWrightStatus::kNoPath:
    case DacreWrightStatus::kStartUncovered:
    case DacreWrightStatus::kGoalUncovered:
      return BaselineStatus::kNoPath;
    case DacreWrightStatus::kStartInvalid:
      return BaselineStatus::kStartInvalid;
    case DacreWrightStatus::kGoalInvalid:
      return BaselineStatus::kGoalInvalid;
    case DacreWrightStatus::kBudgetExceeded:
      return BaselineStatus::kBudgetExceeded;
  }
  return BaselineStatus::kNoPath;
}

std::vector<BaselineOptionSpec> option_specs() {
  return {
      {"robot", "",
       "robot YAML: a wheeled robot whose wheels are symmetric about G (sum u = sum v = sum u*v "
       "= 0), see data/robots/README.md",
       false, true},
      {"max-level", "6", "finest octree level p_max, 1..8 (voxel side = map side / 2^p_max)"},
      {"reference-level", "auto",
       "octree level p0 analysed first, 0..p_max, or auto (the level whose voxel side is "
       "nearest the wheelbase)"},
      {"full", "false", "build the whole octree before the search instead of incrementally", true},
      {"refinements", "1",
       "extra passes of each voxel's analysis with the narrowed placement domain (>= 0)"},
      {"check-spacing", "0.1", "most distance between consecutive path poses [m] (> 0)"},
      {"budget", std::to_string(OctreeOptions{}.budget),
       "voxel analyses (>= 1): the query stops with status budget_exceeded once spent"},
  };
}

std::unique_ptr<BaselinePlanner> make(const BaselineOptions& text) {
  const BaselineOptionReader reader(option_specs(), text);
  DacreWrightOptions o;
  o.octree.max_level = static_cast<int>(reader.number("max-level", 1, 8));
  if (reader.number("max-level", 1, 8) != o.octree.max_level)
    throw BaselineOptionError("max-level", "must be a whole number in 1..8");
  const std::string& p0 = reader.text("reference-level");
  if (p0 != "auto") {
    const double v = reader.number("reference-level", 0, o.octree.max_level);
    if (v != static_cast<int>(v))
      throw BaselineOptionError("reference-level", "must be a whole number or auto");
    o.octree.reference_level = static_cast<int>(v);
  }
  o.full = reader.flag("full");
  o.octree.analysis.refinements = static_cast<int>(reader.count("refinements", 0));
  o.check_spacing = reader.number("check-spacing", 1e-6, 1e6);
  o.octree.budget = reader.count("budget", 1);
  const std::string& file = reader.text("robot");
  return std::make_unique<DacreWrightBaseline>(load_dacre_wright_robot(file), o, file);
}

}  // namespace

DacreWrightBaseline::DacreWrightBaseline(WheeledRobot robot, DacreWrightOptions options,
                                         std::string robot_file)
    : robot_(std::move(robot)), options_(std::move(options)), robot_file_(std::move(robot_file)) {
  options_.validate();
  robot_.validate();
  require_symmetric_wheels(robot_);
}

std::vector<BaselineSetting> DacreWrightBaseline::settings() const {
  return {
      {"robot", "file", robot_file_},
      {"robot", "kind", std::string("wheeled")},
      {"robot", "name", robot_.name},
      {"options", "max_level", static_cast<long long>(options_.octree.max_level)},
      {"options", "reference_level", static_cast<long long>(options_.octree.reference_level)},
      {"options", "full", options_.full},
      {"options", "refinements", static_cast<long long>(options_.octree.analysis.refinements)},
      {"options", "heading_weight", options_.heading_weight},
      {"options", "check_spacing", options_.check_spacing},
      {"options", "heading_spacing", options_.heading_spacing},
      {"options", "budget", static_cast<long long>(options_.octree.budget)},
  };
}

ValidityFunction DacreWrightBaseline::validity(const RuledTerrain& terrain) const {
  const auto robot = std::make_shared<const WheeledRobot>(robot_);
  const RuledTerrain* t = &terrain;
  return [robot, t](const SE2Pose& q) {
    ConfigurationCheck c;
    c.valid = dacre_wright_admissible(*robot, *t, q);
    c.margin = c.valid ? 1.0 : 0.0;
    return c;
  };
}

DacreWrightResult DacreWrightBaseline::plan_full(const RuledTerrain& terrain, const SE2Pose& start,
                                                 const SE2Pose& goal) const {
  return plan_dacre_wright(terrain, robot_, start, goal, options_);
}

BaselineResult DacreWrightBaseline::solve(const RuledTerrain& terrain, const SE2Pose& start,
                                          const SE2Pose& goal) const {
  return to_baseline_result(plan_dacre_wright(terrain, robot_, start, goal, options_),
                            options_.full);
}

BaselineResult to_baseline_result(const DacreWrightResult& r, bool full) {
  BaselineResult out;
  out.status = baseline_status(r.status);
  out.message = std::string(to_string(r.status)) + ": " + r.message;
  if (r.found()) {
    out.path = r.path;
    out.length_m = r.length_m;
  }
  out.preprocessing_seconds = r.preprocessing_seconds;
  out.search_seconds = r.search_seconds;
  for (std::size_t p = 0; p < r.analyses_per_level.size(); ++p) {
    out.counters["voxels_analysed_level_" + std::to_string(p)] = r.analyses_per_level[p];
  }
  out.counters["voxels_analysed"] = r.voxels_analysed();
  out.counters["channel_voxels"] = r.channel.size();
  out.counters["expansions"] = r.expansions;
  out.flags = {{"full_octree", full}};
  return out;
}

BaselineEntry dacre_wright_baseline_entry() {
  return {"dacre-wright",
          "the free-space structuring of Dacre-Wright and Simeon (ICRA 1993): configuration-space "
          "boxes proven admissible from the elevation map (springs and attitude bounded over the "
          "box), an (x, y, theta) octree of them and an incremental A* over its largest FREE "
          "voxels",
          option_specs(), make};
}

}  // namespace talus
