// Bindings of oscidrum/parameters.hpp: Roller, Soil, Trough, Contact, Numerics and Case. Every
// property, keyword, unit, docstring and rule is generated from the field table (fields.hpp):
// a group's properties are the fields whose key starts with "<group>.".
#include <pybind11/stl.h>

#include <deque>
#include <string>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/parameters.hpp"

namespace oscidrum::python {
namespace {

// Docstrings must outlive the module definition: keep them in a container with stable addresses.
const char* keep(std::string text) {
  static std::deque<std::string> store;
  store.push_back(std::move(text));
  return store.back().c_str();
}

std::string with_unit(const Field& f, const std::string& value) {
  const std::string unit = f.unit;
  return unit == "-" ? value : value + " " + unit;
}

std::string field_doc(const Field& f) {
  const std::string unit = f.unit;
  return std::string(f.description) + (unit == "-" ? std::string(" [-]") : " [" + unit + "]") +
         "; " + field_rule(f) + "; default " + format_field(Case{}, f) + ".";
}

bool in_group(const Field& f, std::string_view group) {
  std::string_view key = f.key;
  return key.size() > group.size() && key.substr(0, group.size()) == group &&
         key[group.size()] == '.';
}

const char* short_name(const Field& f, std::string_view group) { return f.key + group.size() + 1; }

// A parameter group (Roller, Soil, ...) is a member of Case; fields address it through a Case.
template <class Group>
struct GroupAccess {
  Group Case::*member;
  const char* group;

