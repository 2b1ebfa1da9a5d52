// Bindings of oscidrum/parameters.hpp: Roller, Soil, Trough, Contact, Numerics and Case. Every
// property, keyword, unit, docstring and rule is generated from the field table (fields.hpp):
// a group's properties are the fields whose key starts with "<group>.".
//
// Values set from Python go through the same typed assignment and the same finalisation as the
// config files and the CLI (oscidrum_io/case_spec.hpp): the same type rules (no '1851' for a
// number, no 1 or 'off' for a boolean, no True for an integer), the shorthands soil.table2_G and
// MMd_fraction, and the rule that a soil key without effect under the soil.input in force is an
// error naming soil.input. Besides dotted keys, every field is reachable by its last component
// when that is unique (mu, G, MMd_fraction, table2_G, ...) and R stands for a circular trough.
#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum_io/case_spec.hpp"
#include "oscidrum_io/config.hpp"

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

bool in_group(std::string_view key, std::string_view group) {
  return key.size() > group.size() && key.substr(0, group.size()) == group &&
         key[group.size()] == '.';
}

std::string_view last_part(std::string_view key) {
  const std::size_t dot = key.rfind('.');
  return dot == std::string_view::npos ? key : key.substr(dot + 1);
}

// ---- flat keyword aliases ------------------------------------------------------------------

// The circular-trough shorthand of the CLI's --R: trough.k = 0, trough.a = R.
constexpr const char* kRadius = "R";

// {last component: dotted key} for every field and shorthand whose last component is unique.
const std::map<std::string, std::string, std::less<>>& aliases() {
  static const std::map<std::string, std::string, std::less<>> table = [] {
    std::map<std::string, int, std::less<>> count;
    std::vector<std::string> keys;
    for (const Field& f : fields()) keys.emplace_back(f.key);
    for (const io::ExtraKey& e : io::extra_keys()) keys.emplace_back(e.key);
    for (const std::string& k : keys) ++count[std::string(last_part(k))];
    std::map<std::string, std::string, std::less<>> out;
    for (const std::string& k : keys)
      if (count[std::string(last_part(k))] == 1) out.emplace(std::string(last_part(k)), k);
    return out;
  }();
  return table;
}

// The dotted key of a flat name in the alias table ("mu" -> "contact.mu"); null if none.
const std::string* alias_of(std::string_view name) {
  const auto& table = aliases();
  const auto it = table.find(name);
  return it != table.end() ? &it->second : nullptr;
}

// The dotted key a Python keyword stands for ("mu" -> "contact.mu"); the key itself if it is a
// field or a shorthand; kRadius for "R". Throws the library's "unknown parameter" error.
std::string resolve_key(std::string_view name) {
  if (find_field(name) != nullptr || io::find_extra_key(name) != nullptr) return std::string(name);
  if (name == kRadius) return kRadius;
  if (const std::string* key = alias_of(name)) return *key;
  throw Error("unknown parameter '" + std::string(name) + "'" + io::suggest_key(name) +
              " (Python also takes the flat names of oscidrum.Case.aliases() and R)");
}

// ---- Python values -> typed config values ---------------------------------------------------

// NumPy scalar types, looked up once (the references are kept for the life of the process).
struct NumpyTypes {
  py::handle boolean, integer, floating;
};
const NumpyTypes& numpy_types() {
  static const NumpyTypes types = [] {
    py::module_ np = py::module_::import("numpy");
    return NumpyTypes{py::object(np.attr("bool_")).release(),
                      py::object(np.attr("integer")).release(),
                      py::object(np.attr("floating")).release()};
  }();
  return types;
}

// " [unit]" of a key for its messages; nothing for a dimensionless or unknown key.
std::string bracketed_unit(const std::string& key) {
  const std::string unit = io::key_unit(key);
  return unit.empty() || unit == "-" ? std::string() : " [" + unit + "]";
}

