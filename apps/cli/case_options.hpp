// case_options.hpp: the flags that describe a case, shared by run, sweep, soil and
// transmissibility. Config file first, then the named flags, then --set in the order given:
// later settings override earlier ones.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "oscidrum/fields.hpp"
#include "oscidrum_io/case_spec.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace oscidrum::cli {

struct CaseOptions {
  // Roller flags, generated from the field table (roller.*): key -> value, and the option.
  std::map<std::string, double> roller;
  // A choice (roller.type, roller.exciter) is given by its name: key -> name.
  std::map<std::string, std::string> roller_choice;
  std::map<std::string, CLI::Option*> roller_flags;

  double G = 0, nu = 0, rho = 0;  // --G [MN/m^2], --nu, --rho
  double ksh = 0, ksv = 0, csh = 0, csv = 0;
  double mu = 0, MMd = 0, MMd_fraction = 0, R = 0, k = 0, a = 0;
  bool pure_rolling = false, soil_formula = false, unilateral = false;
  CLI::Option *G_flag = nullptr, *nu_flag = nullptr, *rho_flag = nullptr;
  CLI::Option *ksh_flag = nullptr, *ksv_flag = nullptr, *csh_flag = nullptr, *csv_flag = nullptr;
  CLI::Option *mu_flag = nullptr, *pure_flag = nullptr, *formula_flag = nullptr,
              *unilateral_flag = nullptr;
  CLI::Option *MMd_flag = nullptr, *fraction_flag = nullptr;
  CLI::Option *R_flag = nullptr, *k_flag = nullptr, *a_flag = nullptr;
  std::vector<std::string> sets;  // --set key=value
  // Keys --set may name (empty: every key); a command that uses only a few parameters rejects
  // the others instead of ignoring them. `command` names it in the message.
  std::vector<std::string> set_keys;
  std::string command;
};

/// --r, --b, --m, --I, --P0, --f, --M0, --kd, --cd: one per roller field of fields() (except g,
/// which --set roller.g reaches: `--g` next to `--G` would invite a costly typo). `only` limits
/// the flags to these keys (empty: all).
void add_roller_flags(CLI::App& app, CaseOptions& o, const std::vector<std::string>& only = {});

/// --G, --soil-formula, --nu, --rho, --ksh, --ksv, --csh, --csv.
void add_soil_flags(CLI::App& app, CaseOptions& o);

/// --mu, --pure-rolling, --MMd, --MMd-fraction, --R, --k, --a.
void add_model_flags(CLI::App& app, CaseOptions& o);

/// --set key=value (repeatable), for any key of `oscidrum fields`; with `only`, for those keys
/// alone (a key the command does not use is an error: exit code 2, not a silent no-op).
void add_set_flag(CLI::App& app, CaseOptions& o, const std::vector<std::string>& only = {});

/// The case of a command that compares the model with measured records (identify, calibrate):
/// --case FILE (`case_help`, group Model), the roller flags but the frequency (each record gives
/// it), the soil, contact, torque and trough flags, and --set.
void add_record_case_flags(CLI::App& app, std::string& config, CaseOptions& o,
                           const std::string& case_help);

/// Apply the flags that were given to `spec`. Throws oscidrum::Error (exit code 2).
void apply(const CaseOptions& o, io::CaseSpec& spec);

/// The shear modulus [Pa] of a --G value, which is in the field table's display unit of soil.G
/// (MN/m^2). Throws oscidrum::Error for a value outside soil.G's rule, and says "did you mean
/// --G 30?" for one that is plainly in Pa (--G 30000000).
double soil_G_flag(double value);

/// The value of a flag that gives a value of the field `f` (--from/--to of continue and diagram)
/// in its SI unit: the text is in the unit the key is typed in on the command line, MN/m^2 for
/// soil.G (as --G: --from 20 is 20 MN/m^2), SI for every other key (as --ksh, --set). Throws
/// oscidrum::Error "FLAG: must be ..." for text that is not a decimal number.
double key_flag_value(const Field& f, const std::string& flag, const std::string& text);

/// The case a command runs: the case file `config` (if any), then the flags and --set of `o`,
/// finalised with its warnings on stderr and validated. `spec` keeps where each key was set.
/// `soil_input`: the soil input of a case whose file and flags name no soil input (soil.input,
/// soil.table2_G or a coefficient): identify's and calibrate's G on the formulas scale go
/// through Appendix B, where soil.nu, soil.rho and roller.b take effect.
Case resolve_case(const std::string& config, const CaseOptions& o, io::CaseSpec& spec,
                  std::optional<SoilInput> soil_input = std::nullopt);

/// continue and diagram: a flag or --set that set `key`, which --param varies, has no effect
/// (the values come from --from and --to): a warning on stderr naming it. A case file's value is
/// the base case's, replaced as the file's other values are by flags: no warning.
void warn_if_replaced_by_param(const io::CaseSpec& spec, const std::string& key);

}  // namespace oscidrum::cli
