#include "talus/kinematic/eldershaw_yim/eldershaw_yim_baseline.hpp"

#include <memory>
#include <utility>

#include "talus/core/error.hpp"

namespace talus {
namespace {

BaselineStatus baseline_status(EldershawYimStatus s) {
  switch (s) {
    case EldershawYimStatus::kFound:
      return BaselineStatus::kFound;
    case EldershawYimStatus::kNoPath:
      return BaselineStatus::kNoPath;
    case EldershawYimStatus::kStartInvalid:
      return BaselineStatus::kStartInvalid;
    case EldershawYimStatus::kGoalInvalid:
      return BaselineStatus::kGoalInvalid;
    case EldershawYimStatus::kBudgetExceeded:
      return BaselineStatus::kBudgetExceeded;
  }
  return BaselineStatus::kNoPath;
}

std::vector<BaselineOptionSpec> option_specs() {
  const EldershawYimPlannerOptions d;
  return {
      {"robot", "",
       "robot YAML: a legged vehicle (type: legged; legs with range and reach, under-carriage, "
       "traction slope, foot print), see data/robots/README.md",
       false, true},
      {"theta-slices", std::to_string(d.theta_slices),
       "heading slices of CGspace: 1 (no rotation) or 8..1024"},
      {"direct", "false", "one A* over the whole CGspace instead of the tree-PRM", true},
      {"prm-points", std::to_string(d.prm_points), "random points of the tree-PRM (>= 0)"},
      {"connect-radius", "0",
       "most xy distance [m] between PRM points the local planner tries to join (>= 0; 0 = 40 "
       "foot prints)"},
      {"connect-attempts", std::to_string(d.connect_attempts),
       "members of one tree tried per new PRM point (>= 1)"},
      {"local-margin", std::to_string(d.local.margin),
       "least extra CG cells around the local planner's bounding box (>= 0)"},
      {"seed", std::to_string(d.seed), "seed of the PRM's random points (>= 0)"},
      {"foot-budget", std::to_string(d.feet.budget),
       "search nodes of the foot-level planner run along a found CG path (>= 0; 0 = do not "
       "plan the feet)"},
      {"feedback-rounds", std::to_string(d.feedback_rounds),
       "times a failed foot plan may mark its blocking CG cell invalid and have the CG path "
       "replanned (section 3.3; 0..1000)"},
      {"workers", std::to_string(d.workers),
       "threads of the local-planner calls (1..256); the plan is the same for any count"},
      {"budget", std::to_string(d.budget),
       "work units (>= 1): CG cells evaluated plus A* expansions; the query stops with status "
       "budget_exceeded once spent"},
  };
}

std::unique_ptr<BaselinePlanner> make(const BaselineOptions& text) {
  const BaselineOptionReader reader(option_specs(), text);
  EldershawYimPlannerOptions o;
  const double slices = reader.number("theta-slices", 1, 1024);
  if (slices != static_cast<int>(slices) || (slices > 1 && slices < 8))
    throw BaselineOptionError("theta-slices", "must be 1 or a whole number in 8..1024");
  o.theta_slices = static_cast<int>(slices);
  o.direct = reader.flag("direct");
  o.prm_points = reader.count("prm-points", 0);
  o.connect_radius = reader.number("connect-radius", 0, 1e9);
  o.connect_attempts = reader.count("connect-attempts", 1);
  const std::size_t margin = reader.count("local-margin", 0);
  if (margin > 100000) throw BaselineOptionError("local-margin", "must be at most 100000 cells");
  o.local.margin = static_cast<int>(margin);
  o.local.heading_weight = 0.0;  // the robot's outer radius
  o.seed = reader.count("seed", 0);
  o.budget = reader.count("budget", 1);
  const std::size_t workers = reader.count("workers", 1);
  if (workers > 256) throw BaselineOptionError("workers", "must be at most 256");
  o.workers = static_cast<int>(workers);
  o.feet.budget = reader.count("foot-budget", 0);
  o.feedback_rounds = reader.count("feedback-rounds", 0);
  if (o.feedback_rounds > 1000)
    throw BaselineOptionError("feedback-rounds", "must be at most 1000");
  o.plan_feet = o.feet.budget > 0;
  if (!o.plan_feet) o.feet.budget = 1;
  const std::string& file = reader.text("robot");
  return std::make_unique<EldershawYimBaseline>(load_legged_robot(file), o, file);
}

}  // namespace

EldershawYimBaseline::EldershawYimBaseline(LeggedRobot robot, EldershawYimPlannerOptions options,
                                           std::string robot_file)
    : robot_(std::move(robot)), options_(std::move(options)), robot_file_(std::move(robot_file)) {
  options_.validate();
  robot_.validate();
}

std::vector<BaselineSetting> EldershawYimBaseline::settings() const {
  return {
      {"robot", "file", robot_file_},
      {"robot", "kind", std::string("legged")},
      {"robot", "name", robot_.name},
      {"robot", "legs", static_cast<long long>(robot_.legs.size())},
      {"robot", "foot_print", robot_.foot_print},
      {"robot", "max_traction_slope", robot_.max_traction_slope},
      {"options", "theta_slices", static_cast<long long>(options_.theta_slices)},
      {"options", "direct", options_.direct},
      {"options", "prm_points", static_cast<long long>(options_.prm_points)},
      {"options", "connect_radius", options_.connect_radius},
      {"options", "connect_attempts", static_cast<long long>(options_.connect_attempts)},
      {"options", "local_margin", static_cast<long long>(options_.local.margin)},
      {"options", "local_margin_fraction", options_.local.margin_fraction},
      {"options", "seed", static_cast<long long>(options_.seed)},
      {"options", "budget", static_cast<long long>(options_.budget)},
      {"options", "feedback_rounds", static_cast<long long>(options_.feedback_rounds)},
      {"options", "foot_budget",
       static_cast<long long>(options_.plan_feet ? options_.feet.budget : 0)},
  };
}

ValidityFunction EldershawYimBaseline::validity(const RuledTerrain& terrain) const {
  const auto robot = std::make_shared<const LeggedRobot>(robot_);
  const auto footmap = std::make_shared<const Footmap>(terrain, *robot);
  const auto lattice =
      std::make_shared<const CgLattice>(terrain.grid(), robot->foot_print, options_.theta_slices);
  return [robot, footmap, lattice](const SE2Pose& q) {
    ConfigurationCheck c;
    if (!footmap->terrain().has_data(q.position())) return c;
    c.valid =
        evaluate_cg_pose(*footmap, *robot, lattice->centre(lattice->cell_of(q))) == CgState::kValid;
    c.margin = c.valid ? 1.0 : 0.0;
    return c;
  };
}

EldershawYimResult EldershawYimBaseline::plan_full(const RuledTerrain& terrain,
                                                   const SE2Pose& start, const SE2Pose& goal,
                                                   const CgRankGroup* ranks) const {
  EldershawYimPlannerOptions o = options_;
  o.ranks = ranks;
  return plan_eldershaw_yim(terrain, robot_, start, goal, o);
}

BaselineResult EldershawYimBaseline::solve(const RuledTerrain& terrain, const SE2Pose& start,
                                           const SE2Pose& goal) const {
  return to_baseline_result(plan_full(terrain, start, goal), options_.direct);
}

BaselineResult to_baseline_result(const EldershawYimResult& r, bool direct) {
  BaselineResult out;
  out.status = baseline_status(r.status);
  out.message = std::string(to_string(r.status)) + ": " + r.message;
  if (r.found()) {
    out.path = r.path;
    out.length_m = r.length_m;
  }
  out.preprocessing_seconds = r.footmap_seconds;
  out.search_seconds = r.search_seconds;
  out.counters = {{"cg_cells_materialised", r.cells_materialised},
                  {"cg_blocks_materialised", r.blocks_materialised},
                  {"cg_cells", r.cg_cells},
                  {"prm_points", r.prm_points.size()},
                  {"prm_edges", r.prm_edges.size()},
                  {"prm_trees", r.prm_trees},
                  {"local_planner_calls", r.local_planner_calls},
                  {"local_planner_successes", r.local_planner_successes},
                  {"recreate_calls", r.recreate_calls},
                  {"expansions", r.expansions},
                  {"samples_drawn", r.samples_drawn},
                  {"foot_planner_nodes", r.foot_planner_nodes},
                  {"feedback_events", r.feedback_events},
                  {"foot_steps_reused", r.foot_steps_reused},
                  {"foot_plan_steps", r.feet_planned ? r.foot_plan.steps.size() : 0}};
  out.stage_seconds = {{"footmap", r.footmap_seconds},   {"materialise", r.materialise_seconds},
                       {"sample", r.sample_seconds},     {"connect", r.connect_seconds},
                       {"recreate", r.recreate_seconds}, {"foot_planner", r.foot_plan.seconds}};
  out.flags = {{"direct", direct}, {"foot_plan_found", r.feet_planned && r.foot_plan.found()}};
  return out;
}

BaselineEntry eldershaw_yim_baseline_entry() {
  return {"eldershaw-yim",
          "the legged-vehicle planner of Eldershaw and Yim (ICRA 2001): a footmap of the slopes "
          "a foot grips, CGspace cells valid where every body quadrant has a foot position in a "
          "leg's range that reaches below the under-carriage, and a tree-PRM (or one direct A*) "
          "of A* local searches over CGspace",
          option_specs(), make};
}

}  // namespace talus
