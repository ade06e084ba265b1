#include "talus/kinematic/hait/hait_baseline.hpp"

#include <limits>
#include <memory>
#include <numbers>
#include <utility>
#include <variant>

#include "talus/core/error.hpp"
#include "talus/kinematic/hait/hait_robot_validity.hpp"

namespace talus {
namespace {

BaselineStatus baseline_status(HaitStatus s) {
  switch (s) {
    case HaitStatus::kFound:
      return BaselineStatus::kFound;
    case HaitStatus::kNoPath:
      return BaselineStatus::kNoPath;
    case HaitStatus::kStartInvalid:
      return BaselineStatus::kStartInvalid;
    case HaitStatus::kGoalInvalid:
      return BaselineStatus::kGoalInvalid;
    case HaitStatus::kNodeLimit:
      return BaselineStatus::kBudgetExceeded;
  }
  return BaselineStatus::kNoPath;
}

std::vector<BaselineOptionSpec> hait_option_specs() {
  return {
      {"robot", "", "robot YAML: wheeled or articulated_chassis (see data/robots/README.md)", false,
       true},
      {"heuristic", "potential-rs",
       "search guidance: euclidean (straight-line distance), potential (potential bitmap at two "
       "control points) or potential-rs (potential, plus the Reeds-Shepp distance near the goal)"},
      {"smooth", "false",
       "smooth the path by valid Reeds-Shepp shortcuts between random configurations on it "
       "(fewer control changes)",
       true},
      {"terrain-uncertainty", "0",
       "elevation interval half-width DZ >= 0 [m] at every node: worst-case checks between the "
       "envelopes z - DZ and z + DZ"},
      {"position-uncertainty", "",
       "RHO,DTHETA: position uncertainty RHO >= 0 [m] and heading uncertainty 0 <= DTHETA < pi "
       "[rad]; the whole neighbourhood must be valid"},
      {"budget", std::to_string(HaitOptions{}.max_nodes),
       "search nodes (>= 1): the A* stops with status budget_exceeded once it has created this "
       "many (checked after each node is developed)"},
  };
}

std::unique_ptr<BaselinePlanner> make_hait(const BaselineOptions& text) {
  const BaselineOptionReader reader(hait_option_specs(), text);
  HaitOptions options;
  try {
    options.heuristic = parse_heuristic(reader.text("heuristic"));
  } catch (const InputError& e) {
    throw BaselineOptionError("heuristic", e.what());
  }
  options.smooth = reader.flag("smooth");
  options.terrain_uncertainty =
      reader.number("terrain-uncertainty", 0.0, std::numeric_limits<double>::infinity());
  const std::vector<double> rho_dtheta = reader.numbers("position-uncertainty", 2);
  if (!rho_dtheta.empty()) {
    if (rho_dtheta[0] < 0.0 || rho_dtheta[1] < 0.0 || rho_dtheta[1] >= std::numbers::pi) {
      throw BaselineOptionError("position-uncertainty",
                                "must be RHO,DTHETA: rho >= 0 [m] and 0 <= dtheta < pi [rad], "
                                "got '" +
                                    reader.text("position-uncertainty") + "'");
    }
    options.position_uncertainty = rho_dtheta[0];
    options.heading_uncertainty = rho_dtheta[1];
  }
  options.max_nodes = reader.count("budget", 1);
  const std::string& file = reader.text("robot");
  return std::make_unique<HaitBaseline>(load_robot(file), options, file);
}

}  // namespace

HaitBaseline::HaitBaseline(Robot robot, HaitOptions options, std::string robot_file)
    : robot_(std::move(robot)), options_(std::move(options)), robot_file_(std::move(robot_file)) {
  options_.validate();
  talus::validate(robot_);
}

std::vector<BaselineSetting> HaitBaseline::settings() const {
  const bool wheeled = std::holds_alternative<WheeledRobot>(robot_);
  const std::string robot_name = std::visit([](const auto& r) { return r.name; }, robot_);
  const auto ll = [](std::size_t n) { return static_cast<long long>(n); };
  return {
      {"robot", "file", robot_file_},
      {"robot", "kind", std::string(wheeled ? "wheeled" : "articulated_chassis")},
      {"robot", "name", robot_name},
      {"options", "heuristic", heuristic_name(options_.heuristic)},
      {"options", "smooth", options_.smooth},
      {"options", "terrain_uncertainty", options_.terrain_uncertainty},
      {"options", "position_uncertainty", options_.position_uncertainty},
      {"options", "heading_uncertainty", options_.heading_uncertainty},
      {"options", "cell_size", options_.cell_size},
      {"options", "theta_bins", static_cast<long long>(options_.theta_bins)},
      {"options", "step", options_.step},
      {"options", "turning_radius", options_.turning_radius},
      {"options", "check_spacing", options_.check_spacing},
      {"options", "margin_weight", options_.margin_weight},
      {"options", "max_nodes", ll(options_.max_nodes)},
      {"options", "connect_goal", options_.connect_goal},
      {"options", "smoothing_iterations", ll(options_.smoothing.iterations)},
      {"options", "smoothing_seed", ll(options_.smoothing.seed)},
  };
}

ValidityFunction HaitBaseline::validity(const RuledTerrain& terrain) const {
  // Shared ownership: the function outlives this call, and HaitRobotValidity's
  // own function() only points at its state.
  const auto model =
      std::make_shared<const HaitRobotValidity>(terrain, robot_, hait_validity_options(options_));
  return [model](const SE2Pose& q) { return model->check(q); };
}

BaselineResult HaitBaseline::solve(const RuledTerrain& terrain, const SE2Pose& start,
                                   const SE2Pose& goal) const {
  const HaitResult r = plan_hait(terrain, robot_, start, goal, options_);
  BaselineResult out;
  out.status = baseline_status(r.status);
  out.message = r.message;
  out.path.reserve(r.path.size());
  out.motions.reserve(r.path.size());
  for (const PathPoint& p : r.path) {
    out.path.push_back(p.pose);
    out.motions.push_back(control_name(p.control));
  }
  out.length_m = r.length_m;
  out.preprocessing_seconds = r.preprocessing_seconds;
  out.search_seconds = r.search_seconds + r.smoothing_seconds;
  out.counters = {{"nodes_created", r.nodes_created},
                  {"nodes_developed", r.nodes_developed},
                  {"placements", r.placements},
                  {"control_changes", r.control_changes},
                  {"control_changes_before_smoothing", r.control_changes_unsmoothed}};
  out.stage_seconds = {{"smoothing", r.smoothing_seconds}};
  out.flags = {{"connected_to_goal", r.connected_to_goal}};
  return out;
}

BaselineEntry hait_baseline_entry() {
  return {"hait",
          "the rough-terrain planner of Hait, Simeon, Taix (Advanced Robotics 16(8), 2002): A* "
          "over (x, y, theta) with the robot placed on the ruled terrain at every checked "
          "configuration (stability, mechanical limits, collision), guided by a heuristic",
          hait_option_specs(), make_hait};
}

}  // namespace talus
