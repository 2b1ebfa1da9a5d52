// Bindings of oscidrum/kinematics.hpp: trough geometry and the functions f1 ... f6 of delta.
#include <variant>

#include "bindings.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/model.hpp"

namespace oscidrum::python {

void bind_kinematics(py::module_& m) {
  py::class_<TroughGeometry>(
      m, "TroughGeometry", "Derived geometry of the log-spiral trough (docs/model.md section 1.4).")
      .def_readonly("r", &TroughGeometry::r, "drum radius [m]")
      .def_readonly("k", &TroughGeometry::k, "spiral parameter [-]")
      .def_readonly("a", &TroughGeometry::a, "spiral parameter [m]")
      .def_readonly("alpha", &TroughGeometry::alpha, "alpha = atan(1/k) [rad]")
      .def_readonly("R0", &TroughGeometry::R0, "R0 = a exp(k theta0) [m]")
      .def_property_readonly(
          "shape",
          [](const TroughGeometry& g) {
            return std::holds_alternative<CircleTrough>(g.shape) ? "circle" : "log_spiral";
          },
          "the trough's shape: 'circle' (k = 0, radius a) or 'log_spiral' (k > 0)");
  m.def(
      "make_trough_geometry",
      [](double r, double k, double a) {
        // The rules of roller.r, trough.k and trough.a, and between them, as for a Case.
        Case c;
        set_field(c, "roller.r", r);
        set_field(c, "trough.k", k);
        set_field(c, "trough.a", a);
        const Model model(c);
        return model.geometry();
      },
      py::arg("r"), py::arg("k"), py::arg("a"),
      "Derived trough geometry from drum radius r [m], spiral k [-] and a [m].\n\n"
      "Raises\n------\noscidrum.Error\n    When r, k or a breaks the rule of roller.r, trough.k or "
      "trough.a, or the trough does not fit the drum (e.g. a <= r for k = 0).");

  py::class_<Kinematics>(m, "Kinematics",
                         "Everything that depends on delta alone, (15)-(16), "
                         "(46)-(50), (33), (37).")
      .def_readonly("x_roll", &Kinematics::x_roll, "(15) [m]")
      .def_readonly("z_roll", &Kinematics::z_roll, "(16) [m]")
      .def_readonly("f1", &Kinematics::f1, "(46) d x_roll / d delta [m]")
      .def_readonly("f2", &Kinematics::f2, "(47) d f1 / d delta [m]")
      .def_readonly("f3", &Kinematics::f3, "(48) d z_roll / d delta [m]")
      .def_readonly("f4", &Kinematics::f4, "(49) d f3 / d delta [m]")
      .def_readonly("f5", &Kinematics::f5, "(50) phi' = f5 delta' in stick [-]")
      .def_readonly("f6", &Kinematics::f6, "(50) d f5 / d delta [-]")
      .def_readonly("f1_bar", &Kinematics::f1_bar, "(33) f1 cos - f3 sin [m]")
      .def_readonly("f2_bar", &Kinematics::f2_bar, "(33) f2 cos - f4 sin [m]")
      .def_readonly("f3_tilde", &Kinematics::f3_tilde, "(37) f1 sin + f3 cos [m]")
      .def_readonly("f4_tilde", &Kinematics::f4_tilde, "(37) f2 sin + f4 cos [m]");
  m.def("kinematics", &kinematics, py::arg("geometry"), py::arg("delta"),
        "Evaluate (15), (16), (46)-(50), (33), (37) at delta [rad].");
  m.def("phi_rolling", &phi_rolling, py::arg("geometry"), py::arg("delta"),
        "Rolling condition (11): phi [rad] as a function of delta [rad] with no slip.");
}

}  // namespace oscidrum::python
