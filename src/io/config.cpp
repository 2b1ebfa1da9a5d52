// Case and study files in TOML (toml++). Locations come from toml++'s source regions.
#include "oscidrum_io/config.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/soil.hpp"

namespace oscidrum::io {
namespace {

constexpr std::size_t kMaxConfigBytes = 16u << 20;

std::string loc(const std::string& name, const toml::source_region& r) {
  return name + ":" + std::to_string(r.begin.line) + ":" + std::to_string(r.begin.column);
}

const char* node_kind(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "a value";
  }
}

// Numbers are decimal everywhere (oscidrum::parse_number for text): TOML's hexadecimal, octal
// and binary integers (0x10, 0o20, 0b10000) are refused, as in flags.
void require_decimal(const toml::node& n) {
  const toml::value<std::int64_t>* i = n.as_integer();
  if (!i) return;
  const toml::value_flags flags = i->flags();
  const char* base = !!(flags & toml::value_flags::format_as_hexadecimal) ? "hexadecimal"
                     : !!(flags & toml::value_flags::format_as_octal)     ? "octal"
                     : !!(flags & toml::value_flags::format_as_binary)    ? "binary"
                                                                          : nullptr;
  if (!base) return;
  const std::string file = n.source().path ? *n.source().path : std::string("<input>");
  throw Error(loc(file, n.source()) + ": numbers must be decimal; got a " + base + " integer (" +
              std::to_string(i->get()) + ")");
}

// A scalar node as a Value; false if it is an array, table or date.
bool to_value(const toml::node& n, Value* out) {
  require_decimal(n);
  if (auto b = n.value_exact<bool>()) return *out = *b, true;
  if (auto i = n.value_exact<std::int64_t>()) return *out = *i, true;
  if (auto d = n.value_exact<double>()) return *out = *d, true;
  if (auto s = n.value_exact<std::string>()) return *out = *s, true;
  return false;
}

// The same, or an error naming the key and the kind received.
Value scalar(const toml::node& n, const std::string& key, const std::string& where) {
  Value v;
  if (to_value(n, &v)) return v;
  if (!find_field(key) && !find_extra_key(key))
    throw Error(where + ": unknown parameter '" + clip(key) + "'" + suggest_key(key));
  throw Error(where + ": " + key + " must be a single value [" + key_unit(key) + "]; got " +
              node_kind(n));
}

// toml++ recurses once per part of a dotted key or table header: [a.a.a. ... .a] 50 000 parts
// deep overflows the stack. Count the parts before parsing (outside strings and comments; in
// keys and headers only, not in values such as 1.5). Nested arrays and inline tables are limited
// by toml++ itself.
constexpr int kMaxKeyParts = 32;

void check_key_depth(std::string_view text, const std::string& name) {
  enum class In { normal, basic, literal, ml_basic, ml_literal, comment };
  In in = In::normal;
  std::vector<char> open;  // [ and { of values and inline tables
  bool key = true;         // in a key or header: at a line start, after { or a , of a {
  int parts = 1, line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    const std::string_view rest = text.substr(i);
    switch (in) {
      case In::comment:
        if (ch == '\n') --i, in = In::normal;
        continue;
      case In::basic:
        if (ch == '\\')
          ++i;
        else if (ch == '"' || ch == '\n')
          in = In::normal;
        continue;
      case In::literal:
        if (ch == '\'' || ch == '\n') in = In::normal;
        continue;
      case In::ml_basic:
        if (ch == '\n') ++line;
        if (ch == '\\')
          ++i;
        else if (rest.starts_with("\"\"\""))
          i += 2, in = In::normal;
        continue;
      case In::ml_literal:
        if (ch == '\n') ++line;
        if (rest.starts_with("\'\'\'")) i += 2, in = In::normal;
        continue;
      case In::normal:
        break;
    }
    if (ch == '\n') {
      ++line;
      if (open.empty()) key = true, parts = 1;
    } else if (ch == '#') {
      in = In::comment;
    } else if (rest.starts_with("\"\"\"")) {
      i += 2, in = In::ml_basic;
    } else if (rest.starts_with("\'\'\'")) {
      i += 2, in = In::ml_literal;
    } else if (ch == '"') {
      in = In::basic;
    } else if (ch == '\'') {
      in = In::literal;
    } else if (key && ch == '.') {
      if (++parts > kMaxKeyParts)
        throw Error(name + ":" + std::to_string(line) + ": a key or table header with more than " +
                    std::to_string(kMaxKeyParts) +
                    " dotted parts; oscidrum keys have at most two (e.g. [soil] or soil.G)");
    } else if (ch == '=') {
      key = false, parts = 1;
    } else if (ch == '[' && key && open.empty()) {
      parts = 1;  // a table header: [a.b] or [[a.b]]
    } else if (ch == '[' || ch == '{') {
      open.push_back(ch);
      key = ch == '{';
      parts = 1;
    } else if (ch == ']' || ch == '}') {
      if (!open.empty()) open.pop_back();
      key = false;
    } else if (ch == ',' && !open.empty() && open.back() == '{') {
      key = true, parts = 1;
    }
  }
}

