// Case flags: generated roller flags, the soil, contact, torque and trough flags, and --set.
#include "case_options.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <optional>

#include "flags.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/text.hpp"
#include "oscidrum_io/config.hpp"
#include "output.hpp"

namespace oscidrum::cli {
namespace {

std::string origin(const std::string& flag, double v) { return flag + " " + fmt(v, 10); }

// Flags override the file: drop what the file said about the same quantity.
void forget(io::CaseSpec& spec, const char* key) {
  spec.origin.erase(std::string(key));
  if (std::string_view(key) == "MMd_fraction") spec.MMd_fraction.reset();
}

}  // namespace

void add_roller_flags(CLI::App& app, CaseOptions& o, const std::vector<std::string>& only) {
  for (const Field& f : fields()) {
    const std::string key = f.key;
    if (!key.starts_with("roller.") || key == "roller.g") continue;
    if (!only.empty() && std::find(only.begin(), only.end(), key) == only.end()) continue;
    // roller.m_f is --mf (Appendix A's symbol); the others are the key's last part.
    const std::string flag = key == "roller.m_f" ? "--mf" : "--" + key.substr(7);
    const std::string help =
        std::string(f.description) + " [" + f.unit + "] (default " + format_field(Case{}, f) + ")";
    if (f.type == FieldType::choice) {
      // By name (--type vibratory), checked by the case's own rule when applied.
      std::string& name = o.roller_choice[key];
      name = format_field(Case{}, f);
      std::string names = f.choices;
      std::replace(names.begin(), names.end(), '|', ',');
      o.roller_flags[key] = app.add_option(flag, name, help)
                                ->type_name("{" + names + "}")
                                ->group("Roller (paper Table 1)");
      continue;
    }
    double& slot = o.roller[key];
    slot = f.get(Case{});
    o.roller_flags[key] = app.add_option(flag, slot, help)->group("Roller (paper Table 1)");
  }
}

double soil_G_flag(double value) {
  const Field& G = *find_field("soil.G");
  const std::string unit = display_unit(G);
  const std::string range = "[" + fmt(G.min / G.display_scale, 10) + ", " +
                            fmt(G.max / G.display_scale, 10) + "] [" + unit + "]";
  if (!std::isfinite(value) || value <= 0)
    throw Error("--G must be in " + range + "; got " + fmt(value, 10), "soil.G", value);
  const double pa = value * G.display_scale;
  if (check_field(G, pa).empty()) return pa;
  // 30000000 is 30 MN/m^2 written in Pa.
  if (check_field(G, value).empty())
    throw Error("--G is the shear modulus in " + unit + " (soils: about 1 to 500), not in " +
                    G.unit + "; got " + fmt(value, 10) + " " + unit + " = " + fmt(pa, 10) + " " +
                    G.unit + ": did you mean --G " + fmt(value / G.display_scale, 10) + "?",
                "soil.G", value);
  throw Error("--G must be in " + range + " (soil.G in " + G.unit + " / " +
                  fmt(G.display_scale, 10) + "); got " + fmt(value, 10),
              "soil.G", value);
}

void add_soil_flags(CLI::App& app, CaseOptions& o) {
  const char* group = "Soil";
  o.G_flag = app.add_option("--G", o.G,
                            "soil shear modulus in MN/m^2 (not Pa: --G 30 is soil.G = 30e6; "
                            "values plainly in Pa are refused). A G of paper Table 2 (5, 10, ..., "
                            "70) gives the Table 2 soil (soil.input = table2), any other G, or "
                            "--soil-formula, Appendix B (42)-(45) (soil.input = modulus)")
                 ->group(group);
  o.formula_flag =
      app.add_flag("--soil-formula", o.soil_formula,
                   "compute ksh, ksv, csh, csv from G, nu, rho by Appendix B (42)-(45) even for a "
                   "Table 2 G")
          ->group(group);
  o.nu_flag = app.add_option("--nu", o.nu, "soil Poisson's ratio [-] (Appendix B; default 0.3)")
                  ->group(group);
  o.rho_flag = app.add_option("--rho", o.rho, "soil density [kg/m^3] (Appendix B; default 1900)")
                   ->group(group);
  o.ksh_flag = app.add_option("--ksh", o.ksh, "horizontal soil spring [N/m]")->group(group);
  o.ksv_flag = app.add_option("--ksv", o.ksv, "vertical soil spring [N/m]")->group(group);
  o.csh_flag = app.add_option("--csh", o.csh, "horizontal soil dashpot [N s/m]")->group(group);
  o.csv_flag = app.add_option("--csv-soil", o.csv, "vertical soil dashpot [N s/m]")->group(group);
}

void add_model_flags(CLI::App& app, CaseOptions& o) {
  const char* group = "Contact, torque and trough";
  o.mu_flag =
      app.add_option("--mu", o.mu, "Coulomb friction coefficient drum/soil [-] (default 0.5)")
          ->group(group);
  o.pure_flag = app.add_flag("--pure-rolling", o.pure_rolling,
                             "ignore the friction limit (mu -> infinity): the drum never slips")
                    ->group(group);
  o.unilateral_flag =
      app.add_flag("--unilateral", o.unilateral,
                   "unilateral contact: the drum may lift off the trough and land again "
                   "(contact.unilateral; docs/model.md section 13)")
          ->group(group);
  o.MMd_flag =
      app.add_option("--MMd", o.MMd, "constant driving torque [N m] (default 0)")->group(group);
  o.fraction_flag =
      app.add_option("--MMd-fraction", o.MMd_fraction,
                     "constant driving torque as a fraction of M0 [-]; the paper uses 0 and 0.05")
          ->group(group);
  o.R_flag = app.add_option("--R", o.R, "circular trough of radius R [m] (> r; default 0.606)")
                 ->group(group);
  o.k_flag = app.add_option("--k", o.k, "log-spiral trough R(theta) = a exp(k theta): k [-]")
                 ->group(group);
  o.a_flag = app.add_option("--a", o.a, "log-spiral trough: a [m]")->group(group);
}

void add_record_case_flags(CLI::App& app, std::string& config, CaseOptions& o,
                           const std::string& case_help) {
  app.add_option("--case", config, case_help)->type_name("CASE.toml")->group("Model");
  add_roller_flags(app, o,
                   {"roller.r", "roller.b", "roller.m", "roller.I", "roller.P0", "roller.M0",
                    "roller.kd", "roller.cd"});
  add_soil_flags(app, o);
  add_model_flags(app, o);
  add_set_flag(app, o);
}

void add_set_flag(CLI::App& app, CaseOptions& o, const std::vector<std::string>& only) {
  o.set_keys = only;
  o.command = app.get_name();
  std::string help;
  if (only.empty()) {
    help =
        "set any parameter: --set KEY=VALUE, SI units, repeatable; keys as in the config file "
        "(see 'oscidrum fields'), e.g. --set numerics.max_periods=2000";
  } else {
    help = "set a parameter this command uses: --set KEY=VALUE, SI units, repeatable; KEY one of";
    for (std::size_t i = 0; i < only.size(); ++i) help += (i ? ", " : " ") + only[i];
    help += " (other keys have no effect here and are errors), e.g. --set " + only.back() + "=" +
            format_field(Case{}, *find_field(only.back()));
  }
  app.add_option("--set", o.sets, help)
      ->allow_extra_args(false)
      // Checked while parsing: `--set --csv out.csv` must not take --csv as its value and leave
      // out.csv to be read as the case file.
      ->check(CLI::Validator(
          [](std::string& s) {
            if (s.find('=') == std::string::npos || s.front() == '=')
              return "--set expects KEY=VALUE (e.g. --set soil.G=25e6); got '" + io::clip(s) + "'";
            return std::string();
          },
          // No description: CLI11 appends it to the type name ("KEY=VALUE:KEY=VALUE ..."),
          // which read as a syntax that is refused.
          "", "KEY=VALUE"))
      ->type_name("KEY=VALUE")
      ->group("Any parameter");
}

namespace {
void apply_flags(const CaseOptions& o, io::CaseSpec& spec);
}  // namespace

Case resolve_case(const std::string& config, const CaseOptions& o, io::CaseSpec& spec,
                  std::optional<SoilInput> soil_input) {
  if (!config.empty()) io::read_case_file(config, spec);
  if (soil_input) {
    // Only where nothing names the soil's input: not the file, and not a flag (applied next,
    // before finalize; a flag that gives the soil sets it itself).
    bool named = false;
    for (const char* key :
         {"soil.input", "soil.table2_G", "soil.ksh", "soil.ksv", "soil.csh", "soil.csv"})
      named = named || spec.given(key);
    if (!named) spec.values.soil.input = *soil_input;
  }
  apply(o, spec);
  std::vector<std::string> warnings;
  const Case c = io::finalize(spec, &warnings);
  for (const std::string& w : warnings) warn(w);
  io::validate(c, spec);
  return c;
}

void apply(const CaseOptions& o, io::CaseSpec& spec) {
  // --set, in order, after the named flags; errors name the setting.
  apply_flags(o, spec);
  for (const std::string& s : o.sets) {
    const std::size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw Error("--set expects KEY=VALUE (e.g. --set soil.G=25e6); got '" + io::clip(s) + "'");
    // Blanks around the key and the value (--set 'roller.f = 40', as a TOML file writes it) are
    // not part of them: the key was unknown as 'roller.f '.
    const auto trimmed = [](const std::string& t) {
      const std::size_t b = t.find_first_not_of(" \t"), e = t.find_last_not_of(" \t");
      return b == std::string::npos ? std::string() : t.substr(b, e - b + 1);
    };
    const std::string key = trimmed(s.substr(0, eq));
    if (!o.set_keys.empty() &&
        std::find(o.set_keys.begin(), o.set_keys.end(), key) == o.set_keys.end()) {
      std::string uses;
      for (std::size_t i = 0; i < o.set_keys.size(); ++i) uses += (i ? ", " : "") + o.set_keys[i];
      throw Error("--set " + s + ": 'oscidrum " + o.command + "' does not use " + key +
                  " (it would have no effect); it uses " + uses);
    }
    // The same key from a flag (or an earlier --set): the later one holds, said; unless it gives
    // the same value ('--G 80 --set soil.input=modulus': --G 80 implies the modulus input, and
    // "overrides --G 80" read as if G had been dropped).
    if (const auto it = spec.origin.find(key);
        it != spec.origin.end() && it->second.rfind("--", 0) == 0) {
      bool same = false;
      if (const Field* f = find_field(key)) {
        try {
          same = parse_field_text(*f, trimmed(s.substr(eq + 1))) == f->get(spec.values);
        } catch (const Error&) {  // refused below, with the key's message
        }
      }
      if (!same) warn("--set " + io::clip(s) + " overrides " + it->second);
    }
    if (key == "MMd") forget(spec, "MMd_fraction");
    if (key == "MMd_fraction") forget(spec, "MMd");
    if (key == "soil.table2_G") io::clear_soil(spec);
    try {
      io::assign_text(spec, key, trimmed(s.substr(eq + 1)), "--set " + io::clip(s));
    } catch (const Error& e) {
      throw Error("--set " + io::clip(s) + ": " + e.what());
    }
  }
}

namespace {

// io::assign, with the flag named in the error ("--mu -1: contact.mu must be >= 0; got -1").
void put(io::CaseSpec& spec, const std::string& key, const io::Value& value,
         const std::string& from) {
  try {
    io::assign(spec, key, value, from);
  } catch (const Error& e) {
    throw Error(from + ": " + e.what());
  }
}

void apply_flags(const CaseOptions& o, io::CaseSpec& spec) {
  for (const auto& [key, flag] : o.roller_flags) {
    if (!given(flag)) continue;
    if (const auto choice = o.roller_choice.find(key); choice != o.roller_choice.end())
      put(spec, key, choice->second, flag->get_name() + " " + choice->second);
    else
      put(spec, key, o.roller.at(key), origin(flag->get_name(), o.roller.at(key)));
  }

  // Soil.
  const bool coefficient_flags =
      given(o.ksh_flag) || given(o.ksv_flag) || given(o.csh_flag) || given(o.csv_flag);
  if (given(o.G_flag)) {
    if (coefficient_flags)
      throw Error("give the soil either by --G or by --ksh, --ksv, --csh, --csv-soil, not both");
    const double G = soil_G_flag(o.G);
    const std::string from = origin("--G", o.G);
    io::clear_soil(spec);
    if (is_table2_G(G) && !o.soil_formula) {
      if (given(o.nu_flag) || given(o.rho_flag))
        throw Error("--G " + fmt(o.G) +
                    " uses paper Table 2, which holds nu = 0.3 and rho = 1900 "
                    "only; add --soil-formula to compute the soil for --nu/--rho by Appendix B");
      put(spec, "soil.table2_G", G, from);
    } else {
      put(spec, "soil.input", std::string("modulus"), from);
      put(spec, "soil.G", G, from);
    }
  } else if (o.soil_formula) {
    forget(spec, "soil.table2_G");
    put(spec, "soil.input", std::string("modulus"), "--soil-formula");
  }
  if (given(o.nu_flag)) put(spec, "soil.nu", o.nu, origin("--nu", o.nu));
  if (given(o.rho_flag)) put(spec, "soil.rho", o.rho, origin("--rho", o.rho));
  if (coefficient_flags) {
    io::materialize_soil(spec);
    const std::pair<CLI::Option*, double> coefficient[] = {
        {o.ksh_flag, o.ksh}, {o.ksv_flag, o.ksv}, {o.csh_flag, o.csh}, {o.csv_flag, o.csv}};
    const char* keys[] = {"soil.ksh", "soil.ksv", "soil.csh", "soil.csv"};
    for (int i = 0; i < 4; ++i)
      if (given(coefficient[i].first))
        put(spec, keys[i], coefficient[i].second,
            origin(coefficient[i].first->get_name(), coefficient[i].second));
  }

  // Contact.
  if (given(o.pure_flag) && given(o.mu_flag))
    throw Error("--pure-rolling ignores friction; give either --mu or --pure-rolling");
  if (given(o.pure_flag)) put(spec, "contact.pure_rolling", true, "--pure-rolling");
  if (given(o.unilateral_flag)) put(spec, "contact.unilateral", true, "--unilateral");
  if (given(o.mu_flag)) {
    put(spec, "contact.mu", o.mu, origin("--mu", o.mu));
    put(spec, "contact.pure_rolling", false, origin("--mu", o.mu));
  }

  // Driving torque.
  if (given(o.MMd_flag) && given(o.fraction_flag))
    throw Error("give the driving torque either by --MMd [N m] or by --MMd-fraction [-], not both");
  if (given(o.MMd_flag)) {
    forget(spec, "MMd_fraction");
    put(spec, "MMd", o.MMd, origin("--MMd", o.MMd));
  }
  if (given(o.fraction_flag)) {
    forget(spec, "MMd");
    put(spec, "MMd_fraction", o.MMd_fraction, origin("--MMd-fraction", o.MMd_fraction));
  }

  // Trough.
  if (given(o.R_flag) && (given(o.k_flag) || given(o.a_flag)))
    throw Error("give the trough either as a circle (--R) or as a log spiral (--k, --a), not both");
  if (given(o.R_flag)) {
    put(spec, "trough.k", 0.0, origin("--R", o.R));
    put(spec, "trough.a", o.R, origin("--R", o.R));
  }
  if (given(o.k_flag)) put(spec, "trough.k", o.k, origin("--k", o.k));
  if (given(o.a_flag)) put(spec, "trough.a", o.a, origin("--a", o.a));
}

}  // namespace

}  // namespace oscidrum::cli

