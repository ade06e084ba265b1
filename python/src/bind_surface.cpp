/// @file
/// bspline: the BPatch surface evaluated on arrays of (x, y), planar B-spline
/// curves, and paths lifted onto a surface.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "talus/bspline/bpatch.hpp"
#include "talus/bspline/bspline_curve.hpp"
#include "talus/bspline/knot_vector.hpp"
#include "talus/bspline/surface_path.hpp"

namespace talus::python {
namespace {

/// Shape of `a` followed by `extra` trailing dimensions.
std::vector<py::ssize_t> shape_with(const DoubleArray& a,
                                    std::initializer_list<py::ssize_t> extra) {
  std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
  shape.insert(shape.end(), extra);
  return shape;
}

/// Evaluates the surface at every (x, y) of the broadcast arrays and writes
/// `per_point` numbers per point through `write(SurfacePoint, double* out)`.
template <class Write>
py::array_t<double> evaluate_on(const BPatch& patch, const py::object& x, const py::object& y,
                                std::initializer_list<py::ssize_t> extra, std::size_t per_point,
                                Write write) {
  const auto [bx, by] = broadcast(x, y);
  py::array_t<double> out(shape_with(bx, extra));
  const double* px = bx.data();
  const double* py_ = by.data();
  double* o = out.mutable_data();
  for (py::ssize_t k = 0; k < bx.size(); ++k) {
    write(patch.evaluate(Vec2(px[k], py_[k])), o + static_cast<std::size_t>(k) * per_point);
  }
  return out;
}

py::array_t<double> curve_knots(const Curve2& c) {
  return to_array(c.knots().knots());
}

}  // namespace

void bind_surface(py::module_& m) {
  py::class_<BPatch, std::shared_ptr<BPatch>>(
      m, "BPatch",
      "The smooth terrain surface z(x, y): a bicubic B-spline over an elevation grid "
      "(talus::BPatch). Evaluation methods take numbers or arrays x, y (broadcast together) "
      "and raise InputError at the first point outside the domain.")
      .def_static("interpolate", &BPatch::interpolate, py::arg("grid"), py::arg("degree") = 3,
                  "Interpolating fit, exact at every node (a grid without NODATA, >= 4 x 4; "
                  "degree 3, bicubic, or 5, biquintic, >= 6 x 6).")
      .def_property_readonly("degree", &BPatch::degree)
      .def_static("fit_smoothing", &BPatch::fit_smoothing, py::arg("grid"), py::arg("smoothing"),
                  "Smoothing fit with curvature weight lambda > 0 (dimensionless).")
      .def_property_readonly("x_min", &BPatch::x_min)
      .def_property_readonly("y_min", &BPatch::y_min)
      .def_property_readonly("x_max", &BPatch::x_max)
      .def_property_readonly("y_max", &BPatch::y_max)
      .def_property_readonly("cellsize", &BPatch::cellsize)
      .def_property_readonly("ncols", &BPatch::ncols)
      .def_property_readonly("nrows", &BPatch::nrows)
      .def("patches", &BPatch::patches)
      .def("control_points", &BPatch::control_points,
           "(ncols + 2) x (nrows + 2) control values; entry (a, b) weights the basis functions "
           "centred on node (a - 1, b - 1)")
      .def(
          "contains",
          [](const BPatch& p, double x, double y) {
            return p.contains({x, y});
          },
          py::arg("x"), py::arg("y"))
      .def(
          "on_data",
          [](const BPatch& p, double x, double y) {
            return p.on_data({x, y});
          },
          py::arg("x"), py::arg("y"))
      .def(
          "height",
          [](const BPatch& p, const py::object& x, const py::object& y) {
            return evaluate_on(p, x, y, {}, 1,
                               [](const SurfacePoint& s, double* o) { o[0] = s.z; });
          },
          py::arg("x"), py::arg("y"), "z(x, y) [m], the shape of x and y broadcast")
      .def(
          "gradient",
          [](const BPatch& p, const py::object& x, const py::object& y) {
            return evaluate_on(p, x, y, {2}, 2, [](const SurfacePoint& s, double* o) {
              o[0] = s.gradient.x();
              o[1] = s.gradient.y();
            });
          },
          py::arg("x"), py::arg("y"), "(z_x, z_y) [-], shape (..., 2)")
      .def(
          "hessian",
          [](const BPatch& p, const py::object& x, const py::object& y) {
            return evaluate_on(p, x, y, {2, 2}, 4, [](const SurfacePoint& s, double* o) {
              o[0] = s.hessian(0, 0);
              o[1] = s.hessian(0, 1);
              o[2] = s.hessian(1, 0);
              o[3] = s.hessian(1, 1);
            });
          },
          py::arg("x"), py::arg("y"), "[[z_xx, z_xy], [z_xy, z_yy]] [1/m], shape (..., 2, 2)")
      .def(
          "normal",
          [](const BPatch& p, const py::object& x, const py::object& y) {
            // The upward unit normal, computed as the path frames compute theirs
            // (bspline/lifted_geometry.hpp), so the two agree bit for bit.
            return evaluate_on(p, x, y, {3}, 3, [](const SurfacePoint& s, double* o) {
              const Vec3 up(-s.gradient.x(), -s.gradient.y(), 1.0);
              const Vec3 n = up / std::sqrt(up.squaredNorm());
              o[0] = n.x();
              o[1] = n.y();
              o[2] = n.z();
            });
          },
          py::arg("x"), py::arg("y"), "upward unit normal (-z_x, -z_y, 1) / norm, shape (..., 3)")
      .def(
          "third_derivatives",
          [](const BPatch& p, double x, double y) {
            return p.third_derivatives({x, y});
          },
          py::arg("x"), py::arg("y"), "(z_xxx, z_xxy, z_xyy, z_yyy) [1/m^2] at one point")
      .def("__repr__", [](const BPatch& p) {
        return "<talus.BPatch " + std::to_string(p.ncols()) + " x " + std::to_string(p.nrows()) +
               " nodes>";
      });

  py::class_<Curve2>(m, "Curve2",
                     "A planar B-spline curve (talus::Curve2): knots, (n, 2) control points.")
      .def(py::init([](int degree, const std::vector<double>& knots, const DoubleArray& control) {
             return Curve2(KnotVector(degree, knots), to_points(control, "control_points"));
           }),
           py::arg("degree"), py::arg("knots"), py::arg("control_points"))
      .def_static(
          "interpolate",
          [](const DoubleArray& points, int degree) {
            return Curve2::interpolate(to_points(points, "points"), degree);
          },
          py::arg("points"), py::arg("degree") = 3,
          "Curve through (n, 2) points, chord-length parameters in [0, 1].")
      .def_property_readonly("degree", &Curve2::degree)
      .def_property_readonly("knots", &curve_knots)
      .def_property_readonly("control_points",
                             [](const Curve2& c) { return to_array(c.control_points()); })
      .def_property_readonly("parameter_begin", &Curve2::parameter_begin)
      .def_property_readonly("parameter_end", &Curve2::parameter_end)
      .def(
          "evaluate",
          [](const Curve2& c, const DoubleArray& t) {
            std::vector<py::ssize_t> shape(t.shape(), t.shape() + t.ndim());
            shape.push_back(2);
            py::array_t<double> out(shape);
            double* o = out.mutable_data();
            for (py::ssize_t k = 0; k < t.size(); ++k) {
              const Vec2 p = c.evaluate(t.data()[k]);
              o[2 * k] = p.x();
              o[2 * k + 1] = p.y();
            }
            return out;
          },
          py::arg("t"), "C(t), shape t.shape + (2,)");

  py::class_<SurfacePath, std::shared_ptr<SurfacePath>>(
      m, "SurfacePath",
      "A planar curve lifted onto a BPatch with its 3-D arc length (talus::SurfacePath); "
      "holds the surface (a BPatch copy shares its coefficients).")
      .def(py::init<const BPatch&, Curve2>(), py::arg("surface"), py::arg("curve"))
      .def("curve", &SurfacePath::curve)
      .def("length", &SurfacePath::length, "3-D length [m]");
}

}  // namespace talus::python
