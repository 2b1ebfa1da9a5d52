// The parameter table (see oscidrum/fields.hpp). Defaults are not repeated here: they are the
// default member initialisers of the structs in parameters.hpp.
#include "oscidrum/fields.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/text.hpp"
#include "util/format.hpp"
#include "util/text.hpp"

namespace oscidrum {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// The trough keys read the shape (key_value) and set it through trough_shape(k, a): k = 0 is the
// circle of radius a, k > 0 the log spiral (oscidrum/trough.hpp).
double trough_k(const Case& c) { return key_value(c.trough.shape, "trough.k"); }
double trough_a(const Case& c) { return key_value(c.trough.shape, "trough.a"); }

// Accessor pairs. Captureless lambdas convert to the plain function pointers of Field.
#define OSCIDRUM_REAL(path) \
  [](const Case& c) { return static_cast<double>(c.path); }, [](Case& c, double v) { c.path = v; }
#define OSCIDRUM_INT(path)                                   \
  [](const Case& c) { return static_cast<double>(c.path); }, \
      [](Case& c, double v) { c.path = static_cast<int>(v); }
#define OSCIDRUM_BOOL(path) \
  [](const Case& c) { return c.path ? 1.0 : 0.0; }, [](Case& c, double v) { c.path = (v != 0.0); }

const std::array kFields = {
    // roller (paper Table 1)
    Field{"roller.r", FieldType::real, "m", "drum radius", 0, inf, true, false, nullptr,
          OSCIDRUM_REAL(roller.r)},
    Field{"roller.b", FieldType::real, "m", "drum width (b0 = b/2 in Appendix B)", 0, inf, true,
          false, nullptr, OSCIDRUM_REAL(roller.b)},
    Field{"roller.m", FieldType::real, "kg", "drum mass", 0, inf, true, false, nullptr,
          OSCIDRUM_REAL(roller.m)},
    Field{"roller.I", FieldType::real, "kg m^2", "drum mass moment of inertia about its centre M",
          0, inf, true, false, nullptr, OSCIDRUM_REAL(roller.I)},
    Field{"roller.P0", FieldType::real, "N", "static axle load; Fz = P0 - m g must be >= 0 (7)", 0,
          inf, true, false, nullptr, OSCIDRUM_REAL(roller.P0)},
    // f is bounded: at 5e-324 Hz the integrator cannot find a step, at 1e308 Hz nu = 2 pi f
    // overflows; rollers run at about 20-70 Hz.
    Field{"roller.f", FieldType::real, "Hz",
          "excitation frequency (nu = 2 pi f); oscillation rollers run at about 20-70 Hz", 0.1,
          1000, false, false, nullptr, OSCIDRUM_REAL(roller.f)},
    Field{"roller.M0", FieldType::real, "N m",
          "amplitude of the oscillation moment (5), M0 = 4 m_u e_u e_w nu^2: it grows with f^2, so "
          "set it with roller.f, or give roller.unbalance instead",
          0, inf, false, false, nullptr, OSCIDRUM_REAL(roller.M0)},
    Field{"roller.unbalance", FieldType::real, "kg m^2",
          "the unbalances' moment m_u e_u e_w; > 0: M0 = 4 m_u e_u e_w nu^2 (5) follows roller.f "
          "and replaces roller.M0 (the paper's roller: 0.22877); 0: roller.M0 as given",
          0, inf, false, false, nullptr, OSCIDRUM_REAL(roller.unbalance)},
    Field{"roller.kd", FieldType::real, "N/m", "drum/frame suspension stiffness", 0, inf, false,
          false, nullptr, OSCIDRUM_REAL(roller.kd)},
    Field{"roller.cd", FieldType::real, "N s/m", "drum/frame suspension damping", 0, inf, false,
          false, nullptr, OSCIDRUM_REAL(roller.cd)},
    Field{"roller.g", FieldType::real, "m/s^2", "gravitational acceleration", 0, inf, false, false,
          nullptr, OSCIDRUM_REAL(roller.g)},
    Field{"roller.m_f", FieldType::real, "kg",
          "effective frame mass on the drum's axle (Appendix A transmissibility only)", 0, inf,
          true, false, nullptr, OSCIDRUM_REAL(roller.m_f)},
    Field{"roller.type", FieldType::choice, "-",
          "which dynamic roller: oscillation (the paper's drum, the moment M0 sin(nu t) (5); the "
          "default) or vibratory (a rotating unbalance force roller.static_moment nu^2 on the "
          "drum centre, docs/model.md section 14)",
          0, 1, false, false, "oscillation|vibratory",
          [](const Case& c) { return static_cast<double>(c.roller.type); },
          [](Case& c, double v) { c.roller.type = static_cast<RollerType>(static_cast<int>(v)); }},
    Field{"roller.static_moment", FieldType::real, "kg m",
          "static moment m_u e_u of the vibratory drum's unbalance (roller.type = vibratory, > 0 "
          "there): force amplitude F0 = m_u e_u nu^2",
          0, inf, false, false, nullptr, OSCIDRUM_REAL(roller.static_moment)},
    Field{"roller.exciter", FieldType::choice, "-",
          "direction of the vibratory drum's force (roller.type = vibratory), z downwards: "
          "circular F0 (cos nu t, sin nu t) (the unbalance turns from +x towards +z), "
          "circular_reversed F0 (-cos nu t, sin nu t) (turning the other way), vertical F0 (0, "
          "sin nu t) (a directed exciter)",
          0, 2, false, false, "circular|circular_reversed|vertical",
          [](const Case& c) { return static_cast<double>(c.roller.exciter); },
          [](Case& c, double v) { c.roller.exciter = static_cast<Exciter>(static_cast<int>(v)); }},
    // soil
    Field{"soil.input", FieldType::choice, "-",
          "how the soil is given: table2 (the row of paper Table 2 at G, the paper's soils; the "
          "default), modulus (G, nu, rho via Appendix B (42)-(45)) or coefficients (ksh, ksv, "
          "csh, csv)",
          0, 2, false, false, "coefficients|modulus|table2",
          [](const Case& c) { return static_cast<double>(c.soil.input); },
          [](Case& c, double v) { c.soil.input = static_cast<SoilInput>(static_cast<int>(v)); }},
    // G is bounded so that a value in the wrong unit is refused with a hint: 30 [Pa] is meant as
    // 30 MN/m^2 (soils: about 1 to 500 MN/m^2; 1e11 Pa is stiffer than steel).
    Field{"soil.G", FieldType::real, "Pa",
          "shear modulus (soil.input = table2: one of Table 2's 5e6, 10e6, ..., 70e6; modulus: "
          "any, through Appendix B)",
          1e4, 1e11, false, false, nullptr, OSCIDRUM_REAL(soil.G), "MN/m^2", 1e6},
    Field{"soil.nu", FieldType::real, "-", "Poisson's ratio (soil.input = modulus)", 0, 0.5, false,
          true, nullptr, OSCIDRUM_REAL(soil.nu)},
    Field{"soil.rho", FieldType::real, "kg/m^3", "density (soil.input = modulus)", 0, inf, true,
          false, nullptr, OSCIDRUM_REAL(soil.rho)},
    Field{"soil.ksh", FieldType::real, "N/m", "horizontal soil spring (soil.input = coefficients)",
          0, inf, true, false, nullptr, OSCIDRUM_REAL(soil.ksh), "MN/m", 1e6},
    Field{"soil.ksv", FieldType::real, "N/m", "vertical soil spring (soil.input = coefficients)", 0,
          inf, true, false, nullptr, OSCIDRUM_REAL(soil.ksv), "MN/m", 1e6},
    Field{"soil.csh", FieldType::real, "N s/m",
          "horizontal soil dashpot (soil.input = coefficients)", 0, inf, true, false, nullptr,
          OSCIDRUM_REAL(soil.csh), "kN s/m", 1e3},
    Field{"soil.csv", FieldType::real, "N s/m", "vertical soil dashpot (soil.input = coefficients)",
          0, inf, true, false, nullptr, OSCIDRUM_REAL(soil.csv), "kN s/m", 1e3},
    // trough
    Field{"trough.k", FieldType::real, "-",
          "log-spiral parameter k (0: circle of radius a); at most 1: a settlement trough, not a "
          "tight spiral",
          0, 1, false, false, nullptr, [](const Case& c) { return trough_k(c); },
          [](Case& c, double v) { c.trough.shape = trough_shape(v, trough_a(c)); }},
    Field{"trough.a", FieldType::real, "m",
          "log-spiral parameter a; the trough radius R when k = 0 (must exceed roller.r)", 0, inf,
          true, false, nullptr, [](const Case& c) { return trough_a(c); },
          [](Case& c, double v) { c.trough.shape = trough_shape(trough_k(c), v); }},
    // contact
    Field{"contact.mu", FieldType::real, "-",
          "Coulomb friction coefficient drum/soil (the kinetic one when contact.mu_static is set)",
          0, inf, false, false, nullptr, OSCIDRUM_REAL(contact.mu)},
    Field{"contact.mu_static", FieldType::real, "-",
          "static friction coefficient of the friction cone (stick while |T| <= mu_static N); -1: "
          "equal to contact.mu; else >= contact.mu",
          -1, inf, false, false, nullptr, OSCIDRUM_REAL(contact.mu_static)},
    Field{"contact.pure_rolling", FieldType::boolean, "-",
          "ignore the friction limit (mu -> infinity): stick throughout", 0, 1, false, false,
          nullptr, OSCIDRUM_BOOL(contact.pure_rolling)},
    Field{"contact.law", FieldType::choice, "-",
          "friction law: coulomb (the paper: stick while |T| <= mu N, slip with T = -s mu N) or "
          "regularised (T = -mu tanh(v_rel / v_eps) N, one smooth phase without stick)",
          0, 1, false, false, "coulomb|regularised",
          [](const Case& c) { return static_cast<double>(c.contact.law); },
          [](Case& c, double v) {
            c.contact.law = static_cast<FrictionChoice>(static_cast<int>(v));
          }},
    // v_eps is bounded below: far below 1e-6 m/s the smooth law is as stiff as a switch and the
    // explicit integrator cannot follow it within any step budget.
    Field{"contact.v_eps", FieldType::real, "m/s",
          "regularisation velocity of contact.law = regularised: tanh(v_rel / v_eps) (-> Coulomb "
          "as v_eps -> 0; slip slower than v_eps is creep, shown as stick)",
          1e-6, 10, false, false, nullptr, OSCIDRUM_REAL(contact.v_eps)},
    Field{"contact.unilateral", FieldType::boolean, "-",
          "unilateral contact: the drum may lift off the trough (N reaching 0) and land again, "
          "with a flight phase between (docs/model.md section 13); false: the paper's permanent "
          "contact, where N reaching 0 ends the run as contact_lost",
          0, 1, false, false, nullptr, OSCIDRUM_BOOL(contact.unilateral)},
    // driving torque
    Field{"MMd", FieldType::real, "N m",
          "constant driving torque (6); the paper uses 0 and 0.05 M0", -inf, inf, false, false,
          nullptr, OSCIDRUM_REAL(MMd)},
    // numerics
    Field{"numerics.method", FieldType::choice, "-",
          "how the periodic steady state is found: shooting (Newton on the period map after a "
          "short transient; on P^p when the period-1 orbit is unstable; falls back to transient "
          "when it fails) or "
          "transient (integrate from rest until it repeats, the paper's method); both agree to "
          "1e-7 on the paper's cases",
          0, 1, false, false, "shooting|transient",
          [](const Case& c) { return static_cast<double>(c.numerics.method); },
          [](Case& c, double v) {
            c.numerics.method = static_cast<SteadyMethod>(static_cast<int>(v));
          }},
    Field{"numerics.rtol", FieldType::real, "-", "relative tolerance of the Dormand-Prince steps",
          0, 1e-2, true, false, nullptr, OSCIDRUM_REAL(numerics.rtol)},
    Field{"numerics.atol", FieldType::real, "-", "absolute tolerance (SI units of each state)", 0,
          1e-2, true, false, nullptr, OSCIDRUM_REAL(numerics.atol)},
    Field{"numerics.max_periods", FieldType::integer, "-",
          "give up the steady-state search after this many excitation periods (with shooting: its "
          "short "
          "transient and period maps, P^p counting p, and the fallback's periods share them)",
          1, 1e7, false, false, nullptr, OSCIDRUM_INT(numerics.max_periods)},
    Field{"numerics.steady_tol", FieldType::real, "-",
          "period-to-period change of the state (scaled by its range) that counts as steady", 0, 1,
          true, false, nullptr, OSCIDRUM_REAL(numerics.steady_tol)},
    Field{"numerics.max_multiplicity", FieldType::integer, "-",
          "longest steady period searched, in excitation periods (shooting: orbits of P^p up to it "
          "when the period-1 orbit is unstable)",
          1, 64, false, false, nullptr, OSCIDRUM_INT(numerics.max_multiplicity)},
    Field{"numerics.output_periods", FieldType::integer, "-",
          "steady periods sampled (times the multiplicity)", 1, 1000, false, false, nullptr,
          OSCIDRUM_INT(numerics.output_periods)},
    Field{"numerics.samples_per_period", FieldType::integer, "-",
          "uniform samples per excitation period in the output (times numerics.output_periods "
          "and numerics.max_multiplicity at most 1e7: the samples a run may keep)",
          16, 1e6, false, false, nullptr, OSCIDRUM_INT(numerics.samples_per_period)},
    Field{"numerics.max_switches_per_period", FieldType::integer, "-",
          "more stick/slip switches than this in one period stop the run as chattering", 2, 1e7,
          false, false, nullptr, OSCIDRUM_INT(numerics.max_switches_per_period)},
    Field{"numerics.max_steps_per_period", FieldType::integer, "-",
          "more integration steps than this in one period stop the run (status budget_exceeded): "
          "a bound on the work of every run",
          100, 1e9, false, false, nullptr, OSCIDRUM_INT(numerics.max_steps_per_period)},
    Field{"numerics.slip_constraint_rate", FieldType::real, "1/s",
          "Baumgarte rate that pulls the slip coupling (39) back to zero; 0 means 2 nu", 0, inf,
          false, false, nullptr, OSCIDRUM_REAL(numerics.slip_constraint_rate)},
    Field{"numerics.suspension_from_static", FieldType::boolean, "-",
          "measure the suspension from static equilibrium instead of t = 0 (not the paper)", 0, 1,
          false, false, nullptr, OSCIDRUM_BOOL(numerics.suspension_from_static)},
    Field{"numerics.continuation", FieldType::boolean, "-",
          "in a study (sweep, run_study) with method shooting: start each case from the steady "
          "state of its neighbour along the swept values, falling back to the start from rest "
          "when that fails (docs/periodic.md); false: every case starts from rest",
          0, 1, false, false, nullptr, OSCIDRUM_BOOL(numerics.continuation)},
    Field{"numerics.start_ramp_periods", FieldType::integer, "-",
          "excitation periods over which the torque is ramped in from rest, (1 - cos(pi t / (n "
          "T))) / 2 (0: all at once, the paper's start); a run whose start from rest loses "
          "contact before a steady state is retried with a ramp of 20 periods",
          0, 1000, false, false, nullptr, OSCIDRUM_INT(numerics.start_ramp_periods)},
};

#undef OSCIDRUM_REAL
#undef OSCIDRUM_INT
#undef OSCIDRUM_BOOL

std::string format_number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string choice_name_of(const char* choices, int index) {
  std::string_view all(choices);
  int i = 0;
  std::size_t start = 0;
  while (true) {
    std::size_t bar = all.find('|', start);
    if (i == index) return std::string(all.substr(start, bar - start));
    if (bar == std::string_view::npos) return {};
    start = bar + 1;
    ++i;
  }
}

[[noreturn]] void throw_unknown(std::string_view key) {
  std::string msg = "unknown parameter '" +
                    (key.size() > 80 ? std::string(key.substr(0, 60)) + "... (" +
                                           std::to_string(key.size()) + " bytes)"
                                     : std::string(key)) +
                    "'";
  if (key.size() > 80) throw Error(msg);
  // The same name in its section first ("M0" -> "roller.M0", "mu" -> "contact.mu"), then a near
  // miss (util/text.hpp): by edit distance to the whole keys alone "M0", "mu" and "muu"
  // suggested "MMd".
  std::vector<std::string_view> keys;
  for (const Field& f : kFields) keys.emplace_back(f.key);
  if (const std::string_view best = detail::closest_key(key, keys); !best.empty())
    msg += "; did you mean '" + std::string(best) + "'?";
  throw Error(msg);
}

}  // namespace