// A Python value as the config reader would see it: bool, int, float or str. Anything else
// (None, lists, objects) is an error naming the key.
io::Value to_value(const std::string& key, py::handle value) {
  const NumpyTypes& np = numpy_types();
  if (py::isinstance<py::bool_>(value) || py::isinstance(value, np.boolean))
    return io::Value(value.cast<bool>());
  if (py::isinstance<SoilInput>(value))
    return io::Value(
        choice_name(*find_field("soil.input"), static_cast<int>(value.cast<SoilInput>())));
  if (py::isinstance<py::str>(value)) return io::Value(value.cast<std::string>());
  if (PyLong_Check(value.ptr()) || py::isinstance(value, np.integer)) {
    py::object number = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
    if (!number) throw py::error_already_set();
    int overflow = 0;
    const long long i = PyLong_AsLongLongAndOverflow(number.ptr(), &overflow);
    if (overflow != 0)
      throw Error(key + " must be " + (find_field(key) ? field_rule(*find_field(key)) : "finite") +
                      bracketed_unit(key) + "; got an integer beyond the 64-bit range, " +
                      python_description(value),
                  key);
    return io::Value(static_cast<std::int64_t>(i));
  }
  if (PyFloat_Check(value.ptr()) || py::isinstance(value, np.floating))
    return io::Value(py::reinterpret_borrow<py::object>(value).cast<double>());
  const Field* f = find_field(key);
  std::string expected = "a number";
  if (f && f->type == FieldType::boolean) expected = "True or False";
  if (f && f->type == FieldType::choice) expected = field_rule(*f);
  throw Error(
      key + " must be " + expected + bracketed_unit(key) + "; got " + python_description(value),
      key);
}

// ---- building a Case the way the config reader does -----------------------------------------

// A Case in the making from Python keywords: typed assignment into a CaseSpec, then the same
// finalisation as a config file.
class Builder {
 public:
  explicit Builder(const Case& base) { spec_.values = base; }

  // One keyword: a group name (object or dict), a dotted key, a shorthand, an alias or R.
  void set(const std::string& name, py::handle value) {
    if (set_group(name, value)) return;
    assign(resolve_key(name), name, value);
  }

  // A key inside a group's dict or a group's own keyword: soil={'G': ...}, Soil(G=...).
  void set_in_group(const char* group, const std::string& name, py::handle value) {
    const std::string key = std::string(group) + "." + name;
    if (find_field(key) == nullptr && io::find_extra_key(key) == nullptr)
      throw Error("unknown parameter '" + key + "'" + io::suggest_key(key));
    assign(key, key, value);
  }

  // A key whose value came with a group object (Case(roller=Roller(...))): given, for the rules.
  void given_as(const std::string& key, const char* group) {
    spec_.origin[key] = std::string("argument ") + group;
  }

  Case finish() const {
    if (radius_ && (spec_.given("trough.k") || spec_.given("trough.a")))
      throw Error(
          "give the trough either as a circle (R) or as a log spiral (trough.k, trough.a), not "
          "both");
    return io::finalize(spec_);
  }

 private:
  bool set_group(const std::string& name, py::handle value);

  void assign(const std::string& key, const std::string& name, py::handle value) {
    // One key, one name: Case(**{'roller.r': 0.6, 'r': 0.7}) would silently take the later.
    // soil.table2_G names soil.G too (it sets soil.input = 'table2' and soil.G).
    for (const std::string& k : {key, key == "soil.table2_G" ? std::string("soil.G") : key}) {
      if (auto [it, fresh] = named_.emplace(k, name); !fresh && it->second != name)
        throw Error(
            k + " is given twice, as '" + it->second + "' and as '" + name + "'; give it once", k);
    }
    const std::string origin = "argument " + name;
    if (key == kRadius) {
      const io::Value v = to_value("trough.a", value);
      io::assign(spec_, "trough.k", 0.0, origin);
      io::assign(spec_, "trough.a", v, origin);
      spec_.origin.erase("trough.k");
      spec_.origin.erase("trough.a");
      radius_ = true;
      return;
    }
    io::assign(spec_, key, to_value(key, value), origin);
  }

  io::CaseSpec spec_;
  bool radius_ = false;
  std::map<std::string, std::string> named_;  // key -> the name it was given by
};

// A parameter group (Roller, Soil, ...) is a member of Case; fields address it through a Case.
template <class Group>
struct GroupAccess {
  Group Case::*member;
  const char* group;

