/// The knot analysis of analysis/ on numpy arrays.

#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "nodus/analysis/knot.hpp"

namespace py = pybind11;

namespace nodus::python {
namespace {

/// The rows of an (n, 3) array as points.
std::vector<Eigen::Vector3d> points_of(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
  if (a.ndim() != 2 || a.shape(1) != 3) throw py::value_error("expected an (n, 3) array of points");
  std::vector<Eigen::Vector3d> points(static_cast<std::size_t>(a.shape(0)));
  const auto v = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    points[static_cast<std::size_t>(i)] = {v(i, 0), v(i, 1), v(i, 2)};
  return points;
}

py::dict invariant_dict(const analysis::KnotInvariant& k) {
  py::dict d;
  d["coefficients"] = k.coefficients;
  d["polynomial"] = k.to_string();
  d["determinant"] = k.determinant();
  d["crossings"] = k.crossings;
  d["direction"] = Eigen::Vector3d(k.direction);
  d["unknot"] = k.is_unknot();
  d["trefoil"] = k.is_trefoil();
  return d;
}

}  // namespace

void bind_analysis(py::module_& m) {
  m.def(
      "knot_invariant",
      [](const py::array_t<double, py::array::c_style | py::array::forcecast>& points) {
        std::vector<Eigen::Vector3d> p = points_of(points);
        analysis::KnotInvariant k;
        {
          py::gil_scoped_release release;
          k = analysis::knot_invariant(p);
        }
        return invariant_dict(k);
      },
      py::arg("points"));
  m.def(
      "min_self_distance",
      [](const py::array_t<double, py::array::c_style | py::array::forcecast>& points,
         const std::vector<double>& arc_length, double separation) {
        const analysis::SelfDistance d =
            analysis::min_self_distance(points_of(points), arc_length, separation);
        return py::make_tuple(d.distance, d.s1, d.s2);
      },
      py::arg("points"), py::arg("arc_length"), py::arg("separation"));
}

}  // namespace nodus::python
