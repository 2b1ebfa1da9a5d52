// python/src/module.cpp: the oscidrum._core extension module. The pure-Python package
// `oscidrum` re-exports everything defined here; see docs/python.md.
#include <pybind11/pybind11.h>

#include <string>

#include "bindings.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/record.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/state.hpp"
#include "oscidrum/transmissibility.hpp"
#include "oscidrum/version.hpp"
#include "oscidrum_paper/validation.hpp"

namespace {

// The read-only result classes have no constructor in Python; T.__new__(T) must still not give
// uninitialised memory: it gives a default-constructed T (see construct_on_new).
template <class... T>
void construct_on_new_all(pybind11::module_& m, const char* const (&names)[sizeof...(T)]) {
  std::size_t i = 0;
  auto one = [&](auto cls) {
    oscidrum::python::construct_on_new(cls);
    const std::string name = names[i++];
    oscidrum::python::def_assigning(
        cls, "__init__", [name](pybind11::handle, const pybind11::args&, const pybind11::kwargs&) {
          throw oscidrum::Error(name +
                                " objects come from the library's functions (simulate, "
                                "compute_metrics, run_study, ...); they have no "
                                "constructor");
        });
  };
  (one(pybind11::reinterpret_borrow<pybind11::class_<T>>(m.attr(names[i]))), ...);
}

}  // namespace

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
  op::bind_branch(m);
  op::bind_diagram(m);
  op::bind_files(m);
  namespace o = oscidrum;
  construct_on_new_all<o::TroughGeometry, o::Kinematics, o::Harmonic, o::Metrics, o::ContactForces,
                       o::DrumMotion, o::RecordMetrics, o::Event, o::Diagnostics, o::Samples,
                       o::Result, o::SoilCoefficients, o::Table2Row, o::Accelerations,
                       o::Transmissibility, o::PaperSeries, o::SeriesResult, o::ValidationRow>(
      m, {"TroughGeometry", "Kinematics", "Harmonic", "Metrics", "ContactForces", "DrumMotion",
          "RecordMetrics", "Event", "Diagnostics", "Samples", "Result", "SoilCoefficients",
          "Table2Row", "Accelerations", "Transmissibility", "PaperSeries", "SeriesResult",
          "ValidationRow"});
}