toml::table parse(std::string_view text, const std::string& name) {
  if (text.find('\0') != std::string_view::npos)
    throw Error(name + ": not a TOML text file (it contains NUL bytes)");
  check_key_depth(text, name);
  try {
    return toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    const std::string description(e.description());
    // A key given twice: the parser's message repeats a quoted key garbled ('"roroller.f" '), so
    // the key is taken from the line itself (the text before its '=').
    if (description.find("cannot redefine existing") != std::string::npos) {
      std::size_t line = 1, begin = 0;
      for (std::size_t i = 0; i < text.size() && line < e.source().begin.line; ++i)
        if (text[i] == '\n') ++line, begin = i + 1;
      std::string_view row = text.substr(begin, text.find('\n', begin) - begin);
      row = row.substr(0, row.find('='));
      while (!row.empty() && (row.back() == ' ' || row.back() == '\t')) row.remove_suffix(1);
      while (!row.empty() && (row.front() == ' ' || row.front() == '\t')) row.remove_prefix(1);
      if (!row.empty() && row.find('[') == std::string_view::npos)
        throw Error(loc(name, e.source()) + ": invalid TOML: the key " + std::string(row) +
                    " is given twice in its table (each key once)");
    }
    throw Error(loc(name, e.source()) + ": invalid TOML: " + description);
  }
}

void require_not_empty(const toml::table& t, const std::string& name, const char* what) {
  if (t.empty())
    throw Error(name + ": the file holds no settings (it is empty or only comments); " + what);
}

// A quoted key with a dot ('roller.r' = 0.6) is, in TOML, one key named "roller.r", not the key r
// of [roller] (which roller.r = 0.6 without quotes is): refused rather than guessed.
void refuse_quoted_dotted_key(std::string_view key, const std::string& where) {
  if (key.find('.') == std::string_view::npos) return;
  throw Error(where + ": '" + clip(key) + "' is a quoted key: TOML reads it as one key named \"" +
                  clip(key) + "\", not as a dotted key; write it without quotes (" + clip(key) +
                  " = ...) or under its [section]",
              std::string(key));
}

