// Bindings of oscidrum/study.hpp. run_study copies the cases, releases the GIL and runs them on
// C++ worker threads; the callbacks re-acquire the GIL. A Python exception in a callback, or
// Ctrl-C, stops the study from starting new cases and is re-raised once the workers are done.
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/study.hpp"
#include "pickling.hpp"

namespace oscidrum::python {
namespace {

std::vector<Case> to_cases(const py::handle& items) {
  if (!py::isinstance<py::iterable>(items) || py::isinstance<py::str>(items) ||
      py::isinstance<py::dict>(items) || py::isinstance<Case>(items))
    throw Error(
        "cases must be a list (or other iterable) of Case objects or {key: value} dicts; "
        "got " +
        python_type_name(items));
  std::vector<Case> cases;
  py::object from_dict = py::module_::import("oscidrum._core").attr("Case").attr("from_dict");
  for (py::handle item : items) {
    const std::string where = "cases[" + std::to_string(cases.size()) + "]";
    if (py::isinstance<Case>(item)) {
      cases.push_back(item.cast<Case>());
    } else if (py::isinstance<py::dict>(item)) {
      try {
        cases.push_back(from_dict(item).cast<Case>());
      } catch (const py::error_already_set& e) {
        throw Error(where + ": " + py::str(e.value()).cast<std::string>());
      }
    } else {
      throw Error(where + " must be a Case or a {key: value} dict; got " +
                  python_description(item));
    }
  }
  return cases;
}

std::vector<CaseOutcome> run_study_py(const py::object& items, Int threads, bool keep_samples,
                                      Int n_harmonics, const py::object& progress,
                                      const py::object& on_case_done, bool samples_in_callback) {
  const std::vector<Case> cases = to_cases(items);
  GuardedCalls calls;
  StudyOptions options;
  options.threads = threads;
  options.keep_samples = keep_samples;
  options.samples_in_callback = samples_in_callback;
  options.n_harmonics = n_harmonics;
  if (!progress.is_none())
    options.progress = [&](std::size_t done, std::size_t total) {
      calls.guarded([&] { progress(done, total); });
    };
  if (!on_case_done.is_none())
    options.on_case_done = [&](std::size_t index, const CaseOutcome& outcome) {
      calls.guarded([&] { on_case_done(index, outcome); });
    };
  // Polled by the runner between cases and once per simulated period.
  options.cancelled = [&]() { return calls.cancelled(); };
  std::vector<CaseOutcome> outcomes =
      run_watching_signals(calls, [&] { return run_study(cases, options); });
  calls.rethrow();
  return outcomes;
}

}  // namespace

void bind_study(py::module_& m) {
  py::class_<CaseOutcome> outcome(m, "CaseOutcome",
                                  "What one case of a study produced. Picklable (for studies on "
                                  "executors), between processes of the same oscidrum build.");
  construct_on_new(outcome);
  outcome.def_static(
      "not_run", [] { return not_run_outcome(); },
      "The outcome of a case a study did not run (valid=False, error='cancelled', status "
      "cancelled, metrics and diagnostic values NaN).");
  pickling::def_pickle(outcome, "CaseOutcome");
  outcome
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
        py::arg("samples_in_callback") = false,
        "Run every case (Case objects or {dotted key: value} dicts) on `threads` C++ worker "
        "threads (0: all cores) with the GIL released. Returns one CaseOutcome per case, in "
        "input order; identical to running them one by one. Invalid cases do not raise: their "
        "outcome has valid=False and the error message.\n\n"
        "keep_samples: keep each steady state's samples (memory: ~0.3 MB per case).\n"
        "n_harmonics: harmonics in the metrics.\n"
        "progress: optional callable progress(done, total), called after each case.\n"
        "on_case_done: optional callable on_case_done(index, outcome), called after each case.\n"
        "samples_in_callback: on_case_done's outcome carries the samples even without "
        "keep_samples (the sampling then costs about a fifth of a case); without it, and "
        "without keep_samples, no case is sampled.\n"
        "An exception raised by a callback (or Ctrl-C) stops new cases from starting and is "
        "re-raised.");
  m.def(
      "_without_samples",
      [](const CaseOutcome& o) {
        CaseOutcome copy = o;
        copy.result.samples = Samples{};
        return copy;
      },
      py::arg("outcome"), "A copy of the outcome without its samples (internal).");
  m.def(
      "run_case",
      [](const Case& c, bool keep_samples, Int n_harmonics) {
        // The argument, not the case: it made an invalid outcome ("compute_metrics: n_max must
        // be < ..."); refused like run_study's.
        const int nyquist = c.numerics.samples_per_period / 2;
        if (n_harmonics < 0 || n_harmonics >= nyquist)
          throw Error("n_harmonics must be in [0, " + std::to_string(nyquist) +
                      ") (numerics.samples_per_period / 2, the samples' Nyquist limit); got " +
                      std::to_string(n_harmonics));
        py::gil_scoped_release release;
        return run_case(c, keep_samples, n_harmonics);
      },
      py::arg("case"), py::arg("keep_samples") = true, py::arg("n_harmonics") = 10,
      "One case as run_study runs it: never raises for invalid parameters (see "
      "CaseOutcome.valid). Raises oscidrum.Error for an n_harmonics outside [0, "
      "numerics.samples_per_period / 2).");
}

}  // namespace oscidrum::python