  // A group of its own (Roller(...), a copy) in a case of defaults; a roller's width counts
  // there (roller.b enters Appendix B under soil.input = "modulus": the soil is not known to a
  // roller of its own, and Roller(b=1.0) was refused for a soil it does not have).
  Case wrap(const Group& g) const {
    Case c;
    c.*member = g;
    if constexpr (std::is_same_v<Group, Roller>) c.soil.input = SoilInput::modulus;
    return c;
  }

  // The case a group object is a view of (Case.roller returns one with reference_internal: the
  // view keeps its case alive, and pybind11 records the case as the view's patient), or nullptr
  // for a group of its own.
  const Case* owner(py::handle self) const {
    const auto& patients = py::detail::get_internals().patients;
    const auto it = patients.find(self.ptr());
    if (it == patients.end()) return nullptr;
    const Group* g = &self.cast<const Group&>();
    for (PyObject* p : it->second) {
      const py::handle h(p);
      if (!py::isinstance<Case>(h)) continue;
      const Case& c = h.cast<const Case&>();
      if (&(c.*member) == g) return &c;
    }
    return nullptr;
  }

  // What a group's keys are judged in (which take effect, the rules that tie keys together): its
  // case for a view (case.roller.b = 1.0 was refused on a case with soil.input = "modulus",
  // judged in a case of defaults, and its repr, str, to_dict, == and pickle left b out), else
  // wrap().
  Case context(py::handle self) const {
    if (const Case* c = owner(self)) return *c;
    return wrap(self.cast<const Group&>());
  }
};

const GroupAccess<Roller> kRoller{&Case::roller, "roller"};
const GroupAccess<Soil> kSoil{&Case::soil, "soil"};
const GroupAccess<Trough> kTrough{&Case::trough, "trough"};
const GroupAccess<Contact> kContact{&Case::contact, "contact"};
const GroupAccess<Numerics> kNumerics{&Case::numerics, "numerics"};

template <class Group>
bool assign_group(Builder& b, Case& values, GroupAccess<Group> access, py::handle value) {
  if (py::isinstance<Group>(value)) {
    const Group& g = value.cast<const Group&>();
    values.*(access.member) = g;
    // Its values in effect (in its own case, for a view) that differ from the defaults count as
    // given, so that the new case's rules judge them: Case(roller=Roller(b=1.0)) on Table 2's
    // soil, where the width has no effect; a width without effect in the view's case is not.
    const Case own = access.context(value), defaults = access.wrap(Group{});
    for (const Field& f : fields()) {
      if (!in_group(f.key, access.group) || !key_in_effect(own, f.key)) continue;
      const double v = f.get(own), d = f.get(defaults);
      if (v == d || (std::isnan(v) && std::isnan(d))) continue;
      b.given_as(f.key, access.group);
    }
    return true;
  }
  if (py::isinstance<py::dict>(value)) {
    for (auto item : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(item.first))
        throw Error(std::string(access.group) + " keys must be strings; got " +
                    python_description(item.first));
      b.set_in_group(access.group, item.first.cast<std::string>(), item.second);
    }
    return true;
  }
  throw Error(std::string(access.group) + " must be a " +
              py::str(py::type::of<Group>().attr("__name__")).cast<std::string>() +
              " or a dict of {name: value}; got " + python_description(value));
}

bool Builder::set_group(const std::string& name, py::handle value) {
  Case& v = spec_.values;
  if (name == kRoller.group) return assign_group(*this, v, kRoller, value);
  if (name == kSoil.group) return assign_group(*this, v, kSoil, value);
  if (name == kTrough.group) return assign_group(*this, v, kTrough, value);
  if (name == kContact.group) return assign_group(*this, v, kContact, value);
  if (name == kNumerics.group) return assign_group(*this, v, kNumerics, value);
  return false;
}

Case build(const Case& base, py::handle mapping) {
  Builder b(base);
  for (auto item : py::reinterpret_borrow<py::dict>(mapping)) {
    if (!py::isinstance<py::str>(item.first))
      throw Error("parameter names must be strings; got " + python_description(item.first));
    b.set(item.first.cast<std::string>(), item.second);
  }
  return b.finish();
}

