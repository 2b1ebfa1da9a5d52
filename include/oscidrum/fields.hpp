// oscidrum/fields.hpp: the one description of every Case parameter. The config reader, the CLI
// overrides, the Python bindings, the docs and Model's validation all read this table, so a
// parameter's key, unit, default and allowed range are written down exactly once.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "oscidrum/parameters.hpp"

namespace oscidrum {

enum class FieldType { real, integer, boolean, choice };

/// One parameter of a Case. Values travel as double (booleans 0/1, choices as their index).
struct Field {
  const char* key;  ///< dotted key, e.g. "soil.G" (config section "soil", key "G")
  FieldType type;
  const char* unit;         ///< SI unit, "-" if dimensionless
  const char* description;  ///< one line, for --help and the docs
  double min;               ///< allowed range [min, max] (see the *_open flags)
  double max;
  bool min_open;        ///< true: value must be > min (not >=)
  bool max_open;        ///< true: value must be < max (not <=)
  const char* choices;  ///< FieldType::choice: names separated by '|', index = value
  double (*get)(const Case&);
  void (*set)(Case&, double);
  /// The unit people read and type the value in, where it is not `unit` (e.g. "MN/m^2" for
  /// soil.G): displayed value = value / display_scale. The one place of these scalings, for
  /// summaries, plots, the web page and the CLI's --G.
  const char* display_unit = nullptr;
  double display_scale = 1.0;
};

/// Every field, in documentation order.
std::span<const Field> fields();

/// The field with this key, or nullptr.
const Field* find_field(std::string_view key);

/// Read a field of a case (throws oscidrum::Error for an unknown key).
double get_field(const Case& c, std::string_view key);

/// Check `value` against the field's rule and set it. Throws oscidrum::Error with a message of
/// the form "soil.G must be > 0 [Pa]; got -5e+06" (or "unknown parameter 'soil.g'; did you mean
/// 'soil.G'?").
void set_field(Case& c, std::string_view key, double value);

/// The value of a field written as text (a --set or a flag), by the same rules as a config file:
/// a decimal number for a real field ("2.5e7"; parse_number: no hex, inf or nan), digits only for
/// an integer field (not "5.0" or "1e3"), exactly true or false for a boolean, a choice's name. The
/// value is not checked against the field's range (check_field does that). Throws oscidrum::Error
/// naming the key and the text.
double parse_field_text(const Field& field, std::string_view text);

/// Set a field from text (parse_field_text, then the field's rule).
void set_field_text(Case& c, std::string_view key, std::string_view text);

/// The rule of a field as text, e.g. "> 0" or "in [0, 0.5)".
std::string field_rule(const Field& field);

/// The value formatted for people (choice names, true/false, %.10g numbers).
std::string format_field(const Case& c, const Field& field);

/// Check one value against the field's rule; empty string if fine, else the error message.
std::string check_field(const Field& field, double value);

/// The index of `name` among a choice field's names (FieldType::choice), or -1.
int choice_index(const Field& field, std::string_view name);

/// The name of choice `index` of a choice field ("" if there is none).
std::string choice_name(const Field& field, int index);

/// The unit a field is shown in (its display_unit, else its unit).
const char* display_unit(const Field& field);

/// Whether the key (a field of fields()) takes effect in `c`: the soil keys that the soil.input in
/// force reads (soil.G for modulus and table2; nu, rho for modulus; ksh, ksv, csh, csv for
/// coefficients), roller.M0 unless roller.unbalance > 0 replaces it, the trough keys the shape
/// is given by; every other key. The config reader refuses a key that would have no effect, the
/// Python reprs and dicts and the web page's exports leave such keys out.
bool key_in_effect(const Case& c, std::string_view key);

/// The friction keys contact.mu, contact.mu_static and contact.law: in effect (key_in_effect)
/// under contact.pure_rolling = true too, so that a case file or a study may switch pure rolling
/// on over a case with friction, though they change nothing there (a warning, not an error).
bool friction_key(std::string_view key);

/// Why a key has no effect in `c`, naming what to change (e.g. "soil.nu has no effect while
/// soil.input = \"table2\" (...); set soil.input = \"modulus\" ..."), or "" if it takes effect.
std::string key_not_in_effect(const Case& c, std::string_view key);

}  // namespace oscidrum
