// CaseSpec: typed assignment of config values, the conveniences soil.table2_G and MMd_fraction,
// and the consistency rules between keys (see docs/config.md).
#include "oscidrum_io/case_spec.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/text.hpp"
#include "oscidrum_io/csv.hpp"
#include "util/format.hpp"
#include "util/text.hpp"

namespace oscidrum::io {
namespace {

constexpr std::array kExtraKeys = {
    ExtraKey{"soil.table2_G", "Pa", "one of 5e6, 10e6, ..., 70e6",
             "shorthand: soil.input = \"table2\" and soil.G = this value, the soil of paper "
             "Table 2 (the paper's simulations)"},
    ExtraKey{"MMd_fraction", "-", "finite",
             "shorthand: MMd = MMd_fraction * M0 (roller.M0, or from roller.unbalance; the paper "
             "uses 0 and 0.05)"},
};

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& ch : out) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

std::vector<std::string_view> all_keys() {
  std::vector<std::string_view> keys;
  for (const Field& f : fields()) keys.emplace_back(f.key);
  for (const ExtraKey& e : kExtraKeys) keys.emplace_back(e.key);
  return keys;
}

[[noreturn]] void type_error(const Field& f, const char* expected, const Value& v) {
  const std::string unit = std::string(f.unit) == "-" ? "" : std::string(" [") + f.unit + "]";
  std::string msg =
      std::string(f.key) + " must be " + expected + unit + "; got " + describe_value(v);
  if (std::holds_alternative<std::string>(v) && f.type != FieldType::choice)
    msg += " (write numbers and booleans without quotes)";
  throw Error(msg, f.key);
}

double number_of(const Value& v, bool* ok) {
  *ok = true;
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  *ok = false;
  return 0.0;
}

constexpr std::array kCoefficientKeys = {"soil.ksh", "soil.ksv", "soil.csh", "soil.csv"};

}  // namespace

std::string format_value(const Value& value) {
  if (const auto* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const auto* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&value)) return format_double_short(*d);
  return std::get<std::string>(value);
}

std::string describe_value(const Value& value) {
  if (std::holds_alternative<bool>(value)) return "a boolean (" + format_value(value) + ")";
  if (std::holds_alternative<std::int64_t>(value))
    return "an integer (" + format_value(value) + ")";
  if (const auto* d = std::get_if<double>(&value)) return "a number (" + num(*d) + ")";
  std::string s = std::get<std::string>(value);
  if (s.size() > 40) s = s.substr(0, 40) + "...";
  return "a string (\"" + s + "\")";
}

std::string clip(std::string_view text) {
  if (text.size() <= 80) return std::string(text);
  return std::string(text.substr(0, 60)) + "... (" + std::to_string(text.size()) + " bytes)";
}

std::span<const ExtraKey> extra_keys() { return kExtraKeys; }

const ExtraKey* find_extra_key(std::string_view key) {
  for (const ExtraKey& e : kExtraKeys)
    if (key == e.key) return &e;
  return nullptr;
}

std::string key_unit(std::string_view key) {
  if (const Field* f = find_field(key)) return f->unit;
  if (const ExtraKey* e = find_extra_key(key)) return e->unit;
  return {};
}

std::string suggest_key(std::string_view key) {
  if (key.size() > 80) return "; see 'oscidrum fields' for every key";  // no edit distances
  const std::vector<std::string_view> keys = all_keys();
  // 0. The trough's radius R (the CLI's --R, Python's R=) is trough.a of a circle (trough.k = 0):
  // by name alone "R" would suggest the drum's radius roller.r.
  if (key == "R" || lower(key) == "trough.r" || lower(key) == "trough.radius")
    return "; did you mean 'trough.a' (the radius R of a circular trough, with trough.k = 0, as "
           "the CLI's --R sets it)?";
  // 1.-2. The same name in another section, or a near miss (util/text.hpp).
  if (const std::string_view best = detail::closest_key(key, keys); !best.empty())
    return "; did you mean '" + std::string(best) + "'?";
  // 3. A known section: list its keys.
  const std::size_t dot = key.find('.');
  if (dot != std::string_view::npos) {
    const std::string_view section = key.substr(0, dot);
    std::string list;
    for (std::string_view k : keys)
      if (k.starts_with(section) && k.size() > section.size() && k[section.size()] == '.')
        list += (list.empty() ? "" : ", ") + std::string(detail::key_last_part(k));
    if (!list.empty()) return "; [" + std::string(section) + "] has " + list;
  }
  return "; see 'oscidrum fields' for every key";
}

