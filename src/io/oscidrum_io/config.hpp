// oscidrum_io/config.hpp: case and study files (TOML, read with toml++), and writing a case back
// as TOML. The syntax is documented in docs/config.md. Every error is an oscidrum::Error whose
// message starts with "FILE:LINE:COLUMN: " and names the key, the rule and the value.
#pragma once

#include <string>
#include <string_view>

#include "oscidrum/parameters.hpp"
#include "oscidrum_io/case_spec.hpp"
#include "oscidrum_io/sweep.hpp"

namespace oscidrum::io {

/// Read a case file on top of `spec` (later values override earlier ones).
void read_case_file(const std::string& path, CaseSpec& spec);

/// The same for TOML text; `name` stands for the file in messages.
void read_case_text(std::string_view text, const std::string& name, CaseSpec& spec);

/// Read a study file: base-case keys at the top level (as in a case file), optional
/// `base = "case.toml"` (relative to the study file) read first, and a [sweep] table.
StudySpec read_study_file(const std::string& path);

/// The same for TOML text; `dir` resolves `base`.
StudySpec read_study_text(std::string_view text, const std::string& name, const std::string& dir);

/// A case file that sets every field of `c` (with unit and description as comments). The keys
/// that would have no effect (key_in_effect) are written as comments. Reading it back gives `c`
/// again (the unused keys aside).
std::string case_to_toml(const Case& c);

/// The whole file as bytes. Throws oscidrum::Error "cannot read FILE: reason".
std::string read_file(const std::string& path);

}  // namespace oscidrum::io
