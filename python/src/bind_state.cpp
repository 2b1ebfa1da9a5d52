// Bindings of oscidrum/state.hpp: the contact phase, the state vector and its accelerations.
#include <cstdio>
#include <string>

#include "bindings.hpp"
#include "oscidrum/state.hpp"

namespace oscidrum::python {

void bind_state(py::module_& m) {
  py::enum_<Phase> phase(
      m, "Phase", "Contact phase; the value of a slip phase is s = sign(v_rel) of (27)-(29).");
  strict_enum(phase);
  phase.value("slip_negative", Phase::slip_negative, "v_rel < 0, T = +mu N > 0 (-1)")
      .value("stick", Phase::stick, "pure rolling, |T| <= mu N (0)")
      .value("slip_positive", Phase::slip_positive, "v_rel > 0, T = -mu N < 0 (+1)")
      .value("flight", Phase::flight,
             "no contact: the drum has lifted off (contact.unilateral), N = T = 0 (2)")
      .value("smooth", Phase::smooth,
             "the one phase of the regularised friction law (2); samples show its apparent "
             "phase (stick while creeping) instead")
      .def_property_readonly(
          "label", [](Phase p) { return to_string(p); },
          "'stick', 'slip+', 'slip-', 'flight' or 'smooth'");

  py::class_<State>(m, "State",
                    "The state q = (delta, x_A, s_A, phi, delta', x_A', s_A', phi') of (51), "
                    "(54).")
      .def(py::init([](double delta, double x_A, double s_A, double phi, double ddelta, double dx_A,
                       double ds_A, double dphi) {
             return State{delta, x_A, s_A, phi, ddelta, dx_A, ds_A, dphi};
           }),
           py::kw_only(), py::arg("delta") = 0.0, py::arg("x_A") = 0.0, py::arg("s_A") = 0.0,
           py::arg("phi") = 0.0, py::arg("ddelta") = 0.0, py::arg("dx_A") = 0.0,
           py::arg("ds_A") = 0.0, py::arg("dphi") = 0.0)
      .def_readwrite("delta", &State::delta, "position angle of the drum in the trough [rad]")
      .def_readwrite("x_A", &State::x_A, "horizontal displacement of the trough [m]")
      .def_readwrite("s_A", &State::s_A, "vertical displacement of the trough, down [m]")
      .def_readwrite("phi", &State::phi, "total drum rotation [rad]")
      .def_readwrite("ddelta", &State::ddelta, "delta' [rad/s]")
      .def_readwrite("dx_A", &State::dx_A, "x_A' [m/s]")
      .def_readwrite("ds_A", &State::ds_A, "s_A' [m/s]")
      .def_readwrite("dphi", &State::dphi, "phi' [rad/s]")
      .def("__repr__", [](const State& q) {
        char buf[320];
        std::snprintf(buf, sizeof buf,
                      "State(delta=%.6g rad, x_A=%.6g m, s_A=%.6g m, phi=%.6g rad, "
                      "ddelta=%.6g rad/s, dx_A=%.6g m/s, ds_A=%.6g m/s, dphi=%.6g rad/s)",
                      q.delta, q.x_A, q.s_A, q.phi, q.ddelta, q.dx_A, q.ds_A, q.dphi);
        return std::string(buf);
      });

  py::class_<Accelerations>(m, "Accelerations", "Second derivatives of the coordinates.")
      .def_readonly("delta", &Accelerations::delta, "delta'' [rad/s^2]")
      .def_readonly("x_A", &Accelerations::x_A, "x_A'' [m/s^2]")
      .def_readonly("s_A", &Accelerations::s_A, "s_A'' [m/s^2]")
      .def_readonly("phi", &Accelerations::phi, "phi'' [rad/s^2]")
      .def("__repr__", [](const Accelerations& a) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "Accelerations(delta=%.6g rad/s^2, x_A=%.6g m/s^2, s_A=%.6g m/s^2, "
                      "phi=%.6g rad/s^2)",
                      a.delta, a.x_A, a.s_A, a.phi);
        return std::string(buf);
      });
}

}  // namespace oscidrum::python
