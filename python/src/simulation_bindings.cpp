/// Simulation: a scenario stepped from Python, its state as numpy arrays.
///
/// The node arrays (positions, directors) are read-only views of the last converged state, without a copy:
/// the state vector keeps its memory for the life of the Simulation (a converged step overwrites it in
/// place), and each view keeps the Simulation alive. They show the state as it is when read, so a view
/// taken before a step shows the state after it: copy (numpy.array(view)) to keep a state. Everything else
/// is computed on request and returned as new arrays.

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "interrupts.hpp"
#include "nodus/analysis/knot.hpp"
#include "nodus/beam/strain_measures.hpp"
#include "nodus/output/contact_table.hpp"
#include "nodus/output/logging.hpp"
#include "nodus/simulation/simulation.hpp"

namespace py = pybind11;

namespace nodus::python {
namespace {

/// One converged step as a dict (the columns of steps.csv; reactions per condition name).
py::dict step_dict(const simulation::Simulation& sim, const simulation::StepRecord& r) {
  py::dict d;
  d["step"] = r.step;
  d["stage"] = sim.scenario().stages.at(static_cast<std::size_t>(r.stage)).name;
  d["stage_index"] = r.stage;
  d["time"] = r.time;
  d["newton_iterations"] = r.newton_iterations;
  d["cutbacks"] = r.cutbacks;
  d["residual"] = r.residual;
  d["increment"] = r.increment;
  d["zones"] = r.zones;
  d["contact_elements"] = r.contact_elements;
  d["detections"] = r.detections;
  d["normal_iterations"] = r.normal_iterations;
  d["penetration_ratio"] = r.penetration_ratio;
  d["normal_force"] = r.normal_force;
  d["tangential_force"] = r.tangential_force;
  d["slipping"] = r.slipping;
  d["loops_converged"] = r.loops_converged;
  d["stabilization_force"] = r.stabilization_force;
  d["min_orientation"] = r.min_orientation;
  d["min_chord"] = r.min_chord;
  d["min_clearance"] = r.min_clearance;
  d["ends_stage"] = r.ends_stage;
  d["step_size"] = r.step_size;
  d["entered"] = r.regime_changes.entered;
  d["left"] = r.regime_changes.left;
  d["to_slip"] = r.regime_changes.to_slip;
  d["to_stick"] = r.regime_changes.to_stick;
  d["cutback_causes"] = r.cutback_causes;
  py::dict reactions;
  for (std::size_t c = 0; c < r.sections.size(); ++c) {
    py::dict f;
    f["force"] = Eigen::Vector3d(r.sections[c].force);
    f["moment"] = Eigen::Vector3d(r.sections[c].moment);
    reactions[py::str(sim.conditions().name(static_cast<int>(c)))] = f;
  }
  d["reactions"] = reactions;
  // Rigid bodies (docs/bodies.md): where each is, and what it exerts on its bound sections.
  py::dict bodies;
  const Eigen::VectorXd& x = sim.state();
  for (std::size_t b = 0; b < r.bodies.size(); ++b) {
    const int dof = sim.model().body_dof(static_cast<int>(b));
    py::dict body;
    body["position"] = Eigen::Vector3d(x.segment<3>(dof));
    body["rotation"] = Eigen::Vector3d(x.segment<3>(dof + 3));
    body["force"] = Eigen::Vector3d(r.bodies[b].force);
    body["moment"] = Eigen::Vector3d(r.bodies[b].moment);
    body["error"] = r.bodies[b].error;
    body["tie"] = r.bodies[b].tie;
    bodies[py::str(sim.model().body(static_cast<int>(b)).name)] = body;
  }
  d["bodies"] = bodies;
  return d;
}

/// Calls the Python step callback (with the GIL) and the stop test of Simulation.run_stage.
class CallbackObserver final : public simulation::StepObserver {
 public:
  CallbackObserver(py::object callback, Interrupts& interrupts, std::optional<py::dict>& last)
      : callback_(std::move(callback)), interrupts_(interrupts), last_(last) {}
  void on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) override {
    py::gil_scoped_acquire gil;
    py::dict d = step_dict(sim, record);
    last_ = d;
    if (callback_.is_none() || interrupts_.pending()) return;
    try {
      const py::object result = callback_(d);
      if (result.ptr() == Py_False) stop_ = true;  // False stops the run; anything else goes on
    } catch (py::error_already_set& e) {
      interrupts_.keep(std::move(e));
    }
  }
  bool stop() const { return stop_; }

