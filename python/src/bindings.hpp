#pragma once
/// @file
/// Shared pieces of the pybind11 module `talus` (python/README.md): one
/// bind_* function per C++ layer, and the array conversions they all use.
/// The binding is a thin layer: every computation is the C++ library's; these
/// helpers only copy between std::vector / Eigen and numpy arrays.
#include <cstddef>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "talus/core/types.hpp"

namespace talus::python {

namespace py = pybind11;

/// A C-contiguous float64 array (copying or converting when needed).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

void bind_core(py::module_& m);
void bind_surface(py::module_& m);
void bind_dynamics(py::module_& m);
void bind_optimal(py::module_& m);
void bind_kinematic(py::module_& m);
void bind_simulation(py::module_& m);

/// A 1-D float64 array holding a copy of `values`.
inline py::array_t<double> to_array(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

/// An (n, 2) float64 array of points.
inline py::array_t<double> to_array(const std::vector<Vec2>& points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{2}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t k = 0; k < points.size(); ++k) {
    a(static_cast<py::ssize_t>(k), 0) = points[k].x();
    a(static_cast<py::ssize_t>(k), 1) = points[k].y();
  }
  return out;
}

/// Points from an (n, 2) array-like; TypeError naming `what` otherwise.
std::vector<Vec2> to_points(const DoubleArray& array, const char* what);

/// `x` and `y` broadcast against each other (numpy rules), as C-contiguous
/// float64 arrays of one shape.
std::pair<DoubleArray, DoubleArray> broadcast(const py::object& x, const py::object& y);

/// A list of references into `parent`'s storage, each keeping `parent` alive.
template <class T>
py::list reference_list(std::vector<T>& items, const py::object& parent) {
  py::list out;
  for (T& item : items)
    out.append(py::cast(&item, py::return_value_policy::reference_internal, parent));
  return out;
}

}  // namespace talus::python