std::span<const Field> fields() { return kFields; }

std::string choice_name(const Field& field, int index) {
  return field.choices ? choice_name_of(field.choices, index) : std::string();
}

const char* display_unit(const Field& field) {
  return field.display_unit ? field.display_unit : field.unit;
}

int choice_index(const Field& field, std::string_view name) {
  if (!field.choices) return -1;
  std::string_view all(field.choices);
  int i = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t bar = all.find('|', start);
    if (all.substr(start, bar - start) == name) return i;
    if (bar == std::string_view::npos) return -1;
    start = bar + 1;
    ++i;
  }
}

const Field* find_field(std::string_view key) {
  for (const Field& f : kFields)
    if (key == f.key) return &f;
  return nullptr;
}

double get_field(const Case& c, std::string_view key) {
  const Field* f = find_field(key);
  if (!f) throw_unknown(key);
  return f->get(c);
}

std::string field_rule(const Field& f) {
  switch (f.type) {
    case FieldType::boolean:
      return "true or false";
    case FieldType::choice: {
      std::string s = "one of ";
      std::string_view all(f.choices);
      for (char ch : all) s += (ch == '|') ? std::string(", ") : std::string(1, ch);
      return s;
    }
    default:
      break;
  }
  const bool lo = std::isfinite(f.min), hi = std::isfinite(f.max);
  std::string kind = f.type == FieldType::integer ? "an integer " : "";
  if (lo && !hi) return kind + (f.min_open ? "> " : ">= ") + format_number(f.min);
  if (!lo && hi) return kind + (f.max_open ? "< " : "<= ") + format_number(f.max);
  if (!lo && !hi) return kind.empty() ? "finite" : "an integer";
  return kind + "in " + (f.min_open ? "(" : "[") + format_number(f.min) + ", " +
         format_number(f.max) + (f.max_open ? ")" : "]");
}

