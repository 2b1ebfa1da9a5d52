// Bindings of oscidrum/error.hpp: oscidrum::Error becomes the Python exception oscidrum.Error, a
// subclass of ValueError carrying the library's message unchanged.
#include <cmath>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/text.hpp"

namespace oscidrum::python {

std::span<const double> span_of(const Array& a, const char* name) {
  if (a.ndim() != 1) throw Error(std::string(name) + " must be a 1-D array");
  return {a.data(), static_cast<std::size_t>(a.size())};
}

void bind_error(py::module_& m) {
  // The exception type lives as long as the module (the translator below refers to it).
  static py::handle type = py::exception<Error>(m, "Error", PyExc_ValueError).release();
  type.attr("__doc__") =
      "Raised for invalid parameters and every other error of the oscidrum library. The message "
      "names the field, the rule and the value received, e.g. "
      "\"soil.G must be > 0 [Pa]; got -5e+06\". Subclass of ValueError. `key` is the dotted key "
      "of the parameter it is about ('soil.G') or None, `value` the value received [SI] or None.";
  type.attr("key") = py::none();
  type.attr("value") = py::none();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      // A message that echoes bytes that are not UTF-8 (a file name, a cell of a binary file)
      // has them escaped as \xNN instead of failing to decode.
      py::object error = py::reinterpret_borrow<py::object>(type)(printable(e.what()));
      if (!e.key().empty()) error.attr("key") = py::str(e.key());
      if (!std::isnan(e.value())) error.attr("value") = py::float_(e.value());
      PyErr_SetObject(type.ptr(), error.ptr());
    }
  });
}

}  // namespace oscidrum::python
