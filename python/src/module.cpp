#include <pybind11/pybind11.h>

#include "bindings.hpp"

PYBIND11_MODULE(_nodus, m) {
  m.doc() =
      "nodus's C++ core. Use the package `nodus` (python/nodus/__init__.py), which builds the documented API "
      "on these functions.";
  m.attr("version") = NODUS_VERSION;
  m.attr("executable") = NODUS_EXECUTABLE;
  nodus::python::bind_scenario(m);
  nodus::python::bind_run(m);
  nodus::python::bind_simulation(m);
  nodus::python::bind_analysis(m);
}