std::string suggest_section(std::string_view section) {
  if (section.size() > 80) section = section.substr(0, 0);
  std::vector<std::string> sections;
  for (std::string_view k : all_keys()) {
    const std::size_t dot = k.find('.');
    if (dot == std::string_view::npos) continue;
    const std::string s(k.substr(0, dot));
    if (std::find(sections.begin(), sections.end(), s) == sections.end()) sections.push_back(s);
  }
  std::string best;
  std::size_t best_d = std::clamp<std::size_t>(section.size() / 3, 1, 3) + 1;
  for (const std::string& s : sections) {
    const std::size_t d = detail::edit_distance(section, s);
    if (d < best_d) best_d = d, best = s;
  }
  if (!best.empty()) return "; did you mean [" + best + "]?";
  std::string list;
  for (const std::string& s : sections) list += (list.empty() ? "" : ", ") + ("[" + s + "]");
  return "; the sections are " + list;
}

bool is_known_section(std::string_view section) {
  for (std::string_view k : all_keys()) {
    const std::size_t dot = k.find('.');
    if (dot != std::string_view::npos && k.substr(0, dot) == section) return true;
  }
  return false;
}

std::string CaseSpec::where(std::string_view key) const {
  auto it = origin.find(key);
  return it == origin.end() ? std::string() : it->second + ": ";
}

