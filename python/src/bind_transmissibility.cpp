// Bindings of oscidrum/transmissibility.hpp: Appendix A, decoupling of drum and frame.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "bindings.hpp"
#include "oscidrum/transmissibility.hpp"

namespace oscidrum::python {

void bind_transmissibility(py::module_& m) {
  py::class_<Transmissibility>(m, "Transmissibility", "Appendix A (40).")
      .def_readonly("omega", &Transmissibility::omega,
                    "natural circular frequency sqrt(kd / m_f) [rad/s]")
      .def_readonly("zeta", &Transmissibility::zeta, "damping ratio cd / (2 m_f omega) [-]")
      .def_readonly("ratio", &Transmissibility::ratio, "nu / omega [-]")
      .def_readonly("Tp", &Transmissibility::Tp, "absolute displacement transmissibility (40) [-]")
      .def("__repr__", [](const Transmissibility& t) {
        char buf[160];
        std::snprintf(buf, sizeof buf,
                      "Transmissibility(omega=%.6g rad/s, zeta=%.6g, ratio=%.6g, Tp=%.6g)", t.omega,
                      t.zeta, t.ratio, t.Tp);
        return std::string(buf);
      });
  m.def("transmissibility", &transmissibility, py::arg("kd") = 4.0e6, py::arg("cd") = 3.0e3,
        py::arg("m_f") = 2760.0, py::arg("nu") = 2.0 * std::numbers::pi * 39.0,
        "Appendix A (40) for a frame of mass m_f [kg] on the suspension kd [N/m], cd [N s/m], "
        "base excitation at nu [rad/s]. Defaults: the paper's roller (Tp = 0.025).");
}

}  // namespace oscidrum::python
