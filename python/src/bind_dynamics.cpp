/// @file
/// dynamics: vehicles (from dicts, YAML text or files), speed limits and
/// acceleration bounds on arrays of station geometry, and VelocityLimits
/// along a path.
#include <cmath>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "bindings.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/admissible_set.hpp"
#include "talus/dynamics/path_velocity_limits.hpp"
#include "talus/dynamics/vehicle.hpp"
#include "talus/dynamics/velocity_limits.hpp"

namespace talus::python {
namespace {

/// One YAML scalar for a Python value: numbers round-trip exactly (repr), infinities
/// are .inf, strings are double-quoted; anything else is a TypeError.
std::string yaml_scalar(const py::handle& value, const std::string& key) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  if (py::isinstance<py::float_>(value)) {
    const double v = value.cast<double>();
    if (std::isnan(v)) return ".nan";
    if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
    return py::repr(value).cast<std::string>();
  }
  if (py::isinstance<py::str>(value)) {
    return py::module_::import("json").attr("dumps")(value).cast<std::string>();
  }
  throw py::type_error("vehicle key '" + key + "': expected a number or a string, got " +
                       py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

/// The dict as the YAML text of a vehicle file, parsed by the C++ reader so that
/// a dict and a file are checked by the same rules with the same messages.
Vehicle vehicle_from_dict(const py::dict& d, const std::string& source) {
  std::string yaml = "{";
  for (const auto& [key, value] : d) {
    if (!py::isinstance<py::str>(key)) throw py::type_error("vehicle keys must be strings");
    const std::string k = key.cast<std::string>();
    if (yaml.size() > 1) yaml += ", ";
    yaml += py::module_::import("json").attr("dumps")(key).cast<std::string>() + ": " +
            yaml_scalar(value, k);
  }
  yaml += "}";
  return parse_vehicle(yaml, source);
}

std::string_view model_name(VehicleModel model) {
  return model == VehicleModel::kRigidBody ? "rigid_body" : "point_mass";
}

/// The keys a vehicle file of this model would have; unlimited limits are omitted,
/// and the body keys (mass, inertia, suspension, tyres) are present iff it has a body.
py::dict vehicle_to_dict(const Vehicle& v) {
  py::dict d;
  d["model"] = std::string(model_name(v.model));
  d["gravity"] = v.gravity;
  d["friction"] = v.friction;
  d["cg_height"] = v.cg_height;
  d["half_track"] = v.half_track;
  if (v.model == VehicleModel::kRigidBody || std::isfinite(v.max_steering))
    d["half_wheelbase"] = v.half_wheelbase;
  if (std::isfinite(v.max_speed)) d["max_speed"] = v.max_speed;
  if (std::isfinite(v.max_accel)) d["max_accel"] = v.max_accel;
  if (std::isfinite(v.max_decel)) d["max_decel"] = v.max_decel;
  if (std::isfinite(v.max_steering)) d["max_steering"] = v.max_steering;
  if (v.contact_reserve != 0.0) d["contact_reserve"] = v.contact_reserve;
  if (v.friction_reserve != 0.0) d["friction_reserve"] = v.friction_reserve;
  if (v.drive_reserve != 0.0) d["drive_reserve"] = v.drive_reserve;
  if (v.axle_friction) d["axle_friction"] = true;
  if (v.body) {  // every key, defaults included: the dict says exactly what the simulation uses
    const VehicleBody& b = *v.body;
    d["mass"] = b.mass;
    d["inertia_roll"] = b.inertia_roll;
    d["inertia_pitch"] = b.inertia_pitch;
    d["inertia_yaw"] = b.inertia_yaw;
    d["wheel_radius"] = b.wheel_radius;
    d["suspension_stiffness"] = b.suspension_stiffness;
    d["suspension_damping"] = b.suspension_damping;
    d["cornering_stiffness"] = b.cornering_stiffness;
  }
  return d;
}

py::list names(const std::vector<Constraint>& constraints) {
  py::list out;
  for (const Constraint c : constraints) out.append(std::string(to_string(c)));
  return out;
}

/// Station geometry arrays broadcast together.
struct GeometryArrays {
  std::vector<DoubleArray> arrays;
  std::vector<py::ssize_t> shape;
  py::ssize_t size = 0;
  StationGeometry at(py::ssize_t k) const {
    return {arrays[0].data()[k], arrays[1].data()[k], arrays[2].data()[k], arrays[3].data()[k],
            arrays[4].data()[k]};
  }
};

/// The station geometry (and `extra`, named `extra_name`) broadcast together; InputError
/// naming the array and the index of the first element that is not finite.
GeometryArrays geometry_arrays(const py::object& kappa_n, const py::object& kappa_g,
                               const py::object& k_t, const py::object& k_q, const py::object& k_r,
                               const py::object& extra = py::none(), const char* extra_name = "") {
  py::tuple all = extra.is_none() ? py::tuple(py::module_::import("numpy").attr("broadcast_arrays")(
                                        kappa_n, kappa_g, k_t, k_q, k_r))
                                  : py::tuple(py::module_::import("numpy").attr("broadcast_arrays")(
                                        kappa_n, kappa_g, k_t, k_q, k_r, extra));
  GeometryArrays g;
  for (const py::handle item : all) {
    DoubleArray a = DoubleArray::ensure(item);
    if (!a) throw py::type_error("station geometry must be numbers or arrays of numbers");
    g.arrays.push_back(std::move(a));
  }
  g.shape.assign(g.arrays[0].shape(), g.arrays[0].shape() + g.arrays[0].ndim());
  g.size = g.arrays[0].size();
  const char* names[] = {"kappa_n", "kappa_g", "k_t", "k_q", "k_r", extra_name};
  for (std::size_t a = 0; a < g.arrays.size(); ++a) {
    for (py::ssize_t k = 0; k < g.size; ++k) {
      if (!std::isfinite(g.arrays[a].data()[k])) {
        throw InputError(std::string(names[a]) + "[" + std::to_string(k) + "] is " +
                         std::to_string(g.arrays[a].data()[k]) +
                         ": station geometry (and speeds, stations) must be finite");
      }
    }
  }
  return g;
}

py::dict limits_on_arrays(const Vehicle& vehicle, const py::object& kappa_n,
                          const py::object& kappa_g, const py::object& k_t, const py::object& k_q,
                          const py::object& k_r) {
  vehicle.validate();
  const AdmissibleSet set(vehicle);
  const GeometryArrays g = geometry_arrays(kappa_n, kappa_g, k_t, k_q, k_r);
  py::array_t<double> v_min(g.shape), v_max(g.shape);
  py::array_t<bool> traversable(g.shape);
  std::vector<Constraint> lower(static_cast<std::size_t>(g.size)), upper(lower.size());
  for (py::ssize_t k = 0; k < g.size; ++k) {
    const SpeedLimits l = set.speed_limits(g.at(k));
    v_min.mutable_data()[k] = l.v_min;
    v_max.mutable_data()[k] = l.v_max;
    traversable.mutable_data()[k] = l.traversable;
    lower[static_cast<std::size_t>(k)] = l.lower_binding;
    upper[static_cast<std::size_t>(k)] = l.upper_binding;
  }
  py::dict out;
  out["v_min"] = v_min;
  out["v_max"] = v_max;
  out["traversable"] = traversable;
  out["lower_binding"] = names(lower);
  out["upper_binding"] = names(upper);
  return out;
}

py::dict bounds_on_arrays(const Vehicle& vehicle, const py::object& kappa_n,
                          const py::object& kappa_g, const py::object& k_t, const py::object& k_q,
                          const py::object& k_r, const py::object& speed) {
  vehicle.validate();
  const AdmissibleSet set(vehicle);
  const GeometryArrays g = geometry_arrays(kappa_n, kappa_g, k_t, k_q, k_r, speed, "speed");
  for (py::ssize_t k = 0; k < g.size; ++k) {
    if (g.arrays[5].data()[k] < 0.0) {
      throw InputError("speed[" + std::to_string(k) + "] is " +
                       std::to_string(g.arrays[5].data()[k]) + ": speeds must be >= 0");
    }
  }
  py::array_t<double> a_min(g.shape), a_max(g.shape);
  py::array_t<bool> feasible(g.shape);
  std::vector<Constraint> lower(static_cast<std::size_t>(g.size)), upper(lower.size()),
      violated(lower.size());
  for (py::ssize_t k = 0; k < g.size; ++k) {
    const AccelerationBounds b = set.acceleration_bounds(g.at(k), g.arrays[5].data()[k]);
    a_min.mutable_data()[k] = b.a_min;
    a_max.mutable_data()[k] = b.a_max;
    feasible.mutable_data()[k] = b.feasible;
    lower[static_cast<std::size_t>(k)] = b.lower_binding;
    upper[static_cast<std::size_t>(k)] = b.upper_binding;
    violated[static_cast<std::size_t>(k)] = b.violated;
  }
  py::dict out;
  out["a_min"] = a_min;
  out["a_max"] = a_max;
  out["feasible"] = feasible;
  out["lower_binding"] = names(lower);
  out["upper_binding"] = names(upper);
  out["violated"] = names(violated);
  return out;
}

/// One per-station number of a VelocityLimits table as an array.
template <class Get>
py::array_t<double> per_station(const VelocityLimits& l, Get get) {
  py::array_t<double> out(static_cast<py::ssize_t>(l.size()));
  for (std::size_t k = 0; k < l.size(); ++k) out.mutable_data()[k] = get(k);
  return out;
}

VelocityLimits limits_from_geometry(const Vehicle& vehicle, const DoubleArray& s,
                                    const py::object& kappa_n, const py::object& kappa_g,
                                    const py::object& k_t, const py::object& k_q,
                                    const py::object& k_r) {
  const GeometryArrays g = geometry_arrays(kappa_n, kappa_g, k_t, k_q, k_r, s, "s");
  if (g.shape.size() != 1) throw py::type_error("s and the geometry must be 1-D arrays");
  for (py::ssize_t k = 1; k < g.size; ++k) {
    if (!(g.arrays[5].data()[k] > g.arrays[5].data()[k - 1])) {
      throw InputError("s must increase strictly: s[" + std::to_string(k) +
                       "] = " + std::to_string(g.arrays[5].data()[k]) + " after s[" +
                       std::to_string(k - 1) + "] = " + std::to_string(g.arrays[5].data()[k - 1]));
    }
  }
  std::vector<PathFrame> frames(static_cast<std::size_t>(g.size));
  for (py::ssize_t k = 0; k < g.size; ++k) {
    PathFrame& f = frames[static_cast<std::size_t>(k)];
    const StationGeometry sg = g.at(k);
    f.s = g.arrays[5].data()[k];
    f.kappa_n = sg.kappa_n;
    f.kappa_g = sg.kappa_g;
    f.k_t = sg.k_t;
    f.k_q = sg.k_q;
    f.k_r = sg.k_r;
  }
  VelocityLimits limits(vehicle);
  limits.compute(frames);  // geometry given without a surface: wheels at the c.g.
  return limits;
}

}  // namespace

void bind_dynamics(py::module_& m) {
  py::enum_<VehicleModel>(m, "VehicleModel")
      .value("POINT_MASS", VehicleModel::kPointMass)
      .value("RIGID_BODY", VehicleModel::kRigidBody);

  py::class_<Vehicle>(m, "Vehicle",
                      "A ground vehicle, SI units (talus::Vehicle); fields as in a vehicle "
                      "file (data/vehicles/README.md). Vehicle() has the C++ defaults.")
      .def(py::init<>())
      .def_static("from_dict", &vehicle_from_dict, py::arg("values"), py::arg("source") = "dict",
                  "A vehicle from the keys of a vehicle file, checked by the file reader: "
                  "unknown or missing keys and bad values raise InputError naming `source`.")
      .def("to_dict", &vehicle_to_dict,
           "The keys of a vehicle file (unlimited max_speed/max_accel/max_decel/max_steering "
           "omitted; "
           "the body keys mass, inertia_*, wheel_radius, suspension_*, cornering_stiffness "
           "when the vehicle has a body).")
      .def_readwrite("model", &Vehicle::model)
      .def_readwrite("gravity", &Vehicle::gravity)
      .def_readwrite("friction", &Vehicle::friction)
      .def_readwrite("cg_height", &Vehicle::cg_height)
      .def_readwrite("half_track", &Vehicle::half_track)
      .def_readwrite("half_wheelbase", &Vehicle::half_wheelbase)
      .def_readwrite("max_speed", &Vehicle::max_speed)
      .def_readwrite("max_accel", &Vehicle::max_accel)
      .def_readwrite("max_decel", &Vehicle::max_decel)
      .def_readwrite("max_steering", &Vehicle::max_steering)
      .def_readwrite("contact_reserve", &Vehicle::contact_reserve)
      .def_readwrite("friction_reserve", &Vehicle::friction_reserve)
      .def_readwrite("drive_reserve", &Vehicle::drive_reserve)
      .def_readwrite("axle_friction", &Vehicle::axle_friction)
      .def("max_curvature", &Vehicle::max_curvature,
           "tan(max_steering) / (2 half_wheelbase) [1/m]; inf without a steering limit")
      .def("validate", &Vehicle::validate)
      .def("__repr__", [](const Vehicle& v) {
        return "talus.Vehicle.from_dict(" + py::repr(vehicle_to_dict(v)).cast<std::string>() + ")";
      });
  m.def("load_vehicle", &load_vehicle, py::arg("path"),
        "Reads a vehicle YAML (or JSON) file; InputError naming the file and key.");
  m.def("parse_vehicle", &parse_vehicle, py::arg("yaml_text"), py::arg("source_name") = "text");

  m.def("speed_limits", &limits_on_arrays, py::arg("vehicle"), py::arg("kappa_n"),
        py::arg("kappa_g"), py::arg("k_t"), py::arg("k_q"), py::arg("k_r"),
        "Speed limits at stations of geometry (kappa_n, kappa_g [1/m]; k_t, k_q, k_r the "
        "vertical unit vector in the path frame), arrays broadcast together: dict of v_min, "
        "v_max [m/s], traversable, lower_binding, upper_binding (constraint names).");
  m.def("acceleration_bounds", &bounds_on_arrays, py::arg("vehicle"), py::arg("kappa_n"),
        py::arg("kappa_g"), py::arg("k_t"), py::arg("k_q"), py::arg("k_r"), py::arg("speed"),
        "Admissible tangential accelerations at stations and speeds [m/s], broadcast: dict of "
        "a_min, a_max [m/s^2], feasible, lower_binding, upper_binding, violated.");

  py::class_<VelocityLimits, std::shared_ptr<VelocityLimits>>(
      m, "VelocityLimits",
      "A vehicle's speed limits at every station of a path (talus::VelocityLimits); "
      "per-station values as arrays.")
      .def(py::init<const Vehicle&, const SurfacePath&, std::size_t>(), py::arg("vehicle"),
           py::arg("path"), py::arg("stations"),
           "Limits at `stations` stations equally spaced in the curve parameter.")
      .def_static("from_geometry", &limits_from_geometry, py::arg("vehicle"), py::arg("s"),
                  py::arg("kappa_n"), py::arg("kappa_g"), py::arg("k_t"), py::arg("k_q"),
                  py::arg("k_r"),
                  "Limits at stations the caller has sampled: arc length s [m] (increasing) "
                  "and the station geometry, 1-D arrays (VelocityLimits::compute(frames)).")
      .def("vehicle", &VelocityLimits::vehicle)
      .def("size", &VelocityLimits::size)
      .def("__len__", &VelocityLimits::size)
      .def("first_untraversable", &VelocityLimits::first_untraversable)
      .def(
          "acceleration_bounds",
          [](const VelocityLimits& l, std::size_t station, double speed) {
            if (station >= l.size()) throw py::index_error("station out of range");
            const AccelerationBounds b = l.acceleration_bounds(station, speed);
            return py::make_tuple(b.a_min, b.a_max, b.feasible);
          },
          py::arg("station"), py::arg("speed"), "(a_min, a_max, feasible) at one station")
      .def_property_readonly("s",
                             [](const VelocityLimits& l) {
                               return per_station(l, [&](std::size_t k) { return l.frame(k).s; });
                             })
      .def_property_readonly(
          "points",
          [](const VelocityLimits& l) {
            py::array_t<double> out({static_cast<py::ssize_t>(l.size()), py::ssize_t{3}});
            for (std::size_t k = 0; k < l.size(); ++k) {
              for (int c = 0; c < 3; ++c) out.mutable_data()[3 * k + c] = l.frame(k).point[c];
            }
            return out;
          },
          "(n, 3) station points x, y, z [m]")
      .def_property_readonly("kappa_n",
                             [](const VelocityLimits& l) {
                               return per_station(
                                   l, [&](std::size_t k) { return l.frame(k).kappa_n; });
                             })
      .def_property_readonly("kappa_g",
                             [](const VelocityLimits& l) {
                               return per_station(
                                   l, [&](std::size_t k) { return l.frame(k).kappa_g; });
                             })
      .def_property_readonly("k_t",
                             [](const VelocityLimits& l) {
                               return per_station(l, [&](std::size_t k) { return l.frame(k).k_t; });
                             })
      .def_property_readonly("k_q",
                             [](const VelocityLimits& l) {
                               return per_station(l, [&](std::size_t k) { return l.frame(k).k_q; });
                             })
      .def_property_readonly("k_r",
                             [](const VelocityLimits& l) {
                               return per_station(l, [&](std::size_t k) { return l.frame(k).k_r; });
                             })
      .def_property_readonly("v_min",
                             [](const VelocityLimits& l) {
                               return per_station(l,
                                                  [&](std::size_t k) { return l.limits(k).v_min; });
                             })
      .def_property_readonly("v_max",
                             [](const VelocityLimits& l) {
                               return per_station(l,
                                                  [&](std::size_t k) { return l.limits(k).v_max; });
                             })
      .def_property_readonly("traversable",
                             [](const VelocityLimits& l) {
                               py::array_t<bool> out(static_cast<py::ssize_t>(l.size()));
                               for (std::size_t k = 0; k < l.size(); ++k)
                                 out.mutable_data()[k] = l.limits(k).traversable;
                               return out;
                             })
      .def_property_readonly("lower_binding",
                             [](const VelocityLimits& l) {
                               std::vector<Constraint> c;
                               for (const SpeedLimits& s : l.all_limits())
                                 c.push_back(s.lower_binding);
                               return names(c);
                             })
      .def_property_readonly("upper_binding", [](const VelocityLimits& l) {
        std::vector<Constraint> c;
        for (const SpeedLimits& s : l.all_limits()) c.push_back(s.upper_binding);
        return names(c);
      });
}

}  // namespace talus::python