 private:
  py::object callback_;
  Interrupts& interrupts_;
  std::optional<py::dict>& last_;
  bool stop_ = false;
};

class PySimulation {
 public:
  explicit PySimulation(const ScenarioHandle& scenario) : sim_(*scenario) {
    for (int n = 0; n < sim_.model().num_nodes(); ++n)
      if (sim_.model().node_dof(n) != 9 * n)
        throw std::logic_error("the beam nodes are not the first blocks");
  }

  const simulation::Simulation& sim() const { return sim_; }
  int num_stages() const { return static_cast<int>(sim_.scenario().stages.size()); }
  bool finished() const { return sim_.progress().stage >= num_stages() || !failure_.empty(); }
  const std::string& failure() const { return failure_; }
  const std::optional<py::dict>& last_step() const { return last_; }

  /// Runs until `stop_when` says so after a step, the callback returns False, or the end; returns the number
  /// of steps converged.
  int advance(std::function<bool(const simulation::StepRecord&)> stop_when, int max_steps,
              const py::object& callback) {
    if (finished()) return 0;  // every stage done, or the run failed (failure())
    // The GIL is released while the run goes on: another thread, or the step callback, calling into this
    // Simulation would read or change what the run is changing.
    if (running_)
      throw std::runtime_error("this Simulation is already running (from another thread or its callback)");
    struct Running {
      bool& flag;
      explicit Running(bool& f) : flag(f) { flag = true; }
      ~Running() { flag = false; }
    } running(running_);
    output::use_stderr_logger();
    Interrupts interrupts;
    CallbackObserver observer(callback, interrupts, last_);
    simulation::RunOptions options;
    options.stop_after_steps = max_steps;
    options.stop_when = [&](const simulation::StepRecord& r) {
      return observer.stop() || (stop_when && stop_when(r));
    };
    options.cancel = [&interrupts] { return interrupts.poll(); };
    simulation::RunSummary summary;
    try {
      py::gil_scoped_release release;
      summary = sim_.run({&observer}, options);
    } catch (...) {
      interrupts.rethrow();  // a Ctrl-C (or a callback's error) comes first
      throw;
    }
    interrupts.rethrow();
    if (!summary.interrupted && !summary.converged) failure_ = summary.failure;
    return summary.new_steps;
  }

  /// Read-only (n, 3) view of field `k` (0: r, 1: d1, 2: d2) of every node, owned by `self`.
  py::array node_field(py::object self, int k) const {
    const Eigen::VectorXd& x = sim_.state();
    const auto n = static_cast<py::ssize_t>(sim_.model().num_nodes());
    py::array_t<double> view({n, py::ssize_t{3}},
                             {py::ssize_t{9 * sizeof(double)}, py::ssize_t{sizeof(double)}}, x.data() + 3 * k,
                             self);
    py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return view;
  }

