/// @file
/// core: ElevationGrid to and from numpy arrays, the ESRI ASCII reader and
/// writer, NODATA filling.
#include <cmath>
#include <string>

#include "bindings.hpp"
#include "talus/core/elevation_grid.hpp"
#include "talus/core/error.hpp"
#include "talus/core/esri_ascii.hpp"
#include "talus/core/terrain_generators.hpp"

namespace talus::python {
namespace {

/// The grid as an (nrows, ncols) array, row j from the south: a[j, i] = at(i, j).
/// NODATA nodes are `nodata` (NaN by default).
py::array_t<double> grid_to_array(const ElevationGrid& grid, double nodata) {
  const auto nx = static_cast<py::ssize_t>(grid.ncols()),
             ny = static_cast<py::ssize_t>(grid.nrows());
  py::array_t<double> out({ny, nx});
  auto a = out.mutable_unchecked<2>();
  for (py::ssize_t j = 0; j < ny; ++j) {
    for (py::ssize_t i = 0; i < nx; ++i) {
      const auto ci = static_cast<std::size_t>(i), cj = static_cast<std::size_t>(j);
      a(j, i) = grid.valid(ci, cj) ? grid.at(ci, cj) : nodata;
    }
  }
  return out;
}

py::array_t<bool> grid_mask(const ElevationGrid& grid) {
  const auto nx = static_cast<py::ssize_t>(grid.ncols()),
             ny = static_cast<py::ssize_t>(grid.nrows());
  py::array_t<bool> out({ny, nx});
  auto a = out.mutable_unchecked<2>();
  for (py::ssize_t j = 0; j < ny; ++j) {
    for (py::ssize_t i = 0; i < nx; ++i) {
      a(j, i) = grid.valid(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
    }
  }
  return out;
}

/// A grid from an (nrows, ncols) array, row 0 the southernmost; NaN entries
/// (and entries where `valid` is False) are NODATA.
ElevationGrid grid_from_array(const DoubleArray& z, double cellsize, double x_min, double y_min,
                              const py::object& valid) {
  if (z.ndim() != 2) throw py::type_error("z must be a 2-D array (nrows, ncols), row 0 the south");
  py::array_t<bool, py::array::c_style | py::array::forcecast> mask;
  const bool has_mask = !valid.is_none();
  if (has_mask) {
    mask = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(valid);
    if (!mask || mask.ndim() != 2 || mask.shape(0) != z.shape(0) || mask.shape(1) != z.shape(1)) {
      throw py::type_error("valid must be a boolean array of z's shape");
    }
  }
  ElevationGrid grid(static_cast<std::size_t>(z.shape(1)), static_cast<std::size_t>(z.shape(0)),
                     cellsize, x_min, y_min);
  const auto a = z.unchecked<2>();
  for (py::ssize_t j = 0; j < z.shape(0); ++j) {
    for (py::ssize_t i = 0; i < z.shape(1); ++i) {
      const auto ci = static_cast<std::size_t>(i), cj = static_cast<std::size_t>(j);
      const double value = a(j, i);
      if (std::isnan(value) || (has_mask && !mask.at(j, i))) {
        grid.set_void(ci, cj);
        continue;
      }
      if (!(std::abs(value) <= kMaxElevationMagnitude)) {
        throw InputError("elevation at node (" + std::to_string(i) + ", " + std::to_string(j) +
                         ") is " + std::to_string(value) + "; expected a finite |z| <= 1e9 m");
      }
      grid.set(ci, cj, value);
    }
  }
  return grid;
}

}  // namespace

void bind_core(py::module_& m) {
  py::class_<ElevationGrid>(m, "ElevationGrid",
                            "A regular grid of elevations [m] with a NODATA mask "
                            "(talus::ElevationGrid). Node (i, j), column i from the west, row j "
                            "from the south, sits at (x_min + i h, y_min + j h). As an array: "
                            "shape (nrows, ncols), a[j, i] = node (i, j), row 0 the south.")
      .def(py::init<std::size_t, std::size_t, double, double, double, double>(), py::arg("ncols"),
           py::arg("nrows"), py::arg("cellsize"), py::arg("x_min"), py::arg("y_min"),
           py::arg("fill") = 0.0)
      .def_static("from_array", &grid_from_array, py::arg("z"), py::arg("cellsize"),
                  py::arg("x_min"), py::arg("y_min"), py::arg("valid") = py::none(),
                  "Grid from an (nrows, ncols) array, z[j, i] = node (i, j), row 0 the south. "
                  "NaN entries, and entries where `valid` is False, are NODATA.")
      .def("to_array", &grid_to_array, py::arg("nodata") = std::nan(""),
           "(nrows, ncols) float64 array, a[j, i] = node (i, j); NODATA nodes are `nodata`.")
      .def("valid_mask", &grid_mask, "(nrows, ncols) bool array: False at NODATA nodes.")
      .def_property_readonly("ncols", &ElevationGrid::ncols)
      .def_property_readonly("nrows", &ElevationGrid::nrows)
      .def_property_readonly(
          "shape", [](const ElevationGrid& g) { return py::make_tuple(g.nrows(), g.ncols()); },
          "(nrows, ncols), the shape of to_array()")
      .def_property_readonly("cellsize", &ElevationGrid::cellsize)
      .def_property_readonly("x_min", &ElevationGrid::x_min)
      .def_property_readonly("y_min", &ElevationGrid::y_min)
      .def_property_readonly("x_max", &ElevationGrid::x_max)
      .def_property_readonly("y_max", &ElevationGrid::y_max)
      .def("node_position", &ElevationGrid::node_position, py::arg("i"), py::arg("j"))
      .def("void_count", &ElevationGrid::void_count)
      .def("elevation_range", &ElevationGrid::elevation_range,
           "(min, max) of the valid elevations, or None if every node is NODATA")
      .def(
          "contains",
          [](const ElevationGrid& g, double x, double y) {
            return g.contains({x, y});
          },
          py::arg("x"), py::arg("y"))
      .def(
          "bilinear",
          [](const ElevationGrid& g, double x, double y) {
            return g.bilinear({x, y});
          },
          py::arg("x"), py::arg("y"))
      .def("__repr__", [](const ElevationGrid& g) {
        return "<talus.ElevationGrid " + std::to_string(g.ncols()) + " x " +
               std::to_string(g.nrows()) + " nodes, cellsize " +
               py::repr(py::float_(g.cellsize())).cast<std::string>() + " m>";
      });

  py::enum_<VoidFill>(m, "VoidFill").value("NEAREST", VoidFill::kNearest);
  m.def("fill_voids", &fill_voids, py::arg("grid"), py::arg("method") = VoidFill::kNearest,
        "A copy of `grid` with every NODATA node filled (talus::fill_voids).");
  m.def("read_esri_ascii", py::overload_cast<const std::string&>(&read_esri_ascii), py::arg("path"),
        "Reads an ESRI ASCII grid (.asc); InputError naming the file and line on any deviation.");
  m.def("write_esri_ascii",
        py::overload_cast<const ElevationGrid&, const std::string&, double>(&write_esri_ascii),
        py::arg("grid"), py::arg("path"), py::arg("nodata_value") = -9999.0,
        "Writes `grid` as ESRI ASCII; values round-trip exactly.");
  m.def(
      "generate_fractal_terrain",
      [](std::size_t ncols, std::size_t nrows, double cellsize, double x_min, double y_min,
         double fractal_dimension, double height_scale, double undulation_amplitude,
         double undulation_wavelength, std::size_t peaks, double peak_height, double peak_radius,
         std::uint64_t seed) {
        FractalTerrainOptions o;
        o.shape = {ncols, nrows, cellsize, x_min, y_min};
        o.fractal_dimension = fractal_dimension;
        o.height_scale = height_scale;
        o.undulation_amplitude = undulation_amplitude;
        o.undulation_wavelength = undulation_wavelength;
        o.peaks = peaks;
        o.peak_height = peak_height;
        o.peak_radius = peak_radius;
        o.seed = seed;
        return generate_fractal_terrain(o);
      },
      py::kw_only(), py::arg("ncols") = 129, py::arg("nrows") = 129, py::arg("cellsize") = 0.24,
      py::arg("x_min") = 0.0, py::arg("y_min") = 0.0, py::arg("fractal_dimension") = 2.05,
      py::arg("height_scale") = 4.2, py::arg("undulation_amplitude") = 0.0,
      py::arg("undulation_wavelength") = 0.0, py::arg("peaks") = 0, py::arg("peak_height") = 0.0,
      py::arg("peak_radius") = 1.0, py::arg("seed") = 1,
      "A seeded fractal terrain (talus::generate_fractal_terrain, `talus terrain generate "
      "fractal`): the same grid for the same arguments, keyword arguments only.");
}

}  // namespace talus::python