// Keys of a case, at the top level of `t` (sections, dotted keys and top-level fields).
// `skip` names top-level keys the caller handles (study files: "base", "sweep").
void read_case_keys(const toml::table& t, const std::string& name, CaseSpec& spec,
                    std::initializer_list<std::string_view> skip) {
  for (auto&& [k, node] : t) {
    const std::string key(k.str());
    if (std::find(skip.begin(), skip.end(), key) != skip.end()) continue;
    const std::string where = loc(name, k.source());
    if (key == "sweep" || key == "base")
      throw Error(where + ": '" + key +
                  "' belongs in a study file (oscidrum sweep), not in a "
                  "case file");
    if (const toml::table* section = node.as_table()) {
      if (!is_known_section(key))
        throw Error(where + ": unknown section [" + clip(key) + "]" + suggest_section(key));
      for (auto&& [sk, sn] : *section) {
        const std::string full = key + "." + std::string(sk.str());
        const std::string swhere = loc(name, sk.source());
        refuse_quoted_dotted_key(sk.str(), swhere);
        if (sn.is_table() && !find_field(full) && !find_extra_key(full))
          throw Error(swhere + ": unknown parameter '" + clip(full) +
                      "' (a table; parameters are " + "numbers, booleans or strings)" +
                      suggest_key(full));
        try {
          assign(spec, full, scalar(sn, full, swhere), swhere);
        } catch (const Error& e) {
          if (std::string_view(e.what()).starts_with(name + ":")) throw;
          throw e.prefixed(swhere + ": ");
        }
      }
      continue;
    }
    refuse_quoted_dotted_key(key, where);
    try {
      assign(spec, key, scalar(node, key, where), where);
    } catch (const Error& e) {
      if (std::string_view(e.what()).starts_with(name + ":")) throw;
      throw e.prefixed(where + ": ");
    }
  }
}

// ---- sweeps ---------------------------------------------------------------------------------

struct Placed {
  toml::source_position pos;
  SweepFactor factor;
};

bool before(const toml::source_position& a, const toml::source_position& b) {
  return a.line != b.line ? a.line < b.line : a.column < b.column;
}

bool is_range(const toml::table& t) {
  if (t.empty()) return false;
  for (auto&& [k, n] : t) {
    (void)n;
    if (k != "start" && k != "stop" && k != "step" && k != "num") return false;
  }
  return true;
}

// x rounded to `decimals` decimal places, as the nearest double to that decimal.
double round_decimals(double x, int decimals) {
  char buf[400];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return std::strtod(buf, nullptr);
}

// The fewest decimals at which start, stop and step are all what they are (to 1e-12 of the
// largest of them), or -1 if none up to 10 significant digits of the largest does.
int range_decimals(double start, double stop, double step) {
  const double scale = std::max({std::abs(start), std::abs(stop), std::abs(step)});
  if (!(scale > 0.0) || !(scale < 1e15)) return -1;
  const double tol = 1e-12 * scale;
  const int most = 9 + std::max(0, -static_cast<int>(std::floor(std::log10(scale))));
  for (int d = 0; d <= std::min(most, 300); ++d) {
    bool exact = true;
    for (double x : {start, stop, step}) exact = exact && std::abs(round_decimals(x, d) - x) <= tol;
    if (exact) return d;
  }
  return -1;
}