void assign(CaseSpec& spec, std::string_view key, const Value& value, const std::string& origin) {
  if (const ExtraKey* e = find_extra_key(key)) {
    bool is_number = false;
    const double v = number_of(value, &is_number);
    if (!is_number)
      throw Error(
          std::string(e->key) + " must be a number [" + e->unit + "]; got " + describe_value(value),
          e->key);
    if (!std::isfinite(v))
      throw Error(std::string(e->key) + " must be finite; got " + num(v), e->key, v);
    if (key == "soil.table2_G") {
      if (!is_table2_G(v)) {
        std::string msg =
            "soil.table2_G must be a G of paper Table 2: 5e6, 10e6, ..., 70e6 [Pa] "
            "(5 ... 70 MN/m^2 in steps of 5); got " +
            num(v);
        msg += is_table2_G(v * 1e6) ? " (values are in Pa: did you mean " + num(v * 1e6) + "?)"
                                    : " (for other G use soil.input = \"modulus\" and soil.G)";
        throw Error(msg, e->key, v);
      }
      // soil.table2_G sets soil.G: a soil.G given before it (the same file, or a --set under a
      // sweep over soil.table2_G) would be dropped without a word. A soil.G given after it
      // overrides it (a sweep over soil.G on a Table 2 base case).
      const auto g = spec.origin.find("soil.G"), t = spec.origin.find("soil.table2_G");
      if (g != spec.origin.end() && (t == spec.origin.end() || t->second != g->second))
        throw Error("soil.table2_G cannot be set together with soil.G (" + g->second +
                        "): soil.table2_G sets soil.G itself; remove one of them",
                    e->key, v);
      spec.values.soil.input = SoilInput::table2;
      spec.values.soil.G = v;
      spec.origin["soil.G"] = origin;
    } else {
      spec.MMd_fraction = v;
    }
    spec.origin[std::string(key)] = origin;
    return;
  }
  const Field* f = find_field(key);
  if (!f) throw Error("unknown parameter '" + clip(key) + "'" + suggest_key(key), std::string(key));
  double v = 0.0;
  switch (f->type) {
    case FieldType::real: {
      bool is_number = false;
      v = number_of(value, &is_number);
      if (!is_number) type_error(*f, "a number", value);
      break;
    }
    case FieldType::integer: {
      // An integer, not a float that happens to be whole (5.0, 1e3): the rule of TOML and of
      // --set alike.
      const auto* i = std::get_if<std::int64_t>(&value);
      if (const auto* d = std::get_if<double>(&value)) {
        const bool whole = std::isfinite(*d) && *d == std::floor(*d) && std::abs(*d) < 1e15;
        throw Error(std::string(f->key) + " must be " + field_rule(*f) + "; got " +
                        (whole ? num(*d) + " written as a float (5.0, 1e3 are floats): write " +
                                     num(*d) + ", without a decimal point or exponent"
                               : num(*d)),
                    f->key, *d);
      }
      if (!i) type_error(*f, "an integer", value);
      v = static_cast<double>(*i);
      break;
    }
    case FieldType::boolean:
      if (!std::holds_alternative<bool>(value)) type_error(*f, "true or false", value);
      v = std::get<bool>(value) ? 1.0 : 0.0;
      break;
    case FieldType::choice: {
      if (!std::holds_alternative<std::string>(value))
        type_error(*f, field_rule(*f).c_str(), value);
      const int i = choice_index(*f, std::get<std::string>(value));
      if (i < 0) type_error(*f, field_rule(*f).c_str(), value);
      v = i;
      break;
    }
  }
  std::string problem = check_field(*f, v);
  // An integer as written: 9223372036854775807 was quoted as the double it rounds to (...808).
  if (const auto* i = std::get_if<std::int64_t>(&value); i && !problem.empty()) {
    const std::string as_double = "; got " + detail::shortest(v);
    if (const std::size_t at = problem.find(as_double); at != std::string::npos)
      problem.replace(at, as_double.size(), "; got " + std::to_string(*i));
  }
  if (!problem.empty()) throw Error(problem, f->key, v);
  f->set(spec.values, v);
  spec.origin[std::string(key)] = origin;
}

void assign_text(CaseSpec& spec, std::string_view key, std::string_view text,
                 const std::string& origin) {
  const Field* f = find_field(key);
  if (!f && !find_extra_key(key))
    throw Error("unknown parameter '" + clip(key) + "'" + suggest_key(key));
  if (!f) {  // the shorthands are numbers
    const std::optional<double> v = parse_number(text);
    if (!v)
      throw Error(std::string(key) + " must be " + number_rule() + " [" + key_unit(key) +
                  "]; got '" +
                  printable(text.size() > 40 ? std::string(text.substr(0, 40)) + "..."
                                             : std::string(text)) +
                  "'");
    return assign(spec, key, *v, origin);
  }
  // One rule set, the field table's: the same text is accepted here and in Python.
  const double v = parse_field_text(*f, text);
  switch (f->type) {
    case FieldType::boolean:
      return assign(spec, key, v != 0.0, origin);
    case FieldType::choice:
      return assign(spec, key, std::string(text), origin);
    case FieldType::integer:
      if (std::abs(v) >= 9e18)
        throw Error(std::string(key) + " must be " + field_rule(*f) + "; got " + std::string(text));
      return assign(spec, key, static_cast<std::int64_t>(v), origin);
    case FieldType::real:
      break;
  }
  assign(spec, key, v, origin);
}

void clear_soil(CaseSpec& spec) {
  for (auto it = spec.origin.begin(); it != spec.origin.end();)
    it = it->first.starts_with("soil.") ? spec.origin.erase(it) : std::next(it);
}

