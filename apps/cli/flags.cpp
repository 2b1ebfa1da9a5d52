// Strict numeric flags (flags.hpp).
#include "flags.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <string>

#include "oscidrum/error.hpp"
#include "oscidrum/text.hpp"
#include "output.hpp"

namespace oscidrum::cli {
namespace {

std::string shown(const std::string& s) {
  return "'" + printable(s.size() > 40 ? s.substr(0, 40) + "..." : s) + "'";
}

// "" if `s` is a number of the option's type, else why not.
std::string strict(bool integer, const std::string& s) {
  if (!integer) {
    if (parse_number(s)) return {};
    return std::string("must be ") + number_rule() + "; got " + shown(s);
  }
  std::size_t i = (!s.empty() && (s[0] == '-' || s[0] == '+')) ? 1 : 0;
  bool digits = i < s.size() && s.size() - i <= 18;
  for (; digits && i < s.size(); ++i) digits = s[i] >= '0' && s[i] <= '9';
  if (digits) return {};
  return "must be an integer (digits only); got " + shown(s);
}

void add_checks(CLI::App& app) {
  for (CLI::Option* opt : app.get_options()) {
    // CLI11 appends its validators' descriptions: "FLOAT:POSITIVE", "INT:INT in [2 - 200]".
    const std::string full = opt->get_type_name();
    const std::string type = full.substr(0, full.find(':'));
    if (type != "FLOAT" && type != "INT" && type != "UINT") continue;
    const bool integer = type != "FLOAT";
    CLI::Validator* first = nullptr;
    try {
      first = opt->get_validator(0);
    } catch (const CLI::OptionNotFound&) {
      first = nullptr;
    }
    if (!first) {
      opt->check(CLI::Validator([integer](std::string& s) { return strict(integer, s); }, ""));
      continue;
    }
    // Before the option's own rule: CLI11's Range reads "0x10" as 16 and lets "nan" through.
    const CLI::Validator own = *first;
    first->operation([integer, own](std::string& s) {
      std::string problem = strict(integer, s);
      return problem.empty() ? own(s) : problem;
    });
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) add_checks(*sub);
}

}  // namespace

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& text) {
        // The text is a decimal number: strict_numbers checked it first.
        const double v = std::strtod(text.c_str(), nullptr);
        return v > 0 ? std::string() : "must be > 0; got " + text;
      },
      "POSITIVE");
}

CLI::Validator non_negative_number() {
  return CLI::Validator(
      [](std::string& text) {
        const double v = std::strtod(text.c_str(), nullptr);
        return v >= 0 ? std::string() : "must be >= 0; got " + text;
      },
      "NONNEGATIVE");
}

void strict_numbers(CLI::App& app) { add_checks(app); }

void check_flag(const std::string& flag, double value, double lo, double hi,
                const std::string& unit, const std::string& why, bool lo_open, bool hi_open) {
  if (std::isfinite(value) && (lo_open ? value > lo : value >= lo) &&
      (hi_open ? value < hi : value <= hi))
    return;
  throw Error(flag + " must be in " + (lo_open ? "(" : "[") + fmt(lo, 6) + ", " + fmt(hi, 6) +
              (hi_open ? ")" : "]") + (unit.empty() ? "" : " [" + unit + "]") +
              (why.empty() ? "" : " (" + why + ")") + "; got " + fmt(value, 6));
}

}  // namespace oscidrum::cli
