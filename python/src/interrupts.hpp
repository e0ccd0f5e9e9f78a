#pragma once
/// Ctrl-C and Python errors while nodus computes without the GIL.
///
/// nodus releases the GIL while it computes. Python's own SIGINT handler only sets a flag that the
/// interpreter acts on when it runs Python code again, so a long run would not stop. The run asks
/// Interrupts::poll() after every Newton iteration and every step: poll() takes the GIL, runs the pending
/// signal handlers (PyErr_CheckSignals) and keeps the exception they raise (KeyboardInterrupt for Ctrl-C);
/// the run then stops at its last converged state and rethrow() raises that exception in the caller. An
/// exception raised by a Python callback (a step callback) is kept the same way.

#include <chrono>
#include <memory>
#include <optional>

#include <pybind11/pybind11.h>

namespace nodus::python {

class Interrupts {
 public:
  /// True once a signal handler or a callback raised. Call without the GIL (it takes it).
  bool poll() {
    if (error_) return true;
    // At most every kPollSeconds: taking the GIL can wait for another Python thread's switch interval.
    const auto now = std::chrono::steady_clock::now();
    if (now - last_poll_ < std::chrono::duration<double>(kPollSeconds)) return false;
    last_poll_ = now;
    pybind11::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) error_.emplace();  // fetches KeyboardInterrupt (or the handler's error)
    return error_.has_value();
  }
  /// Keeps the Python error being handled (call with the GIL, inside a catch of error_already_set).
  void keep(pybind11::error_already_set&& error) {
    if (!error_) error_.emplace(std::move(error));
  }
  bool pending() const { return error_.has_value(); }
  /// Least wall time between two looks for pending signals [s]: Ctrl-C stops within about this much of the
  /// end of a Newton iteration.
  static constexpr double kPollSeconds = 0.05;

  /// Raises the kept error, if any (call with the GIL).
  void rethrow() {
    if (!error_) return;
    pybind11::error_already_set error = std::move(*error_);
    error_.reset();
    throw error;
  }

 private:
  std::optional<pybind11::error_already_set> error_;
  std::chrono::steady_clock::time_point last_poll_{};
};

}  // namespace nodus::python
