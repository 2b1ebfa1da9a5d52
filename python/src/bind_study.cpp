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

namespace oscidrum::python {
namespace {

// ---- pickling of CaseOutcome (for studies on executors: outcomes travel between processes) ----
// A flat little-endian byte string of this build's structs, headed by a format tag and the sizes
// of the fixed-size parts; only the same oscidrum build reads it back. The members of
// Diagnostics, Samples and Metrics come from the output tables (oscidrum/outputs.hpp), so a new
// output travels without a change here.

constexpr std::uint32_t kOutcomeFormat = 0x4f534333;  // "OSC3"

class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&v);
    bytes_.append(p, sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(v.size());
    if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put(const std::string& s) {
    put<std::uint64_t>(s.size());
    bytes_ += s;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <class T>
  void get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    take(&v, sizeof(T));
  }
  template <class T>
  void get(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::uint64_t n = 0;
    get(n);
    if (n > (bytes_.size() - pos_) / sizeof(T)) fail();
    v.resize(n);
    if (n > 0) take(v.data(), n * sizeof(T));
  }
  void get(std::string& s) {
    std::uint64_t n = 0;
    get(n);
    if (n > bytes_.size() - pos_) fail();
    s.assign(bytes_.substr(pos_, n));
    pos_ += n;
  }
  template <class T>
  T get() {
    T v{};
    get(v);
    return v;
  }
  bool at_end() const { return pos_ == bytes_.size(); }
  [[noreturn]] static void fail() {
    throw Error(
        "cannot restore a CaseOutcome: the state is not one written by this build of oscidrum");
  }

 private:
  void take(void* out, std::size_t n) {
    if (n > bytes_.size() - pos_) fail();
    std::memcpy(out, bytes_.data() + pos_, n);
    pos_ += n;
  }
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

// Every member of a CaseOutcome, in one order for writing (Writer) and reading (Reader).
template <class IO, class O>
void each_member(IO&& io, O& o) {
  auto& r = o.result;
  auto& d = r.diagnostics;
  io(o.valid), io(o.error), io(r.status), io(r.message);
#define OSCIDRUM_MEMBER(type, name, initial, unit, label, description) io(d.name);
  OSCIDRUM_DIAGNOSTICS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER
  io(r.frequency), io(r.sample_periods), io(r.samples_per_period);
#define OSCIDRUM_MEMBER(type, name, unit, label, description) io(r.samples.name);
  OSCIDRUM_SAMPLE_COLUMNS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER
  io(r.events), io(r.stick_time), io(r.slip_positive_time), io(r.slip_negative_time),
      io(r.flight_time);
  io(r.floquet.multipliers), io(r.floquet.max_modulus), io(r.floquet.stability);
  io(r.period1_floquet.multipliers), io(r.period1_floquet.max_modulus),
      io(r.period1_floquet.stability);
#define OSCIDRUM_MEMBER(type, name, unit, label, description) io(o.metrics.name);
  OSCIDRUM_METRICS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER
}

py::bytes outcome_state(const CaseOutcome& o) {
  Writer w;
  w.put(kOutcomeFormat);
  w.put<std::uint32_t>(sizeof(Event));
  w.put<std::uint32_t>(sizeof(Harmonic));
  each_member([&](const auto& v) { w.put(v); }, o);
  return py::bytes(w.bytes());
}

CaseOutcome outcome_from_state(py::handle state) {
  if (!py::isinstance<py::bytes>(state)) Reader::fail();
  const std::string bytes = state.cast<std::string>();
  Reader rd(bytes);
  if (rd.get<std::uint32_t>() != kOutcomeFormat || rd.get<std::uint32_t>() != sizeof(Event) ||
      rd.get<std::uint32_t>() != sizeof(Harmonic))
    Reader::fail();
  CaseOutcome o;
  each_member([&](auto& v) { rd.get(v); }, o);
  if (!rd.at_end()) Reader::fail();
  return o;
}

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

std::vector<CaseOutcome> run_study_py(const py::object& items, int threads, bool keep_samples,
                                      int n_harmonics, const py::object& progress,
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
  outcome.def("__getstate__", &outcome_state);
  outcome.def_static(
      "not_run",
      [] {
        CaseOutcome o;
        o.valid = false;
        o.error = "cancelled";
        return o;
      },
      "The outcome of a case a study did not run (valid=False, error='cancelled').");
  def_assigning(outcome, "__setstate__",
                [](CaseOutcome& self, py::handle state) { self = outcome_from_state(state); });
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
      [](const Case& c, bool keep_samples, int n_harmonics) {
        py::gil_scoped_release release;
        return run_case(c, keep_samples, n_harmonics);
      },
      py::arg("case"), py::arg("keep_samples") = true, py::arg("n_harmonics") = 10,
      "One case as run_study runs it: never raises for invalid parameters (see "
      "CaseOutcome.valid).");
}

}  // namespace oscidrum::python