std::vector<Value> range_values(const toml::table& t, const std::string& key,
                                const std::string& where) {
  auto number = [&](const char* part, bool* is_int) -> std::optional<double> {
    const toml::node* n = t.get(part);
    if (!n) return std::nullopt;
    require_decimal(*n);
    if (auto i = n->value_exact<std::int64_t>()) return *is_int = *is_int && true, double(*i);
    if (auto d = n->value_exact<double>()) return *is_int = false, *d;
    throw Error(where + ": " + key + " range: " + part + " must be a number; got " + node_kind(*n));
  };
  bool all_int = true;
  const auto start = number("start", &all_int), stop = number("stop", &all_int);
  const auto step = number("step", &all_int), num = number("num", &all_int);
  if (!start || !stop || (step.has_value() == num.has_value()))
    throw Error(where + ": " + key + " range must be {start, stop, step} or {start, stop, num}");
  if (!std::isfinite(*start) || !std::isfinite(*stop))
    throw Error(where + ": " + key + " range: start and stop must be finite");
  // -1e308 ... 1e308: each end finite, their span not (the values came out NaN, blamed on the key).
  if (!std::isfinite(*stop - *start))
    throw Error(where + ": " + key + " range: stop - start overflows (start " +
                format_value(*start) + ", stop " + format_value(*stop) +
                "): give a range whose span is a finite number");
  // num counts values: an integer as TOML writes one (3.0 is a float, as for an integer key).
  if (const toml::node* n = t.get("num"); n && n->value_exact<double>())
    throw Error(where + ": " + key + " range: num must be an integer; got " + format_value(*num) +
                " written as a float (3.0 and 1e3 are floats): write " +
                (*num == std::floor(*num) && std::abs(*num) < 1e15
                     ? format_value(static_cast<double>(static_cast<std::int64_t>(*num))) + ","
                     : std::string("a whole number")) +
                " without a decimal point or exponent");
  // A range of one value sweeps nothing (docs/config.md: a fixed value belongs in the base case).
  if (*start == *stop)
    throw Error(where + ": " + key + " range: start and stop are both " + format_value(*start) +
                "; a fixed value belongs in the base case");
  // Values as the user would write them: a range of written decimals gives values of those
  // decimals (0.2 ... 0.8 in 13 steps: 0.25, not 0.30000000000000004). The precision is the
  // fewest decimals that hold start, stop and the step; a step with no short decimal form
  // (0 ... 1 in 3 steps) leaves the values as computed.
  const double step_size = step ? *step : (num && *num > 1 ? (*stop - *start) / (*num - 1.0) : 0.0);
  const int decimals = range_decimals(*start, *stop, step_size);
  std::vector<Value> out;
  auto push = [&](double v) {
    if (decimals >= 0) v = round_decimals(v, decimals);
    if (out.size() >= kMaxStudyCases)
      throw Error(where + ": " + key + " range has more than " + std::to_string(kMaxStudyCases) +
                  " values");
    if (all_int)
      out.emplace_back(static_cast<std::int64_t>(std::llround(v)));
    else
      out.emplace_back(v);
  };
  if (step) {
    const double s = *step, span = *stop - *start;
    if (!std::isfinite(s) || s == 0.0 || (span != 0.0 && (span > 0) != (s > 0)))
      throw Error(where + ": " + key +
                  " range: step must be non-zero and go from start towards "
                  "stop; got step = " +
                  format_value(s));
    const double count = std::floor(span / s + 1e-9);
    if (count >= static_cast<double>(kMaxStudyCases))
      throw Error(where + ": " + key + " range has more than " + std::to_string(kMaxStudyCases) +
                  " values");
    for (long i = 0; i <= static_cast<long>(count); ++i) {
      const double v = *start + static_cast<double>(i) * s;
      push(std::abs(v - *stop) <= 1e-9 * std::abs(s) ? *stop : v);  // the end point exactly
    }
  } else {
    const double n = *num;
    if (!(n >= 2) || n != std::floor(n) || n > static_cast<double>(kMaxStudyCases))
      throw Error(where + ": " + key + " range: num must be an integer in [2, " +
                  std::to_string(kMaxStudyCases) + "]; got " + format_value(n) +
                  (n == 1 ? " (a fixed value belongs in the base case)" : ""));
    all_int = false;
    const long count = static_cast<long>(n);
    for (long i = 0; i < count; ++i)
      push(i + 1 == count ? *stop
                          : *start + (*stop - *start) * static_cast<double>(i) /
                                         static_cast<double>(count - 1));
  }
  if (out.size() < 2)
    throw Error(where + ": " + key + " range gives one value (" + format_value(out.front()) +
                "): the step is longer than stop - start; a fixed value belongs in the base case");
  return out;
}

