/// @file
/// optimal: the time-optimal profile, the one evaluation rule
/// (evaluate_trajectory), the global search and the two-stage planner.
/// Lifetimes: a BPatch copy shares its coefficients, so a Trajectory, its
/// SurfacePath and a GlobalSearchWorkspace hold the surface they were made
/// on themselves and need nothing kept alive for them; everything read out
/// of a result keeps the result alive.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <pybind11/functional.h>

#include "bindings.hpp"
#include "parameter_bindings.hpp"
#include "talus/optimal/global_search.hpp"
#include "talus/optimal/path_optimizer.hpp"
#include "talus/optimal/planner.hpp"
#include "talus/optimal/planner_parameters.hpp"
#include "talus/optimal/time_optimal_profile.hpp"
#include "talus/optimal/trajectory.hpp"

namespace talus::python {
namespace {

py::list constraint_names(const std::vector<Constraint>& constraints) {
  py::list out;
  for (const Constraint c : constraints) out.append(std::string(to_string(c)));
  return out;
}

py::object cost_field(const GlobalSearchResult& r, const std::vector<double>& field) {
  if (field.empty()) return py::none();
  py::array_t<double> out({static_cast<py::ssize_t>(r.ny), static_cast<py::ssize_t>(r.nx)});
  std::copy(field.begin(), field.end(), out.mutable_data());
  return py::object(std::move(out));
}

template <class Enum, Enum (*parse)(std::string_view)>
Enum enum_or_name(const py::object& value) {
  if (py::isinstance<py::str>(value)) return parse(value.cast<std::string>());
  return value.cast<Enum>();
}

void bind_profile(py::module_& m) {
  m.attr("DEFAULT_STATION_SPACING") = kDefaultStationSpacing;
  py::class_<ProfileOptions>(m, "ProfileOptions", "Start and end speeds [m/s] of a profile.")
      .def(py::init([](double start_speed, double end_speed) {
             return ProfileOptions{start_speed, end_speed};
           }),
           py::arg("start_speed") = 0.0, py::arg("end_speed") = 0.0)
      .def_readwrite("start_speed", &ProfileOptions::start_speed)
      .def_readwrite("end_speed", &ProfileOptions::end_speed)
      .def("validate", &ProfileOptions::validate);

  py::enum_<ProfileStatus>(m, "ProfileStatus")
      .value("OK", ProfileStatus::kOk)
      .value("INFEASIBLE", ProfileStatus::kInfeasible);
  py::enum_<ControlKind>(m, "ControlKind")
      .value("ACCELERATE", ControlKind::kAccelerate)
      .value("DECELERATE", ControlKind::kDecelerate)
      .value("LIMIT", ControlKind::kLimit)
      .def(
          "__str__", [](ControlKind k) { return std::string(to_string(k)); }, py::prepend());

  py::class_<SwitchingPoint>(m, "SwitchingPoint")
      .def_readonly("station", &SwitchingPoint::station)
      .def_readonly("s", &SwitchingPoint::s)
      .def_readonly("from_", &SwitchingPoint::from, "the control before ('from' is reserved)")
      .def_readonly("to", &SwitchingPoint::to);

  py::class_<TimeOptimalProfile>(
      m, "TimeOptimalProfile",
      "The time-optimal profile along a path (talus::TimeOptimalProfile); "
      "per-station values as arrays.")
      .def_readonly("status", &TimeOptimalProfile::status)
      .def_readonly("message", &TimeOptimalProfile::message)
      .def_readonly("travel_time", &TimeOptimalProfile::travel_time, "[s]")
      .def_property_readonly(
          "s", [](const TimeOptimalProfile& p) { return to_array(p.s); }, "[m]")
      .def_property_readonly(
          "v", [](const TimeOptimalProfile& p) { return to_array(p.v); }, "[m/s]")
      .def_property_readonly(
          "a", [](const TimeOptimalProfile& p) { return to_array(p.a); },
          "s'' of the step that starts at the station [m/s^2]")
      .def_property_readonly(
          "t", [](const TimeOptimalProfile& p) { return to_array(p.t); }, "[s]")
      .def_property_readonly(
          "v_max", [](const TimeOptimalProfile& p) { return to_array(p.v_max); }, "[m/s]")
      .def_property_readonly(
          "binding", [](const TimeOptimalProfile& p) { return constraint_names(p.binding); })
      .def_property_readonly("control",
                             [](const TimeOptimalProfile& p) {
                               py::list out;
                               for (const ControlKind c : p.control)
                                 out.append(std::string(to_string(c)));
                               return out;
                             })
      .def_readonly("switching_points", &TimeOptimalProfile::switching_points)
      .def_readonly("infeasible_station", &TimeOptimalProfile::infeasible_station)
      .def_property_readonly(
          "infeasible_binding",
          [](const TimeOptimalProfile& p) { return std::string(to_string(p.infeasible_binding)); })
      .def_readonly("merged_stations", &TimeOptimalProfile::merged_stations);

  py::class_<TimeOptimalProfileSolver>(m, "TimeOptimalProfileSolver",
                                       "Solves the time-optimal profile; reuse one for many paths.")
      .def(py::init<>())
      .def(
          "solve",
          [](TimeOptimalProfileSolver& s, const VelocityLimits& limits,
             const ProfileOptions& options) { return s.solve(limits, options); },
          py::arg("limits"), py::arg("options") = ProfileOptions{});

  m.def("station_count", &station_count, py::arg("length"),
        py::arg("spacing") = kDefaultStationSpacing);
  m.def("default_station_spacing", &default_station_spacing, py::arg("surface"), py::arg("vehicle"),
        "max(cell size, vehicle half-track) / 10 [m]: the spacing a station_spacing of 0 selects");

  py::class_<TrajectoryOptions>(m, "TrajectoryOptions")
      .def(py::init([](double start_speed, double end_speed, double station_spacing) {
             TrajectoryOptions o;
             o.speeds = {start_speed, end_speed};
             o.station_spacing = station_spacing;
             return o;
           }),
           py::arg("start_speed") = 0.0, py::arg("end_speed") = 0.0,
           py::arg("station_spacing") = 0.0)
      .def_readwrite("speeds", &TrajectoryOptions::speeds)
      .def_readwrite("station_spacing", &TrajectoryOptions::station_spacing)
      .def("validate", &TrajectoryOptions::validate);

  py::class_<Trajectory>(m, "Trajectory",
                         "A path on the surface with its limits and time-optimal profile "
                         "(talus::Trajectory); holds its surface.")
      .def_property_readonly(
          "path",
          py::cpp_function(
              [](const Trajectory& t) { return std::const_pointer_cast<SurfacePath>(t.path); },
              py::keep_alive<0, 1>()),
          "the SurfacePath, or None if the curve could not be lifted")
      .def_property_readonly(
          "limits",
          py::cpp_function(
              [](const Trajectory& t) { return std::const_pointer_cast<VelocityLimits>(t.limits); },
              py::keep_alive<0, 1>()),
          "the VelocityLimits at its stations, or None")
      .def_readonly("profile", &Trajectory::profile)
      .def_readonly("message", &Trajectory::message)
      .def("feasible", &Trajectory::feasible)
      .def("travel_time", &Trajectory::travel_time, "[s]; inf when infeasible")
      .def("length", &Trajectory::length, "3-D length [m]; NaN without a path");

  m.def(
      "evaluate_trajectory",
      [](const BPatch& surface, const Vehicle& vehicle, const Curve2& curve,
         const TrajectoryOptions& options) {
        return evaluate_trajectory(surface, vehicle, curve, options);
      },
      py::arg("surface"), py::arg("vehicle"), py::arg("curve"),
      py::arg("options") = TrajectoryOptions{},
      "The one evaluation rule: lift `curve` onto `surface`, limits every "
      "options.station_spacing metres, the time-optimal profile.");
}

void bind_global_search(py::module_& m) {
  py::class_<ExcludedRegion>(m, "ExcludedRegion", "a disc whose lattice nodes the search avoids")
      .def(py::init([](const Vec2& centre, double radius) {
             return ExcludedRegion{centre, radius};
           }),
           py::arg("centre"), py::arg("radius"))
      .def_readwrite("centre", &ExcludedRegion::centre, "[m]")
      .def_readwrite("radius", &ExcludedRegion::radius, "[m] (> 0)");

  py::class_<GlobalSearchOptions>(m, "GlobalSearchOptions")
      .def(py::init<>())
      .def_readwrite("lattice_spacing", &GlobalSearchOptions::lattice_spacing, "[m]; 0 = cell size")
      .def_readwrite("connectivity", &GlobalSearchOptions::connectivity, "8, 16 or 32")
      .def_readwrite("candidates", &GlobalSearchOptions::candidates)
      .def_readwrite("distinctness", &GlobalSearchOptions::distinctness, "[m]; 0 = automatic")
      .def_readwrite("max_cost_ratio", &GlobalSearchOptions::max_cost_ratio)
      .def_readwrite("cost_fields", &GlobalSearchOptions::cost_fields)
      .def_readwrite("excluded", &GlobalSearchOptions::excluded, "list of ExcludedRegion")
      .def_readwrite("braking_rule", &GlobalSearchOptions::braking_rule)
      .def_readwrite("turn_limit", &GlobalSearchOptions::turn_limit,
                     "keep the lattice's turns within the vehicle's steering limit")
      .def("validate", &GlobalSearchOptions::validate);

  py::enum_<GlobalSearchStatus>(m, "GlobalSearchStatus")
      .value("OK", GlobalSearchStatus::kOk)
      .value("UNREACHABLE", GlobalSearchStatus::kUnreachable)
      .value("STOPPED", GlobalSearchStatus::kStopped);

  py::class_<CandidatePath>(m, "CandidatePath")
      .def_property_readonly(
          "vertices", [](const CandidatePath& c) { return to_array(c.vertices); },
          "(n, 2) lattice vertices [m], start node to goal node")
      .def_readonly("cost_seconds", &CandidatePath::cost_seconds)
      .def_readonly("length_m", &CandidatePath::length_m);

  py::class_<GlobalSearchResult>(m, "GlobalSearchResult")
      .def_readonly("status", &GlobalSearchResult::status)
      .def_readonly("message", &GlobalSearchResult::message)
      .def_readonly("candidates", &GlobalSearchResult::candidates)
      .def_readonly("start_node", &GlobalSearchResult::start_node)
      .def_readonly("goal_node", &GlobalSearchResult::goal_node)
      .def_readonly("nodes", &GlobalSearchResult::nodes)
      .def_readonly("edges_evaluated", &GlobalSearchResult::edges_evaluated)
      .def_readonly("expanded", &GlobalSearchResult::expanded)
      .def_readonly("reachable_nodes", &GlobalSearchResult::reachable_nodes)
      .def_readonly("search_seconds", &GlobalSearchResult::search_seconds)
      .def_property_readonly(
          "resolution",
          [](const GlobalSearchResult& r) { return std::string(to_string(r.resolution)); },
          "what ran: 'full' or 'multi' (coarse to fine)")
      .def_readonly("coarse_nodes", &GlobalSearchResult::coarse_nodes)
      .def_readonly("route_nodes", &GlobalSearchResult::route_nodes,
                    "the route level's nodes under a time budget (0: none ran)")
      .def_readonly("coarse_candidates", &GlobalSearchResult::coarse_candidates,
                    "the candidates are a coarser level's routes (the budget stopped the finer)")
      .def_readonly("nx", &GlobalSearchResult::nx)
      .def_readonly("ny", &GlobalSearchResult::ny)
      .def_readonly("spacing", &GlobalSearchResult::spacing)
      .def_readonly("origin", &GlobalSearchResult::origin)
      .def_property_readonly(
          "cost_from_start",
          [](const GlobalSearchResult& r) { return cost_field(r, r.cost_from_start); },
          "(ny, nx) array [s], inf = unreached; None if not computed")
      .def_property_readonly("cost_to_goal", [](const GlobalSearchResult& r) {
        return cost_field(r, r.cost_to_goal);
      });

  m.def("global_search",
        py::overload_cast<const BPatch&, const Vehicle&, const Vec2&, const Vec2&,
                          const GlobalSearchOptions&>(&global_search),
        py::arg("surface"), py::arg("vehicle"), py::arg("start"), py::arg("goal"),
        py::arg("options") = GlobalSearchOptions{}, py::call_guard<py::gil_scoped_release>());

  py::class_<GlobalSearchWorkspace>(m, "GlobalSearchWorkspace",
                                    "Edge costs kept between global searches of one surface "
                                    "and vehicle (same results, each later search a graph "
                                    "search only); it holds its own copy of the surface it serves")
      .def(py::init<>())
      .def("lattices", &GlobalSearchWorkspace::lattices)
      .def("clear", &GlobalSearchWorkspace::clear);
  m.def("global_search",
        py::overload_cast<const BPatch&, const Vehicle&, const Vec2&, const Vec2&,
                          const GlobalSearchOptions&, GlobalSearchWorkspace&>(&global_search),
        py::arg("surface"), py::arg("vehicle"), py::arg("start"), py::arg("goal"),
        py::arg("options"), py::arg("workspace"), py::call_guard<py::gil_scoped_release>());
}

void bind_planner(py::module_& m) {
  py::enum_<PathSolver>(m, "PathSolver")
      .value("IPOPT", PathSolver::kIpopt)
      .value("NLOPT_LBFGS", PathSolver::kNloptLbfgs)
      .value("NLOPT_BOBYQA", PathSolver::kNloptBobyqa)
      .def(
          "__str__", [](PathSolver s) { return std::string(to_string(s)); }, py::prepend());
  py::enum_<PathFormulation>(m, "PathFormulation")
      .value("NESTED", PathFormulation::kNested)
      .value("SIMULTANEOUS", PathFormulation::kSimultaneous)
      .def(
          "__str__", [](PathFormulation f) { return std::string(to_string(f)); }, py::prepend());

  py::class_<PathOptimizerOptions>(m, "PathOptimizerOptions",
                                   "Options of the local stage; solver and formulation also take "
                                   "their names ('nlopt-bobyqa', 'simultaneous').")
      .def(py::init<>())
      .def_property(
          "formulation", [](const PathOptimizerOptions& o) { return o.formulation; },
          [](PathOptimizerOptions& o, const py::object& v) {
            o.formulation = enum_or_name<PathFormulation, &parse_path_formulation>(v);
          })
      .def_property(
          "solver", [](const PathOptimizerOptions& o) { return o.solver; },
          [](PathOptimizerOptions& o, const py::object& v) {
            o.solver = enum_or_name<PathSolver, &parse_path_solver>(v);
          })
      .def_readwrite("control_points", &PathOptimizerOptions::control_points)
      .def_readwrite("adaptive_control_points", &PathOptimizerOptions::adaptive_control_points)
      .def_readwrite("max_control_points", &PathOptimizerOptions::max_control_points)
      .def_readwrite("station_spacing", &PathOptimizerOptions::station_spacing)
      .def_readwrite("max_search_stations", &PathOptimizerOptions::max_search_stations)
      .def_readwrite("max_iterations", &PathOptimizerOptions::max_iterations)
      .def_readwrite("max_evaluations", &PathOptimizerOptions::max_evaluations)
      .def_readwrite("relative_tolerance", &PathOptimizerOptions::relative_tolerance)
      .def_readwrite("simultaneous_lateral_iterations",
                     &PathOptimizerOptions::simultaneous_lateral_iterations)
      .def_readwrite("simultaneous_max_iterations",
                     &PathOptimizerOptions::simultaneous_max_iterations)
      .def_readwrite("simultaneous_tolerance", &PathOptimizerOptions::simultaneous_tolerance)
      .def_readwrite("simultaneous_limited_memory",
                     &PathOptimizerOptions::simultaneous_limited_memory)
      .def_readwrite("speeds", &PathOptimizerOptions::speeds)
      .def("validate", &PathOptimizerOptions::validate);

  py::class_<OptimizedPath>(m, "OptimizedPath")
      .def_readonly("curve", &OptimizedPath::curve)
      .def_readonly("initial_curve", &OptimizedPath::initial_curve)
      .def_readonly("control_points", &OptimizedPath::control_points)
      .def_readonly("travel_time", &OptimizedPath::travel_time)
      .def_readonly("initial_time", &OptimizedPath::initial_time)
      .def_readonly("formulation", &OptimizedPath::formulation)
      .def_readonly("solver", &OptimizedPath::solver)
      .def_readonly("solver_status", &OptimizedPath::solver_status)
      .def_readonly("converged", &OptimizedPath::converged)
      .def_readonly("nlp_travel_time", &OptimizedPath::nlp_travel_time)
      .def_readonly("phase", &OptimizedPath::phase)
      .def_readonly("best_attempt", &OptimizedPath::best_attempt)
      .def_readonly("solver_failed", &OptimizedPath::solver_failed)
      .def_readonly("iterations", &OptimizedPath::iterations)
      .def_readonly("evaluations", &OptimizedPath::evaluations)
      .def_readonly("gradient_evaluations", &OptimizedPath::gradient_evaluations)
      .def_readonly("finite_difference_fallbacks", &OptimizedPath::finite_difference_fallbacks)
      .def_readonly("optimality", &OptimizedPath::optimality)
      .def_readonly("stations", &OptimizedPath::stations)
      .def_readonly("seconds", &OptimizedPath::seconds);

  py::class_<PlanningProblem>(m, "PlanningProblem",
                              "What to plan (talus::PlanningProblem); holds a copy of its surface.")
      .def(py::init([](const BPatch& surface, const Vehicle& vehicle, const Vec2& start,
                       const Vec2& goal, double start_speed, double end_speed,
                       std::optional<double> start_heading, std::optional<double> goal_heading) {
             PlanningProblem p(surface, vehicle, start, goal);
             p.start_speed = start_speed;
             p.end_speed = end_speed;
             p.start_heading = start_heading;
             p.goal_heading = goal_heading;
             return p;
           }),
           py::arg("surface"), py::arg("vehicle"), py::arg("start"), py::arg("goal"),
           py::arg("start_speed") = 0.0, py::arg("end_speed") = 0.0,
           py::arg("start_heading") = py::none(), py::arg("goal_heading") = py::none())
      .def_property_readonly(
          "surface", [](const PlanningProblem& p) -> const BPatch& { return *p.surface; },
          py::return_value_policy::reference_internal)
      .def_readwrite("vehicle", &PlanningProblem::vehicle)
      .def_readwrite("start", &PlanningProblem::start)
      .def_readwrite("goal", &PlanningProblem::goal)
      .def_readwrite("start_speed", &PlanningProblem::start_speed)
      .def_readwrite("end_speed", &PlanningProblem::end_speed)
      .def_readwrite("start_heading", &PlanningProblem::start_heading,
                     "[rad] counter-clockwise from east, or None (free)")
      .def_readwrite("goal_heading", &PlanningProblem::goal_heading,
                     "[rad] counter-clockwise from east, or None (free)")
      .def("validate", &PlanningProblem::validate);

  py::enum_<PlannerStage>(m, "PlannerStage")
      .value("GLOBAL_SEARCH", PlannerStage::kGlobalSearch)
      .value("LOCAL_OPTIMISATION", PlannerStage::kLocalOptimisation)
      .value("DONE", PlannerStage::kDone)
      .def(
          "__str__", [](PlannerStage s) { return std::string(to_string(s)); }, py::prepend());
  py::class_<PlannerProgress>(m, "PlannerProgress")
      .def_readonly("stage", &PlannerProgress::stage)
      .def_readonly("candidate", &PlannerProgress::candidate)
      .def_readonly("candidates", &PlannerProgress::candidates)
      .def_readonly("seconds", &PlannerProgress::seconds);

  py::class_<PlannerOptions> options(
      m, "PlannerOptions",
      "Options of plan() (talus::PlannerOptions). PlannerOptions(**kwargs) sets any of "
      "planner_parameters() by name (the same names, bounds and documentation as `talus plan`'s "
      "options), and each is an attribute; `global_search` is C++'s `global` (a Python "
      "keyword).");
  options
      .def(py::init([](const py::kwargs& kwargs) {
             PlannerOptions o;
             for (const auto& [key, value] : kwargs)
               set_parameter(planner_parameters(), o, key.cast<std::string>(), value);
             return o;
           }),
           "PlannerOptions(**kwargs): the defaults, with the named planner_parameters() set")
      .def_readwrite("global_search", &PlannerOptions::global)
      .def_readwrite("local", &PlannerOptions::local)
      .def_readwrite("optimize", &PlannerOptions::optimize)
      .def_readwrite("progress", &PlannerOptions::progress,
                     "None, or a callable(PlannerProgress) -> bool; False stops the plan")
      .def(
          "parameters",
          [](const PlannerOptions& o) { return parameter_values(planner_parameters(), o); },
          "{name: value} of every planner parameter (as summary.json's `options`)")
      .def("validate", &PlannerOptions::validate);
  add_parameter_attributes(options, planner_parameters());
  m.def(
      "planner_parameters", [] { return describe_parameters(planner_parameters()); },
      "The declared planner parameters: [{name, kind, doc, default, lower, upper, choices, "
      "cli}], as talus/optimal/planner_parameters.hpp declares them");

  py::enum_<PlannerStatus>(m, "PlannerStatus")
      .value("OK", PlannerStatus::kOk)
      .value("UNREACHABLE", PlannerStatus::kUnreachable)
      .value("INFEASIBLE", PlannerStatus::kInfeasible)
      .value("STOPPED", PlannerStatus::kStopped)
      .value("TIME_LIMIT", PlannerStatus::kTimeLimit)
      .def(
          "__str__", [](PlannerStatus s) { return std::string(to_string(s)); }, py::prepend());

  py::class_<LocalCertificate>(
      m, "LocalCertificate",
      "An optimum's local-optimality certificate "
      "(talus::certify_local_optimum; PlannerOptions.certify, on by default)")
      .def_readonly("certified", &LocalCertificate::certified)
      .def_readonly("rounds", &LocalCertificate::rounds)
      .def_readonly("radius", &LocalCertificate::radius, "[m]")
      .def_readonly("tolerance", &LocalCertificate::tolerance)
      .def_readonly("travel_time", &LocalCertificate::travel_time, "[s]")
      .def_readonly("best_time", &LocalCertificate::best_time, "[s]")
      .def_readonly("improvement", &LocalCertificate::improvement, "relative, >= 0")
      .def_readonly("evaluations", &LocalCertificate::evaluations)
      .def_readonly("solver_status", &LocalCertificate::solver_status)
      .def_readonly("seconds", &LocalCertificate::seconds);

  py::class_<CandidateOutcome>(m, "CandidateOutcome")
      .def_readonly("candidate", &CandidateOutcome::candidate)
      .def_readonly("optimization", &CandidateOutcome::optimization)
      .def_readonly("optimizer_message", &CandidateOutcome::optimizer_message)
      .def_readonly("initial", &CandidateOutcome::initial)
      .def_readonly("trajectory", &CandidateOutcome::trajectory)
      .def_readonly("kept_initial", &CandidateOutcome::kept_initial)
      .def_readonly("certificate", &CandidateOutcome::certificate, "LocalCertificate or None")
      .def_readonly("certificate_kept", &CandidateOutcome::certificate_kept)
      .def_readonly("reported_attempt", &CandidateOutcome::reported_attempt)
      .def_readonly("seconds", &CandidateOutcome::seconds)
      .def("feasible", &CandidateOutcome::feasible);

  py::class_<PlannerTimings>(m, "PlannerTimings")
      .def_readonly("global_search", &PlannerTimings::global)
      .def_readonly("local", &PlannerTimings::local)
      .def_readonly("evaluation", &PlannerTimings::evaluation)
      .def_readonly("total", &PlannerTimings::total);

  py::class_<PlannerResult>(m, "PlannerResult",
                            "The planner's result (talus::PlannerResult); keeps the problem "
                            "and its surface alive.")
      .def_readonly("status", &PlannerResult::status)
      .def_readonly("message", &PlannerResult::message)
      .def_readonly("global_search", &PlannerResult::global)
      .def_property_readonly("candidates",
                             [](py::object self) {
                               return reference_list(self.cast<PlannerResult&>().candidates, self);
                             })
      .def_readonly("best_candidate", &PlannerResult::best_candidate)
      .def_readonly("seconds", &PlannerResult::seconds)
      .def("best", &PlannerResult::best, py::return_value_policy::reference_internal,
           "the best Trajectory, or None")
      .def("travel_time", &PlannerResult::travel_time)
      .def("global_travel_time", &PlannerResult::global_travel_time)
      .def("improvement_percent", &PlannerResult::improvement_percent)
      .def("brief_report", &PlannerResult::brief_report);

  m.def("plan", &plan, py::arg("problem"), py::arg("options") = PlannerOptions{},
        py::keep_alive<0, 1>(), py::call_guard<py::gil_scoped_release>(),
        "Plans `problem` (talus::plan): global candidates, local optimisation of each, the "
        "fastest trajectory. Releases the GIL while it runs.");
}

}  // namespace

void bind_optimal(py::module_& m) {
  bind_profile(m);
  bind_global_search(m);
  bind_planner(m);
}

}  // namespace talus::python
