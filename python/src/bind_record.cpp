// Bindings of oscidrum/record.hpp: metrics of a measured acceleration record (paper Fig. 23).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <deque>
#include <span>
#include <string>
#include <variant>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/record.hpp"

namespace oscidrum::python {
namespace {

py::array_t<double> column(const std::vector<Harmonic>& h, double Harmonic::*member) {
  py::array_t<double> a(static_cast<py::ssize_t>(h.size()));
  auto out = a.mutable_unchecked<1>();
  for (std::size_t n = 0; n < h.size(); ++n) out(static_cast<py::ssize_t>(n)) = h[n].*member;
  return a;
}

const char* doc(const RecordOutput& o) {
  static std::deque<std::string> docs;  // stable addresses
  docs.push_back(std::string(o.description) + " [" + o.unit + "]" +
                 (is_scalar(o) ? "" : " (list of Harmonic)"));
  return docs.back().c_str();
}

}  // namespace

void bind_record(py::module_& m) {
  py::class_<RecordMetrics> cls(
      m, "RecordMetrics",
      "Metrics of a measured record, from a least-squares harmonic fit (docs/outputs.md).");
  for (const RecordOutput& o : record_outputs())
    std::visit([&](auto member) { cls.def_readonly(o.name, member, doc(o)); }, o.member);
  cls.def_property_readonly_static(
         "scalar_names",
         [](py::handle) {
           py::list names;
           for (const RecordOutput& o : record_outputs())
             if (is_scalar(o)) names.append(o.name);
           return names;
         },
         "names of the scalar outputs, in to_dict order")
      .def(
          "to_dict",
          [](const RecordMetrics& r) {
            py::dict d;
            for (const RecordOutput& o : record_outputs())
              if (is_scalar(o)) d[o.name] = scalar_value(r, o);
            return d;
          },
          "The scalar outputs as {name: value}.")
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
