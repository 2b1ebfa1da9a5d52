// Bindings of oscidrum/fields.hpp: the one table of every Case parameter. The parameter classes
// of bind_parameters.cpp generate their properties from this table, so Python never repeats a
// key, a unit or a rule.
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"

namespace oscidrum::python {
namespace {

const char* type_name(FieldType type) {
  switch (type) {
    case FieldType::real:
      return "real";
    case FieldType::integer:
      return "integer";
    case FieldType::boolean:
      return "boolean";
    case FieldType::choice:
      return "choice";
  }
  return "?";
}

std::vector<std::string> choice_names(const Field& f) {
  std::vector<std::string> names;
  if (f.choices == nullptr) return names;
  std::string current;
  for (const char* p = f.choices; *p != '\0'; ++p) {
    if (*p == '|') {
      names.push_back(current);
      current.clear();
    } else {
      current += *p;
    }
  }
  names.push_back(current);
  return names;
}

}  // namespace

py::object field_value(const Case& c, const Field& field) {
  const double v = field.get(c);
  switch (field.type) {
    case FieldType::real:
      return py::float_(v);
    case FieldType::integer:
      return py::int_(static_cast<long long>(v));
    case FieldType::boolean:
      return py::bool_(v != 0.0);
    case FieldType::choice:
      return py::str(format_field(c, field));
  }
  return py::none();
}

void set_field_value(Case& c, std::string_view key, py::handle value) {
  const Field* field = find_field(key);
  if (field == nullptr) {
    set_field(c, key, 0.0);  // throws the library's "unknown parameter ...; did you mean" error
    return;
  }
  if (py::isinstance<py::str>(value)) {
    set_field_text(c, key, value.cast<std::string>());
    return;
  }
  if (py::isinstance<py::bool_>(value)) {
    set_field(c, key, value.cast<bool>() ? 1.0 : 0.0);
    return;
  }
  if (py::hasattr(value, "__index__") || py::hasattr(value, "__float__")) {
    // Integers, floats, NumPy scalars and pybind11 enums (SoilInput) all convert to float.
    py::object number = py::hasattr(value, "__index__")
                            ? py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()))
                            : py::reinterpret_borrow<py::object>(value);
    if (!number) throw py::error_already_set();
    set_field(c, key, py::float_(number).cast<double>());
    return;
  }
  const std::string unit = field->unit;
  throw Error(std::string(field->key) + " must be a number" +
                  (unit == "-" ? std::string() : " [" + unit + "]") + "; got " +
                  py::repr(value).cast<std::string>(),
              field->key);
}

void bind_fields(py::module_& m) {
  py::class_<Field>(m, "Field",
                    "One parameter of a Case, from the library's field table (fields.hpp). "
                    "Read-only.")
      .def_property_readonly(
          "key", [](const Field& f) { return f.key; }, "dotted key, e.g. 'soil.G'")
      .def_property_readonly(
          "type", [](const Field& f) { return type_name(f.type); },
          "'real', 'integer', 'boolean' or 'choice'")
      .def_property_readonly(
          "unit", [](const Field& f) { return f.unit; }, "SI unit, '-' if dimensionless")
      .def_property_readonly(
          "description", [](const Field& f) { return f.description; }, "one-line description")
      .def_property_readonly(
          "rule", [](const Field& f) { return field_rule(f); },
          "the allowed values as text, e.g. '> 0' or 'in [0, 0.5)'")
      .def_property_readonly(
          "min", [](const Field& f) { return f.min; }, "lower bound")
      .def_property_readonly(
          "max", [](const Field& f) { return f.max; }, "upper bound")
      .def_property_readonly(
          "min_open", [](const Field& f) { return f.min_open; },
          "True: the value must be > min (not >=)")
      .def_property_readonly(
          "max_open", [](const Field& f) { return f.max_open; },
          "True: the value must be < max (not <=)")
      .def_property_readonly("choices", &choice_names, "names of a choice field (else empty)")
      .def_property_readonly(
          "display_unit", [](const Field& f) { return display_unit(f); },
          "the unit people read and type the value in, e.g. 'MN/m^2' for soil.G (else `unit`)")
      .def_property_readonly(
          "display_scale", [](const Field& f) { return f.display_scale; },
          "value in display_unit = value / display_scale (1e6 for soil.G)")
      .def_property_readonly(
          "default", [](const Field& f) { return field_value(Case{}, f); },
          "the default value (the paper's roller, Table 2 soil at G = 25 MN/m^2)")
      .def(
          "check",
          [](const Field& f, py::handle value) {
            // As assigning it to a Case judges it: check(True) on roller.m and check(2.0) on an
            // integer field said None (a double argument took both), and the Case refused them.
            try {
              field_argument(f.key, value);
            } catch (const Error& e) {
              return py::object(py::str(e.what()));
            }
            return py::object(py::none());
          },
          py::arg("value"),
          "None if `value` may be assigned to this field of a Case (its type: a number, an "
          "integer, True/False or a choice's name; its rule), else the error message the "
          "assignment raises.")
      .def("__repr__", [](const Field& f) {
        std::string unit = f.unit;
        return std::string("Field('") + f.key + "', " + type_name(f.type) +
               (unit == "-" ? std::string() : ", [" + unit + "]") + ", " + field_rule(f) + ": " +
               f.description + ")";
      });

  m.def(
      "fields",
      []() {
        py::list out;
        for (const Field& f : fields())
          out.append(py::cast(&f, py::return_value_policy::reference));
        return out;
      },
      "Every parameter of a Case, in documentation order (list of Field).");
  m.def(
      "find_field",
      [](const std::string& key) -> const Field* {
        const Field* f = find_field(key);
        if (f == nullptr) get_field(Case{}, key);  // raises the "did you mean" error
        return f;
      },
      py::arg("key"), py::return_value_policy::reference,
      "The Field with this dotted key; raises oscidrum.Error for an unknown key.");
}

}  // namespace oscidrum::python