// One swept key: a list, a range table, or "all" for soil.table2_G. Nested tables are dotted
// keys ([sweep.soil] G = [...] is "soil.G").
void collect_axes(const toml::node& node, const std::string& key, const toml::source_region& at,
                  const std::string& name, std::vector<Placed>& out, bool grouped) {
  const std::string where = loc(name, at);
  if (const toml::table* t = node.as_table(); t && t->empty())
    throw Error(where + ": sweep entry " + clip(key) +
                " is an empty table; give a list [a, b, ...] or a range {start, stop, step} or "
                "{start, stop, num}");
  if (const toml::table* t = node.as_table(); t && !is_range(*t)) {
    // A parameter's table that is no range (a key beside start, stop, step, num: scale = "log")
    // was taken for nested keys: "unknown parameter 'soil.G.num'".
    if (find_field(key) || find_extra_key(key)) {
      std::string others;
      for (auto&& [k, n] : *t) {
        (void)n;
        if (k != "start" && k != "stop" && k != "step" && k != "num")
          others += (others.empty() ? "'" : ", '") + std::string(k.str()) + "'";
      }
      throw Error(where + ": " + key + " range: its keys are start, stop and step or num; got " +
                  others +
                  " (a range is evenly spaced; for other values, such as logarithmic ones, give "
                  "the list [a, b, ...])");
    }
    for (auto&& [k, n] : *t)
      collect_axes(n, key + "." + std::string(k.str()), k.source(), name, out, grouped);
    return;
  }
  if (!find_field(key) && !find_extra_key(key))
    throw Error(where + ": unknown parameter '" + clip(key) + "'" + suggest_key(key));
  SweepAxis axis{key, {}, where};
  if (const toml::table* t = node.as_table()) {
    // An integer key's range of floats ({start = 64.0, ...}) is refused as its list of floats is.
    if (const Field* f = find_field(key); f && f->type == FieldType::integer)
      for (const char* part : {"start", "stop", "step"})
        if (const toml::node* n = t->get(part); n && n->value_exact<double>())
          throw Error(loc(name, n->source()) + ": " + key + " range: " + part +
                      " must be an integer (" + key + " is an integer key); got " +
                      format_value(*n->value_exact<double>()) +
                      " written as a float (5.0, 1e3 are floats): write it without a decimal "
                      "point or exponent");
    axis.values = range_values(*t, key, where);
    // A range over an integer key gives integers when its values are whole (num = ... makes
    // numbers): {start = 1000, stop = 5000, num = 3} is 1000, 3000, 5000.
    if (const Field* f = find_field(key); f && f->type == FieldType::integer)
      for (Value& v : axis.values)
        if (const double* d = std::get_if<double>(&v);
            d && *d == std::floor(*d) && std::abs(*d) < 9e18)
          v = static_cast<std::int64_t>(*d);
  } else if (const toml::array* a = node.as_array()) {
    for (const toml::node& e : *a) {
      Value v;
      if (!to_value(e, &v))
        throw Error(loc(name, e.source()) + ": sweep values of " + key +
                    " must be numbers, booleans or strings; got " + node_kind(e));
      axis.values.push_back(std::move(v));
    }
    if (axis.values.size() < 2)
      throw Error(where + ": sweep list " + key +
                  (axis.values.empty() ? std::string(" is empty") : std::string(" has one value")) +
                  "; give at least two (a fixed value belongs in the base case)");
  } else if (auto s = node.value_exact<std::string>();
             s && key == "soil.table2_G" && (*s == "all" || *s == "table2")) {
    for (const Table2Row& row : table2()) axis.values.emplace_back(row.G);
  } else {
    throw Error(where + ": sweep entry " + key +
                " must be a list [a, b, ...], a range "
                "{start, stop, step} or {start, stop, num}" +
                (key == "soil.table2_G" ? std::string(", or \"all\"") : std::string()) + "; got " +
                (node.is_string() ? "the string \"" + clip(*node.value_exact<std::string>()) + "\""
                                  : std::string("one value")) +
                " (a fixed value belongs in the base case)");
  }
  // Check each value's type and rule now, where the line is known.
  for (const Value& v : axis.values) {
    CaseSpec probe;
    try {
      assign(probe, key, v, where);
    } catch (const Error& e) {
      throw e.prefixed(where + ": sweep value of ");
    }
  }
  if (grouped) {
    out.back().factor.axes.push_back(std::move(axis));
  } else {
    out.push_back(Placed{at.begin, SweepFactor{{std::move(axis)}}});
  }
}