namespace {
bool check_field_value(const Field& f, double v) {
  bool good = std::isfinite(v);
  if (good && f.type == FieldType::integer) good = (v == std::floor(v));
  if (good && (f.type == FieldType::boolean)) good = (v == 0.0 || v == 1.0);
  if (good && f.type == FieldType::choice) good = (v == std::floor(v)) && v >= f.min && v <= f.max;
  if (good && (f.type == FieldType::real || f.type == FieldType::integer)) {
    good = f.min_open ? v > f.min : v >= f.min;
    if (good) good = f.max_open ? v < f.max : v <= f.max;
  }
  return good;
}
}  // namespace

std::string check_field(const Field& f, double v) {
  if (check_field_value(f, v)) return {};
  std::string unit = std::string(f.unit) == "-" ? "" : std::string(" [") + f.unit + "]";
  // inf satisfies "> 0" as written: a rule with bounds says that the value must be finite too.
  const std::string rule = field_rule(f);
  const bool say_finite = !std::isfinite(v) && rule != "finite" && f.type == FieldType::real;
  std::string msg = std::string(f.key) + " must be " + (say_finite ? "finite and " : "") + rule +
                    unit + "; got " + detail::shortest(v);
  // A value that is right in the unit people say it in (30 for 30 MN/m^2) was meant in it.
  if (f.display_unit && std::isfinite(v) && check_field_value(f, v * f.display_scale))
    msg += " (values are in " + std::string(f.unit) + ": did you mean " +
           detail::shortest(v * f.display_scale) + ", i.e. " + detail::shortest(v) + " " +
           f.display_unit + "?)";
  return msg;
}