void materialize_soil(CaseSpec& spec) {
  Soil& soil = spec.values.soil;
  SoilCoefficients k;
  try {
    k = soil_coefficients(soil, spec.values.roller);
  } catch (const Error& e) {
    throw e.prefixed(spec.where(e.key()));
  }
  soil.ksh = k.ksh, soil.ksv = k.ksv, soil.csh = k.csh, soil.csv = k.csv;
  soil.input = SoilInput::coefficients;
  std::map<std::string, std::string, std::less<>> kept;
  for (const auto& [key, where] : spec.origin)
    if (!key.starts_with("soil.") ||
        std::find(kCoefficientKeys.begin(), kCoefficientKeys.end(), key) != kCoefficientKeys.end())
      kept.emplace(key, where);
  spec.origin = std::move(kept);
}

namespace {

// The soil as the spec gives it: the shorthand soil.table2_G against soil.input, coefficient keys
// under the default input, and a Table 2 G that the table holds.
void resolve_soil(const CaseSpec& spec, Case& c) {
  if (spec.given("soil.input") && spec.given("soil.table2_G"))
    throw Error(spec.where("soil.input") +
                    "soil.input cannot be set together with soil.table2_G (" +
                    spec.origin.at("soil.table2_G") +
                    "), which means soil.input = \"table2\"; remove one of them",
                "soil.input");
  // Coefficient keys while soil.input was left at its default (table2): the soil is given by its
  // coefficients, those not given from the Table 2 row at soil.G (the default soil's).
  const bool input_given = spec.given("soil.input") || spec.given("soil.table2_G");
  bool coefficient_given = false;
  for (const char* key : kCoefficientKeys) coefficient_given = coefficient_given || spec.given(key);
  if (!input_given && coefficient_given && c.soil.input == SoilInput::table2) {
    const Soil given = c.soil;
    SoilCoefficients row;
    try {
      row = soil_coefficients(c.soil, c.roller);
    } catch (const Error& e) {
      throw e.prefixed(spec.where(e.key()));
    }
    c.soil.input = SoilInput::coefficients;
    c.soil.ksh = spec.given("soil.ksh") ? given.ksh : row.ksh;
    c.soil.ksv = spec.given("soil.ksv") ? given.ksv : row.ksv;
    c.soil.csh = spec.given("soil.csh") ? given.csh : row.csh;
    c.soil.csv = spec.given("soil.csv") ? given.csv : row.csv;
  }
  // Every soil key given must take effect under the input in force.
  for (const auto& [key, where] : spec.origin) {
    if (!key.starts_with("soil.") || !find_field(key)) continue;
    const std::string why = key_not_in_effect(c, key);
    if (!why.empty()) throw Error(where + ": " + why, key);
  }
  // The one conversion, for its check (a G that Table 2 does not hold), with the key's origin.
  try {
    (void)soil_coefficients(c.soil, c.roller);
  } catch (const Error& e) {
    std::string because;
    if (spec.given("soil.table2_G"))
      because = " (soil.G is used with Table 2 because of soil.table2_G (" +
                spec.origin.at("soil.table2_G") + "))";
    throw Error(spec.where(e.key()) + e.what() + because, e.key(), e.value());
  }
}

}  // namespace

