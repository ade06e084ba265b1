#include "dynamic_vs_kinematic_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "hait_figures.hpp"
#include "hait_scenarios.hpp"
#include "number_format.hpp"
#include "plot.hpp"
#include "report.hpp"
#include "stopwatch.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/core/error.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/kinematic/driving_pieces.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/polyline_travel_time.hpp"

namespace talus::experiments {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The point mass matched to marsokhod_chassis.yaml: half track = the axle
/// half width l, centre of mass 0.35 m up, rover-like drive and speed limits.
Vehicle matched_vehicle() {
  Vehicle v;
  v.model = VehicleModel::kPointMass;
  v.friction = 0.7;
  v.cg_height = 0.35;
  v.half_track = 0.45;
  v.max_speed = 2.0;
  v.max_accel = 1.0;
  v.max_decel = 1.0;
  return v;
}

struct Row {
  std::string terrain;
  double kinematic_plan_seconds = 0, kinematic_length = 0, kinematic_time = kInf;
  std::size_t pieces = 0;
  double talus_plan_seconds = 0, talus_length = 0, talus_time = kInf;
  std::vector<PathPoint> kinematic_path;
  std::vector<PathPoint> talus_path;
};

Row compare(const std::string& name, const HaitScenario& s, const BaselinePlanner& kinematic,
            const Vehicle& vehicle) {
  Row row;
  row.terrain = name;
  const BPatch surface = BPatch::interpolate(s.grid);
  TimeOptimalProfileSolver solver;

  // Kinematic: plan, then split at cusps (each piece driven rest to rest); a
  // step against the heading is driven in reverse.
  const auto t0 = Clock::now();
  const BaselineResult kr = kinematic.plan(RuledTerrain(s.grid), s.start, s.goal);
  row.kinematic_plan_seconds = seconds_since(t0);
  if (!kr.found()) throw SolverError(name + ": no kinematic path (" + kr.message + ")");
  for (const SE2Pose& q : kr.path) row.kinematic_path.push_back({q, {}});
  row.kinematic_length = kr.length_m;
  row.kinematic_time = 0.0;
  for (const DrivingPiece& piece : split_at_cusps(kr.path)) {
    row.kinematic_time += polyline_travel_time(surface, vehicle, piece.points, {}, &solver);
    ++row.pieces;
  }

  // Talus: global minimum-time search, then the local optimiser (Ipopt).
  PlannerOptions options;
  options.global.candidates = 1;
  options.local.solver = PathSolver::kIpopt;
  const PlannerResult planned =
      plan(PlanningProblem(surface, vehicle, s.start.position(), s.goal.position()), options);
  if (planned.status == PlannerStatus::kUnreachable) {
    throw SolverError(name + ": no global candidate");
  }
  row.talus_plan_seconds = planned.seconds.total;
  if (const Trajectory* best = planned.best()) {
    row.talus_time = best->travel_time();
    row.talus_length = best->length();
    for (std::size_t k = 0; k < best->limits->size(); k += 5) {
      const Vec3& p = best->limits->frame(k).point;
      row.talus_path.push_back({{p.x(), p.y(), 0.0}, {}});
    }
  }
  return row;
}

}  // namespace

