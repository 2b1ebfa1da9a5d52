// Bindings of oscidrum/record.hpp: metrics of a measured acceleration record (paper Fig. 23).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <span>
#include <string>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/record.hpp"

namespace oscidrum::python {
namespace {

py::array_t<double> column(const std::vector<Harmonic>& h, double Harmonic::*member) {
  py::array_t<double> a(static_cast<py::ssize_t>(h.size()));
  auto out = a.mutable_unchecked<1>();
  for (std::size_t n = 0; n < h.size(); ++n) out(static_cast<py::ssize_t>(n)) = h[n].*member;
  return a;
}

}  // namespace

void bind_record(py::module_& m) {
  py::class_<RecordMetrics>(m, "RecordMetrics",
                            "Metrics of a measured record, from a least-squares harmonic fit.")
      .def_readonly("ddx_harmonics", &RecordMetrics::ddx_harmonics,
                    "harmonics n = 0 ... n_max of x_M'' (absolute-time phases) [m/s^2]")
      .def_readonly("ddz_harmonics", &RecordMetrics::ddz_harmonics,
                    "harmonics n = 0 ... n_max of z_M'' [m/s^2]")
      .def_property_readonly(
          "ddx_amplitude",
          [](const RecordMetrics& r) { return column(r.ddx_harmonics, &Harmonic::amplitude); },
          "A_n of x_M'' [m/s^2]")
      .def_property_readonly(
          "ddz_amplitude",
          [](const RecordMetrics& r) { return column(r.ddz_harmonics, &Harmonic::amplitude); },
          "A_n of z_M'' [m/s^2]")
      .def_property_readonly(
          "ddx_phase",
          [](const RecordMetrics& r) { return column(r.ddx_harmonics, &Harmonic::phase); },
          "theta_n of x_M'' [rad]")
      .def_property_readonly(
          "ddz_phase",
          [](const RecordMetrics& r) { return column(r.ddz_harmonics, &Harmonic::phase); },
          "theta_n of z_M'' [rad]")
      .def_readonly("ddx_max", &RecordMetrics::ddx_max, "largest fitted x_M'' [m/s^2]")
      .def_readonly("ddx_min", &RecordMetrics::ddx_min, "smallest fitted x_M'' [m/s^2]")
      .def_readonly("ddz_max", &RecordMetrics::ddz_max, "largest fitted z_M'' [m/s^2]")
      .def_readonly("ddz_min", &RecordMetrics::ddz_min, "smallest fitted z_M'' [m/s^2]")
      .def_readonly("psi_xz", &RecordMetrics::psi_xz,
                    "theta_2(z) - 2 theta_1(x), wrapped to (-pi, pi] [rad]")
      .def_readonly("area", &RecordMetrics::area, "area of the fitted periodic figure [m^2/s^4]")
      .def_readonly("cycles", &RecordMetrics::cycles, "excitation periods the record spans [-]")
      .def_readonly("residual_x", &RecordMetrics::residual_x,
                    "RMS of record minus fit relative to the RMS of x_M'' [-]")
      .def_readonly("residual_z", &RecordMetrics::residual_z,
                    "RMS of record minus fit relative to the RMS of z_M'' [-]")
      .def("__repr__", [](const RecordMetrics& r) {
        char buf[240];
        std::snprintf(buf, sizeof buf,
                      "RecordMetrics(cycles=%.4g, ddx_max=%.6g m/s^2, ddz_max=%.6g m/s^2, "
                      "psi_xz=%.6g rad, area=%.6g m^2/s^4, residual_x=%.3g, residual_z=%.3g)",
                      r.cycles, r.ddx_max, r.ddz_max, r.psi_xz, r.area, r.residual_x, r.residual_z);
        return std::string(buf);
      });
  m.def(
      "analyze_record",
      [](const Array& t, const Array& ddx, const Array& ddz, double f, int n_max) {
        return analyze_record(span_of(t, "t"), span_of(ddx, "ddx_M"), span_of(ddz, "ddz_M"), f,
                              n_max);
      },
      py::arg("t"), py::arg("ddx_M"), py::arg("ddz_M"), py::arg("f"), py::arg("n_max") = 10,
      "Metrics of a measured record: fit y(t) = sum_n (a_n cos(n nu t) + b_n sin(n nu t)) to "
      "x_M'' and z_M'' [m/s^2] sampled at t [s] (strictly increasing, any spacing, at least one "
      "period of f [Hz]) by least squares, then evaluate the metrics on the fitted periodic "
      "signals. Raises oscidrum.Error on inconsistent input.");
}

}  // namespace oscidrum::python