Case set_one(const Case& base, const std::string& key, py::handle value) {
  Builder b(base);
  b.set(key, value);
  return b.finish();
}

// ---- which keys are in effect, reprs ---------------------------------------------------------

// Keys without effect (the config reader rejects them) are left out of reprs and dicts: the
// library's key_in_effect, as for the config files and the web page.
bool in_effect(const Case& c, std::string_view key) { return key_in_effect(c, key); }

// The flat keyword for a key (its alias if it has one, else the dotted key).
std::string keyword(std::string_view key) {
  const std::string_view last = last_part(key);
  auto it = aliases().find(last);
  return it != aliases().end() && it->second == key ? std::string(last) : std::string(key);
}

// Python source for a value: shortest round-trip float, int, True/False, quoted choice name.
std::string python_literal(const Case& c, const Field& f) {
  const py::object v = field_value(c, f);
  return py::repr(v).cast<std::string>();
}

// "name=value" for every field of `keys_of` (a group prefix, or "" for the whole case) whose value
// differs from the default and is in effect; flat keywords when `flat`, else names in the group.
std::vector<std::string> differing(const Case& c, const char* group, bool flat) {
  const Case d{};
  std::vector<std::string> out;
  std::string_view first_trough_key;
  for (const Field& f : fields())
    if (first_trough_key.empty() && in_group(f.key, "trough")) first_trough_key = f.key;
  for (const Field& f : fields()) {
    const std::string_view key = f.key;
    if (group != nullptr && !in_group(key, group)) continue;
    if (!in_effect(c, key)) continue;
    const std::string name =
        flat ? keyword(key)
             : std::string(group ? key.substr(std::string_view(group).size() + 1) : key);
    if (flat && in_group(key, "trough")) {
      // The trough as its shape describes itself: a circle is R=..., a log spiral k=..., a=...
      if (key == first_trough_key && !(c.trough.shape == d.trough.shape))
        for (const TroughParameter& p : parameters(c.trough.shape))
          if (p.key != nullptr)
            out.push_back(
                (std::string(p.symbol) == kRadius ? std::string(kRadius) : keyword(p.key)) + "=" +
                py::repr(py::float_(p.value)).cast<std::string>());
      continue;
    }
    if (f.get(c) == f.get(d)) continue;
    out.push_back(name + "=" + python_literal(c, f));
  }
  return out;
}

std::string join(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : ", ") + p;
  return out;
}

// `c`: the group's context (GroupAccess::context).
std::string group_repr(const Case& c, const char* group, const char* cls) {
  return std::string(cls) + "(" + join(differing(c, group, false)) + ")";
}

// A readable listing with units (str()); `c`: the group's context.
std::string group_str(const Case& c, const char* group, const char* cls) {
  std::string out = std::string(cls) + "(";
  bool first = true;
  for (const Field& f : fields()) {
    if (!in_group(f.key, group) || !in_effect(c, f.key)) continue;
    if (!first) out += ", ";
    first = false;
    out += std::string(last_part(f.key)) + "=" + with_unit(f, format_field(c, f));
  }
  return out + ")";
}

// Every field in effect (or every field with `all`) as {name: value}.
py::dict values_dict(const Case& c, const char* group, bool all) {
  py::dict d;
  for (const Field& f : fields()) {
    if (group != nullptr && !in_group(f.key, group)) continue;
    if (!all && !in_effect(c, f.key)) continue;
    const std::string_view key = f.key;
    d[py::str(std::string(group ? key.substr(std::string_view(group).size() + 1) : key))] =
        field_value(c, f);
  }
  return d;
}

// `group`: of that group only (a and b its contexts, which may differ outside it), or nullptr.
// A key counts where it is in effect in both (a view's width on Table 2's soil, which its repr
// leaves out, equals a roller of its own with another width).
bool equal_in_effect(const Case& a, const Case& b, const char* group) {
  if ((group == nullptr || std::string_view(group) == "soil") && a.soil.input != b.soil.input)
    return false;
  for (const Field& f : fields()) {
    if (group != nullptr && !in_group(f.key, group)) continue;
    if (in_effect(a, f.key) && in_effect(b, f.key) && f.get(a) != f.get(b)) return false;
  }
  return true;
}