  Case wrap(const Group& g) const {
    Case c;
    c.*member = g;
    return c;
  }
};

template <class Group>
std::string group_repr(const GroupAccess<Group>& access, const Group& g, const char* cls) {
  const Case c = access.wrap(g);
  std::string out = std::string(cls) + "(";
  bool first = true;
  for (const Field& f : fields()) {
    if (!in_group(f, access.group)) continue;
    if (!first) out += ", ";
    first = false;
    out += std::string(short_name(f, access.group)) + "=" + with_unit(f, format_field(c, f));
  }
  return out + ")";
}

template <class Group>
py::dict group_dict(const GroupAccess<Group>& access, const Group& g) {
  const Case c = access.wrap(g);
  py::dict d;
  for (const Field& f : fields())
    if (in_group(f, access.group)) d[short_name(f, access.group)] = field_value(c, f);
  return d;
}

template <class Group>
py::class_<Group> bind_group(py::module_& m, const char* cls, const char* doc,
                             GroupAccess<Group> access) {
  py::class_<Group> c(m, cls, doc);
  c.def(
      py::init([access](const py::kwargs& kwargs) {
        Case wrapped = access.wrap(Group{});
        for (auto item : kwargs)
          set_field_value(wrapped,
                          std::string(access.group) + "." + py::str(item.first).cast<std::string>(),
                          item.second);
        return wrapped.*(access.member);
      }),
      keep(std::string("Keyword construction; defaults are the paper's values. Keywords: ") + [&] {
        std::string names;
        for (const Field& f : fields())
          if (in_group(f, access.group))
            names += std::string(names.empty() ? "" : ", ") + short_name(f, access.group);
        return names;
      }() + ". Raises oscidrum.Error for an unknown keyword or a value that breaks its rule."));
  for (const Field& f : fields()) {
    if (!in_group(f, access.group)) continue;
    const Field* field = &f;
    c.def_property(
        short_name(f, access.group),
        [access, field](const Group& g) { return field_value(access.wrap(g), *field); },
        [access, field](Group& g, py::handle value) {
          Case wrapped = access.wrap(g);
          set_field_value(wrapped, field->key, value);
          g = wrapped.*(access.member);
        },
        keep(field_doc(f)));
  }
  c.def("__repr__", [access, cls](const Group& g) { return group_repr(access, g, cls); });
  c.def(
      "to_dict", [access](const Group& g) { return group_dict(access, g); },
      "The values as {name: value} (SI units).");
  c.def(
      "__eq__",
      [access](const Group& a, const Group& b) {
        const Case ca = access.wrap(a), cb = access.wrap(b);
        for (const Field& f : fields())
          if (in_group(f, access.group) && f.get(ca) != f.get(cb)) return false;
        return true;
      },
      py::is_operator());
  c.attr("__hash__") = py::none();
  c.def("__copy__", [](const Group& g) { return g; });
  c.def(
      "__deepcopy__", [](const Group& g, const py::dict&) { return g; }, py::arg("memo"));
  c.def(py::pickle([access](const Group& g) { return group_dict(access, g); },
                   [access](const py::dict& d) {
                     Case wrapped = access.wrap(Group{});
                     for (auto item : d)
                       set_field_value(wrapped,
                                       std::string(access.group) + "." +
                                           py::str(item.first).cast<std::string>(),
                                       item.second);
                     return wrapped.*(access.member);
                   }));
  return c;
}

// Assign a Case member from either a group object or a {name: value} mapping.
template <class Group>
void assign_group(Case& c, GroupAccess<Group> access, py::handle value) {
  if (py::isinstance<Group>(value)) {
    c.*(access.member) = value.cast<Group>();
    return;
  }
  if (py::isinstance<py::dict>(value)) {
    for (auto item : py::reinterpret_borrow<py::dict>(value))
      set_field_value(c, std::string(access.group) + "." + py::str(item.first).cast<std::string>(),
                      item.second);
    return;
  }
  throw Error(std::string(access.group) + " must be a " +
              py::str(py::type::of<Group>().attr("__name__")).cast<std::string>() +
              " or a dict; got " + py::repr(value).cast<std::string>());
}

const GroupAccess<Roller> kRoller{&Case::roller, "roller"};
const GroupAccess<Soil> kSoil{&Case::soil, "soil"};
const GroupAccess<Trough> kTrough{&Case::trough, "trough"};
const GroupAccess<Contact> kContact{&Case::contact, "contact"};
const GroupAccess<Numerics> kNumerics{&Case::numerics, "numerics"};

// Set one Case keyword: a group name, "MMd" or any dotted key.
void set_case_item(Case& c, const std::string& key, py::handle value) {
  if (key == kRoller.group) return assign_group(c, kRoller, value);
  if (key == kSoil.group) return assign_group(c, kSoil, value);
  if (key == kTrough.group) return assign_group(c, kTrough, value);
  if (key == kContact.group) return assign_group(c, kContact, value);
  if (key == kNumerics.group) return assign_group(c, kNumerics, value);
  set_field_value(c, key, value);
}

py::dict case_dict(const Case& c) {
  py::dict d;
  for (const Field& f : fields()) d[f.key] = field_value(c, f);
  return d;
}

Case case_from_mapping(py::handle mapping, Case c = {}) {
  for (auto item : py::reinterpret_borrow<py::dict>(mapping))
    set_case_item(c, py::str(item.first).cast<std::string>(), item.second);
  return c;
}

std::string case_repr(const Case& c) {
  std::string out = "Case(\n";
  out += "  roller=" + group_repr(kRoller, c.roller, "Roller") + ",\n";
  out += "  soil=" + group_repr(kSoil, c.soil, "Soil") + ",\n";
  out += "  trough=" + group_repr(kTrough, c.trough, "Trough") + ",\n";
  out += "  contact=" + group_repr(kContact, c.contact, "Contact") + ",\n";
  out += "  MMd=" + with_unit(*find_field("MMd"), format_field(c, *find_field("MMd"))) + ",\n";
  out += "  numerics=" + group_repr(kNumerics, c.numerics, "Numerics") + ")";
  return out;
}

}  // namespace

void bind_parameters(py::module_& m) {
  py::enum_<SoilInput>(m, "SoilInput", "How the soil is given (Soil.input accepts the name too).")
      .value("coefficients", SoilInput::coefficients,
             "directly as the discrete Kelvin-Voigt coefficients ksh, ksv, csh, csv")
      .value("modulus", SoilInput::modulus,
             "as continuum (G, nu, rho), converted by Appendix B (42)-(45)");

  bind_group<Roller>(m, "Roller",
                     "The drum and its suspension (paper Table 1: HAMM HD+ 90 VO). SI units.",
                     kRoller);
  bind_group<Soil>(m, "Soil",
                   "The soil below the drum: continuum (G, nu, rho) when input = 'modulus', or "
                   "discrete Kelvin-Voigt coefficients (ksh, ksv, csh, csv) when input = "
                   "'coefficients' (the default: paper Table 2 at G = 25 MN/m^2).",
                   kSoil);
  bind_group<Trough>(m, "Trough",
                     "Settlement trough, logarithmic spiral R(theta) = a exp(k theta) (8); k = 0 "
                     "is a circle of radius a.",
                     kTrough);
  bind_group<Contact>(m, "Contact", "Drum/soil contact (Coulomb friction).", kContact);
  bind_group<Numerics>(m, "Numerics",
                       "Numerical options of the hybrid integration and the steady-state search.",
                       kNumerics);

  py::class_<Case> cls(m, "Case",
                       "One simulation case: roller, soil, trough, contact, driving torque MMd "
                       "[N m] and numerics. Defaults are the paper's roller on the Table 2 soil at "
                       "G = 25 MN/m^2, circular trough R = 0.606 m, mu = 0.5, MMd = 0.");
  cls.def(py::init([](const py::kwargs& kwargs) { return case_from_mapping(kwargs); }),
          "Keyword construction: roller=, soil=, trough=, contact=, numerics= (objects or dicts), "
          "MMd= [N m], and any dotted key through ** (e.g. Case(**{'soil.ksh': 11.4e6})). "
          "Raises oscidrum.Error for an unknown key or a value that breaks its rule.");
  cls.def_readwrite("roller", &Case::roller, "the drum and suspension (Roller)");
  cls.def_readwrite("soil", &Case::soil, "the soil (Soil)");
  cls.def_readwrite("trough", &Case::trough, "the settlement trough (Trough)");
  cls.def_readwrite("contact", &Case::contact, "the contact (Contact)");
  cls.def_readwrite("numerics", &Case::numerics, "numerical options (Numerics)");
  const Field* mmd = find_field("MMd");
  cls.def_property(
      "MMd", [mmd](const Case& c) { return field_value(c, *mmd); },
      [](Case& c, py::handle v) { set_field_value(c, "MMd", v); }, keep(field_doc(*mmd)));
  cls.def(
      "get",
      [](const Case& c, const std::string& key) {
        return field_value(
            c, *[&] {
              const Field* f = find_field(key);
              if (f == nullptr) get_field(c, key);  // throws "unknown parameter"
              return f;
            }());
      },
      py::arg("key"),
      "The value of a dotted key, e.g. case.get('soil.ksh') [SI unit of the field].");
  cls.def(
      "set",
      [](Case& c, const std::string& key, py::handle value) { set_field_value(c, key, value); },
      py::arg("key"), py::arg("value"),
      "Set a dotted key, e.g. case.set('soil.G', 5e6). Numbers are SI; booleans and choice "
      "names are accepted. Raises oscidrum.Error with the library's message, e.g. "
      "\"soil.G must be > 0 [Pa]; got -5e+06\".");
  cls.def(
      "to_dict", &case_dict,
      "Every field as {dotted key: value} in documentation order (SI units, choices as names).");
  cls.def_static(
      "from_dict", [](const py::dict& d) { return case_from_mapping(d); }, py::arg("values"),
      "Build a Case from {dotted key: value} (missing keys keep their defaults); group names "
      "('soil', ...) may map to objects or dicts.");
  cls.def(
      "replace",
      [](const Case& c, const py::kwargs& kwargs) { return case_from_mapping(kwargs, c); },
      "A copy with some values changed, e.g. case.replace(MMd=2747.35, **{'contact.pure_rolling': "
      "True}).");
  cls.def(
      "copy", [](const Case& c) { return c; }, "A copy.");
  cls.def(
      "validate", [](const Case& c) { Model model(c); },
      "Check every field and the rules that tie fields together (as simulate does); raises "
      "oscidrum.Error on the first problem.");
  cls.def_static(
      "keys",
      []() {
        py::list keys;
        for (const Field& f : fields()) keys.append(f.key);
        return keys;
      },
      "Every dotted key, in documentation order.");
  cls.def("__repr__", &case_repr);
  cls.def(
      "__eq__",
      [](const Case& a, const Case& b) {
        for (const Field& f : fields())
          if (f.get(a) != f.get(b)) return false;
        return true;
      },
      py::is_operator());
  cls.attr("__hash__") = py::none();
  cls.def("__copy__", [](const Case& c) { return c; });
  cls.def(
      "__deepcopy__", [](const Case& c, const py::dict&) { return c; }, py::arg("memo"));
  cls.def(py::pickle([](const Case& c) { return case_dict(c); },
                     [](const py::dict& d) { return case_from_mapping(d); }));
}

}  // namespace oscidrum::python