namespace oscidrum::cli {

void warn_if_replaced_by_param(const io::CaseSpec& spec, const std::string& key) {
  const auto it = spec.origin.find(key);
  if (it == spec.origin.end() || !it->second.starts_with("--")) return;
  warn(it->second + " has no effect: --param " + key + " takes its values from --from to --to");
}

double key_flag_value(const Field& f, const std::string& flag, const std::string& text) {
  const std::optional<double> shown = parse_number(text);
  if (!shown)
    throw Error(flag + ": must be " + number_rule() + " [" +
                (f.display_unit ? f.display_unit : f.unit) + "]; got '" + text + "'");
  // The unit the key is typed in elsewhere on the command line: its case flag's. Only --G takes
  // its field's display unit (MN/m^2); --ksh, --csh, ... and --set take SI, although tables show
  // those in MN/m and kN s/m.
  if (!f.display_unit || std::string_view(f.key) != "soil.G") return *shown;
  const double value = *shown * f.display_scale;
  // A value typed in SI where the flag takes the display unit (--from 20e6 for soil.G, meant as
  // 20 MN/m^2): out of the field's range as typed, within it as SI. Said with what was meant.
  if (!check_field(f, value).empty() && check_field(f, *shown).empty())
    throw Error(flag + ": " + f.key + " is given in " + f.display_unit + " here, not in " + f.unit +
                    "; got " + text + " " + f.display_unit + " = " + fmt(value, 10) + " " + f.unit +
                    ", outside its range: did you mean " + flag + " " +
                    fmt(*shown / f.display_scale, 10) + "?",
                f.key, value);
  // Out of range as typed: said in the unit it was typed in (the check in Pa said "got 5000
  // (values are in Pa: did you mean 5e+09, i.e. 5000 MN/m^2?)" of --to 0.005).
  if (!check_field(f, value).empty())
    throw Error(flag + ": " + f.key + " must be in [" + fmt(f.min / f.display_scale, 10) + ", " +
                    fmt(f.max / f.display_scale, 10) + "] [" + f.display_unit + "] here; got " +
                    text,
                f.key, value);
  return value;
}

}  // namespace oscidrum::cli
