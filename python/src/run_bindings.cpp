/// run(): `nodus run` as a call, the GIL released while it computes, Ctrl-C stopping it as a kill would.

#include <filesystem>
#include <string>

#include <pybind11/stl.h>
#include <spdlog/spdlog.h>

#include "bindings.hpp"
#include "interrupts.hpp"
#include "nodus/output/logging.hpp"
#include "nodus/run/run.hpp"
#include "nodus/scenario/fingerprint.hpp"

namespace py = pybind11;

namespace nodus::python {

void bind_run(py::module_& m) {
  py::class_<run::Outcome>(m, "RunOutcome", "How a run ended.")
      .def_readonly("converged", &run::Outcome::converged, "The main run and every branch completed.")
      .def_readonly("interrupted", &run::Outcome::interrupted,
                    "Stopped before the end (stop_after_steps, or cancelled): resume it.")
      .def_readonly("already_complete", &run::Outcome::already_complete,
                    "Nothing was computed: the run in the folder had finished (resume).")
      .def("__repr__", [](const run::Outcome& o) {
        return "RunOutcome(converged=" + std::string(o.converged ? "True" : "False") +
               ", interrupted=" + (o.interrupted ? "True" : "False") +
               ", already_complete=" + (o.already_complete ? "True" : "False") + ")";
      });

  m.def(
      "run",
      [](const ScenarioHandle& scenario, const std::string& out, int jobs, bool resume, bool quiet,
         bool verbose, const std::string& branch, int stop_after_steps, const std::string& executable,
         const std::string& timing_from) {
        output::use_stderr_logger();
        spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info);
        run::Request request;
        request.scenario_path = scenario->path;
        request.out = out;
        request.jobs = jobs;
        request.resume = resume;
        request.quiet = quiet;
        request.verbose = verbose;
        request.branch = branch;
        request.stop_after_steps = stop_after_steps;
        request.timing_from = timing_from;
        // Branch processes read the scenario file: a scenario built in code has none and runs its branches
        // in this process, one at a time (the same results).
        if (!scenario->path.empty() && scenario->path != kDataLabel && jobs > 1 && !executable.empty()) {
          // Branch processes read the file again: only if it still holds this scenario, branches included.
          const auto everything = [](const scenario::Scenario& s) {
            std::string text = scenario::state_fingerprint_text(s, static_cast<int>(s.stages.size()));
            for (std::size_t b = 0; b < s.branches.size(); ++b) {
              const scenario::Scenario part = scenario::branch_scenario(s, b);
              text += s.branches[b].name + "\n" +
                      scenario::state_fingerprint_text(part, static_cast<int>(part.stages.size()));
            }
            return text;
          };
          bool same = false;
          try {
            same = everything(scenario::read_scenario(scenario->path)) == everything(*scenario);
          } catch (const scenario::ScenarioError&) {
          }
          if (same)
            request.branch_executable = executable;
          else
            spdlog::warn("{} has changed since it was read: the branches run in this process, one at a time",
                         scenario->path);
        }
        Interrupts interrupts;
        request.cancel = [&interrupts] { return interrupts.poll(); };
        run::Outcome outcome;
        try {
          py::gil_scoped_release release;
          outcome = run::run(*scenario, request);
        } catch (...) {
          interrupts.rethrow();  // a Ctrl-C (or a callback's error) comes first
          throw;
        }
        interrupts.rethrow();
        return outcome;
      },
      py::arg("scenario"), py::arg("out"), py::arg("jobs") = 1, py::arg("resume") = false,
      py::arg("quiet") = false, py::arg("verbose") = false, py::arg("branch") = "",
      py::arg("stop_after_steps") = 0, py::arg("executable") = "", py::arg("timing_from") = "",
      "Runs a scenario as `nodus run` does; see nodus.run.");
}

}  // namespace nodus::python