void set_field(Case& c, std::string_view key, double value) {
  const Field* f = find_field(key);
  if (!f) throw_unknown(key);
  std::string problem = check_field(*f, value);
  if (!problem.empty()) throw Error(problem, f->key, value);
  f->set(c, value);
}

double parse_field_text(const Field& f, std::string_view text) {
  const std::string s(text);
  const std::string unit = std::string(f.unit) == "-" ? "" : std::string(" [") + f.unit + "]";
  const std::string shown = printable(s.size() > 40 ? s.substr(0, 40) + "..." : s);
  switch (f.type) {
    case FieldType::boolean:
      if (text == "true") return 1.0;
      if (text == "false") return 0.0;
      throw Error(std::string(f.key) + " must be true or false; got '" + shown + "'", f.key);
    case FieldType::choice: {
      const int i = choice_index(f, text);
      if (i < 0)
        throw Error(std::string(f.key) + " must be " + field_rule(f) + "; got '" + shown + "'",
                    f.key);
      return i;
    }
    case FieldType::integer: {
      // Digits only (an optional sign): 5.0 and 1e3 are numbers, not integers, as in TOML.
      std::size_t i = (!s.empty() && (s[0] == '-' || s[0] == '+')) ? 1 : 0;
      bool digits = i < s.size() && s.size() <= 19;
      for (; digits && i < s.size(); ++i) digits = std::isdigit(static_cast<unsigned char>(s[i]));
      if (!digits)
        throw Error(std::string(f.key) + " must be " + field_rule(f) + unit +
                        " (digits only); got '" + shown + "'",
                    f.key);
      return static_cast<double>(std::strtoll(s.c_str(), nullptr, 10));
    }
    case FieldType::real:
      break;
  }
  const std::optional<double> v = parse_number(s);
  // With the rule (a range): the same value in TOML said it, `--set KEY=nan` did not.
  const std::string rule = field_rule(f);
  if (!v)
    throw Error(std::string(f.key) + " must be " + number_rule() +
                    (rule == "finite" ? std::string() : " " + rule) + unit + "; got '" + shown +
                    "'",
                f.key);
  return *v;
}

