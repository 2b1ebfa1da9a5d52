// python/src/bindings.hpp: the pieces of the oscidrum._core extension module. One bind_*
// function per public header of the library.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <span>
#include <string_view>

#include "oscidrum/fields.hpp"
#include "oscidrum/parameters.hpp"

namespace oscidrum::python {

namespace py = pybind11;

void bind_error(py::module_& m);
void bind_fields(py::module_& m);
void bind_parameters(py::module_& m);
void bind_state(py::module_& m);
void bind_kinematics(py::module_& m);
void bind_model(py::module_& m);
void bind_result(py::module_& m);
void bind_simulate(py::module_& m);
void bind_metrics(py::module_& m);
void bind_study(py::module_& m);
void bind_soil(py::module_& m);
void bind_transmissibility(py::module_& m);
void bind_record(py::module_& m);
void bind_identify(py::module_& m);
void bind_validation(py::module_& m);

/// A float64 NumPy array argument (converted if needed, C-contiguous).
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The data of a 1-D array as a span; oscidrum::Error naming the argument if it is not 1-D.
std::span<const double> span_of(const Array& a, const char* name);

/// The value of a field as a Python object: float (real), int (integer), bool (boolean) or str
/// (choice name).
py::object field_value(const Case& c, const Field& field);

/// Set a field from a Python value (number, bool, or text as set_field_text reads it). Throws
/// oscidrum::Error with the library's message when the value breaks the field's rule.
void set_field_value(Case& c, std::string_view key, py::handle value);

}  // namespace oscidrum::python
