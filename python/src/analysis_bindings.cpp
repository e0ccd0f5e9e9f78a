/// The knot analysis of analysis/ on numpy arrays.

#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "nodus/analysis/knot.hpp"
#include "nodus/analysis/knot_metrics.hpp"

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

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<int, py::array::c_style | py::array::forcecast>;

Eigen::VectorXd vector_of(const DoubleArray& a, py::ssize_t n, const char* name) {
  if (a.ndim() != 1 || a.shape(0) != n)
    throw py::value_error(std::string("contact column ") + name + ": expected " + std::to_string(n) +
                          " values");
  return Eigen::Map<const Eigen::VectorXd>(a.data(), n);
}

/// The contact table from a dict of columns (Simulation.contact_elements(), or the columns of
/// contact_final.csv: x_i, y_i, z_i instead of position_i; state as 0/1/2).
analysis::ContactTable table_of(const py::dict& c) {
  const auto column = [&](const char* name) {
    if (!c.contains(name)) throw py::value_error(std::string("contact: expected a column ") + name);
    DoubleArray a = DoubleArray::ensure(c[name]);
    if (!a) throw py::value_error(std::string("contact column ") + name + ": expected numbers");
    return a;
  };
  if (!c.contains("zone")) throw py::value_error("contact: expected a dict of columns with 'zone'");
  const DoubleArray zone = column("zone");
  const py::ssize_t n = zone.ndim() == 1 ? zone.shape(0) : -1;
  if (n < 0) throw py::value_error("contact column zone: expected a 1-D array");
  analysis::ContactTable t;
  t.resize(static_cast<std::size_t>(n));
  t.zone = vector_of(zone, n, "zone").cast<int>();
  for (const char* name : {"beam_i", "beam_j"})
    (std::string(name) == "beam_i" ? t.beam_i : t.beam_j) =
        c.contains(name) ? Eigen::VectorXi(vector_of(column(name), n, name).cast<int>())
                         : Eigen::VectorXi::Zero(n);
  t.zeta = vector_of(column("zeta"), n, "zeta");
  t.abscissa_i = vector_of(column("abscissa_i"), n, "abscissa_i");
  t.abscissa_j = vector_of(column("abscissa_j"), n, "abscissa_j");
  for (const char side : {'i', 'j'}) {
    analysis::Points& p = side == 'i' ? t.particle_i : t.particle_j;
    const std::string position = std::string("position_") + side;
    if (c.contains(position.c_str())) {
      const DoubleArray a = column(position.c_str());
      if (a.ndim() != 2 || a.shape(0) != n || a.shape(1) != 3)
        throw py::value_error("contact column " + position + ": expected an (n, 3) array");
      p = Eigen::Map<const analysis::Points>(a.data(), n, 3);
    } else {
      for (int k = 0; k < 3; ++k) {
        const std::string name = std::string(1, "xyz"[k]) + "_" + side;
        p.col(k) = vector_of(column(name.c_str()), n, name.c_str());
      }
    }
  }
  t.gap = vector_of(column("gap"), n, "gap");
  t.normal_force = vector_of(column("normal_force"), n, "normal_force");
  t.tangential_force = vector_of(column("tangential_force"), n, "tangential_force");
  t.state = c.contains("state") ? Eigen::VectorXi(vector_of(column("state"), n, "state").cast<int>())
                                : Eigen::VectorXi::Constant(n, analysis::kNoStatus);
  t.check();
  return t;
}

analysis::Centreline centreline_of(const DoubleArray& points, const DoubleArray& arc_length) {
  analysis::Centreline c;
  c.points = points_of(points);
  if (arc_length.ndim() != 1 || arc_length.shape(0) != static_cast<py::ssize_t>(c.points.size()))
    throw py::value_error("arc_length: expected one value per point");
  c.arc_length.assign(arc_length.data(), arc_length.data() + arc_length.shape(0));
  return c;
}

