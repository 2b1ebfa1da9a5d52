// oscidrum/text.hpp: numbers read from text, and text that goes into a one-line message. One
// parser for every number a user types (CLI flags, --set, case files' strings, Python strings).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace oscidrum {

/// A number written in decimal: an optional sign, digits with at most one '.', an optional
/// exponent (e or E, optional sign, digits), e.g. 25, -0.5, .5, 2.5e+06. Nothing else: no empty
/// text, no spaces, no hexadecimal (0x10), no inf or nan, no trailing characters. Returns
/// std::nullopt for anything else and for a value too large for a double (1e999); a value too
/// small for one (1e-999) is 0.
std::optional<double> parse_number(std::string_view text);

/// The rule parse_number applies, for messages: "a decimal number".
const char* number_rule();

/// `text` as it can go into a one-line message: bytes that are not part of valid UTF-8 and control
/// characters (line breaks included) are written as \xNN; everything else is kept.
std::string printable(std::string_view text);

/// The candidate nearest to `word` (edit distance, ASCII case ignored) if it is within
/// `max_distance` edits and within a third of the word's length (a flag's without its dashes; at
/// least one edit), else "": for "did you mean ...?" in messages.
std::string nearest(std::string_view word, const std::vector<std::string>& candidates,
                    std::size_t max_distance = 2);

}  // namespace oscidrum
