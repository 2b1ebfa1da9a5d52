// Bindings of oscidrum/model.hpp: a validated Case with its derived constants, and the
// equations of motion evaluated at one state (for checks and teaching; simulate() needs none).
#include "bindings.hpp"
#include "oscidrum/model.hpp"

namespace oscidrum::python {

void bind_model(py::module_& m) {
  py::class_<Model>(m, "Model",
                    "An immutable, validated model: the Case plus its derived constants. "
                    "Construction raises oscidrum.Error naming the field, the rule and the value.")
      .def(py::init<const Case&>(), py::arg("case"))
      .def_property_readonly(
          "parameters", [](const Model& md) { return md.parameters(); }, "the Case (a copy)")
      .def_property_readonly("geometry", &Model::geometry, "trough geometry")
      .def_property_readonly("ksh", &Model::ksh, "horizontal soil spring [N/m]")
      .def_property_readonly("ksv", &Model::ksv, "vertical soil spring [N/m]")
      .def_property_readonly("csh", &Model::csh, "horizontal soil dashpot [N s/m]")
      .def_property_readonly("csv", &Model::csv, "vertical soil dashpot [N s/m]")
      .def_property_readonly("W", &Model::W, "m g + Fz (= P0) [N]")
      .def_property_readonly("Fz", &Model::Fz, "P0 - m g (7) [N]")
      .def_property_readonly("nu", &Model::nu, "excitation circular frequency 2 pi f [rad/s]")
      .def_property_readonly("period", &Model::period, "excitation period 1/f [s]")
      .def_property_readonly("z_ref", &Model::z_ref, "suspension reference of z_M [m]")
      .def("torque", &Model::torque, py::arg("t"), "MM(t) = M0 sin(nu t) + MMd [N m] at t [s]")
      .def("initial_state", &Model::initial_state,
           "At rest at the bottom of the trough, s_A = (W + kd z_ref)/(ksv + kd).");

  py::class_<ContactForces>(m, "ContactForces", "Contact forces at C.")
      .def_readonly("N", &ContactForces::N, "normal force (26) [N]")
      .def_readonly("T", &ContactForces::T, "tangential force (24)-(25) [N]");
  m.def("contact_forces", &contact_forces, py::arg("model"), py::arg("state"),
        "N and T [N] at a state (functions of the state alone: the soil is massless).");
  m.def("slip_velocity", &slip_velocity, py::arg("model"), py::arg("state"),
        "(13): v_rel = r f5 delta' - r phi' [m/s].");
  m.def("accelerations", &accelerations, py::arg("model"), py::arg("t"), py::arg("state"),
        py::arg("phase"), py::arg("baumgarte") = 0.0,
        "Second derivatives in the given phase at time t [s]; baumgarte [1/s] stabilises (39).");
  m.def("slip_constraint_residual", &slip_constraint_residual, py::arg("model"), py::arg("state"),
        py::arg("s"), "Residual of the slip coupling (39) [N] for s = +1 or -1.");

  py::class_<DrumMotion>(m, "DrumMotion", "Drum-centre motion (14), (17), (18).")
      .def_readonly("x_M", &DrumMotion::x_M, "[m]")
      .def_readonly("z_M", &DrumMotion::z_M, "[m], down positive")
      .def_readonly("dx_M", &DrumMotion::dx_M, "[m/s]")
      .def_readonly("dz_M", &DrumMotion::dz_M, "[m/s]")
      .def_readonly("ddx_M", &DrumMotion::ddx_M, "[m/s^2]")
      .def_readonly("ddz_M", &DrumMotion::ddz_M, "[m/s^2]");
  m.def("drum_motion", &drum_motion, py::arg("model"), py::arg("state"), py::arg("accelerations"),
        "Drum-centre displacement, velocity and acceleration.");
}

}  // namespace oscidrum::python
