// Bindings of oscidrum/validation.hpp: the paper's studies (paper_series, paper_case,
// run_paper_studies) and the check of every result the paper states (validate,
// validation_markdown). run_paper_studies releases the GIL while the cases run on C++ worker
// threads; the progress callback re-acquires it. Ctrl-C (or an exception raised by the callback)
// cancels the run within a simulated period and is re-raised.
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum_paper/validation.hpp"

namespace oscidrum::python {
namespace {

std::string join_G(const std::vector<double>& G) {
  std::string out;
  for (std::size_t i = 0; i < G.size(); ++i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%g", i ? ", " : "", G[i] / 1e6);
    out += buf;
  }
  return out;
}

std::vector<SeriesResult> run_paper_studies_py(Int threads, bool keep_samples, Int n_harmonics,
                                               const py::object& progress) {
  GuardedCalls calls;
  PaperRunOptions options;
  options.threads = threads;
  options.keep_samples = keep_samples;
  options.n_harmonics = n_harmonics;
  if (!progress.is_none())
    options.progress = [&](std::size_t done, std::size_t total) {
      calls.guarded([&] { progress(done, total); });
    };
  // Polled between cases and once per simulated period: Ctrl-C (or an exception of the progress
  // callback) stops the run within a period.
  options.cancelled = [&]() { return calls.cancelled(); };
  std::vector<SeriesResult> results;
  try {
    results = run_watching_signals(calls, [&] { return run_paper_studies(options); });
  } catch (const Error&) {
    if (!calls.failed()) throw;  // "cancelled" because of a kept exception: raise that instead
  }
  calls.rethrow();
  return results;
}

// The results validate() reads, without the kept samples (which it does not use, and which
// would cost ~0.3 MB per case to copy). Checks what validate() indexes without checking.
std::vector<SeriesResult> for_validation(const py::iterable& items) {
  std::vector<SeriesResult> out;
  for (py::handle item : items) {
    if (!py::isinstance<SeriesResult>(item))
      throw Error("validate: results must be the SeriesResults of run_paper_studies(); results[" +
                  std::to_string(out.size()) + "] is " + python_description(item));
    const SeriesResult& s = item.cast<const SeriesResult&>();
    for (const Metrics& m : s.metrics)
      if (m.ddx_harmonics.size() < 3 || m.ddz_harmonics.size() < 3)
        throw Error("validate: series '" + s.series.id +
                    "' has fewer than 2 harmonics; run run_paper_studies with n_harmonics >= 2");
    SeriesResult light;
    light.series = s.series;
    light.status = s.status;
    light.metrics = s.metrics;
    light.diagnostics = s.diagnostics;
    out.push_back(std::move(light));
  }
  return out;
}

}  // namespace

void bind_validation(py::module_& m) {
  py::class_<PaperSeries>(m, "PaperSeries",
                          "One curve of the paper (read-only): a contact model, driving torque "
                          "and trough, over a list of G. paper_case(series, G) gives its cases.")
      .def_readonly("id", &PaperSeries::id, "stable identifier, e.g. 'rolling_MMd0_R0.606'")
      .def_readonly("description", &PaperSeries::description,
                    "e.g. 'pure rolling, MMd = 0, circle R = 0.606 m'")
      .def_readonly("pure_rolling", &PaperSeries::pure_rolling,
                    "True: pure rolling; False: stick-slip with Coulomb friction mu")
      .def_readonly("MMd_fraction", &PaperSeries::MMd_fraction,
                    "constant driving torque MMd / M0 [-]")
      .def_readonly("k", &PaperSeries::k, "trough spiral parameter k [-] (0: circle)")
      .def_readonly("a", &PaperSeries::a,
                    "trough spiral parameter a [m] (the circle's radius R when k = 0)")
      .def_readonly("G", &PaperSeries::G,
                    "shear moduli of the series [Pa] (list); Table 2 values use Table 2's soil, "
                    "others Appendix B")
      .def_readonly("mu", &PaperSeries::mu, "friction coefficient when not pure_rolling [-]")
      .def("__repr__", [](const PaperSeries& s) {
        char buf[160];
        std::snprintf(buf, sizeof buf,
                      "', pure_rolling=%s, MMd_fraction=%g, k=%g, a=%g m, mu=%g, G=[",
                      s.pure_rolling ? "True" : "False", s.MMd_fraction, s.k, s.a, s.mu);
        return "PaperSeries(id='" + s.id + buf + join_G(s.G) + "] MN/m^2)";
      });

  m.def("paper_series", &paper_series,
        "Every series the paper plots (Figs. 7-22), as a list of PaperSeries: pure rolling "
        "MMd = 0 for circle R = 0.603, 0.606, 0.62, 0.65 m (0.62 m is our choice: the paper "
        "prints only three of its four radii), pure rolling MMd = 0.05 M0, stick-slip (mu = 0.5) "
        "MMd = 0 and 0.05 M0, all over Table 2's G = 5 ... 70 MN/m^2 on R = 0.606 m unless said; "
        "the trough-shape pair at G = 5 MN/m^2 (circle R = 0.603 m, spiral k = 0.002, "
        "a = 0.601 m); the soft-soil series towards G -> 0 (Appendix B, Fig. 10) and the freely "
        "turning drum (mu = 0).");
  m.def(
      "paper_case",
      [](const PaperSeries& series, py::handle G) {
        // G by the rule of soil.G, as Case takes it: NaN, -5e6 or True made a Case holding it.
        return paper_case(series, field_argument("soil.G", G));
      },
      py::arg("series"), py::arg("G"),
      "The Case the paper simulates for `series` (a PaperSeries) at shear modulus G [Pa]: "
      "Table 1 roller, Table 2 soil when G is a Table 2 value (Appendix B otherwise), the "
      "series' contact model, MMd = MMd_fraction * M0 [N m] and trough (k [-], a [m]). "
      "Raises oscidrum.Error for a G outside soil.G's rule.");

  py::class_<SeriesResult>(m, "SeriesResult",
                           "The outcome of one PaperSeries (read-only): per G of series.G, in "
                           "that order, the status, metrics and diagnostics.")
      .def_readonly("series", &SeriesResult::series, "the PaperSeries")
      .def_property_readonly(
          "status",
          [](const SeriesResult& r) {
            std::vector<std::string> names;
            for (Status s : r.status) names.emplace_back(to_string(s));
            return names;
          },
          "status per G as text (list of str, e.g. 'steady_state'; Status.name)")
      .def_readonly("metrics", &SeriesResult::metrics, "Metrics per G (list)")
      .def_readonly("diagnostics", &SeriesResult::diagnostics, "Diagnostics per G (list)")
      .def_readonly("results", &SeriesResult::results,
                    "Result per G with its steady-state samples (list; empty unless "
                    "run_paper_studies(keep_samples=True))")
      .def("__len__", [](const SeriesResult& r) { return r.series.G.size(); })
      .def("__repr__", [](const SeriesResult& r) {
        std::size_t steady = 0;
        for (Status s : r.status) steady += s == Status::steady_state;
        return "SeriesResult(id='" + r.series.id + "', " + std::to_string(steady) + "/" +
               std::to_string(r.status.size()) + " steady, samples " +
               (r.results.empty() ? "not kept" : "kept") + ")";
      });

  m.def("run_paper_studies", &run_paper_studies_py, py::arg("threads") = 0,
        py::arg("keep_samples") = false, py::arg("n_harmonics") = 10,
        py::arg("progress") = py::none(),
        "Run every case of paper_series() (about 100) on `threads` C++ worker threads "
        "(0: all cores) with the GIL released; returns one SeriesResult per series, in "
        "paper_series() order. Takes a few seconds.\n\n"
        "keep_samples: keep each steady state (SeriesResult.results; ~0.3 MB per case), for "
        "figures.\n"
        "n_harmonics: harmonics in the metrics (validate needs >= 2).\n"
        "progress: optional callable progress(done, total), called after each case with the GIL "
        "held. An exception it raises (or Ctrl-C) is re-raised once every case has run; the "
        "study cannot be stopped early.\n"
        "Raises oscidrum.Error if a case is invalid.");

  py::class_<ValidationRow>(m, "ValidationRow",
                            "One line of the validation table (read-only): a result the paper "
                            "states, what oscidrum computes and whether they agree.")
      .def_readonly("id", &ValidationRow::id, "short stable identifier, e.g. 'fig9a.xmax_G5'")
      .def_readonly("figure", &ValidationRow::figure,
                    "where the paper says it, e.g. 'Fig. 9a', 'Figs. 11, 14', 'Sect. 3.4'")
      .def_readonly("claim", &ValidationRow::claim, "what the paper states")
      .def_readonly("paper", &ValidationRow::paper, "the paper's number or statement (with units)")
      .def_readonly("oscidrum", &ValidationRow::oscidrum, "what oscidrum computes (with units)")
      .def_readonly("rule", &ValidationRow::rule, "the acceptance rule applied")
      .def_readonly("agrees", &ValidationRow::agrees, "True: the rule holds")
      .def_readonly("checkable", &ValidationRow::checkable,
                    "False: the paper gives nothing a simulation can be compared with (agrees is "
                    "then False and meaningless)")
      .def_readonly("note", &ValidationRow::note,
                    "explanation, given where it does not agree or is not checkable")
      .def(
          "to_dict",
          [](const ValidationRow& r) {
            py::dict d;
            d["id"] = r.id;
            d["figure"] = r.figure;
            d["claim"] = r.claim;
            d["paper"] = r.paper;
            d["oscidrum"] = r.oscidrum;
            d["rule"] = r.rule;
            d["agrees"] = r.agrees;
            d["checkable"] = r.checkable;
            d["note"] = r.note;
            return d;
          },
          "{field: value} of every field, in table order.")
      .def("__repr__", [](const ValidationRow& r) {
        return "ValidationRow(id='" + r.id + "', figure='" + r.figure + "', " +
               (!r.checkable ? "not checkable"
                : r.agrees   ? "agrees"
                             : "does not agree") +
               ")";
      });

  m.def(
      "validate", [](const py::iterable& results) { return validate(for_validation(results)); },
      py::arg("results"),
      "Check every result the paper states (docs/validation.md) against the SeriesResults of "
      "run_paper_studies(): a list of ValidationRow, the same rows as `oscidrum validate` and "
      "docs/validation.md. Raises oscidrum.Error if a series or G is missing.");
  m.def("validation_markdown", &validation_markdown, py::arg("rows"),
        "The rows as a Markdown table followed by a summary line ('N of M checkable claims "
        "agree.'), as in docs/validation.md.");
}

}  // namespace oscidrum::python