void read_sweep(const toml::node& node, const std::string& name, const std::string& where,
                StudySpec& study) {
  const toml::table* sweep = node.as_table();
  if (!sweep) throw Error(where + ": sweep must be a table ([sweep]); got " + node_kind(node));
  std::vector<Placed> placed;
  std::string saw_group;  // where a [[sweep.group]] is (for the check against zip mode)
  for (auto&& [k, n] : *sweep) {
    const std::string key(k.str());
    const std::string at = loc(name, k.source());
    if (key == "mode") {
      auto mode = n.value_exact<std::string>();
      if (mode && *mode == "product")
        study.mode = SweepMode::product;
      else if (mode && *mode == "zip")
        study.mode = SweepMode::zip;
      else
        throw Error(at + ": sweep.mode must be \"product\" or \"zip\"");
    } else if (key == "group") {
      const toml::array* groups = n.as_array();
      if (!groups || !groups->is_array_of_tables())
        throw Error(at + ": sweep.group must be an array of tables ([[sweep.group]])");
      saw_group = at;
      for (const toml::node& g : *groups) {
        placed.push_back(Placed{g.source().begin, {}});
        std::vector<Placed> axes;
        for (auto&& [gk, gn] : *g.as_table()) {
          axes.push_back(Placed{gk.source().begin, {}});
          collect_axes(gn, std::string(gk.str()), gk.source(), name, axes, true);
        }
        std::stable_sort(axes.begin(), axes.end(),
                         [](const Placed& a, const Placed& b) { return before(a.pos, b.pos); });
        for (Placed& a : axes)
          for (SweepAxis& axis : a.factor.axes) placed.back().factor.axes.push_back(axis);
        if (placed.back().factor.axes.empty())
          throw Error(loc(name, g.source()) + ": an empty [[sweep.group]]");
      }
    } else {
      collect_axes(n, key, k.source(), name, placed, false);
    }
  }
  if (study.mode == SweepMode::zip && !saw_group.empty())
    throw Error(saw_group +
                ": [[sweep.group]] zips keys inside a product; with mode = \"zip\" every key is "
                "zipped already: put the group's keys in [sweep] itself");
  std::stable_sort(placed.begin(), placed.end(),
                   [](const Placed& a, const Placed& b) { return before(a.pos, b.pos); });
  for (Placed& p : placed) study.factors.push_back(std::move(p.factor));
}

std::string toml_number(double v) {
  for (int precision = 15; precision <= 17; ++precision) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v || precision == 17) {
      std::string s = buf;
      if (s.find_first_of(".en") == std::string::npos) s += ".0";
      return s;
    }
  }
  return {};
}

}  // namespace

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error("cannot read " + path + ": it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read " + path + ": " + std::strerror(errno));
  std::string text;
  char buf[65536];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxConfigBytes)
      throw Error("cannot read " + path + ": larger than 16 MiB; is it a config file?");
  }
  if (in.bad()) throw Error("cannot read " + path + ": read error");
  return text;
}

void read_case_text(std::string_view text, const std::string& name, CaseSpec& spec) {
  const toml::table t = parse(text, name);
  require_not_empty(t, name,
                    "a case file sets parameters, e.g. [roller] r = 0.6 (see docs/config.md); to "
                    "run the paper's defaults, give no file");
  read_case_keys(t, name, spec, {});
}

void read_case_file(const std::string& path, CaseSpec& spec) {
  read_case_text(read_file(path), path, spec);
}

