// Bindings of oscidrum/soil.hpp: Appendix B coefficients and the paper's Table 2.
#include <pybind11/stl.h>

#include <cstdio>
#include <string>

#include "bindings.hpp"
#include "oscidrum/soil.hpp"

namespace oscidrum::python {

void bind_soil(py::module_& m) {
  py::class_<SoilCoefficients>(m, "SoilCoefficients",
                               "Discrete Kelvin-Voigt soil coefficients (Appendix B).")
      .def_readonly("a0", &SoilCoefficients::a0, "half contact length (43) [m] (0 if given)")
      .def_readonly("ksh", &SoilCoefficients::ksh, "horizontal spring (42) [N/m]")
      .def_readonly("ksv", &SoilCoefficients::ksv, "vertical spring (42) [N/m]")
      .def_readonly("csh", &SoilCoefficients::csh, "horizontal dashpot (44) [N s/m]")
      .def_readonly("csv", &SoilCoefficients::csv, "vertical dashpot (45) [N s/m]")
      .def("__repr__", [](const SoilCoefficients& s) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "SoilCoefficients(a0=%.6g m, ksh=%.6g N/m, ksv=%.6g N/m, csh=%.6g N s/m, "
                      "csv=%.6g N s/m)",
                      s.a0, s.ksh, s.ksv, s.csh, s.csv);
        return std::string(buf);
      });
  // The Soil overload first: the other takes any Python object as G (judged as the field).
  m.def(
      "soil_coefficients",
      [](const Soil& soil, const Roller& roller) { return soil_coefficients(soil, roller); },
      py::arg("soil"), py::arg("roller") = Roller{},
      "The coefficients a Soil describes (through Appendix B when soil.input == 'modulus').");
  m.def(
      "soil_coefficients",
      [](py::handle G, py::handle nu, py::handle rho, const Roller& roller) {
        // G, nu and rho by the rules of soil.G, soil.nu and soil.rho, as Case takes them:
        // soil_coefficients(25.0) took 25 Pa (a0 = 96 m) without the "did you mean ... MN/m^2"
        // hint, and True for 1 Pa.
        return soil_coefficients(field_argument("soil.G", G), field_argument("soil.nu", nu),
                                 field_argument("soil.rho", rho), roller);
      },
      py::arg("G"), py::arg("nu") = 0.3, py::arg("rho") = 1900.0, py::arg("roller") = Roller{},
      "Appendix B: a0 (43) [m], ksh, ksv (42) [N/m], csh, csv (44)-(45) [N s/m] from G [Pa], nu "
      "[-], rho [kg/m^3] and the roller's r, b, P0. G, nu and rho follow the rules of soil.G, "
      "soil.nu and soil.rho (oscidrum.Error otherwise, as for a Case). Note: (42) does not "
      "reproduce Table 2's springs (docs/model.md section 1.3); use table2_soil() for the "
      "paper's figures.");

  py::class_<Table2Row>(m, "Table2Row", "One row of the paper's Table 2 (SI units).")
      .def_readonly("G", &Table2Row::G, "shear modulus [Pa]")
      .def_readonly("a0", &Table2Row::a0, "half contact length [m]")
      .def_readonly("ksh", &Table2Row::ksh, "[N/m]")
      .def_readonly("ksv", &Table2Row::ksv, "[N/m]")
      .def_readonly("csh", &Table2Row::csh, "[N s/m]")
      .def_readonly("csv", &Table2Row::csv, "[N s/m]")
      .def("__repr__", [](const Table2Row& r) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "Table2Row(G=%.6g Pa, a0=%.6g m, ksh=%.6g N/m, ksv=%.6g N/m, csh=%.6g N s/m, "
                      "csv=%.6g N s/m)",
                      r.G, r.a0, r.ksh, r.ksv, r.csh, r.csv);
        return std::string(buf);
      });
  m.def(
      "table2", []() { return std::vector<Table2Row>(table2().begin(), table2().end()); },
      "Paper Table 2: G = 5 ... 70 MN/m^2 in steps of 5 (nu = 0.3, rho = 1900 kg/m^3), as a "
      "list of Table2Row in SI units.");
  m.def("table2_soil", &table2_soil, py::arg("G"),
        "The soil of paper Table 2 at G (input = 'coefficients').\n\n"
        "Parameters\n----------\nG : float\n    Shear modulus [Pa], one of 5e6, 10e6, ..., "
        "70e6.\n\nReturns\n-------\nSoil\n\nRaises\n------\noscidrum.Error\n    For "
        "another G.\n\nExamples\n--------\n>>> oscidrum.table2_soil(5e6).ksh   # [N/m]\n"
        "11400000.0\n");
}

}  // namespace oscidrum::python