py::dict state_dict(py::handle state, const char* what) {
  if (!py::isinstance<py::dict>(state))
    throw Error(std::string("cannot restore a ") + what + " from " + python_description(state) +
                "; expected the dict of its __getstate__");
  return py::reinterpret_borrow<py::dict>(state);
}

template <class Group>
Group group_from(const GroupAccess<Group>& access, const py::dict& kwargs) {
  Builder b(access.wrap(Group{}));
  for (auto item : kwargs) {
    if (!py::isinstance<py::str>(item.first))
      throw Error(std::string(access.group) + " keys must be strings; got " +
                  python_description(item.first));
    b.set_in_group(access.group, item.first.cast<std::string>(), item.second);
  }
  return b.finish().*(access.member);
}

template <class Group>
py::class_<Group> bind_group(py::module_& m, const char* cls, const char* doc,
                             GroupAccess<Group> access) {
  std::string names;
  for (const Field& f : fields())
    if (in_group(f.key, access.group))
      names += std::string(names.empty() ? "" : ", ") + std::string(last_part(f.key));
  py::class_<Group> c(m, cls, keep(std::string(doc) + "\n\nKeywords: " + names + "."));
  construct_on_new(c);
  def_assigning(
      c, "__init__",
      [access](Group& self, const py::kwargs& kwargs) { self = group_from(access, kwargs); },
      keep(std::string("Keyword construction; defaults are the paper's values.\n\n"
                       "Parameters\n----------\n**kwargs\n    ") +
           names +
           " (SI units; see the properties).\n\nRaises\n------\noscidrum.Error\n    For an unknown "
           "keyword, a value of the wrong type or one that breaks its rule."));
  for (const Field& f : fields()) {
    if (!in_group(f.key, access.group)) continue;
    const Field* field = &f;
    c.def_property(
        std::string(last_part(f.key)).c_str(),
        [access, field](py::handle self) { return field_value(access.context(self), *field); },
        [access, field](py::handle self, py::handle value) {
          self.cast<Group&>() = set_one(access.context(self), field->key, value).*(access.member);
        },
        keep(field_doc(f)));
  }
  c.def("__repr__", [access, cls](py::handle self) {
    return group_repr(access.context(self), access.group, cls);
  });
  c.def("__str__", [access, cls](py::handle self) {
    return group_str(access.context(self), access.group, cls);
  });
  c.def(
      "to_dict",
      [access](py::handle self, bool all) {
        return values_dict(access.context(self), access.group, all);
      },
      py::arg("all") = false,
      "The values as {name: value} (SI units); soil values without effect under soil.input only "
      "with all=True.");
  c.def(
      "__eq__",
      [access](py::handle self, py::handle other) {
        if (!py::isinstance<Group>(other)) return false;
        return equal_in_effect(access.context(self), access.context(other), access.group);
      },
      py::is_operator());
  c.attr("__hash__") = py::none();
  c.def("__copy__", [](const Group& g) { return g; });
  c.def(
      "__deepcopy__", [](const Group& g, const py::dict&) { return g; }, py::arg("memo"));
  c.def("__getstate__", [access](py::handle self) {
    return values_dict(access.context(self), access.group, false);
  });
  def_assigning(c, "__setstate__", [access, cls](Group& self, py::handle state) {
    self = group_from(access, state_dict(state, cls));
  });
  return c;
}

// case.soil (a view into the case: case.soil.G = ... changes the case) and case.soil = value
// (a Soil or a dict, by the rules of Case()).
template <class Group>
void def_group_property(py::class_<Case>& cls, GroupAccess<Group> access, const char* doc) {
  cls.def_property(
      access.group,
      py::cpp_function([access](Case& c) -> Group& { return c.*(access.member); },
                       py::return_value_policy::reference_internal),
      [access](Case& c, py::handle value) {
        py::dict d;
        d[access.group] = value;
        c = build(c, d);
      },
      doc);
}

py::dict case_dict(const Case& c, bool all) { return values_dict(c, nullptr, all); }

std::string case_repr(const Case& c) { return "Case(" + join(differing(c, nullptr, true)) + ")"; }