StudySpec read_study_text(std::string_view text, const std::string& name, const std::string& dir) {
  const toml::table t = parse(text, name);
  require_not_empty(t, name, "a study file needs a [sweep] table (see docs/config.md)");
  StudySpec study;
  study.source = name;
  if (const toml::node* base = t.get("base")) {
    const std::string where = loc(name, base->source());
    auto path = base->value_exact<std::string>();
    if (!path) throw Error(where + ": base must be the path of a case file (a string)");
    std::filesystem::path p(*path);
    if (p.is_relative() && !dir.empty()) p = std::filesystem::path(dir) / p;
    try {
      read_case_file(p.string(), study.base);
    } catch (const Error& e) {
      throw Error(where + ": in base case: " + e.what());
    }
  }
  read_case_keys(t, name, study.base, {"base", "sweep"});
  const toml::node* sweep = t.get("sweep");
  if (!sweep)
    throw Error(name +
                ": a study file needs a [sweep] table naming the parameters to vary, "
                "e.g. [sweep] \"soil.table2_G\" = \"all\" (see docs/config.md)");
  read_sweep(*sweep, name, loc(name, sweep->source()), study);
  return study;
}

StudySpec read_study_file(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return read_study_text(read_file(path), path, dir);
}

std::string case_to_toml(const Case& c) {
  std::ostringstream out;
  out << "# oscidrum case file: every parameter (SI units; see docs/config.md)\n";
  std::string section;
  auto value_text = [&](const Field& f) {
    switch (f.type) {
      case FieldType::boolean:
        return std::string(f.get(c) != 0.0 ? "true" : "false");
      case FieldType::choice: {
        std::string quoted(1, '"');  // (not "\"" + s: GCC 12 -Wrestrict false positive)
        quoted += format_field(c, f);
        quoted += '"';
        return quoted;
      }
      case FieldType::integer:
        return std::to_string(static_cast<long long>(f.get(c)));
      case FieldType::real:
        break;
    }
    return toml_number(f.get(c));
  };
  // Keys that would have no effect (key_in_effect) are written as comments (reading them would be
  // an error).
  const std::string input = format_field(c, *find_field("soil.input"));
  auto unused = [&](const std::string& key) -> std::string {
    // The roller is given by M0 or by its unbalance, not both (5).
    if (key == "roller.M0" && c.roller.type == RollerType::oscillation && !key_in_effect(c, key))
      return "replaced by unbalance";
    if (key == "roller.unbalance" && c.roller.unbalance == 0.0) return "unused: M0 is given";
    if (key.starts_with("soil.") && !key_in_effect(c, key)) return "unused with input = " + input;
    // In effect (a file may give them with pure rolling, with a warning), but at their defaults
    // they were not given: as comments, so that the printed case read back does not warn of
    // keys nobody set.
    if (c.contact.pure_rolling && friction_key(key) &&
        find_field(key)->get(c) == find_field(key)->get(Case{}))
      return "unused while pure_rolling = true";
    if (!key_in_effect(c, key)) return "unused";
    return "";
  };
  auto line = [&](const Field& f, const std::string& name) {
    const std::string why = unused(f.key);
    out << (why.empty() ? "" : "# ") << name << " = " << value_text(f) << "  # [" << f.unit << "] "
        << (why.empty() ? std::string() : "(" + why + ") ") << f.description << "\n";
  };
  // Top-level keys first (TOML puts everything after a [section] header into it).
  for (const Field& f : fields()) {
    const std::string key = f.key;
    if (key.find('.') == std::string::npos) line(f, key);
  }
  for (const Field& f : fields()) {
    const std::string key = f.key;
    const std::size_t dot = key.find('.');
    if (dot == std::string::npos) continue;
    if (key.substr(0, dot) != section) {
      section = key.substr(0, dot);
      out << "\n[" << section << "]\n";
    }
    line(f, key.substr(dot + 1));
  }
  return out.str();
}

}  // namespace oscidrum::io