 private:
  simulation::Simulation sim_;
  std::optional<py::dict> last_;
  std::string failure_;
  bool running_ = false;  ///< advance() is under way (its GIL released)
};

template <class T>
py::array_t<T> vector_array(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::array_t<double> rows3(const std::vector<Eigen::Vector3d>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int c = 0; c < 3; ++c) m(static_cast<py::ssize_t>(i), c) = v[i][c];
  return a;
}

py::dict contact_arrays(const simulation::Simulation& sim) {
  const contact::ContactGeometry empty;
  const contact::ContactGeometry& g = sim.contact() ? *sim.contact() : empty;
  const std::vector<simulation::ContactState>& states = sim.contact_states();
  const bool forces = states.size() == g.elements.size();
  std::vector<int> zone, beam_i, beam_j, element_i, element_j, status;
  std::vector<double> zeta, abscissa_i, abscissa_j, gap, normal_force, tangential_force;
  std::vector<Eigen::Vector3d> position_i, position_j, normal, friction, intermediate;
  for (std::size_t k = 0; k < g.elements.size(); ++k) {
    const contact::ContactElement& e = g.elements[k];
    zone.push_back(e.zone);
    beam_i.push_back(e.particle_i.beam);
    beam_j.push_back(e.particle_j.beam);
    element_i.push_back(e.particle_i.element);
    element_j.push_back(e.particle_j.element);
    zeta.push_back(e.zeta);
    abscissa_i.push_back(e.particle_i.abscissa);
    abscissa_j.push_back(e.particle_j.abscissa);
    position_i.push_back(e.position_i);
    position_j.push_back(e.position_j);
    intermediate.push_back(e.intermediate);
    normal.push_back(e.normal);
    gap.push_back(e.gap);
    if (forces) {
      const simulation::ContactState& s = states[k];
      normal_force.push_back(s.normal_reaction);
      friction.push_back(s.tangential);
      tangential_force.push_back(s.tangential.norm());
      status.push_back(static_cast<int>(output::contact_status(s)));
    } else {  // no contact forces (contact.forces: false), or no converged step yet: as contact_final.csv
      const double nan = std::numeric_limits<double>::quiet_NaN();
      normal_force.push_back(nan);
      friction.push_back(Eigen::Vector3d::Constant(nan));
      tangential_force.push_back(nan);
      status.push_back(-1);
    }
  }
  py::dict d;
  d["zone"] = vector_array(zone);
  d["beam_i"] = vector_array(beam_i);
  d["beam_j"] = vector_array(beam_j);
  d["element_i"] = vector_array(element_i);
  d["element_j"] = vector_array(element_j);
  d["zeta"] = vector_array(zeta);
  d["abscissa_i"] = vector_array(abscissa_i);
  d["abscissa_j"] = vector_array(abscissa_j);
  d["position_i"] = rows3(position_i);
  d["position_j"] = rows3(position_j);
  d["intermediate"] = rows3(intermediate);
  d["normal"] = rows3(normal);
  d["gap"] = vector_array(gap);
  d["normal_force"] = vector_array(normal_force);
  d["friction_force"] = rows3(friction);
  d["tangential_force"] = vector_array(tangential_force);
  d["state"] = vector_array(status);
  return d;
}

py::dict zone_arrays(const simulation::Simulation& sim) {
  const contact::ContactGeometry empty;
  const contact::ContactGeometry& g = sim.contact() ? *sim.contact() : empty;
  std::vector<int> beam_i, beam_j, first, count;
  std::vector<double> a, b, c, d;
  for (const contact::ProximityZone& z : g.zones) {
    beam_i.push_back(z.beam_i);
    beam_j.push_back(z.beam_j);
    a.push_back(z.a);
    b.push_back(z.b);
    c.push_back(z.c);
    d.push_back(z.d);
    first.push_back(z.first_element);
    count.push_back(z.num_elements);
  }
  py::dict out;
  out["beam_i"] = vector_array(beam_i);
  out["beam_j"] = vector_array(beam_j);
  out["a"] = vector_array(a);
  out["b"] = vector_array(b);
  out["c"] = vector_array(c);
  out["d"] = vector_array(d);
  out["first_element"] = vector_array(first);
  out["contact_elements"] = vector_array(count);
  return out;
}

py::array_t<double> strain_table(const Eigen::Matrix<double, beam::kNumStrains, Eigen::Dynamic>& s) {
  py::array_t<double> a({static_cast<py::ssize_t>(s.cols()), py::ssize_t{beam::kNumStrains}});
  auto m = a.mutable_unchecked<2>();
  for (Eigen::Index e = 0; e < s.cols(); ++e)
    for (int k = 0; k < beam::kNumStrains; ++k) m(e, k) = s(k, e);
  return a;
}

}  // namespace