Case finalize(const CaseSpec& spec, std::vector<std::string>* warnings) {
  Case c = spec.values;
  resolve_soil(spec, c);
  // The oscillation moment: M0, or the unbalance that gives M0 at every f (5).
  if (spec.given("roller.unbalance") && spec.given("roller.M0") && c.roller.unbalance > 0.0)
    throw Error(spec.where("roller.unbalance") +
                    "roller.unbalance gives M0 = 4 m_u e_u e_w nu^2 (5), so it cannot be given "
                    "together with roller.M0 (" +
                    spec.origin.at("roller.M0") + "); remove one of them",
                "roller.unbalance");
  // Every other key given must take effect too (roller.M0 under a base case's unbalance, ...).
  for (const auto& [key, where] : spec.origin) {
    if (key.starts_with("soil.") || !find_field(key)) continue;
    const std::string why = key_not_in_effect(c, key);
    if (!why.empty()) throw Error(where + ": " + why, key);
  }
  const bool vibratory = c.roller.type == RollerType::vibratory;
  if (warnings && !vibratory && c.roller.unbalance == 0.0 && c.roller.f != Roller{}.f &&
      !spec.given("roller.M0"))
    warnings->push_back(spec.where("roller.f") + "roller.f = " + num(c.roller.f) +
                        " Hz with M0 fixed at " + num(c.roller.M0) +
                        " N m (the paper's roller at 39 Hz); a real roller's M0 = 4 m_u e_u e_w "
                        "nu^2 (5) grows with f^2: give roller.unbalance (the paper's: 0.22877 kg "
                        "m^2), or set roller.M0 to say the moment is meant");
  // Pure rolling has no friction limit: a friction coefficient given with it changes nothing (a
  // warning, not an error: a study may sweep contact.pure_rolling over a base case with mu).
  if (warnings && c.contact.pure_rolling)
    for (const Field& f : fields())
      if (const std::string key = f.key; friction_key(key) && spec.given(key))
        warnings->push_back(spec.where(key) + key +
                            " has no effect while contact.pure_rolling = "
                            "true (rolling without a friction limit); it applies with "
                            "contact.pure_rolling = false");
  if (spec.MMd_fraction) {
    if (vibratory)
      throw Error(spec.where("MMd_fraction") +
                      "MMd_fraction has no effect while roller.type = \"vibratory\" (MMd_fraction "
                      "* M0, and the vibratory drum has no oscillation moment M0); give MMd [N m]",
                  "MMd_fraction");
    if (spec.given("MMd"))
      throw Error(spec.where("MMd") + "MMd cannot be given together with MMd_fraction (" +
                  spec.origin.at("MMd_fraction") + "); remove one of them");
    c.MMd = *spec.MMd_fraction * oscillation_moment(c.roller);
    // Finite each, their product not (MMd_fraction = 1e308 was refused as "MMd must be finite",
    // a key the file does not hold).
    if (!std::isfinite(c.MMd))
      throw Error(spec.where("MMd_fraction") + "MMd_fraction = " + num(*spec.MMd_fraction) +
                      " gives MMd = MMd_fraction * M0 beyond double precision (M0 = " +
                      num(oscillation_moment(c.roller)) +
                      " N m); the driving torque is a fraction of M0, about -0.2 to 0.2",
                  "MMd_fraction", *spec.MMd_fraction);
  }
  return c;
}

namespace {

// Where the first key that `message` names and the spec has an origin for was given: a rule
// between keys names the one it checks (roller.P0 >= roller.m * roller.g) and may have been broken
// by another (roller.m = 1e308 in the file, P0 left at its default). Empty: none.
std::string where_mentioned(const CaseSpec& spec, std::string_view message) {
  std::size_t first = std::string_view::npos;
  std::string at;
  for (const auto& [key, origin] : spec.origin) {
    for (std::size_t pos = message.find(key); pos != std::string_view::npos;
         pos = message.find(key, pos + 1)) {
      const std::size_t end = pos + key.size();
      const auto part_of_name = [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '.';
      };
      if ((end < message.size() && part_of_name(message[end])) ||
          (pos > 0 && part_of_name(message[pos - 1])))
        continue;
      if (pos < first) first = pos, at = origin + ": ";
      break;
    }
  }
  return at;
}

}  // namespace

void validate(const Case& c, const CaseSpec& spec) {
  try {
    const Model model(c);
    (void)model;
  } catch (const Error& e) {
    std::string at = spec.where(e.key());
    if (at.empty()) at = where_mentioned(spec, e.what());
    throw e.prefixed(at);
  }
}

}  // namespace oscidrum::io
