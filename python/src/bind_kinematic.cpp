/// @file
/// kinematic: every registered baseline planner (planner_registry()),
/// listed and run by name with its text options, on the ruled terrain; and a
/// baseline's path driven at the time-optimal profile (driven_path_time,
/// polyline_travel_time), the yardstick every comparison uses.
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "talus/core/ruled_terrain.hpp"
#include "talus/kinematic/baseline_options.hpp"
#include "talus/kinematic/baseline_planner.hpp"
#include "talus/kinematic/baseline_registry.hpp"
#include "talus/optimal/driven_path_time.hpp"
#include "talus/optimal/polyline_travel_time.hpp"
#include "talus/planners/planner_registry.hpp"

namespace talus::python {
namespace {

/// Python values as the registry's text options: strings as they are, booleans
/// "true" / "false", numbers as their shortest exact repr.
BaselineOptions text_options(const py::dict& options) {
  BaselineOptions out;
  for (const auto& [key, value] : options) {
    if (!py::isinstance<py::str>(key)) throw py::type_error("baseline option keys must be strings");
    const std::string k = key.cast<std::string>();
    if (py::isinstance<py::bool_>(value)) {
      out[k] = value.cast<bool>() ? "true" : "false";
    } else if (py::isinstance<py::str>(value)) {
      out[k] = value.cast<std::string>();
    } else if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) {
      out[k] = py::repr(value).cast<std::string>();
    } else {
      throw py::type_error("baseline option '" + k + "': expected a string, number or bool");
    }
  }
  return out;
}

SE2Pose to_pose(const std::vector<double>& q, const char* what) {
  if (q.size() != 3) throw py::type_error(std::string(what) + " must be (x, y, theta)");
  return {q[0], q[1], q[2]};
}

py::array_t<double> poses(const std::vector<SE2Pose>& path) {
  py::array_t<double> out({static_cast<py::ssize_t>(path.size()), py::ssize_t{3}});
  double* o = out.mutable_data();
  for (std::size_t k = 0; k < path.size(); ++k) {
    o[3 * k] = path[k].x;
    o[3 * k + 1] = path[k].y;
    o[3 * k + 2] = path[k].theta;
  }
  return out;
}

/// Poses from an (n, 3) array of x, y, theta.
std::vector<SE2Pose> to_poses(const DoubleArray& array) {
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::type_error("path must be an (n, 3) array");
  std::vector<SE2Pose> out(static_cast<std::size_t>(array.shape(0)));
  const auto a = array.unchecked<2>();
  for (py::ssize_t k = 0; k < array.shape(0); ++k)
    out[static_cast<std::size_t>(k)] = {a(k, 0), a(k, 1), a(k, 2)};
  return out;
}

py::list settings(const BaselinePlanner& planner) {
  py::list out;
  for (const BaselineSetting& s : planner.settings()) {
    out.append(py::make_tuple(s.section, s.key,
                              std::visit([](const auto& v) { return py::cast(v); }, s.value)));
  }
  return out;
}

}  // namespace

