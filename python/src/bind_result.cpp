// Bindings of oscidrum/result.hpp. The steady-state samples are exposed as read-only NumPy
// views into the C++ vectors (no copy); each view keeps its Result alive.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <cstdio>
#include <deque>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/result.hpp"

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

// The columns of docs/csv-columns.md: (attribute, CSV header).
struct Column {
  const char* name;
  const char* header;
  std::vector<double> Samples::*member;
};
const Column kColumns[] = {
    {"t", "t[s]", &Samples::t},
    {"delta", "delta[rad]", &Samples::delta},
    {"phi", "phi[rad]", &Samples::phi},
    {"x_A", "x_A[m]", &Samples::x_A},
    {"s_A", "s_A[m]", &Samples::s_A},
    {"ddelta", "ddelta[rad/s]", &Samples::ddelta},
    {"dphi", "dphi[rad/s]", &Samples::dphi},
    {"dx_A", "dx_A[m/s]", &Samples::dx_A},
    {"ds_A", "ds_A[m/s]", &Samples::ds_A},
    {"x_M", "x_M[m]", &Samples::x_M},
    {"z_M", "z_M[m]", &Samples::z_M},
    {"ddx_M", "ddx_M[m/s^2]", &Samples::ddx_M},
    {"ddz_M", "ddz_M[m/s^2]", &Samples::ddz_M},
    {"N", "N[N]", &Samples::N},
    {"T", "T[N]", &Samples::T},
    {"v_rel", "v_rel[m/s]", &Samples::v_rel},
    {"torque", "torque[N m]", &Samples::torque},
};

const char* column_doc(const char* header) {
  static std::deque<std::string> docs;  // stable addresses
  docs.push_back(std::string("steady-state samples, column ") + header +
                 " of docs/csv-columns.md (read-only NumPy view)");
  return docs.back().c_str();
}

}  // namespace

void bind_result(py::module_& m) {
  py::enum_<Status> status(m, "Status",
                           "How a simulation ended (Result.status; .name gives the text).");
  status.value("steady_state", Status::steady_state, "the response repeats; steady state sampled")
      .value("max_periods_reached", Status::max_periods_reached,
             "no steady state within numerics.max_periods (last periods sampled)")
      .value("contact_lost", Status::contact_lost, "N <= 0: lift-off, not covered by the model")
      .value("chattering", Status::chattering, "too many stick/slip switches in a vanishing time")
      .value("non_finite", Status::non_finite, "a NaN or infinity appeared in the state")
      .value("invalid_geometry", Status::invalid_geometry,
             "trough curvature radius fell to the drum radius (f5 <= 0)")
      .value("gross_slip", Status::gross_slip,
             "the drum spins: the driving torque exceeds what friction can hold")
      .value("budget_exceeded", Status::budget_exceeded,
             "more steps in one period than numerics.max_steps_per_period")
      .value("cancelled", Status::cancelled, "stopped by the caller");
  strict_enum(status);

  py::enum_<EventKind> event_kind(m, "EventKind", "Kind of a located event.");
  event_kind.value("stick_to_slip", EventKind::stick_to_slip, "|T| reached mu N")
      .value("slip_to_stick", EventKind::slip_to_stick,
             "v_rel reached 0 and the stick solution stays in the friction cone")
      .value("slip_reversal", EventKind::slip_reversal,
             "v_rel reached 0, stick not sustainable: slip on with the opposite sign")
      .value("contact_lost", EventKind::contact_lost, "N reached 0");
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

  py::class_<Diagnostics> diag(m, "Diagnostics", "Counters of a run.");
  diag.def_readonly("periods_simulated", &Diagnostics::periods_simulated,
                    "excitation periods integrated before sampling [-]")
      .def_readonly("periods_to_steady", &Diagnostics::periods_to_steady,
                    "period index at which the steady state was found (-1: never) [-]")
      .def_readonly("multiplicity", &Diagnostics::multiplicity,
                    "steady period in excitation periods (0: none found) [-]")
      .def_readonly("final_change", &Diagnostics::final_change,
                    "last period-to-period change (scaled) [-]")
      .def_readonly("steps", &Diagnostics::steps, "accepted integrator steps")
      .def_readonly("rejected_steps", &Diagnostics::rejected_steps, "rejected trial steps")
      .def_readonly("rhs_evaluations", &Diagnostics::rhs_evaluations, "right-hand-side evaluations")
      .def_readonly("events", &Diagnostics::events, "located events")
      .def_readonly("switches", &Diagnostics::switches, "stick/slip phase changes")
      .def_readonly("reversals", &Diagnostics::reversals, "slip -> slip reversals")
      .def_readonly("switches_per_period", &Diagnostics::switches_per_period,
                    "in the sampled steady state [-]")
      .def_readonly("max_slip_residual", &Diagnostics::max_slip_residual,
                    "max |(39)| / max(N) during slip [-]")
      .def_readonly("min_N", &Diagnostics::min_N, "smallest normal force seen [N]")
      .def(
          "to_dict",
          [](const Diagnostics& d) {
            py::dict out;
            for (const char* name :
                 {"periods_simulated", "periods_to_steady", "multiplicity", "final_change", "steps",
                  "rejected_steps", "rhs_evaluations", "events", "switches", "reversals",
                  "switches_per_period", "max_slip_residual", "min_N"})
              out[name] = py::cast(d).attr(name);
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

  py::class_<Samples> samples(m, "Samples",
                              "The sampled steady state (uniform samples over "
                              "Result.sample_periods excitation periods). Every column of "
                              "docs/csv-columns.md is a read-only float64 NumPy view; `phase` is "
                              "an int8 array (0 stick, 1 slip+, -1 slip-).");
  for (const Column& col : kColumns) {
    auto member = col.member;
    samples.def_property_readonly(
        col.name,
        [member](py::object self) { return view(self.cast<const Samples&>().*member, self); },
        column_doc(col.header));
  }
  samples.def_property_readonly(
      "phase", [](const Samples& s) { return phase_array(s.phase); },
      "contact phase per sample: 0 stick, 1 slip+ (v_rel > 0), -1 slip- (int8 copy)");
  samples.def("__len__", &Samples::size);
  samples.def_property_readonly_static(
      "columns",
      [](py::handle) {
        py::list names;
        for (const Column& col : kColumns) names.append(col.name);
        names.append("phase");
        return names;
      },
      "attribute names in CSV column order");
  samples.def_property_readonly_static(
      "headers",
      [](py::handle) {
        py::list names;
        for (const Column& col : kColumns) names.append(col.header);
        names.append("phase[-]");
        return names;
      },
      "CSV headers name[unit] (docs/csv-columns.md), in column order");
  samples.def(
      "to_dict",
      [](py::object self) {
        py::dict out;
        for (const Column& col : kColumns) out[col.name] = self.attr(col.name);
        out["phase"] = self.attr("phase");
        return out;
      },
      "{name: array} of every column.");
  samples.def("__repr__",
              [](const Samples& s) { return "Samples(" + std::to_string(s.size()) + " samples)"; });

  py::class_<Result>(m, "Result", "What a simulation returns.")
      .def_readonly("status", &Result::status, "Status (status.name is the text)")
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
