#include "talus/optimal/planner_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace talus {
namespace {

using Options = PlannerOptions;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::vector<Parameter<Options>> global_stage() {
  return {
      integer_parameter<Options>(
          "candidates", [](auto& o) -> auto& { return o.global.candidates; }, 1, 1000,
          "distinct candidate corridors wanted (fewer when no other corridor costs at most "
          "twice the best); each is optimised by the local stage"),
      real_parameter<Options>(
          "lattice_spacing", [](auto& o) -> auto& { return o.global.lattice_spacing; }, 0.0,
          kInfinity, "lattice node spacing [m]; 0 = the terrain's cell size"),
      integer_parameter<Options>("connectivity",
                                 [](auto& o) -> auto& { return o.global.connectivity; }, 8, 32,
                                 "neighbours per lattice node", {8, 16, 32}),
      choice_parameter<Options>(
          "resolution", [](auto& o) -> auto& { return o.global.resolution; },
          {"auto", "full", "multi"}, [](GlobalSearchResolution r) { return to_string(r); },
          [](const std::string& name) { return parse_global_search_resolution(name); },
          "global search: full (every lattice node), multi (a coarse lattice 4x coarser, then "
          "the fine lattice in a corridor around its candidates, widened while needed; no "
          "cost fields) or auto (multi above 1000000 lattice nodes, full below; the summary's "
          "search_resolution says which ran)"),
      integer_parameter<Options>(
          "threads", [](auto& o) -> auto& { return o.global.threads; }, 0, 1024,
          "threads computing the global search's edge costs (0 = one per hardware thread); the "
          "plan is the same for any count"),
      flag_parameter<Options>(
          "braking_rule", [](auto& o) -> auto& { return o.global.braking_rule; },
          "global search: lattice edges on which the vehicle could not brake at any speed are "
          "untraversable (off: keep them, and the feedback rounds remove those no profile "
          "drives; for studying the rule and the rounds)"),
      flag_parameter<Options>(
          "turn_limit", [](auto& o) -> auto& { return o.global.turn_limit; },
          "global search: routes turn no more sharply than the vehicle's steering limit "
          "(max_steering) realises between two edges (off: position-only search, connectivity "
          "+ 1 times fewer states; the local stage still keeps the limit)"),
  };
}

std::vector<Parameter<Options>> planner_level() {
  // The time limit is the termination's time budget (a stop request set in
  // code is replaced when the time limit is set).
  Parameter<Options> time_limit = detail::entry<Options>(
      "time_limit", ParameterKind::kReal,
      "wall-clock budget of the whole plan [s] (inf = none): on it the status is time_limit "
      "and the best feasible trajectory found by then is returned; a tile-size map is searched "
      "on a coarse route level first, so a route is found whatever the budget (talus plan: "
      "counted from the end of reading the inputs, the fit included; past it no figures)",
      0.0);
  time_limit.lower_open = true;
  time_limit.allow_infinity = true;
  time_limit.get = [](const Options& o) { return ParameterValue(o.termination.smallest_budget()); };
  time_limit.set = [](Options& o, const ParameterValue& v) {
    const double seconds = std::get<double>(v);
    o.termination = std::isinf(seconds) ? Termination{} : Termination::time_budget(seconds);
  };
  return {
      integer_parameter<Options>(
          "feedback_rounds", [](auto& o) -> auto& { return o.feedback_rounds; }, 0, 1000,
          "how many times the global search may be re-run with the stretches excluded where a "
          "candidate's initial fit has no admissible profile (a disc round the failing "
          "station; 0 = off)"),
      real_parameter<Options>(
          "feedback_radius", [](auto& o) -> auto& { return o.feedback_radius; }, 0.0, kInfinity,
          "radius of each stretch the feedback rounds exclude when first excluded [m] (it doubles "
          "each round a failure falls inside it again); 0 = two lattice spacings"),
      real_parameter<Options>(
          "station_spacing", [](auto& o) -> auto& { return o.station_spacing; }, 0.0, kInfinity,
          "station spacing of the final profiles [m]; 0 = max(cell size, the vehicle's "
          "half_track) / 10 (0.1 m at 1 m cells for the rover); at least 0.001 m otherwise"),
      std::move(time_limit),
  };
}

std::vector<Parameter<Options>> local_stage() {
  Parameter<Options> control_points = integer_parameter<Options>(
      "control_points", [](auto& o) -> auto& { return o.local.control_points; }, 4,
      kMaxPlannerControlPoints,
      "local stage: control points of each optimised clamped cubic (start and goal fixed)");
  const auto set_count = control_points.set;
  control_points.set = [set_count](Options& o, const ParameterValue& v) {
    set_count(o, v);  // the adaptive fit grows from it, never below it
    o.local.max_control_points = std::max(o.local.max_control_points, o.local.control_points);
  };
  return {
      std::move(control_points),
      integer_list_parameter<Options>(
          "more_control_points", [](auto& o) -> auto& { return o.local.more_control_points; }, 4,
          kMaxPlannerControlPoints,
          "local stage: further starts of each candidate from fits with these control-point "
          "counts, the fastest kept (optima[].attempts[].control_points says which fit each "
          "solve started from)"),
      choice_parameter<Options>(
          "solver", [](auto& o) -> auto& { return o.local.solver; },
          {"ipopt", "nlopt-lbfgs", "nlopt-bobyqa"}, [](PathSolver s) { return to_string(s); },
          [](const std::string& name) { return parse_path_solver(name); },
          "local solver: ipopt (interior point, exact adjoint gradient), nlopt-lbfgs (exact "
          "gradient) or nlopt-bobyqa (derivative-free); nested formulation only"),
      choice_parameter<Options>(
          "formulation", [](auto& o) -> auto& { return o.local.formulation; },
          {"nested", "simultaneous"}, [](PathFormulation f) { return to_string(f); },
          [](const std::string& name) { return parse_path_formulation(name); },
          "local stage: nested (the travel time of the exact profile as a function of the "
          "control points) or simultaneous (direct transcription: control points and squared "
          "speeds in one smooth Ipopt NLP; the reported time is still the exact profile's)"),
      integer_parameter<Options>(
          "restarts", [](auto& o) -> auto& { return o.local.restarts; }, 0, 100,
          "local stage: restarts of a candidate's optimisation that ends without converging (an "
          "iteration or evaluation cap): the first from its best point with fresh solver state, "
          "the others from that point perturbed laterally by two cells (seeded)"),
      flag_parameter<Options>(
          "certify", [](auto& o) -> auto& { return o.certify; },
          "local stage: certify each optimum as a local minimum of the travel time (a "
          "derivative-free trust-region search, BOBYQA, within a quarter cell of every control "
          "point finds nothing faster by more than 0.05 %; a faster point it finds is kept); "
          "optima[].certificate reports it"),
      flag_parameter<Options>(
          "polish", [](auto& o) -> auto& { return o.local.polish; },
          "local stage, nested formulation: polish each candidate's optimum with the "
          "simultaneous NLP in lateral offsets, which converges by Ipopt's own status where the "
          "nested objective's kinks stop the solver on a cap (about 0.3-2 s per candidate and "
          "start on the fractal battery)"),
  };
}

ParameterTable<Options> build() {
  std::vector<Parameter<Options>> all;
  for (auto part : {global_stage, planner_level, local_stage}) {
    for (Parameter<Options>& p : part()) all.push_back(std::move(p));
  }
  return ParameterTable<Options>("PlannerOptions", std::move(all));
}

}  // namespace

const ParameterTable<PlannerOptions>& planner_parameters() {
  static const ParameterTable<PlannerOptions> table = build();
  return table;
}

}  // namespace talus
