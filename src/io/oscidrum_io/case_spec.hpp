// oscidrum_io/case_spec.hpp: a case as the user wrote it (config file, flags, sweep values),
// before it becomes a Case. It remembers where every explicit value came from, so that errors
// can name the file and line, and it holds the convenience that must be resolved only once all
// values are known (a sweep over roller.M0 with MMd_fraction).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "oscidrum/parameters.hpp"

namespace oscidrum::io {

/// A value as it arrives from a TOML file, a flag or a sweep list.
using Value = std::variant<bool, std::int64_t, double, std::string>;

/// "true", "3", "2.5e+06" (the shortest text that reads back exactly), or the string itself.
std::string format_value(const Value& value);

/// "a boolean (true)", "an integer (3)", "a number (2.5)", "a string (\"x\")": for messages.
std::string describe_value(const Value& value);

/// Text from the user as it goes into a message: as is up to 80 bytes, else its first 60 and
/// "... (N bytes)" (a 1 MB key is not echoed in a 1 MB line).
std::string clip(std::string_view text);

/// A config key that is not a field of fields(): a convenience resolved by finalize().
struct ExtraKey {
  const char* key;
  const char* unit;
  const char* rule;
  const char* description;
};

/// soil.table2_G and MMd_fraction, in documentation order.
std::span<const ExtraKey> extra_keys();
const ExtraKey* find_extra_key(std::string_view key);

/// The unit of a field or extra key ("-" if dimensionless); empty for an unknown key.
std::string key_unit(std::string_view key);

/// "; did you mean 'soil.G'?" for the closest known key (fields and extra keys), else the keys
/// of the section, else a pointer to `oscidrum fields`.
std::string suggest_key(std::string_view key);

/// "; did you mean [roller]?" for a misspelt section, or the list of sections.
std::string suggest_section(std::string_view section);

/// True if `section` ("roller", "soil", ...) is the first part of some key.
bool is_known_section(std::string_view section);

/// A case in the making.
struct CaseSpec {
  Case values;  ///< every field; defaults = the paper's roller
  /// Keys set explicitly, and where: "case.toml:3:1", "--G", "--set soil.G=5e6", "sweep (...)".
  std::map<std::string, std::string, std::less<>> origin;
  std::optional<double> MMd_fraction;  ///< MMd = MMd_fraction * roller.M0

  bool given(std::string_view key) const { return origin.find(key) != origin.end(); }
  /// "case.toml:3:1: " for a given key, "" otherwise.
  std::string where(std::string_view key) const;
};

/// Set `key` (a field of fields() or an extra key) from a typed value, checking the type and the
/// field's rule. Throws oscidrum::Error without location ("soil.G must be > 0 [Pa]; got -5");
/// callers that know the location prefix it.
void assign(CaseSpec& spec, std::string_view key, const Value& value, const std::string& origin);

/// Set `key` from command-line text ("25e6", "true", "modulus").
void assign_text(CaseSpec& spec, std::string_view key, std::string_view text,
                 const std::string& origin);

/// Forget how the soil was given (for a flag that redefines it): values stay, origins go.
void clear_soil(CaseSpec& spec);

/// Turn the soil into explicit coefficients (Table 2 or Appendix B as soil.input says, by the
/// model's own conversion), so that a flag can override one of them.
void materialize_soil(CaseSpec& spec);

/// Resolve the conveniences and check the rules that tie keys together (a key given that would
/// have no effect, by key_in_effect; a G that Table 2 does not hold; MMd and MMd_fraction both
/// given, ...). Coefficient keys given while soil.input was left at its default (table2) give the
/// soil by its coefficients, the others from the Table 2 row at soil.G. Warnings (plausible
/// mistakes that are not errors) are appended to `warnings` if given. Throws oscidrum::Error
/// naming the origin.
Case finalize(const CaseSpec& spec, std::vector<std::string>* warnings = nullptr);

/// Validate `c` as Model does; on failure rethrow with the origin of the key the error carries.
void validate(const Case& c, const CaseSpec& spec);

}  // namespace oscidrum::io
