#pragma once
/// @file
/// Python attributes, keyword arguments and descriptions generated from a
/// declared parameter table (talus/core/parameter_table.hpp): the names,
/// bounds and documentation are the table's, so Python says what the CLI
/// says. A value of the wrong type or out of bounds raises ValueError
/// (talus::InputError) naming the parameter.
#include <string>
#include <variant>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "talus/core/error.hpp"
#include "talus/core/parameter_table.hpp"

namespace talus::python {

namespace py = pybind11;

/// `value` as the kind a parameter holds; InputError naming `name` and what it
/// `accepts` when it is not one.
inline ParameterValue parameter_value_from_python(ParameterKind kind, const std::string& name,
                                                  const std::string& accepts,
                                                  const py::handle& value) {
  const bool is_bool = py::isinstance<py::bool_>(value);
  const bool is_int = py::isinstance<py::int_>(value) && !is_bool;
  try {
    switch (kind) {
      case ParameterKind::kFlag:
        if (is_bool) return value.cast<bool>();
        break;
      case ParameterKind::kInteger:
        if (is_int) return value.cast<long long>();
        break;
      case ParameterKind::kReal:
        if (is_int || py::isinstance<py::float_>(value)) return value.cast<double>();
        break;
      case ParameterKind::kChoice:
        if (py::isinstance<py::str>(value)) return value.cast<std::string>();
        break;
      case ParameterKind::kIntegerList:
        if (!py::isinstance<py::str>(value) && py::isinstance<py::sequence>(value))
          return value.cast<std::vector<long long>>();
        break;
    }
  } catch (const py::cast_error&) {
  }
  throw InputError(name + " must be " + accepts + ", got " + py::repr(value).cast<std::string>());
}

inline py::object parameter_value_to_python(const ParameterValue& value) {
  return std::visit([](const auto& v) { return py::object(py::cast(v)); }, value);
}

template <class Options>
void set_parameter(const ParameterTable<Options>& table, Options& options, const std::string& name,
                   const py::handle& value) {
  const Parameter<Options>& p = table.at(name);
  table.set(options, name,
            parameter_value_from_python(p.kind, name, ParameterTable<Options>::accepted(p), value));
}

/// {name: value} of every parameter of `options`.
template <class Options>
py::dict parameter_values(const ParameterTable<Options>& table, const Options& options) {
  py::dict out;
  for (const auto& [name, value] : table.values(options))
    out[py::str(name)] = parameter_value_to_python(value);
  return out;
}

/// A read-write attribute per parameter, documented by the table.
template <class Options, class... Extra>
void add_parameter_attributes(py::class_<Options, Extra...>& cls,
                              const ParameterTable<Options>& table) {
  for (const Parameter<Options>& p : table.entries()) {
    const std::string name = p.name;
    // The table outlives the module (a function-local static), so its
    // strings can back pybind11's const char* names and docs.
    cls.def_property(
        p.name.c_str(),
        [&table, name](const Options& o) {
          return parameter_value_to_python(table.at(name).get(o));
        },
        [&table, name](Options& o, const py::object& value) {
          set_parameter(table, o, name, value);
        },
        p.doc.c_str());
  }
}

/// [{name, kind, doc, default, lower, upper, choices, cli}] of the table.
template <class Options>
py::list describe_parameters(const ParameterTable<Options>& table) {
  using Table = ParameterTable<Options>;
  py::list out;
  for (const Parameter<Options>& p : table.entries()) {
    py::dict d;
    d["name"] = p.name;
    d["kind"] = std::string(to_string(p.kind));
    d["doc"] = p.doc;
    d["accepts"] = Table::accepted(p);
    d["default"] = parameter_value_to_python(Table::default_value(p));
    d["lower"] = p.lower;
    d["upper"] = p.upper;
    d["choices"] = p.kind == ParameterKind::kInteger ? py::cast(p.allowed) : py::cast(p.choices);
    d["cli"] = Table::spelled(p, ParameterSpelling::kCli);
    out.append(d);
  }
  return out;
}

}  // namespace talus::python
