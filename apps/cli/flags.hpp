// flags.hpp: the checks every numeric flag gets. Numbers on the command line are decimal text
// (oscidrum::parse_number: no empty text, hex, inf or nan), checked while CLI11 parses, before a
// flag's own rule; bounds that follow from the data (a window no longer than the record) are
// checked after reading it, by check_flag.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace CLI {
class App;
}

namespace oscidrum::cli {

/// Whether the user gave the flag (an option that exists and was parsed at least once).
inline bool given(const CLI::Option* flag) { return flag && flag->count() > 0; }

/// Put the strict number check first on every numeric option (CLI11 type FLOAT, INT or UINT) of
/// `app` and of its subcommands: "--G: must be a decimal number; got '0x10'", "--harmonics:
/// must be an integer (digits only); got '1e3'". Call after every command was added.
void strict_numbers(CLI::App& app);

/// The rules "> 0" and ">= 0" with the project's messages ("--f: must be > 0; got -3"): CLI11's
/// PositiveNumber and NonNegativeNumber print their range, 0 to 1.8e308, with all its digits.
CLI::Validator positive_number();
CLI::Validator non_negative_number();

/// A flag's value against a rule known only after parsing (from the data): finite and in
/// [lo, hi] (an open end with lo_open / hi_open). Throws oscidrum::Error
/// "FLAG must be in [lo, hi] [unit] (why); got VALUE" (`why` may be empty).
void check_flag(const std::string& flag, double value, double lo, double hi,
                const std::string& unit, const std::string& why = "", bool lo_open = false,
                bool hi_open = false);

}  // namespace oscidrum::cli