void bind_simulation(py::module_& m) {
  std::vector<std::string> names;
  for (int k = 0; k < beam::kNumStrains; ++k) names.emplace_back(beam::strain_name(k));
  m.attr("strain_names") = names;
  m.attr("contact_states") = std::vector<std::string>{"open", "stick", "slip"};

  py::class_<PySimulation>(m, "_Simulation", "The stepping interface under nodus.Simulation (see there).")
      .def(py::init<const ScenarioHandle&>(), py::arg("scenario"))
      .def(
          "advance",
          [](PySimulation& s, int max_steps, bool to_stage_end, const py::object& callback) {
            std::function<bool(const simulation::StepRecord&)> stop;
            if (to_stage_end) stop = [](const simulation::StepRecord& r) { return r.ends_stage; };
            return s.advance(stop, max_steps, callback);
          },
          py::arg("max_steps") = 0, py::arg("to_stage_end") = false, py::arg("callback") = py::none())
      .def_property_readonly("finished", &PySimulation::finished)
      .def_property_readonly("failure", &PySimulation::failure)
      .def_property_readonly("last_step", &PySimulation::last_step)
      .def_property_readonly("time", [](const PySimulation& s) { return s.sim().time(); })
      .def_property_readonly("steps", [](const PySimulation& s) { return s.sim().steps(); })
      .def_property_readonly("stage_index", [](const PySimulation& s) { return s.sim().progress().stage; })
      .def_property_readonly("positions",
                             [](py::object self) { return self.cast<PySimulation&>().node_field(self, 0); })
      .def_property_readonly("d1",
                             [](py::object self) { return self.cast<PySimulation&>().node_field(self, 1); })
      .def_property_readonly("d2",
                             [](py::object self) { return self.cast<PySimulation&>().node_field(self, 2); })
      .def_property_readonly("state", [](const PySimulation& s) { return Eigen::VectorXd(s.sim().state()); })
      .def_property_readonly("reference_positions",
                             [](const PySimulation& s) {
                               const Eigen::VectorXd& x = s.sim().model().reference();
                               std::vector<Eigen::Vector3d> r;
                               for (int n = 0; n < s.sim().model().num_nodes(); ++n)
                                 r.push_back(x.segment<3>(9 * n));
                               return rows3(r);
                             })
      .def_property_readonly("node_beam",
                             [](const PySimulation& s) {
                               const model::Model& model = s.sim().model();
                               std::vector<int> beam(static_cast<std::size_t>(model.num_nodes()), 0);
                               for (int e = 0; e < model.num_elements(); ++e)
                                 for (int i = 0; i < 3; ++i)
                                   beam[static_cast<std::size_t>(model.element_first_node(e) + i)] =
                                       model.element_beam(e);
                               return vector_array(beam);
                             })
      .def_property_readonly("element_beam",
                             [](const PySimulation& s) {
                               std::vector<int> beam;
                               for (int e = 0; e < s.sim().model().num_elements(); ++e)
                                 beam.push_back(s.sim().model().element_beam(e));
                               return vector_array(beam);
                             })
      .def_property_readonly(
          "element_nodes",
          [](const PySimulation& s) {
            const model::Model& model = s.sim().model();
            py::array_t<int> a({static_cast<py::ssize_t>(model.num_elements()), py::ssize_t{3}});
            auto v = a.mutable_unchecked<2>();
            for (int e = 0; e < model.num_elements(); ++e)
              for (int i = 0; i < 3; ++i) v(e, i) = model.element_first_node(e) + i;
            return a;
          })
      .def(
          "element_strains",
          [](const PySimulation& s, double xi) {
            if (!(xi >= -1.0 && xi <= 1.0)) throw py::value_error("xi: expected a value in [-1, 1]");
            return strain_table(s.sim().model().element_strains(s.sim().state(), xi));
          },
          py::arg("xi") = 0.0)
      .def("node_strains",
           [](const PySimulation& s) { return strain_table(s.sim().model().node_strains(s.sim().state())); })
      .def(
          "centreline",
          [](const PySimulation& s, int beam, int segments) {
            const analysis::Centreline c =
                analysis::beam_centreline(s.sim().model(), s.sim().state(), beam, segments);
            return py::make_tuple(rows3(c.points), vector_array(c.arc_length));
          },
          py::arg("beam") = 0, py::arg("segments_per_element") = 2)
      .def("contact_elements", [](const PySimulation& s) { return contact_arrays(s.sim()); })
      .def("zones", [](const PySimulation& s) { return zone_arrays(s.sim()); })
      .def("internal_energy",
           [](const PySimulation& s) { return s.sim().model().internal_energy(s.sim().state()); });
}

}  // namespace nodus::python
