// Bindings of oscidrum/metrics.hpp: harmonics, enclosed area and the metrics of a steady state.
// Harmonics are returned both as NumPy arrays (amplitude, phase) and as Harmonic objects.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <deque>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/metrics.hpp"

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

// Scalar metrics in a fixed order: (name, unit, member).
struct Scalar {
  const char* name;
  const char* unit;
  double Metrics::*member;
  const char* doc;
};
const Scalar kScalars[] = {
    {"ddx_max", "m/s^2", &Metrics::ddx_max, "largest x_M''"},
    {"ddx_min", "m/s^2", &Metrics::ddx_min, "smallest x_M''"},
    {"ddz_max", "m/s^2", &Metrics::ddz_max, "largest z_M'' (down positive)"},
    {"ddz_min", "m/s^2", &Metrics::ddz_min, "smallest z_M''"},
    {"delta_max", "rad", &Metrics::delta_max, "largest position angle delta"},
    {"delta_min", "rad", &Metrics::delta_min, "smallest position angle delta"},
    {"phi_lag", "pi rad", &Metrics::phi_lag,
     "lag between M0 sin(nu t) and phi: theta_1 of phi (drift removed), wrapped to (-2, 0], in "
     "units of pi (paper Fig. 10)"},
    {"phi_amplitude", "rad", &Metrics::phi_amplitude, "A_1 of phi"},
    {"psi_xz", "rad", &Metrics::psi_xz,
     "lag psi = theta_2(z_M'') - 2 theta_1(x_M'') wrapped to (-pi, pi] (docs/model.md; "
     "psi > 0: the 2f component of z_M'' leads)"},
    {"area", "m^2/s^4", &Metrics::area,
     "area enclosed by z_M'' over x_M'' (non-zero winding, both lobes count)"},
    {"stick_fraction", "-", &Metrics::stick_fraction, "stick share of the sampled time"},
    {"slip_positive_fraction", "-", &Metrics::slip_positive_fraction, "slip+ share"},
    {"slip_negative_fraction", "-", &Metrics::slip_negative_fraction, "slip- share"},
};

const char* scalar_doc(const Scalar& s) {
  static std::deque<std::string> docs;  // stable addresses
  docs.push_back(std::string(s.doc) + " [" + s.unit + "]");
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
                          "Metrics of a simulated steady state (docs/model.md). Harmonic n "
                          "of x_M'' is ddx_amplitude[n] [m/s^2], ddx_phase[n] [rad], n = 0 ... "
                          "n_max (n = 0: the mean).");
  for (const Scalar& s : kScalars) cls.def_readonly(s.name, s.member, scalar_doc(s));
  cls.def_readonly("ddx_harmonics", &Metrics::ddx_harmonics,
                   "harmonics n = 0 ... n_max of x_M'' (list of Harmonic) [m/s^2]")
      .def_readonly("ddz_harmonics", &Metrics::ddz_harmonics,
                    "harmonics n = 0 ... n_max of z_M'' (list of Harmonic) [m/s^2]")
      .def_property_readonly(
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
            for (const Scalar& s : kScalars) names.append(s.name);
            return names;
          },
          "names of the scalar metrics, in to_dict order")
      .def_property_readonly_static(
          "units",
          [](py::handle) {
            py::dict units;
            for (const Scalar& s : kScalars) units[s.name] = s.unit;
            return units;
          },
          "{scalar metric: unit}")
      .def(
          "to_dict",
          [](const Metrics& mt) {
            py::dict d;
            for (const Scalar& s : kScalars) d[s.name] = mt.*(s.member);
            return d;
          },
          "The scalar metrics as {name: value} (units: Metrics.units).")
      .def("__repr__", [](const Metrics& mt) {
        std::string out = "Metrics(";
        bool first = true;
        for (const Scalar& s : kScalars) {
          char buf[96];
          std::snprintf(buf, sizeof buf, "%s%s=%.6g%s%s", first ? "" : ", ", s.name, mt.*(s.member),
                        std::string(s.unit) == "-" ? "" : " ",
                        std::string(s.unit) == "-" ? "" : s.unit);
          out += buf;
          first = false;
        }
        return out + ", harmonics n <= " +
               std::to_string(mt.ddx_harmonics.empty() ? 0 : mt.ddx_harmonics.size() - 1) + ")";
      });

  m.def(
      "harmonics",
      [](const Array& y, int cycles, double f, double t0, int n_max) {
        auto h = harmonics(span_of(y, "y"), cycles, f, t0, n_max);
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
  m.def("wrap_pi", &wrap_pi, py::arg("angle"), "Wrap an angle [rad] to (-pi, pi].");
  m.def("compute_metrics", &compute_metrics, py::arg("result"), py::arg("n_max") = 10,
        "Metrics of a Result's steady state (docs/model.md).\n\n"
        "Parameters\n----------\nresult : Result\n    A result with samples.\nn_max : int, "
        "default 10\n    Highest harmonic.\n\n"
        "Returns\n-------\nMetrics\n    ddx_max, ddz_max [m/s^2], phi_lag [pi rad], psi_xz "
        "[rad], area [m^2/s^4], stick_fraction [-], harmonics, ... (units: Metrics.units).\n\n"
        "Raises\n------\noscidrum.Error\n    If the result holds no samples.\n\n"
        "Examples\n--------\n>>> m = oscidrum.compute_metrics(oscidrum.simulate(oscidrum.Case()))"
        "\n>>> round(m.area, 1)   # [m^2/s^4]\n22.8\n");
}

}  // namespace oscidrum::python