py::dict metrics_dict(const analysis::KnotMetrics& k) {
  py::dict d;
  d["zones"] = k.zones;
  d["contact_elements"] = k.contact_elements;
  d["elements_in_contact"] = k.elements_in_contact;
  d["intermediate_length"] = k.intermediate_length;
  d["max_normal"] = k.max_normal;
  d["total_normal"] = k.total_normal;
  d["max_tangential"] = k.max_tangential;
  d["total_tangential"] = k.total_tangential;
  d["tail_angle"] = k.tail_angle;
  d["loop_radius"] = k.loop_radius;
  d["loop_length"] = k.loop_length;
  d["max_penetration"] = k.max_penetration;
  d["s_a"] = k.s_a;
  d["s_b"] = k.s_b;
  const analysis::ReactionsTable& r = k.reactions;
  py::dict reactions;
  reactions["element"] = r.element;
  reactions["zone"] = Eigen::VectorXi(r.zone);
  reactions["zeta"] = Eigen::VectorXd(r.zeta);
  reactions["abscissa"] = Eigen::VectorXd(r.abscissa);
  reactions["s_i"] = Eigen::VectorXd(r.s_i);
  reactions["s_j"] = Eigen::VectorXd(r.s_j);
  reactions["midpoint"] = Eigen::MatrixXd(r.midpoint);
  reactions["normal"] = Eigen::VectorXd(r.normal);
  reactions["tangential"] = Eigen::VectorXd(r.tangential);
  reactions["state"] = Eigen::VectorXi(r.state);
  d["reactions"] = reactions;
  return d;
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
  m.def(
      "min_distance_between",
      [](const py::array_t<double, py::array::c_style | py::array::forcecast>& points1,
         const std::vector<double>& arc_length1,
         const py::array_t<double, py::array::c_style | py::array::forcecast>& points2,
         const std::vector<double>& arc_length2) {
        const analysis::CurveDistance d =
            analysis::min_distance_between(points_of(points1), arc_length1, points_of(points2), arc_length2);
        return py::make_tuple(d.distance, d.s1, d.s2);
      },
      py::arg("points1"), py::arg("arc_length1"), py::arg("points2"), py::arg("arc_length2"));
  m.def(
      "analyse_knot",
      [](const DoubleArray& points, const DoubleArray& arc_length, const py::dict& contact, double tail_chord,
         double min_spacing, int min_loop_nodes) {
        const analysis::Centreline c = centreline_of(points, arc_length);
        const analysis::ContactTable t = table_of(contact);
        analysis::KnotMetrics k;
        {
          py::gil_scoped_release release;
          k = analysis::analyse_knot(c, t, {tail_chord, min_spacing, min_loop_nodes});
        }
        return metrics_dict(k);
      },
      py::arg("points"), py::arg("arc_length"), py::arg("contact"), py::arg("tail_chord"),
      py::arg("min_spacing"), py::arg("min_loop_nodes"));
  m.def(
      "tail_angle",
      [](const DoubleArray& points, const DoubleArray& arc_length, double s_a, double s_b,
         double tail_chord) {
        return analysis::tail_angle(centreline_of(points, arc_length), s_a, s_b, tail_chord);
      },
      py::arg("points"), py::arg("arc_length"), py::arg("s_a"), py::arg("s_b"), py::arg("tail_chord"));
  m.def(
      "fit_circle",
      [](const DoubleArray& points) {
        const std::vector<Eigen::Vector3d> p = points_of(points);
        analysis::Points rows(static_cast<Eigen::Index>(p.size()), 3);
        for (std::size_t i = 0; i < p.size(); ++i) rows.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
        return analysis::fit_circle(rows);
      },
      py::arg("points"));
  m.def(
      "rod_radius",
      [](const std::vector<std::pair<DoubleArray, DoubleArray>>& centrelines,
         const std::vector<py::dict>& contacts, double default_radius) {
        std::vector<analysis::Centreline> c;
        for (const auto& [points, s] : centrelines) c.push_back(centreline_of(points, s));
        std::vector<analysis::ContactTable> t;
        for (const py::dict& d : contacts) t.push_back(table_of(d));
        return analysis::rod_radius(c, t, default_radius);
      },
      py::arg("centrelines"), py::arg("contacts"), py::arg("default_radius"));
}

}  // namespace nodus::python
