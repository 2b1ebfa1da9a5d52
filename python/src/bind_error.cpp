// Bindings of oscidrum/error.hpp: oscidrum::Error becomes the Python exception oscidrum.Error, a
// subclass of ValueError carrying the library's message unchanged.
#include "bindings.hpp"
#include "oscidrum/error.hpp"

namespace oscidrum::python {

std::span<const double> span_of(const Array& a, const char* name) {
  if (a.ndim() != 1) throw Error(std::string(name) + " must be a 1-D array");
  return {a.data(), static_cast<std::size_t>(a.size())};
}

void bind_error(py::module_& m) {
  auto error = py::register_exception<Error>(m, "Error", PyExc_ValueError);
  error.attr("__doc__") =
      "Raised for invalid parameters and every other error of the oscidrum library. The message "
      "names the field, the rule and the value received, e.g. "
      "\"soil.G must be > 0 [Pa]; got -5e+06\". Subclass of ValueError.";
}

}  // namespace oscidrum::python
