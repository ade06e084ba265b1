/// @file
/// The module `talus`: Talus's exceptions as Python exception classes, then
/// one bind_* call per layer (core, surface, dynamics, optimal, simulation, kinematic).
#include <exception>
#include <string>
#include <utility>

#include "bindings.hpp"
#include "talus/core/error.hpp"
#include "talus/kinematic/baseline_options.hpp"

namespace talus::python {
namespace {

// The exception classes, created once at import and kept for the process's life
// (the translator below is a plain function, so they cannot be captured).
PyObject* error_type = nullptr;
PyObject* input_error_type = nullptr;
PyObject* baseline_option_error_type = nullptr;
PyObject* infeasible_error_type = nullptr;
PyObject* solver_error_type = nullptr;

PyObject* new_exception(py::module_& m, const char* name, py::handle bases, const char* doc) {
  const std::string qualified = std::string("talus.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.attr(name) = py::handle(type);  // the module takes its own reference; `type` is ours
  return type;
}

/// C++ exception -> the Python class of the same name, with the same message.
void translate(std::exception_ptr exception) {
  try {
    if (exception) std::rethrow_exception(exception);
  } catch (const BaselineOptionError& e) {
    py::object instance = py::handle(baseline_option_error_type)(e.what());
    instance.attr("key") = e.key();
    instance.attr("reason") = e.reason();
    PyErr_SetObject(baseline_option_error_type, instance.ptr());
  } catch (const InputError& e) {
    PyErr_SetString(input_error_type, e.what());
  } catch (const InfeasibleError& e) {
    PyErr_SetString(infeasible_error_type, e.what());
  } catch (const SolverError& e) {
    PyErr_SetString(solver_error_type, e.what());
  } catch (const Error& e) {
    PyErr_SetString(error_type, e.what());
  }
}

void bind_errors(py::module_& m) {
  error_type = new_exception(m, "Error", PyExc_RuntimeError,
                             "Base of every exception Talus raises (talus::Error); str() is the "
                             "C++ message, the one the talus CLI prints.");
  input_error_type = new_exception(
      m, "InputError", py::make_tuple(py::handle(error_type), py::handle(PyExc_ValueError)),
      "Bad input: a malformed file, a NaN, a point off the map, an invalid option "
      "(talus::InputError).");
  baseline_option_error_type = new_exception(m, "BaselineOptionError", py::handle(input_error_type),
                                             "A bad value for one baseline option; .key and "
                                             ".reason name it (talus::BaselineOptionError).");
  infeasible_error_type =
      new_exception(m, "InfeasibleError", py::handle(error_type),
                    "A well-formed but physically impossible request (talus::InfeasibleError).");
  solver_error_type =
      new_exception(m, "SolverError", py::handle(error_type),
                    "A numerical solver failed; the message names it (talus::SolverError).");
  py::register_exception_translator(&translate);
}

}  // namespace

std::vector<Vec2> to_points(const DoubleArray& array, const char* what) {
  if (array.ndim() != 2 || array.shape(1) != 2) {
    throw py::type_error(std::string(what) + " must be an (n, 2) array of x, y [m]");
  }
  std::vector<Vec2> points(static_cast<std::size_t>(array.shape(0)));
  const auto a = array.unchecked<2>();
  for (py::ssize_t k = 0; k < array.shape(0); ++k) {
    points[static_cast<std::size_t>(k)] = Vec2(a(k, 0), a(k, 1));
    if (!points[static_cast<std::size_t>(k)].allFinite()) {
      throw InputError(std::string(what) + "[" + std::to_string(k) +
                       "] is not finite: points must be finite x, y [m]");
    }
  }
  return points;
}

std::pair<DoubleArray, DoubleArray> broadcast(const py::object& x, const py::object& y) {
  const py::tuple both = py::module_::import("numpy").attr("broadcast_arrays")(x, y);
  DoubleArray bx = DoubleArray::ensure(both[0]), by = DoubleArray::ensure(both[1]);
  if (!bx || !by) throw py::type_error("x and y must be numbers or arrays of numbers [m]");
  return {std::move(bx), std::move(by)};
}

}  // namespace talus::python

PYBIND11_MODULE(talus, m) {
  namespace tp = talus::python;
  m.doc() =
      "Talus: time-optimal trajectory planning of ground vehicles over rough terrain.\n\n"
      "A thin binding of the C++ library: the same classes, functions, fields and messages "
      "(C++ methods stay methods, fields are attributes; per-station results are numpy "
      "arrays). SI units throughout: x east, y north, z up [m].";
  m.attr("__version__") = TALUS_VERSION;
  tp::bind_errors(m);
  tp::bind_core(m);
  tp::bind_surface(m);
  tp::bind_dynamics(m);
  tp::bind_optimal(m);
  tp::bind_simulation(m);
  tp::bind_kinematic(m);
}
