// Bindings of oscidrum/kinematics.hpp: trough geometry and the functions f1 ... f6 of delta.
#include <deque>
#include <string>

#include "bindings.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/model.hpp"

namespace oscidrum::python {
namespace {
// Docstrings must outlive the module definition.
const char* keep_doc(std::string text) {
  static std::deque<std::string> store;
  store.push_back(std::move(text));
  return store.back().c_str();
}
}  // namespace

void bind_kinematics(py::module_& m) {
  std::string names;
  for (const std::string& n : trough_shape_names())
    names += (names.empty() ? "'" : ", '") + n + "'";
  py::class_<TroughGeometry>(
      m, "TroughGeometry",
      "A drum of radius r in a trough of some shape (docs/model.md section 1.4). The shape "
      "describes itself: its name, a summary and its parameters (given and derived), each also an "
      "attribute (geometry.R of a circle; geometry.k, .a, .alpha, .R0 of a log spiral).")
      .def_readonly("r", &TroughGeometry::r, "drum radius [m]")
      .def_property_readonly(
          "shape", [](const TroughGeometry& g) { return trough_name(g.shape); },
          keep_doc("the trough's shape: one of " + names))
      .def_property_readonly(
          "summary", [](const TroughGeometry& g) { return summary(g.shape); },
          "the shape in words, e.g. 'circle, R = 0.606 m'")
      .def_property_readonly(
          "parameters",
          [](const TroughGeometry& g) {
            py::dict d;
            for (const TroughParameter& p : parameters(g.shape)) d[p.symbol] = p.value;
            return d;
          },
          "the shape's parameters {symbol: value} in SI units (e.g. {'R': 0.606}; a log spiral "
          "also its derived alpha [rad] and R0 [m])")
      .def_property_readonly(
          "curvature_radius",
          [](const TroughGeometry& g) { return curvature_radius_at_bottom(g.shape); },
          "radius of curvature of the trough at its bottom [m] (R of a circle, sqrt(1+k^2) R0 of a "
          "log spiral)")
      .def("__getattr__",
           [](const TroughGeometry& g, const std::string& name) {
             for (const TroughParameter& p : parameters(g.shape))
               if (name == p.symbol) return p.value;
             throw py::attribute_error("a " + std::string(trough_name(g.shape)) +
                                       " trough has no parameter '" + name + "'");
           })
      .def("__repr__", [](const TroughGeometry& g) {
        return "TroughGeometry(r=" + py::repr(py::float_(g.r)).cast<std::string>() + ", " +
               summary(g.shape) + ")";
      });
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
  m.def("kinematics", py::overload_cast<const TroughGeometry&, double>(&kinematics),
        py::arg("geometry"), py::arg("delta"),
        "Evaluate (15), (16), (46)-(50), (33), (37) at delta [rad].");
  m.def("phi_rolling", py::overload_cast<const TroughGeometry&, double>(&phi_rolling),
        py::arg("geometry"), py::arg("delta"),
        "Rolling condition (11): phi [rad] as a function of delta [rad] with no slip.");
}

}  // namespace oscidrum::python
