// Bindings of oscidrum_io/files.hpp for the pure-Python package: every file the package writes
// (plots, CSV, Markdown, netCDF) goes through io::OutputFile, as the CLI's do: atomically
// beside its target, through symbolic links, a FIFO or device written in place, anything else
// refused. Private (underscore names): the package's oscidrum._files wraps them.
#include <pybind11/pybind11.h>

#include <string>

#include "bindings.hpp"
#include "oscidrum_io/files.hpp"

namespace oscidrum::python {

void bind_files(py::module_& m) {
  m.def(
      "_write_file",
      [](const std::string& path, const py::bytes& data) {
        std::string text = data;  // copied with the GIL held
        py::gil_scoped_release release;
        io::write_file_atomic(path, text);
      },
      py::arg("path"), py::arg("data"),
      "Write `data` (bytes) to `path` atomically (oscidrum_io's write_file_atomic). `path` is a "
      "str or os.fsencode'd bytes.");
  py::class_<io::OutputFile>(
      m, "_OutputFile",
      "An output file being written: write to .write_path (a temporary file beside the target, "
      "or a FIFO or device itself), then commit() renames it over the target; discard() (or "
      "garbage collection) deletes it.")
      .def(py::init<std::string, bool>(), py::arg("path"), py::arg("regular_only") = false)
      .def_property_readonly("write_path", &io::OutputFile::write_path)
      .def_property_readonly("direct", &io::OutputFile::direct)
      .def("commit", &io::OutputFile::commit)
      .def("discard", &io::OutputFile::discard);
}

}  // namespace oscidrum::python