std::string case_str(const Case& c) {
  std::string out = "Case(\n";
  out += "  roller=" + group_str(c, kRoller.group, "Roller") + ",\n";
  out += "  soil=" + group_str(c, kSoil.group, "Soil") + ",\n";
  out += "  trough=" + group_str(c, kTrough.group, "Trough") + ",\n";
  out += "  contact=" + group_str(c, kContact.group, "Contact") + ",\n";
  out += "  MMd=" + with_unit(*find_field("MMd"), format_field(c, *find_field("MMd"))) + ",\n";
  out += "  numerics=" + group_str(c, kNumerics.group, "Numerics") + ")";
  return out;
}

std::string alias_table() {
  std::string out;
  for (const auto& [alias, key] : aliases()) out += "    " + alias + " -> " + key + "\n";
  return out + "    R -> trough.k = 0 and trough.a = R (a circular trough of radius R)\n";
}

}  // namespace

std::string dotted_field_key(std::string_view name) {
  if (find_field(name) != nullptr) return std::string(name);
  if (const std::string* key = alias_of(name); key && find_field(*key) != nullptr) return *key;
  return std::string(name);
}

double field_argument(std::string_view key, py::handle value) {
  const std::string k(key);
  const Field* f = find_field(k);
  if (f == nullptr) throw Error("unknown parameter '" + k + "'" + io::suggest_key(k));
  io::CaseSpec spec;
  io::assign(spec, k, to_value(k, value), "argument " + k);
  return f->get(spec.values);
}

std::string python_type_name(py::handle value) {
  return py::str(py::type::of(value).attr("__name__")).cast<std::string>();
}

std::string python_description(py::handle value) {
  std::string text = py::repr(value).cast<std::string>();
  if (text.size() > 60) text = text.substr(0, 60) + "...";
  return python_type_name(value) + " (" + text + ")";
}