void set_field_text(Case& c, std::string_view key, std::string_view text) {
  const Field* f = find_field(key);
  if (!f) throw_unknown(key);
  if (f->type == FieldType::choice || f->type == FieldType::boolean)
    return f->set(c, parse_field_text(*f, text));
  set_field(c, key, parse_field_text(*f, text));
}

std::string format_field(const Case& c, const Field& f) {
  double v = f.get(c);
  switch (f.type) {
    case FieldType::boolean:
      return v != 0.0 ? "true" : "false";
    case FieldType::choice:
      return choice_name_of(f.choices, static_cast<int>(v));
    default:
      return format_number(v);
  }
}

namespace {

const char* input_name(SoilInput input) {
  switch (input) {
    case SoilInput::coefficients:
      return "coefficients";
    case SoilInput::modulus:
      return "modulus";
    case SoilInput::table2:
      return "table2";
  }
  return "?";
}

bool is_one_of(std::string_view key, std::initializer_list<std::string_view> keys) {
  for (std::string_view k : keys)
    if (key == k) return true;
  return false;
}

// What each soil input reads, and what a key it does not read should make the user do.
std::string soil_key_not_in_effect(const Soil& soil, std::string_view key) {
  const bool modulus_key = is_one_of(key, {"soil.G", "soil.nu", "soil.rho"});
  const bool coefficient_key = is_one_of(key, {"soil.ksh", "soil.ksv", "soil.csh", "soil.csv"});
  if (!modulus_key && !coefficient_key) return "";
  const std::string head =
      std::string(key) + " has no effect while soil.input = \"" + input_name(soil.input) + "\"";
  switch (soil.input) {
    case SoilInput::modulus:
      if (!coefficient_key) return "";
      return head +
             " (the coefficients come from G, nu, rho by Appendix B); remove it or set "
             "soil.input = \"coefficients\"";
    case SoilInput::table2:
      if (key == "soil.G") return "";
      if (coefficient_key)
        return head +
               " (Table 2 gives ksh, ksv, csh, csv at soil.G); remove it or set soil.input = "
               "\"coefficients\"";
      return head +
             " (Table 2 holds nu = 0.3, rho = 1900 kg/m^3 only); remove it, or set soil.input = "
             "\"modulus\" to compute the soil from G, nu, rho by Appendix B";
    case SoilInput::coefficients:
      if (coefficient_key) return "";
      return head +
             " (the soil is ksh, ksv, csh, csv); set soil.input = \"modulus\" to compute the "
             "coefficients by Appendix B, or \"table2\" (soil.table2_G) for paper Table 2";
  }
  return "";
}

}  // namespace

