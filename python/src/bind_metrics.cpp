// Bindings of oscidrum/metrics.hpp: harmonics, enclosed area and the metrics of a steady state.
// Harmonics are returned both as NumPy arrays (amplitude, phase) and as Harmonic objects.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/output_table.hpp"
#include "pickling.hpp"

namespace oscidrum::python {
namespace {

py::array_t<double> amplitudes(const std::vector<Harmonic>& h) {
  py::array_t<double> a(static_cast<py::ssize_t>(h.size()));
  auto out = a.mutable_unchecked<1>();
  for (std::size_t n = 0; n < h.size(); ++n) out(static_cast<py::ssize_t>(n)) = h[n].amplitude;
  return a;
}

py::array_t<double> phases(const std::vector<Harmonic>& h) {
  py::array_t<double> a(static_cast<py::ssize_t>(h.size()));
  auto out = a.mutable_unchecked<1>();
  for (std::size_t n = 0; n < h.size(); ++n) out(static_cast<py::ssize_t>(n)) = h[n].phase;
  return a;
}

// "description [unit]" with a stable address, for docstrings.
const char* doc(const MetricOutput& o) {
  static std::deque<std::string> docs;  // stable addresses
  docs.push_back(std::string(o.description) + " [" + o.unit + "]" +
                 (is_scalar(o) ? "" : " (list of Harmonic)"));
  return docs.back().c_str();
}

}  // namespace

void bind_metrics(py::module_& m) {
  py::class_<Harmonic>(m, "Harmonic",
                       "One harmonic n f of y(t) = sum_n A_n sin(n nu t + theta_n), t absolute.")
      .def_readonly("amplitude", &Harmonic::amplitude, "A_n >= 0 [unit of the signal]")
      .def_readonly("phase", &Harmonic::phase, "theta_n in (-pi, pi] [rad]")
      .def("__repr__", [](const Harmonic& h) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "Harmonic(amplitude=%.6g, phase=%.6g rad)", h.amplitude,
                      h.phase);
        return std::string(buf);
      });

  py::class_<Metrics> cls(m, "Metrics",
                          "Metrics of a simulated steady state (docs/outputs.md). Harmonic n "
                          "of x_M'' is ddx_amplitude[n] [m/s^2], ddx_phase[n] [rad], n = 0 ... "
                          "n_max (n = 0: the mean). Picklable, between processes of the same "
                          "oscidrum build.");
  pickling::def_pickle(cls, "Metrics");
  for (const MetricOutput& o : metric_outputs())
    std::visit([&](auto member) { cls.def_readonly(o.name, member, doc(o)); }, o.member);
  cls.def_property_readonly(
         "ddx_amplitude", [](const Metrics& mt) { return amplitudes(mt.ddx_harmonics); },
         "A_n of x_M'', n = 0 ... n_max [m/s^2]")
      .def_property_readonly(
          "ddx_phase", [](const Metrics& mt) { return phases(mt.ddx_harmonics); },
          "theta_n of x_M'' [rad]")
      .def_property_readonly(
          "ddz_amplitude", [](const Metrics& mt) { return amplitudes(mt.ddz_harmonics); },
          "A_n of z_M'', n = 0 ... n_max [m/s^2]")
      .def_property_readonly(
          "ddz_phase", [](const Metrics& mt) { return phases(mt.ddz_harmonics); },
          "theta_n of z_M'' [rad]")
      .def_property_readonly_static(
          "scalar_names",
          [](py::handle) {
            py::list names;
            for (const MetricOutput& o : metric_outputs())
              if (is_scalar(o)) names.append(o.name);
            return names;
          },
          "names of the scalar metrics, in to_dict order")
      .def_property_readonly_static(
          "units",
          [](py::handle) {
            py::dict units;
            for (const MetricOutput& o : metric_outputs()) units[o.name] = o.unit;
            return units;
          },
          "{scalar metric: unit}")
      .def(
          "to_dict",
          [](const Metrics& mt) {
            py::dict d;
            for (const MetricOutput& o : metric_outputs())
              if (is_scalar(o)) d[o.name] = scalar_value(mt, o);
            return d;
          },
          "The scalar metrics as {name: value} (units: Metrics.units).")
      .def("__repr__", [](const Metrics& mt) {
        std::string out = "Metrics(";
        bool first = true;
        for (const MetricOutput& o : metric_outputs()) {
          if (!is_scalar(o)) continue;
          char buf[96];
          std::snprintf(buf, sizeof buf, "%s%s=%.6g%s%s", first ? "" : ", ", o.name,
                        scalar_value(mt, o), std::string(o.unit) == "-" ? "" : " ",
                        std::string(o.unit) == "-" ? "" : o.unit);
          out += buf;
          first = false;
        }
        return out + ", harmonics n <= " +
               std::to_string(mt.ddx_harmonics.empty() ? 0 : mt.ddx_harmonics.size() - 1) + ")";
      });

  m.def(
      "harmonics",
      [](const Array& y, Int cycles, double f, double t0, Int n_max) {
        // A NaN sample made every amplitude NaN without a word on where it was.
        const auto ys = span_of(y, "y");
        for (std::size_t i = 0; i < ys.size(); ++i)
          if (!std::isfinite(ys[i]))
            throw Error("harmonics: y[" + std::to_string(i) + "] = " + std::to_string(ys[i]) +
                        ": every sample must be finite (drop or fill the gap first)");
        auto h = harmonics(ys, cycles, f, t0, n_max);
        return std::make_pair(amplitudes(h), phases(h));
      },
      py::arg("y"), py::arg("cycles"), py::arg("f"), py::arg("t0") = 0.0, py::arg("n_max") = 10,
      "Harmonics n = 0 ... n_max of y, uniformly sampled over exactly `cycles` periods of f [Hz] "
      "starting at t0 [s] (a DFT over whole periods: no window, no leakage). Returns the arrays "
      "(amplitude [unit of y], phase [rad]) with y(t) = sum A_n sin(n 2 pi f t + theta_n).");
  m.def(
      "enclosed_area",
      [](const Array& x, const Array& y) {
        if (x.size() != y.size()) throw Error("enclosed_area: x and y must have the same length");
        return enclosed_area(span_of(x, "x"), span_of(y, "y"));
      },
      py::arg("x"), py::arg("y"),
      "Area of the region enclosed by the closed polygon (x, y) (non-zero winding: both lobes "
      "of a figure-eight count) [unit x * unit y].");
  m.def(
      "absent_signals",
      [](const Array& ddx_amplitude, const Array& ddz_amplitude) {
        auto spectrum = [](const Array& a, const char* name) {
          Spectrum h;
          for (double v : span_of(a, name)) h.push_back({v, 0.0});
          return h;
        };
        const AbsentSignals s = absent_signals(spectrum(ddx_amplitude, "ddx_amplitude"),
                                               spectrum(ddz_amplitude, "ddz_amplitude"));
        return std::make_pair(s.ddx, s.ddz);
      },
      py::arg("ddx_amplitude"), py::arg("ddz_amplitude"),
      "Whether x_M'' and z_M'' are absent as a whole, from their harmonic amplitudes A_0 ... A_n "
      "(Metrics.ddx_amplitude, ddz_amplitude) [m/s^2]: every component of the signal at most 1e-6 "
      "of the largest component of the two, or below 1e-12 g (round-off of a motion that has "
      "none, such as the directed vertical exciter's x_M''). Returns (ddx_absent, ddz_absent).");
  m.def("wrap_pi", &wrap_pi, py::arg("angle"), "Wrap an angle [rad] to (-pi, pi].");
  m.def(
      "vibration_modulus",
      [](const Array& z, const Array& F, double R, double L, double nu) {
        return vibration_modulus(span_of(z, "z"), span_of(F, "F"), R, L, nu);
      },
      py::arg("z"), py::arg("F"), py::arg("R"), py::arg("L"), py::arg("nu"),
      "The Evib-type vibration modulus [Pa] of a closed force-displacement loop: the Young's "
      "modulus under which Lundberg's rigid cylinder settles as the drum does on the loop's "
      "loading branch (Metrics.evib; docs/outputs.md).\n\n"
      "Parameters\n----------\nz : array of float\n    The drum centre's vertical displacement "
      "[m], downwards, in time order over one steady period (the last point joins the first).\n"
      "F : array of float\n    The soil's vertical force on the drum [N] at the same instants "
      "(0 in flight).\nR : float\n    Drum radius [m], > 0 (oscidrum's drum: "
      "roller.r).\nL : float\n    Drum length [m], > 0 (roller.b).\nnu : float\n    The soil's "
      "Poisson's ratio [-], in [0, 0.5).\n\n"
      "Returns\n-------\nfloat\n    E [Pa] from the loading branch, from the loop's least z "
      "forward to its largest: its end the branch's largest F, its start the landing (where F "
      "rises from 0, interpolated linearly) after a flight, else the branch's first point. NaN "
      "for a degenerate loop (no positive force, no rise in force or in z, fewer than 3 points, "
      "a non-finite value).\n\n"
      "Raises\n------\noscidrum.Error\n    If z or F is not 1-D, their lengths differ, or R, "
      "L, nu are out of range (the message names the argument).");
  m.def(
      "compute_metrics",
      [](const Result& result, Int n_max, const std::optional<Case>& c) {
        if (!c) return compute_metrics(result, n_max);
        const Model model(*c);
        return compute_metrics(model, result, n_max);
      },
      py::arg("result"), py::arg("n_max") = 10, py::arg("case") = py::none(),
      "Metrics of a Result's steady state (docs/outputs.md).\n\n"
      "Parameters\n----------\nresult : Result\n    A steady-state result with samples.\n"
      "n_max : int, default 10\n    Highest harmonic.\n"
      "case : Case, optional\n    The Case the result was simulated with: the metrics are then "
      "read off the trajectory's dense output, as `run` and `run_study` do, independent of "
      "numerics.samples_per_period; without it, off the uniform samples.\n\n"
      "Returns\n-------\nMetrics\n    ddx_max, ddz_max [m/s^2], phi_lag [pi rad], psi_xz "
      "[rad], area [m^2/s^4], stick_fraction [-], harmonics, ... (units: Metrics.units).\n\n"
      "Raises\n------\noscidrum.Error\n    If the result is no steady state or holds no "
      "samples.\n\n"
      "Examples\n--------\n>>> case = oscidrum.Case()\n"
      ">>> m = oscidrum.compute_metrics(oscidrum.simulate(case), case=case)"
      "\n>>> round(m.area, 1)   # [m^2/s^4]\n22.8\n");
}

}  // namespace oscidrum::python
