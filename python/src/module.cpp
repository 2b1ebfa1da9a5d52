// python/src/module.cpp: the oscidrum._core extension module. The pure-Python package
// `oscidrum` re-exports everything defined here; see docs/python.md.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "oscidrum/version.hpp"

PYBIND11_MODULE(_core, m) {
  namespace op = oscidrum::python;
  m.doc() =
      "Compiled core of oscidrum: the oscillation-drum model of Paulmichl, Adam & Adam (2019). "
      "All quantities are SI; units are given in brackets in every docstring.";
  m.attr("__version__") = oscidrum::version;
  // Order matters for readable signatures: types before the functions that use them.
  op::bind_error(m);
  op::bind_fields(m);
  op::bind_parameters(m);
  op::bind_state(m);
  op::bind_kinematics(m);
  op::bind_soil(m);
  op::bind_transmissibility(m);
  op::bind_model(m);
  op::bind_result(m);
  op::bind_metrics(m);
  op::bind_record(m);
  op::bind_identify(m);
  op::bind_simulate(m);
  op::bind_study(m);
  op::bind_validation(m);
}