void bind_parameters(py::module_& m) {
  py::enum_<SoilInput> soil_input(m, "SoilInput",
                                  "How the soil is given (Soil.input accepts the name too).");
  soil_input
      .value("coefficients", SoilInput::coefficients,
             "directly as the discrete Kelvin-Voigt coefficients ksh, ksv, csh, csv")
      .value("modulus", SoilInput::modulus,
             "as continuum (G, nu, rho), converted by Appendix B (42)-(45)")
      .value("table2", SoilInput::table2,
             "the row of paper Table 2 at G (nu = 0.3, rho = 1900 kg/m^3); the default");
  strict_enum(soil_input);

  bind_group<Roller>(m, "Roller",
                     "The drum and its suspension (paper Table 1: HAMM HD+ 90 VO). SI units.",
                     kRoller);
  bind_group<Soil>(m, "Soil",
                   "The soil below the drum: the row of paper Table 2 at G when input = 'table2' "
                   "(the default, G = 25 MN/m^2), continuum (G, nu, rho) through Appendix B when "
                   "input = 'modulus', or discrete Kelvin-Voigt coefficients (ksh, ksv, csh, csv) "
                   "when input = 'coefficients'. G is in Pa (30 MN/m^2 is 30e6). Setting a key "
                   "without effect under the input in force is an error naming soil.input; "
                   "table2_G=G is input='table2' with G.",
                   kSoil);
  bind_group<Trough>(m, "Trough",
                     "Settlement trough, logarithmic spiral R(theta) = a exp(k theta) (8); k = 0 "
                     "is a circle of radius a.",
                     kTrough);
  bind_group<Contact>(m, "Contact", "Drum/soil contact (Coulomb friction).", kContact);
  bind_group<Numerics>(m, "Numerics",
                       "Numerical options of the hybrid integration and the steady-state search.",
                       kNumerics);

  py::class_<Case> cls(
      m, "Case",
      keep("One simulation case: roller, soil, trough, contact, driving torque MMd [N m] and "
           "numerics. Defaults are the paper's roller on the Table 2 soil at G = 25 MN/m^2, "
           "circular trough R = 0.606 m, mu = 0.5, MMd = 0.\n\n"
           "Parameters\n----------\n**kwargs\n"
           "    Any field by its dotted key (``**{'contact.mu': 0.3}``) or by its flat name when "
           "that is unique (``mu=0.3``), the groups roller=, soil=, trough=, contact=, numerics= "
           "(objects or dicts), and the shorthands of the config files: ``table2_G`` [Pa] (the "
           "soil of paper Table 2 at G), ``MMd_fraction`` [-] (MMd = MMd_fraction * M0) and "
           "``R`` [m] (a circular trough: trough.k = 0, trough.a = R). SI units. Flat names:\n\n" +
           alias_table() +
           "\nRaises\n------\noscidrum.Error\n    For an unknown key, a value of the wrong type "
           "('1851' for a number, 1 or 'off' for a boolean, True for an integer), a value that "
           "breaks its rule, or a key without effect (e.g. nu while soil.input = 'table2', the "
           "default: set input='modulus'), or a G that Table 2 does not hold while soil.input = "
           "'table2'.\n\n"
           "Examples\n--------\n>>> import oscidrum\n"
           ">>> case = oscidrum.Case(table2_G=5e6, mu=0.3, MMd_fraction=0.05, R=0.62)\n"
           ">>> oscidrum.Model(case).ksh      # [N/m], paper Table 2 at G = 5 MN/m^2\n"
           "11400000.0\n"
           ">>> oscidrum.Case(G=30e6).soil.input     # Table 2 at 30 MN/m^2, as the CLI's --G 30\n"
           "'table2'\n"
           ">>> oscidrum.Case(input='modulus', G=27e6).soil.G   # [Pa], Appendix B soil\n"
           "27000000.0\n"));
  construct_on_new(cls);
  def_assigning(
      cls, "__init__", [](Case& self, const py::kwargs& kwargs) { self = build(Case{}, kwargs); },
      "Keyword construction; see the class docstring.");
  def_group_property(cls, kRoller, "the drum and suspension (Roller, or a dict of its values)");
  def_group_property(cls, kSoil, "the soil (Soil, or a dict of its values)");
  def_group_property(cls, kTrough, "the settlement trough (Trough, or a dict of its values)");
  def_group_property(cls, kContact, "the contact (Contact, or a dict of its values)");
  def_group_property(cls, kNumerics, "numerical options (Numerics, or a dict of its values)");
  const Field* mmd = find_field("MMd");
  cls.def_property(
      "MMd", [mmd](const Case& c) { return field_value(c, *mmd); },
      [](Case& c, py::handle v) { c = set_one(c, "MMd", v); }, keep(field_doc(*mmd)));
  cls.def(
      "get",
      [](const Case& c, const std::string& name) {
        const std::string key = resolve_key(name);
        if (key == kRadius) return py::object(py::float_(get_field(c, "trough.a")));
        if (const Field* f = find_field(key)) return field_value(c, *f);
        if (key == "MMd_fraction") return py::object(py::float_(c.MMd / c.roller.M0));
        return py::object(py::float_(c.soil.G));  // soil.table2_G
      },
      py::arg("key"),
      "The value of a key: dotted ('soil.ksh'), flat ('ksh') or a shorthand.\n\n"
      "Parameters\n----------\nkey : str\n    e.g. 'contact.mu' or 'mu'.\n\n"
      "Returns\n-------\nfloat, int, bool or str\n    In the SI unit of the field.\n\n"
      "Raises\n------\noscidrum.Error\n    For an unknown key.\n\n"
      "Examples\n--------\n>>> oscidrum.Case().get('ksh')   # [N/m]\n41400000.0");
  cls.def(
      "set", [](Case& c, const std::string& key, py::handle value) { c = set_one(c, key, value); },
      py::arg("key"), py::arg("value"),
      "Set one key (dotted, flat or a shorthand), by the rules of the config files.\n\n"
      "Parameters\n----------\nkey : str\n    e.g. 'soil.input', 'mu', 'table2_G'.\n"
      "value : float, int, bool or str\n    SI units; booleans must be True/False, choices "
      "their names.\n\n"
      "Raises\n------\noscidrum.Error\n    With the library's message, e.g. \"soil.G must be > 0 "
      "[Pa]; got -5e+06\", or \"... soil.G has no effect while soil.input = "
      "\\\"coefficients\\\" ...\".\n\n"
      "Examples\n--------\n>>> c = oscidrum.Case()\n>>> c.set('soil.input', 'modulus')\n"
      ">>> c.set('soil.G', 5e6)              # [Pa]\n>>> c.soil.G\n5000000.0");
  cls.def("to_dict", &case_dict, py::arg("all") = false,
          "Every field in effect as {dotted key: value} in documentation order (SI units, "
          "choices as names); Case.from_dict reads it back. With all=True also the soil values "
          "that the soil.input in force ignores (which from_dict rejects).");
  cls.def_static(
      "from_dict", [](const py::dict& d) { return build(Case{}, d); }, py::arg("values"),
      "Build a Case from {key: value} (dotted, flat or shorthand keys; missing keys keep their "
      "defaults); group names ('soil', ...) may map to objects or dicts. Raises oscidrum.Error "
      "as Case() does.");
  cls.def(
      "replace", [](const Case& c, const py::kwargs& kwargs) { return build(c, kwargs); },
      "A copy with some values changed (keywords as for Case()), e.g. case.replace(mu=0.3, "
      "MMd_fraction=0.05).");
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
  cls.def_static(
      "aliases",
      []() {
        py::dict d;
        for (const auto& [alias, key] : aliases()) d[py::str(alias)] = key;
        return d;
      },
      "The flat keywords: {name: dotted key} for every field and shorthand whose last component "
      "is unique (plus R, the circular-trough shorthand, which is not listed).");
  cls.def("__repr__", &case_repr);
  cls.def("__str__", &case_str);
  cls.def(
      "__eq__",
      [](const Case& a, py::handle other) {
        return py::isinstance<Case>(other) && equal_in_effect(a, other.cast<Case>(), nullptr);
      },
      py::is_operator());
  cls.attr("__hash__") = py::none();
  cls.def("__copy__", [](const Case& c) { return c; });
  cls.def(
      "__deepcopy__", [](const Case& c, const py::dict&) { return c; }, py::arg("memo"));
  cls.def("__getstate__", [](const Case& c) { return case_dict(c, false); });
  def_assigning(cls, "__setstate__", [](Case& self, py::handle state) {
    self = build(Case{}, state_dict(state, "Case"));
  });

  m.def(
      "load_case",
      [](const py::object& path) {
        if (!py::isinstance<py::str>(path) && !py::hasattr(path, "__fspath__"))
          throw Error("load_case: path must be a str or os.PathLike; got " +
                      python_description(path));
        io::CaseSpec spec;
        io::read_case_file(py::str(py::module_::import("os").attr("fspath")(path)), spec);
        return io::finalize(spec);
      },
      py::arg("path"),
      "Read a case file (TOML) as the command line tool does (docs/config.md).\n\n"
      "Parameters\n----------\npath : str or os.PathLike\n    The case file.\n\n"
      "Returns\n-------\nCase\n\n"
      "Raises\n------\noscidrum.Error\n    \"FILE:LINE:COLUMN: ...\" naming the key and rule, as "
      "`oscidrum run` reports it.\n\n"
      "Examples\n--------\n>>> case = oscidrum.load_case('examples/case.toml')   # doctest: +SKIP\n"
      ">>> case.trough.a                                # [m]   # doctest: +SKIP");
  m.def(
      "key_in_effect",
      [](const Case& c, const std::string& key) {
        get_field(c, key);  // raises the "did you mean" error for an unknown key
        return key_in_effect(c, key);
      },
      py::arg("case"), py::arg("key"),
      "Whether a key takes effect in the case: the soil keys its soil.input reads (soil.G for "
      "'table2' and 'modulus'; nu, rho for 'modulus'; ksh, ksv, csh, csv for 'coefficients'), "
      "roller.M0 unless roller.unbalance replaces it, the trough keys of its shape, and every "
      "other key. The library's rule, as the config files and the web page apply it.\n\n"
      "Examples\n--------\n>>> oscidrum.key_in_effect(oscidrum.Case(), 'soil.nu')\nFalse");
  m.def(
      "case_to_toml", [](const Case& c) { return io::case_to_toml(c); }, py::arg("case"),
      "The case as the text of a case file (TOML, every key with unit and description); "
      "load_case reads it back.");
}

}  // namespace oscidrum::python
