/// @file
/// The vehicle simulation seen from a plan: a planned trajectory as a
/// reference, driven by the tracker on the rigid-body simulation
/// (track_trajectory), at several speed scales (check_closed_loop), and the
/// largest speed scale still driven to the goal (find_speed_scale_limit).
/// The trace comes back as arrays; the margins as a dict.
#include <string>
#include <vector>

#include "bindings.hpp"
#include "talus/dynamics/trajectory_tracking.hpp"
#include "talus/dynamics/vehicle_simulation.hpp"
#include "talus/optimal/closed_loop_check.hpp"

namespace talus::python {
namespace {

/// The trace's per-sample quantities as arrays of one length.
py::dict trace_arrays(const TrackingResult& r) {
  const auto& trace = r.simulation.trace;
  const auto column = [&](auto value) {
    std::vector<double> out;
    out.reserve(trace.size());
    for (std::size_t k = 0; k < trace.size(); ++k) out.push_back(value(k));
    return to_array(out);
  };
  py::dict d;
  d["t"] = column([&](std::size_t k) { return trace[k].t; });
  d["x"] = column([&](std::size_t k) { return trace[k].state.position.x(); });
  d["y"] = column([&](std::size_t k) { return trace[k].state.position.y(); });
  d["z"] = column([&](std::size_t k) { return trace[k].state.position.z(); });
  d["roll"] = column([&](std::size_t k) { return trace[k].state.roll; });
  d["pitch"] = column([&](std::size_t k) { return trace[k].state.pitch; });
  d["yaw"] = column([&](std::size_t k) { return trace[k].state.yaw; });
  d["speed"] = column([&](std::size_t k) { return trace[k].speed; });
  d["steering"] = column([&](std::size_t k) { return trace[k].controls.steering; });
  d["drive_force"] = column([&](std::size_t k) { return trace[k].controls.drive_force; });
  d["lateral_load_ratio"] = column([&](std::size_t k) { return trace[k].lateral_load_ratio; });
  d["side_slip"] = column([&](std::size_t k) { return trace[k].side_slip; });
  d["friction_utilisation"] = column([&](std::size_t k) { return trace[k].friction_utilisation; });
  d["normal_load_ratio"] = column([&](std::size_t k) { return trace[k].normal_load_ratio; });
  d["s"] = column([&](std::size_t k) { return r.tracking[k].s; });
  d["cross_track"] = column([&](std::size_t k) { return r.tracking[k].cross_track; });
  d["desired_speed"] = column([&](std::size_t k) { return r.tracking[k].desired_speed; });
  return d;
}

/// The simulation's peaks and minima over the whole run (the failure events' margins).
py::dict margins(const VehicleSimulationDiagnostics& d) {
  py::dict m;
  m["peak_lateral_load_ratio"] = d.peak_lateral_load_ratio;
  m["min_normal_load"] = d.min_normal_load;
  m["min_normal_load_ratio"] = d.min_normal_load_ratio;
  m["min_total_normal_load_ratio"] = d.min_total_normal_load_ratio;
  m["peak_slip_angle"] = d.peak_slip_angle;
  m["peak_side_slip"] = d.peak_side_slip;
  m["peak_speed"] = d.peak_speed;
  m["peak_roll"] = d.peak_roll;
  m["peak_pitch"] = d.peak_pitch;
  m["roll_limit"] = d.roll_limit;
  m["pitch_limit"] = d.pitch_limit;
  m["longest_airborne"] = d.longest_airborne;
  m["longest_side_slip"] = d.longest_side_slip;
  m["side_lift_time"] = d.side_lift_time;
  m["peak_friction_utilisation"] = d.peak_friction_utilisation;
  m["peak_wheel_friction_utilisation"] = d.peak_wheel_friction_utilisation;
  return m;
}

void bind_tracking(py::module_& m) {
  py::class_<ReferenceTrajectory>(m, "ReferenceTrajectory",
                                  "A planned trajectory to drive: planar points and the planned "
                                  "speed at each (talus::ReferenceTrajectory).")
      .def(py::init([](const DoubleArray& points, const std::vector<double>& speed) {
             ReferenceTrajectory r{to_points(points, "points"), speed};
             r.validate();
             return r;
           }),
           py::arg("points"), py::arg("speed"))
      .def_property_readonly("points",
                             [](const ReferenceTrajectory& r) { return to_array(r.points); })
      .def_property_readonly("speed",
                             [](const ReferenceTrajectory& r) { return to_array(r.speed); });
  m.def("reference_trajectory", &reference_trajectory, py::arg("trajectory"),
        "The stations of a feasible Trajectory with its profile speeds, as a ReferenceTrajectory.");

  py::class_<TrackingOptions>(m, "TrackingOptions",
                              "The tracker and its simulation (talus::TrackingOptions).")
      .def(py::init([](double speed_scale) {
             TrackingOptions o;
             o.speed_scale = speed_scale;
             return o;
           }),
           py::arg("speed_scale") = 1.0)
      .def_readwrite("speed_scale", &TrackingOptions::speed_scale, "multiplies the planned speed")
      .def_property(
          "steering_law",
          [](const TrackingOptions& o) { return std::string(to_string(o.steering_law)); },
          [](TrackingOptions& o, const std::string& name) {
            o.steering_law = parse_steering_law(name);
          },
          "'curvature' (the default) or 'pure_pursuit'")
      .def_readwrite("lookahead_time", &TrackingOptions::lookahead_time, "[s]")
      .def_readwrite("max_steering", &TrackingOptions::max_steering,
                     "[rad]; 0 = the vehicle's own limit")
      .def_readwrite("speed_preview_time", &TrackingOptions::speed_preview_time, "[s]")
      .def_property(
          "output_interval", [](const TrackingOptions& o) { return o.simulation.output_interval; },
          [](TrackingOptions& o, double dt) { o.simulation.output_interval = dt; },
          "the trace's sample interval [s]")
      .def("validate", &TrackingOptions::validate);

  py::class_<TrackingResult>(m, "TrackingResult",
                             "One drive of a planned trajectory (talus::TrackingResult).")
      .def_property_readonly(
          "status", [](const TrackingResult& r) { return std::string(to_string(r.status)); },
          "'reached_goal', 'timeout', 'rollover', 'side_slip', ...")
      .def_readonly("message", &TrackingResult::message)
      .def_readonly("path_length", &TrackingResult::path_length, "[m]")
      .def_readonly("progress", &TrackingResult::progress, "s reached / path length")
      .def_readonly("travel_time", &TrackingResult::travel_time, "simulated [s]")
      .def_readonly("planned_time", &TrackingResult::planned_time, "at the speed scale [s]")
      .def_readonly("max_cross_track", &TrackingResult::max_cross_track, "[m]")
      .def_readonly("rms_cross_track", &TrackingResult::rms_cross_track, "[m]")
      .def_readonly("max_speed_excess", &TrackingResult::max_speed_excess, "[m/s]")
      .def_readonly("seconds", &TrackingResult::seconds, "wall time [s]")
      .def("reached",
           [](const TrackingResult& r) { return r.status == TrackingStatus::kReachedGoal; })
      .def_property_readonly(
          "margins", [](const TrackingResult& r) { return margins(r.simulation.diagnostics); },
          "peaks and minima of the run: dict of floats")
      .def_property_readonly("trace", &trace_arrays,
                             "dict of equal-length arrays: t, x, y, z, roll, pitch, yaw, speed, "
                             "steering, drive_force, lateral_load_ratio, side_slip, "
                             "friction_utilisation, normal_load_ratio, s, cross_track, "
                             "desired_speed")
      .def("brief_report", &TrackingResult::brief_report);

  m.def("track_trajectory", &track_trajectory, py::arg("surface"), py::arg("vehicle"),
        py::arg("reference"), py::arg("options") = TrackingOptions{},
        py::call_guard<py::gil_scoped_release>(),
        "Drives `reference` on `surface` with `vehicle` (which needs a body) by the tracker on "
        "the rigid-body simulation. Releases the GIL while it runs.");
}

void bind_speed_scale_limit(py::module_& m) {
  py::class_<SpeedScaleLimitOptions>(m, "SpeedScaleLimitOptions",
                                     "The bisection of find_speed_scale_limit.")
      .def(py::init<>())
      .def_readwrite("lowest", &SpeedScaleLimitOptions::lowest)
      .def_readwrite("highest", &SpeedScaleLimitOptions::highest)
      .def_readwrite("tolerance", &SpeedScaleLimitOptions::tolerance)
      .def_readwrite("schedule_tolerance", &SpeedScaleLimitOptions::schedule_tolerance)
      .def_readwrite("tracking", &SpeedScaleLimitOptions::tracking)
      .def("validate", &SpeedScaleLimitOptions::validate);

  py::class_<ClosedLoopDrive>(m, "ClosedLoopDrive")
      .def_readonly("speed_scale", &ClosedLoopDrive::speed_scale)
      .def_readonly("result", &ClosedLoopDrive::result)
      .def("reached", &ClosedLoopDrive::reached)
      .def("schedule_ratio", &ClosedLoopDrive::schedule_ratio,
           "simulated over planned time (NaN unless reached)")
      .def("kept_schedule", &ClosedLoopDrive::kept_schedule, py::arg("tolerance"),
           "reached the goal within (1 + tolerance) x the planned time");

  py::class_<SpeedScaleLimit>(m, "SpeedScaleLimit",
                              "The largest speed scale s* driven to the goal on schedule.")
      .def_property_readonly(
          "status", [](const SpeedScaleLimit& r) { return std::string(to_string(r.status)); },
          "'bracketed', 'reaches_highest' or 'fails_lowest'")
      .def_readonly("largest_reaching_scale", &SpeedScaleLimit::largest_reaching_scale, "s*")
      .def_readonly("smallest_failing_scale", &SpeedScaleLimit::smallest_failing_scale)
      .def_readonly("drives", &SpeedScaleLimit::drives)
      .def("bounding_reason", &SpeedScaleLimit::bounding_reason)
      .def("brief_report", &SpeedScaleLimit::brief_report);

  m.def("find_speed_scale_limit", &find_speed_scale_limit, py::arg("surface"), py::arg("vehicle"),
        py::arg("trajectory"), py::arg("options") = SpeedScaleLimitOptions{},
        py::call_guard<py::gil_scoped_release>(),
        "Bisection on the speed scale: the largest multiple of the planned speed at which the "
        "simulated vehicle drives `trajectory` to the goal on schedule. Releases the GIL.");
}

}  // namespace

void bind_simulation(py::module_& m) {
  bind_tracking(m);
  bind_speed_scale_limit(m);
}

}  // namespace talus::python
