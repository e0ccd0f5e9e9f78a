#pragma once
/// The parts of the extension module nodus._nodus, each bound by its own file. The Python package
/// (python/nodus/__init__.py) builds the user-facing API on them; docs/python.md documents it.

#include <memory>

#include <pybind11/pybind11.h>

#include "nodus/scenario/scenario.hpp"

namespace nodus::python {

/// A scenario read and checked by the C++ reader, shared by the Python objects that use it.
using ScenarioHandle = std::shared_ptr<scenario::Scenario>;

/// The path of a scenario built from Python data: it names it in messages ("<dict>: KEY: expected ..."), and
/// tells run() that there is no file for branch processes to read.
inline constexpr const char* kDataLabel = "<dict>";

/// ScenarioError, the YAML <-> Python conversions, the scenario reader, the key table
/// (scenario_bindings.cpp).
void bind_scenario(pybind11::module_& m);
/// run(): `nodus run` as a call (run_bindings.cpp).
void bind_run(pybind11::module_& m);
/// Simulation: the stepping interface and the state as arrays (simulation_bindings.cpp).
void bind_simulation(pybind11::module_& m);
/// The knot analysis of analysis/ (analysis_bindings.cpp).
void bind_analysis(pybind11::module_& m);

}  // namespace nodus::python
