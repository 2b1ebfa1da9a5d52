// Bindings of oscidrum/study.hpp. run_study copies the cases, releases the GIL and runs them on
// C++ worker threads; the callbacks re-acquire the GIL. A Python exception in a callback, or
// Ctrl-C, stops the study from starting new cases and is re-raised once the workers are done.
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/study.hpp"

namespace oscidrum::python {
namespace {

// 50 ms in steady_clock ticks.
constexpr std::int64_t kPollTicks =
    std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::milliseconds(50))
        .count();

std::vector<Case> to_cases(const py::iterable& items) {
  std::vector<Case> cases;
  py::object from_dict = py::module_::import("oscidrum._core").attr("Case").attr("from_dict");
  for (py::handle item : items) {
    if (py::isinstance<py::dict>(item))
      cases.push_back(from_dict(item).cast<Case>());
    else
      cases.push_back(item.cast<Case>());
  }
  return cases;
}

std::vector<CaseOutcome> run_study_py(const py::iterable& items, int threads, bool keep_samples,
                                      int n_harmonics, const py::object& progress,
                                      const py::object& on_case_done) {
  const std::vector<Case> cases = to_cases(items);
  std::exception_ptr error;                // written with the GIL held, so the GIL guards it
  std::atomic<bool> stop{false};           // set once `error` is: read without the GIL
  std::atomic<std::int64_t> next_poll{0};  // steady_clock ticks of the next signal check
  StudyOptions options;
  options.threads = threads;
  options.keep_samples = keep_samples;
  options.n_harmonics = n_harmonics;
  auto guarded = [&](auto&& call) {
    py::gil_scoped_acquire gil;
    if (error) return;
    try {
      call();
    } catch (...) {
      error = std::current_exception();
      stop.store(true);
    }
  };
  if (!progress.is_none())
    options.progress = [&](std::size_t done, std::size_t total) {
      guarded([&] { progress(done, total); });
    };
  if (!on_case_done.is_none())
    options.on_case_done = [&](std::size_t index, const CaseOutcome& outcome) {
      guarded([&] { on_case_done(index, outcome); });
    };
  // Polled by the runner between cases and once per simulated period: look for Ctrl-C at most
  // every 50 ms, so that the workers do not queue for the GIL.
  options.cancelled = [&]() {
    if (stop.load()) return true;
    const std::int64_t now = std::chrono::steady_clock::now().time_since_epoch().count();
    std::int64_t due = next_poll.load();
    if (now < due || !next_poll.compare_exchange_strong(due, now + kPollTicks)) return false;
    guarded([] {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    });
    return stop.load();
  };
  std::vector<CaseOutcome> outcomes;
  {
    py::gil_scoped_release release;
    outcomes = run_study(cases, options);
  }
  if (error) std::rethrow_exception(error);
  return outcomes;
}

}  // namespace

void bind_study(py::module_& m) {
  py::class_<CaseOutcome>(m, "CaseOutcome", "What one case of a study produced.")
      .def_readonly("valid", &CaseOutcome::valid,
                    "False: the case was rejected (invalid parameters); see `error`")
      .def_readonly("error", &CaseOutcome::error, "the oscidrum.Error message when not valid")
      .def_readonly("result", &CaseOutcome::result,
                    "Result (samples empty unless keep_samples=True)")
      .def_readonly("metrics", &CaseOutcome::metrics, "Metrics (computed whenever samples exist)")
      .def_property_readonly(
          "ok", [](const CaseOutcome& o) { return o.valid && ok(o.result.status); },
          "valid and reached a steady state")
      .def("__repr__", [](const CaseOutcome& o) {
        if (!o.valid) return "CaseOutcome(invalid: " + o.error + ")";
        return std::string("CaseOutcome(status=") + to_string(o.result.status) +
               ", area=" + std::to_string(o.metrics.area) + " m^2/s^4)";
      });

  m.def("run_study", &run_study_py, py::arg("cases"), py::arg("threads") = 0,
        py::arg("keep_samples") = false, py::arg("n_harmonics") = 10,
        py::arg("progress") = py::none(), py::arg("on_case_done") = py::none(),
        "Run every case (Case objects or {dotted key: value} dicts) on `threads` C++ worker "
        "threads (0: all cores) with the GIL released. Returns one CaseOutcome per case, in "
        "input order; identical to running them one by one. Invalid cases do not raise: their "
        "outcome has valid=False and the error message.\n\n"
        "keep_samples: keep each steady state's samples (memory: ~0.3 MB per case).\n"
        "n_harmonics: harmonics in the metrics.\n"
        "progress: optional callable progress(done, total), called after each case.\n"
        "on_case_done: optional callable on_case_done(index, outcome), called after each case.\n"
        "An exception raised by a callback (or Ctrl-C) stops new cases from starting and is "
        "re-raised.");
  m.def(
      "run_case",
      [](const Case& c, bool keep_samples, int n_harmonics) {
        py::gil_scoped_release release;
        return run_case(c, keep_samples, n_harmonics);
      },
      py::arg("case"), py::arg("keep_samples") = true, py::arg("n_harmonics") = 10,
      "One case as run_study runs it: never raises for invalid parameters (see "
      "CaseOutcome.valid).");
}

}  // namespace oscidrum::python
