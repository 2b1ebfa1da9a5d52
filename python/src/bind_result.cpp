// Bindings of oscidrum/result.hpp. The steady-state samples are exposed as read-only NumPy
// views into the C++ vectors (no copy); each view keeps its Result alive.
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/result.hpp"
#include "pickling.hpp"

namespace oscidrum::python {
namespace {

// A read-only 1-D view of v whose lifetime is tied to `owner`.
py::array_t<double> view(const std::vector<double>& v, py::handle owner) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()), v.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::array_t<std::int8_t> phase_array(const std::vector<Phase>& phases) {
  py::array_t<std::int8_t> a(static_cast<py::ssize_t>(phases.size()));
  auto out = a.mutable_unchecked<1>();
  for (std::size_t j = 0; j < phases.size(); ++j)
    out(static_cast<py::ssize_t>(j)) = static_cast<std::int8_t>(phases[j]);
  return a;
}

// "description [unit]" with a stable address, for docstrings.
const char* doc(const std::string& text) {
  static std::deque<std::string> docs;
  docs.push_back(text);
  return docs.back().c_str();
}

std::string header(const SampleOutput& c) { return std::string(c.name) + "[" + c.unit + "]"; }

}  // namespace

void bind_result(py::module_& m) {
  py::enum_<Status> status(m, "Status",
                           "How a simulation ended (Result.status; .name gives the text).");
  for (const StatusInfo& st : statuses()) status.value(st.name, st.status, st.description);
  strict_enum(status);

  py::enum_<EventKind> event_kind(m, "EventKind", "Kind of a located event.");
  event_kind.value("stick_to_slip", EventKind::stick_to_slip, "|T| reached mu N")
      .value("slip_to_stick", EventKind::slip_to_stick,
             "v_rel reached 0 and the stick solution stays in the friction cone")
      .value("slip_reversal", EventKind::slip_reversal,
             "v_rel reached 0, stick not sustainable: slip on with the opposite sign")
      .value("contact_lost", EventKind::contact_lost, "N reached 0 (permanent contact)")
      .value("lift_off", EventKind::lift_off,
             "N reached 0 with contact.unilateral: the drum leaves the trough")
      .value("landing", EventKind::landing, "the gap closed: contact resumes");
  strict_enum(event_kind);

  py::class_<Event>(m, "Event", "One located event.")
      .def_readonly("t", &Event::t, "time [s]")
      .def_readonly("kind", &Event::kind, "EventKind")
      .def_readonly("from_phase", &Event::from, "Phase before the event")
      .def_readonly("to_phase", &Event::to, "Phase after the event")
      .def("__repr__", [](const Event& e) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "Event(t=%.9g s, %s, %s -> %s)", e.t, to_string(e.kind),
                      to_string(e.from), to_string(e.to));
        return std::string(buf);
      });

  py::class_<Diagnostics> diag(m, "Diagnostics",
                               "Counters of a run (docs/outputs.md). Picklable, between processes "
                               "of the same oscidrum build.");
  pickling::def_pickle(diag, "Diagnostics");
  for (const DiagnosticOutput& d : diagnostic_outputs())
    std::visit(
        [&](auto member) {
          const char* text = doc(std::string(d.description) + " [" + d.unit + "]");
          using T = std::remove_cvref_t<decltype(std::declval<const Diagnostics&>().*member)>;
          if constexpr (std::is_enum_v<T>)  // by its name, e.g. 'shooting'
            diag.def_property_readonly(
                d.name,
                [member](const Diagnostics& x) { return std::string(to_string(x.*member)); }, text);
          else
            diag.def_readonly(d.name, member, text);
        },
        d.member);
  diag.def_property_readonly_static(
          "names",
          [](py::handle) {
            py::list names;
            for (const DiagnosticOutput& d : diagnostic_outputs()) names.append(d.name);
            return names;
          },
          "names of the diagnostics, in output order")
      .def_property_readonly_static(
          "units",
          [](py::handle) {
            py::dict units;
            for (const DiagnosticOutput& d : diagnostic_outputs()) units[d.name] = d.unit;
            return units;
          },
          "{diagnostic: unit}");
  diag.def(
          "to_dict",
          [](py::object self) {
            py::dict out;
            for (const DiagnosticOutput& d : diagnostic_outputs()) out[d.name] = self.attr(d.name);
            return out;
          },
          "The counters as a dict.")
      .def("__repr__", [](const Diagnostics& d) {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "Diagnostics(periods_simulated=%d, periods_to_steady=%d, multiplicity=%d, "
                      "final_change=%.3g, steps=%ld, events=%ld, switches=%ld, reversals=%ld, "
                      "min_N=%.6g N)",
                      d.periods_simulated, d.periods_to_steady, d.multiplicity, d.final_change,
                      d.steps, d.events, d.switches, d.reversals, d.min_N);
        return std::string(buf);
      });

  m.def(
      "sample_columns",
      [] {
        py::list out;
        for (const SampleOutput& col : sample_outputs())
          out.append(py::make_tuple(col.name, col.unit));
        return out;
      },
      "The columns of the sampled steady state (docs/csv-columns.md): (name, unit) pairs in file "
      "order, from the output table.");

  py::class_<Samples> samples(m, "Samples",
                              "The sampled steady state (uniform samples over "
                              "Result.sample_periods excitation periods). Every column of "
                              "docs/csv-columns.md is a read-only float64 NumPy view; `phase` is "
                              "an int8 array (0 stick, 1 slip+, -1 slip-). Picklable (a copy), "
                              "between processes of the same oscidrum build.");
  pickling::def_pickle(samples, "Samples");
  for (const SampleOutput& col : sample_outputs()) {
    std::visit(
        [&](auto member) {
          using T = typename std::remove_cvref_t<decltype(std::declval<Samples>().*member)>;
          if constexpr (std::is_same_v<T, SamplePhases>) {
            samples.def_property_readonly(
                col.name, [member](const Samples& s) { return phase_array(s.*member); },
                doc(std::string(col.description) + " (int8 copy)"));
          } else {
            samples.def_property_readonly(
                col.name,
                [member](py::object self) {
                  return view(self.cast<const Samples&>().*member, self);
                },
                doc("steady-state samples, column " + header(col) +
                    " of docs/csv-columns.md: " + col.description + " (read-only NumPy view)"));
          }
        },
        col.member);
  }
  samples.def("__len__", &Samples::size);
  samples.def_property_readonly_static(
      "columns",
      [](py::handle) {
        py::list names;
        for (const SampleOutput& col : sample_outputs()) names.append(col.name);
        return names;
      },
      "attribute names in CSV column order");
  samples.def_property_readonly_static(
      "headers",
      [](py::handle) {
        py::list names;
        for (const SampleOutput& col : sample_outputs()) names.append(header(col));
        return names;
      },
      "CSV headers name[unit] (docs/csv-columns.md), in column order");
  samples.def(
      "to_dict",
      [](py::object self) {
        py::dict out;
        for (const SampleOutput& col : sample_outputs()) out[col.name] = self.attr(col.name);
        return out;
      },
      "{name: array} of every column.");
  samples.def("__repr__",
              [](const Samples& s) { return "Samples(" + std::to_string(s.size()) + " samples)"; });

  py::class_<Result> result(m, "Result",
                            "What a simulation returns. Picklable, between processes of the same "
                            "oscidrum build.");
  pickling::def_pickle(result, "Result");
  result.def_readonly("status", &Result::status, "Status (status.name is the text)")
      .def_property_readonly(
          "ok", [](const Result& r) { return ok(r.status); }, "True only for a steady state")
      .def_readonly("message", &Result::message, "human-readable explanation of the status")
      .def_readonly("diagnostics", &Result::diagnostics, "Diagnostics")
      .def_readonly("frequency", &Result::frequency, "excitation frequency f [Hz]")
      .def_property_readonly(
          "period", [](const Result& r) { return r.frequency > 0 ? 1.0 / r.frequency : 0.0; },
          "excitation period 1/f [s]")
      .def_readonly("sample_periods", &Result::sample_periods,
                    "excitation periods covered by `samples` [-]")
      .def_readonly("samples_per_period", &Result::samples_per_period, "[-]")
      .def_readonly("samples", &Result::samples, "the steady state (Samples)")
      .def_readonly("events", &Result::events, "every event of the run, in time order")
      .def_readonly("stick_time", &Result::stick_time,
                    "time in stick within the sampled window [s]")
      .def_readonly("slip_positive_time", &Result::slip_positive_time,
                    "time in slip+ within the sampled window [s]")
      .def_readonly("slip_negative_time", &Result::slip_negative_time,
                    "time in slip- within the sampled window [s]")
      .def_readonly("flight_time", &Result::flight_time,
                    "time in flight within the sampled window [s] (contact.unilateral)")
      .def_property_readonly(
          "floquet_multipliers", [](const Result& r) { return r.floquet.multipliers; },
          "Floquet multipliers of the steady state by decreasing modulus (shooting only; empty "
          "otherwise) [-]")
      .def_property_readonly(
          "floquet_max_modulus",
          [](const Result& r) {
            return r.floquet.stability == Stability::unknown ? std::nan("") : r.floquet.max_modulus;
          },
          "largest |multiplier|: the transient decays like it per period (NaN without shooting)")
      .def_property_readonly(
          "stability", [](const Result& r) { return std::string(to_string(r.floquet.stability)); },
          "'stable', 'fold' (+1), 'period_doubling' (-1), 'torus' (complex pair) or 'unknown'")
      .def_property_readonly(
          "period1_floquet_multipliers",
          [](const Result& r) { return r.period1_floquet.multipliers; },
          "a steady state repeating every p > 1 periods found by shooting on P^p: the Floquet "
          "multipliers of the unstable period-1 orbit it replaced (empty otherwise) [-]")
      .def_property_readonly(
          "period1_stability",
          [](const Result& r) { return std::string(to_string(r.period1_floquet.stability)); },
          "the stability of that period-1 orbit (e.g. 'period_doubling'), or 'unknown'")
      .def("__repr__", [](const Result& r) {
        char buf[300];
        std::snprintf(buf, sizeof buf,
                      "Result(status=%s, f=%.6g Hz, periods_to_steady=%d, multiplicity=%d, "
                      "samples=%zu over %d periods, events=%zu)",
                      to_string(r.status), r.frequency, r.diagnostics.periods_to_steady,
                      r.diagnostics.multiplicity, r.samples.size(), r.sample_periods,
                      r.events.size());
        return std::string(buf);
      });
}

}  // namespace oscidrum::python