std::string key_not_in_effect(const Case& c, std::string_view key) {
  if (key.starts_with("soil.")) return soil_key_not_in_effect(c.soil, key);
  const bool vibratory = c.roller.type == RollerType::vibratory;
  if (vibratory && (key == "roller.M0" || key == "roller.unbalance"))
    return std::string(key) +
           " has no effect while roller.type = \"vibratory\" (its excitation is the unbalance "
           "force roller.static_moment nu^2, no moment); remove it or set roller.type = "
           "\"oscillation\"";
  if (!vibratory && (key == "roller.static_moment" || key == "roller.exciter"))
    return std::string(key) +
           " has no effect while roller.type = \"oscillation\" (the paper's drum, excited by the "
           "moment M0 sin(nu t)); remove it or set roller.type = \"vibratory\"";
  if (key == "roller.M0" && c.roller.unbalance > 0.0)
    return "roller.M0 has no effect while roller.unbalance > 0, which gives M0 = 4 m_u e_u e_w "
           "nu^2 (5); remove one of them";
  if (key == "contact.v_eps" &&
      (c.contact.law != FrictionChoice::regularised || c.contact.pure_rolling))
    return "contact.v_eps has no effect unless contact.law = \"regularised\" (and not "
           "contact.pure_rolling); remove it or set contact.law = \"regularised\"";
  // The drum width enters Appendix B (42)-(45) and the vibratory drum's Evib-type modulus (on a
  // soil with a Poisson's ratio), nothing else: the paper's drum is planar.
  if (key == "roller.b" && c.soil.input != SoilInput::modulus &&
      !(vibratory && c.soil.input == SoilInput::table2))
    return std::string("roller.b has no effect while soil.input = \"") + input_name(c.soil.input) +
           "\"" + (vibratory ? "" : " and roller.type = \"oscillation\"") +
           " (the drum width enters Appendix B, soil.input = \"modulus\"" +
           (vibratory ? "" : ", and the vibratory drum's Evib-type modulus") +
           "; the model itself is planar); remove it or set soil.input = \"modulus\"";
  if (key.starts_with("trough.") && std::isnan(key_value(c.trough.shape, key)))
    return std::string(key) + " has no effect on a " + trough_name(c.trough.shape) + " trough";
  return "";
}

bool friction_key(std::string_view key) {
  return key == "contact.mu" || key == "contact.mu_static" || key == "contact.law";
}

bool key_in_effect(const Case& c, std::string_view key) {
  return key_not_in_effect(c, key).empty();
}

}  // namespace oscidrum