void bind_kinematic(py::module_& m) {
  py::class_<RuledTerrain>(m, "RuledTerrain",
                           "The grid as bilinear patches (talus::RuledTerrain), the kinematic "
                           "baselines' terrain.")
      .def(py::init<ElevationGrid>(), py::arg("grid"))
      .def("grid", &RuledTerrain::grid, py::return_value_policy::reference_internal)
      .def("spacing", &RuledTerrain::spacing)
      .def(
          "contains",
          [](const RuledTerrain& t, double x, double y) {
            return t.contains({x, y});
          },
          py::arg("x"), py::arg("y"))
      .def(
          "has_data",
          [](const RuledTerrain& t, double x, double y) {
            return t.has_data({x, y});
          },
          py::arg("x"), py::arg("y"))
      .def(
          "elevation",
          [](const RuledTerrain& t, double x, double y) {
            return t.elevation({x, y});
          },
          py::arg("x"), py::arg("y"))
      .def(
          "gradient",
          [](const RuledTerrain& t, double x, double y) {
            return t.gradient({x, y});
          },
          py::arg("x"), py::arg("y"));

  py::enum_<BaselineStatus>(m, "BaselineStatus")
      .value("FOUND", BaselineStatus::kFound)
      .value("NO_PATH", BaselineStatus::kNoPath)
      .value("START_INVALID", BaselineStatus::kStartInvalid)
      .value("GOAL_INVALID", BaselineStatus::kGoalInvalid)
      .value("BUDGET_EXCEEDED", BaselineStatus::kBudgetExceeded)
      .def(
          "__str__", [](BaselineStatus s) { return to_string(s); }, py::prepend());

  py::class_<BaselineResult>(m, "BaselineResult")
      .def_readonly("status", &BaselineResult::status)
      .def_readonly("message", &BaselineResult::message)
      .def_property_readonly(
          "path", [](const BaselineResult& r) { return poses(r.path); },
          "(n, 3) poses x, y [m], theta [rad]")
      .def_readonly("motions", &BaselineResult::motions)
      .def_readonly("length_m", &BaselineResult::length_m)
      .def_readonly("preprocessing_seconds", &BaselineResult::preprocessing_seconds)
      .def_readonly("search_seconds", &BaselineResult::search_seconds)
      .def_readonly("counters", &BaselineResult::counters)
      .def_readonly("stage_seconds", &BaselineResult::stage_seconds)
      .def_readonly("flags", &BaselineResult::flags)
      .def("found", &BaselineResult::found)
      .def("brief_report", &BaselineResult::brief_report);

  py::class_<BaselineOptionSpec>(m, "BaselineOptionSpec")
      .def_readonly("key", &BaselineOptionSpec::key)
      .def_readonly("default_value", &BaselineOptionSpec::default_value)
      .def_readonly("help", &BaselineOptionSpec::help)
      .def_readonly("flag", &BaselineOptionSpec::flag)
      .def_readonly("required", &BaselineOptionSpec::required)
      .def("__repr__", [](const BaselineOptionSpec& s) {
        return "<talus.BaselineOptionSpec " + s.key + " = '" + s.default_value + "'>";
      });

  py::class_<BaselineEntry>(m, "BaselineEntry", "One registered baseline: name, summary, options.")
      .def_readonly("name", &BaselineEntry::name)
      .def_readonly("summary", &BaselineEntry::summary)
      .def_readonly("options", &BaselineEntry::options);

  py::class_<BaselinePlanner>(m, "BaselinePlanner",
                              "A configured kinematic baseline (talus::BaselinePlanner).")
      .def("name", &BaselinePlanner::name)
      .def("settings", &settings, "[(section, key, value)], defaults filled in")
      .def(
          "plan",
          [](const BaselinePlanner& p, const RuledTerrain& terrain,
             const std::vector<double>& start, const std::vector<double>& goal) {
            const SE2Pose a = to_pose(start, "start"), b = to_pose(goal, "goal");
            const py::gil_scoped_release release;
            return p.plan(terrain, a, b);
          },
          py::arg("terrain"), py::arg("start"), py::arg("goal"),
          "Plans from start to goal, each (x, y, theta); releases the GIL.");

  // A baseline's path driven at the time-optimal profile (the velocity stage of a path-velocity
  // decomposition): how `talus baseline NAME --vehicle` and the sweeps compare paths.
  py::class_<DrivenPathResult>(m, "DrivenPathResult")
      .def_property_readonly(
          "status", [](const DrivenPathResult& r) { return std::string(to_string(r.status)); },
          "'ok', 'infeasible' or 'not_tangent' (a path that moves sideways)")
      .def_readonly("message", &DrivenPathResult::message)
      .def_readonly("travel_time", &DrivenPathResult::travel_time, "[s]; inf unless ok")
      .def_readonly("length", &DrivenPathResult::length, "3-D [m]")
      .def_readonly("planar_length", &DrivenPathResult::planar_length, "[m]")
      .def_property_readonly("pieces", [](const DrivenPathResult& r) { return r.pieces.size(); })
      .def("brief_report", &DrivenPathResult::brief_report);
  m.def(
      "driven_path_time",
      [](const BPatch& surface, const Vehicle& vehicle, const DoubleArray& path) {
        const std::vector<SE2Pose> configurations = to_poses(path);
        const py::gil_scoped_release release;
        return driven_path_time(surface, vehicle, configurations);
      },
      py::arg("surface"), py::arg("vehicle"), py::arg("path"),
      "A path of (n, 3) poses (a BaselineResult.path) driven along its own segments and arcs, "
      "rest to rest at every cusp, at the time-optimal profile (talus::driven_path_time).");
  m.def(
      "polyline_travel_time",
      [](const BPatch& surface, const Vehicle& vehicle, const DoubleArray& points) {
        const std::vector<Vec2> polyline = to_points(points, "points");
        const py::gil_scoped_release release;
        return polyline_travel_time(surface, vehicle, polyline);
      },
      py::arg("surface"), py::arg("vehicle"), py::arg("points"),
      "Rest-to-rest time-optimal travel time [s] along a clamped cubic fitted to (n, 2) planar "
      "points (talus::polyline_travel_time); inf where no profile is admissible.");

  m.def(
      "baseline_names", [] { return planner_registry().names(); },
      "The registered baselines, in registration order (talus baseline NAME).");
  m.def(
      "baseline",
      [](const std::string& name) -> const BaselineEntry& {
        return planner_registry().entry(name);
      },
      py::arg("name"), py::return_value_policy::reference,
      "The registry entry called `name`; InputError listing the names if there is none.");
  m.def(
      "make_baseline",
      [](const std::string& name, const py::dict& options) {
        return planner_registry().make(name, text_options(options));
      },
      py::arg("name"), py::arg("options") = py::dict(),
      "A configured planner; options as in `talus baseline NAME --KEY VALUE` (strings, numbers "
      "or bools); BaselineOptionError names a bad one.");
  m.def(
      "run_baseline",
      [](const std::string& name, const RuledTerrain& terrain, const std::vector<double>& start,
         const std::vector<double>& goal, const py::dict& options) {
        const std::unique_ptr<BaselinePlanner> planner =
            planner_registry().make(name, text_options(options));
        const SE2Pose a = to_pose(start, "start"), b = to_pose(goal, "goal");
        const py::gil_scoped_release release;
        return planner->plan(terrain, a, b);
      },
      py::arg("name"), py::arg("terrain"), py::arg("start"), py::arg("goal"),
      py::arg("options") = py::dict(), "make_baseline(name, options).plan(terrain, start, goal)");
}

}  // namespace talus::python
