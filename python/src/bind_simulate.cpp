// Bindings of oscidrum/simulate.hpp. The integration runs with the GIL released; the progress
// callback re-acquires it, and Ctrl-C (SIGINT) cancels the run and raises KeyboardInterrupt.
#include <chrono>
#include <exception>
#include <string>

#include "bindings.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/simulate.hpp"

namespace oscidrum::python {
namespace {

Result simulate_model(const Model& model, const py::object& progress) {
  // Checked before the integration starts: called with a non-callable, the first period would
  // raise Python's bare "'int' object is not callable".
  if (!progress.is_none() && PyCallable_Check(progress.ptr()) == 0)
    throw Error("progress must be None or a callable progress(period: int, change: float); got " +
                python_description(progress));
  std::exception_ptr error;
  const bool has_callback = !progress.is_none();
  auto next_poll = std::chrono::steady_clock::now();
  ProgressCallback callback = [&](int period, double change) -> bool {
    if (!has_callback) {  // only Ctrl-C to look for: at most every 50 ms, not every period
      const auto now = std::chrono::steady_clock::now();
      if (now < next_poll) return true;
      next_poll = now + std::chrono::milliseconds(50);
    }
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (has_callback) {
        py::object go_on = progress(period, change);
        if (!go_on.is_none()) {
          const int truth = PyObject_IsTrue(go_on.ptr());
          if (truth < 0) throw py::error_already_set();
          return truth == 1;
        }
      }
      return true;
    } catch (...) {
      error = std::current_exception();
      return false;
    }
  };
  Result result;
  {
    py::gil_scoped_release release;
    result = simulate(model, callback);
  }
  if (error) std::rethrow_exception(error);
  return result;
}

}  // namespace

void bind_simulate(py::module_& m) {
  const char* doc =
      "Integrate from rest at the bottom of the trough to the steady state and sample it "
      "(Dormand-Prince 8(5,3), events located on the dense output).\n\n"
      "Parameters\n----------\ncase : Case (or model : Model)\n    The parameters (SI units).\n"
      "progress : callable, optional\n    progress(period: int, change: float) once per "
      "integrated excitation period with the period-to-period change [-]; return False to "
      "cancel (the result then has status cancelled).\n\n"
      "Returns\n-------\nResult\n    status, message, diagnostics, the sampled steady state "
      "(samples: t [s], ddx_M, ddz_M [m/s^2], ...), events; Result.to_dataframe() gives the "
      "samples as a pandas DataFrame.\n\n"
      "Raises\n------\noscidrum.Error\n    For invalid parameters (numerical trouble is "
      "reported in Result.status, not raised).\nKeyboardInterrupt\n    On Ctrl-C (the GIL is "
      "released while integrating).\n\n"
      "Examples\n--------\n>>> r = oscidrum.simulate(oscidrum.Case(table2_G=5e6, "
      "pure_rolling=True))\n>>> r.status.name\n'steady_state'\n>>> float(r.samples.ddx_M.max())"
      "   # [m/s^2]  # doctest: +SKIP\n";
  m.def(
      "simulate",
      [](const Case& c, const py::object& progress) { return simulate_model(Model(c), progress); },
      py::arg("case"), py::arg("progress") = py::none(), doc);
  m.def("simulate", &simulate_model, py::arg("model"), py::arg("progress") = py::none(), doc);
}

}  // namespace oscidrum::python