void run_dynamic_vs_kinematic(const ExperimentContext& context) {
  require_gnuplot();
  const std::unique_ptr<BaselinePlanner> kinematic = BaselineRegistry::builtin().make(
      "hait", {{"robot", (context.data_dir / "robots" / "marsokhod_chassis.yaml").string()},
               {"heuristic", "potential-rs"},
               {"smooth", "true"}});
  const Vehicle vehicle = matched_vehicle();
  std::vector<std::pair<std::string, HaitScenario>> scenarios{
      {"crescent", hait_heuristics_scenario(context.quick)},
      {"gorge", hait_gorge_scenario(context.quick)}};
  std::vector<Row> rows;
  std::string csv =
      "terrain,kinematic_length_m,kinematic_pieces,kinematic_time_s,kinematic_plan_seconds,"
      "talus_length_m,talus_time_s,talus_plan_seconds,time_ratio\n";
  for (const auto& [name, s] : scenarios) {
    rows.push_back(compare(name, s, *kinematic, vehicle));
    const Row& r = rows.back();
    csv += name + "," + csv_number(r.kinematic_length) + "," + std::to_string(r.pieces) + "," +
           csv_number(r.kinematic_time) + "," + csv_number(r.kinematic_plan_seconds) + "," +
           csv_number(r.talus_length) + "," + csv_number(r.talus_time) + "," +
           csv_number(r.talus_plan_seconds) + "," + csv_number(r.kinematic_time / r.talus_time) +
           "\n";
    std::vector<HaitRoute> routes;
    routes.push_back(
        {r.kinematic_path,
         "kinematic (Hait et al.) + time-optimal profile: " + fmt("%.1f", r.kinematic_time) + " s",
         "#2c7fb8"});
    routes.push_back(
        {r.talus_path, "Talus time-optimal: " + fmt("%.1f", r.talus_time) + " s", "#e6550d"});
    render_hait_map(context.output_dir, "map_" + name, s, routes,
                    "dynamic-vs-kinematic: " + name + " terrain");
  }
  write_text_file(context.output_dir / "comparison.csv", csv);
  for (const Row& r : rows) {
    ExperimentSummary& summary = *context.summary;
    summary.set("kinematic_time_" + r.terrain + "_s", r.kinematic_time, "s");
    summary.set("talus_time_" + r.terrain + "_s", r.talus_time, "s");
    summary.set("time_ratio_" + r.terrain, r.kinematic_time / r.talus_time, "1");
    summary.set("talus_time_over_length_at_max_speed_" + r.terrain,
                r.talus_time / (r.talus_length / vehicle.max_speed), "1",
                "> 1: no profile beats its own length at the top speed");
  }

  Report report("dynamic-vs-kinematic: path–velocity decomposition vs Talus's time-optimal plan");
  report.paragraph(
      "**Set-up.** Terrains: the hait-heuristics problem (`crescent`) and the hait-uncertainty "
      "problem (`gorge`, without uncertainty). The kinematic path is `plan_hait` (articulated "
      "chassis `marsokhod_chassis.yaml`, potential-rs, smoothed); it is split at its cusps and "
      "each forward or reverse piece is fitted with a clamped cubic (`resample_polyline` + "
      "`fit_clamped_cubic`, one control point per metre, 4–48) and driven rest to rest at its "
      "exact time-optimal profile; the travel time is the sum. Talus's plan is `global_search` "
      "(one candidate) then `optimize_path` (Ipopt), from rest to rest, its profile recomputed at "
      "0.1 m stations. Both profiles use the interpolating B-patch of the same grid. Vehicle: a "
      "point mass matched to the chassis: half track 0.45 m (the axle half width), centre of mass "
      "0.35 m high, friction 0.7, max speed 2 m/s, drive and brake 1 m/s². The kinematic planner "
      "knows nothing of speed, so this compares routes, not planners of the same problem.");
  if (context.quick) report.paragraph("**Quick mode**: smaller maps.");
  Table table({"terrain", "kinematic length [m]", "pieces", "kinematic time [s]",
               "Talus length [m]", "Talus time [s]", "time ratio", "kinematic planning [s]",
               "Talus planning [s]"});
  for (const Row& r : rows) {
    table.row({r.terrain, sig3(r.kinematic_length), std::to_string(r.pieces),
               fmt("%.2f", r.kinematic_time), sig3(r.talus_length), fmt("%.2f", r.talus_time),
               fmt("%.2f", r.kinematic_time / r.talus_time), fmt("%.3g", r.kinematic_plan_seconds),
               fmt("%.3g", r.talus_plan_seconds)});
  }
  report.table(table)
      .paragraph(
          "The paper has no such comparison (it plans kinematically only); time ratio = "
          "kinematic ÷ Talus.")
      .write(context.output_dir, "`comparison.csv`, `map_crescent.png`, `map_gorge.png`.",
             {{"crescent", "map_crescent.png"}, {"gorge", "map_gorge.png"}});
}

}  // namespace talus::experiments
