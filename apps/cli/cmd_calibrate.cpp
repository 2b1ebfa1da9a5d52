// oscidrum calibrate: the roller from reference records of known soil: chosen parameters of the
// case (roller.M0, roller.P0, roller.kd, ...) fitted to one or more whole records at once, with
// uncertainties, 95 % intervals and identify's warnings; writes the calibrated case file that
// `identify --case` then uses (calibrate.hpp, docs/identify.md "Calibrating the roller").
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "case_options.hpp"
#include "commands.hpp"
#include "estimate_json.hpp"
#include "flags.hpp"
#include "oscidrum/calibrate.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/version.hpp"
#include "oscidrum_io/config.hpp"
#include "output.hpp"
#include "record_input.hpp"
#include "terminal.hpp"

namespace oscidrum::cli {
namespace {

struct CalibrateCliOptions {
  std::vector<std::string> references;  // RECORD[@G]
  RecordInput input;                    // how every reference is read (its file aside)
  WindowOptions windows;
  std::string config;
  CaseOptions c;
  std::vector<std::string> fit{"roller.M0"};
  std::string soil_scale = "formulas";
  int compare = 4;
  double range = 10.0;
  bool no_profile = false;
  std::string out, json, format = "table";
};

// A reference argument: the record's file and, after the last '@', the soil's G [MN/m^2] on the
// soil scale (none: the case's soil).
// How its record was read goes to `notes`.
Reference reference_of(const std::string& arg, const CalibrateCliOptions& o, const Case& base,
                       SoilScale scale, std::vector<std::string>& notes) {
  const std::size_t at = arg.rfind('@');
  Reference ref;
  RecordInput in = o.input;
  in.file = arg.substr(0, at);
  if (in.file.empty()) throw Error("calibrate: reference '" + arg + "' has no record file");
  ref.name = in.file;
  ref.soil = base.soil;
  if (at != std::string::npos) {
    const Field& G = *find_field("soil.G");
    double value = 0;
    try {
      value = parse_field_text(G, arg.substr(at + 1)) * G.display_scale;
    } catch (const Error&) {
      throw Error("calibrate: the G of reference '" + arg +
                  "' (after '@') must be a decimal number [MN/m^2]; got '" + arg.substr(at + 1) +
                  "'");
    }
    try {
      ref.soil = soil_on_scale(value, scale, base.soil);
      ref.G = value;
      ref.scale = scale;
    } catch (const Error& e) {
      // RECORD@25e6 is 25 MN/m^2 written in Pa (as --G 25e6 is): say so, as --G does.
      std::string hint;
      try {
        (void)soil_on_scale(value / G.display_scale, scale, base.soil);
        hint = " (G after '@' is in MN/m^2, not in Pa: did you mean " + in.file + "@" +
               fmt(value / G.display_scale / G.display_scale, 10) + "?)";
      } catch (const Error&) {
      }
      throw Error("calibrate: the G of reference '" + arg + "': " + e.what() + hint);
    }
  }
  const RecordColumns rec = read_record(in);
  // Each reference's own notes, named by its file (two references may be read differently).
  for (const std::string& note : rec.notes) notes.push_back(in.file + ": " + note);
  ref.z_open = rec.z_open;
  ref.units_open = rec.units_open;
  try {
    ref.data = measure_record(rec.t, rec.ddx_M, rec.ddz_M, o.windows);
  } catch (const Error& e) {
    throw Error(in.file + ": " + e.what());
  }
  return ref;
}

std::string value_text(const Estimate& e) {
  auto f = [](double v, int d) { return std::isfinite(v) ? fmt(v, d) : std::string("?"); };
  return f(e.value, 6) + " +- " + f(e.standard_uncertainty, 2) + "  [" + (e.lower_open ? "<" : "") +
         f(e.lower, 5) + ", " + f(e.upper, 5) + (e.upper_open ? ">" : "") + "]";
}

nlohmann::ordered_json calibration_json(const Calibration& cal, const CalibrateCliOptions& o) {
  nlohmann::ordered_json est = nlohmann::json::array(), refs = nlohmann::json::array();
  for (const Estimate& e : cal.estimates) est.push_back(estimate_json(e));
  for (const ReferenceFit& r : cal.references)
    refs.push_back({{"record", r.name},
                    {"f", r.f},
                    {"tau", r.time_shift},
                    {"rms_residual", r.rms_residual},
                    {"relative_residual", r.relative_residual},
                    {"reduced_chi2", r.reduced_chi2},
                    {"model_sampled", r.model_sampled},
                    {"z_negated", r.z_negated},
                    {"read_in_g", r.read_in_g}});
  return {{"schema", "oscidrum-calibrate/1"},
          {"references", refs},
          {"soil_scale", o.soil_scale},
          {"compare_harmonics", o.compare},
          {"estimates", est},
          {"reduced_chi2", cal.reduced_chi2},
          {"condition", cal.condition},
          {"converged", cal.converged},
          {"message", cal.message},
          {"iterations", cal.iterations},
          {"simulations", cal.simulations},
          {"warnings", cal.warnings}};
}

// The calibrated case file: what was fitted, on what, and how well, as comments; then every field.
std::string case_file(const Calibration& cal, const std::vector<std::string>& args) {
  std::ostringstream out;
  out << "# Calibrated by oscidrum " << version << " (oscidrum calibrate) on";
  for (const std::string& a : args) out << " " << a;
  out << "\n# estimate +- standard uncertainty [95 % interval]:\n";
  for (const Estimate& e : cal.estimates)
    out << "#   " << e.name << " = " << value_text(e) << " " << e.unit << "\n";
  out << "# reduced chi^2 " << fmt(cal.reduced_chi2, 3) << "\n";
  for (const std::string& w : cal.warnings) out << "# WARNING: " << w << "\n";
  out << "# Use it as the roller of an identification: oscidrum identify RECORD --case FILE\n\n"
      << io::case_to_toml(cal.calibrated);
  return out.str();
}

int run(const CalibrateCliOptions& o) {
  // (--out may name the case file: the calibrated case replaces it, which is meant.)
  std::vector<NamedFile> files = {{"--out", o.out}, {"--json", o.json}};
  for (const std::string& r : o.references)
    files.push_back({"the reference record", r.substr(0, r.rfind('@')), true});
  check_distinct_files(files);
  io::CaseSpec spec;
  // The references' G on the formulas scale go through Appendix B: nu, rho and the drum width b
  // take effect (--b 1.5 was refused as having no effect under the default Table 2 soil).
  const Case base = resolve_case(
      o.config, o.c, spec,
      o.soil_scale == "formulas" ? std::optional<SoilInput>(SoilInput::modulus) : std::nullopt);
  const SoilScale scale = soil_scale_from(o.soil_scale, "--soil-scale");
  install_interrupt_handlers();
  std::vector<Reference> refs;
  std::vector<std::string> notes;  // how the records were read, said once nothing can fail
  for (const std::string& arg : o.references) {
    refs.push_back(reference_of(arg, o, base, scale, notes));
    if (interrupted()) return interrupted_exit_code();
  }
  CalibrateOptions co;
  co.parameters = o.fit;
  co.harmonics = o.compare;
  co.range = o.range;
  co.profile = !o.no_profile;
  const Calibration cal = calibrate(base, refs, co);
  report_reading(notes);
  if (interrupted()) {
    std::cerr << "oscidrum: interrupted; nothing written\n";
    return interrupted_exit_code();
  }
  const nlohmann::ordered_json j = calibration_json(cal, o);
  if (!o.out.empty()) write_output(o.out, case_file(cal, o.references));
  if (!o.json.empty()) write_output(o.json, j.dump(2) + "\n");
  if (o.format == "json") {
    std::cout << j.dump(2) << "\n";
  } else {
    Summary s;
    s.section("Calibration");
    for (const Estimate& e : cal.estimates)
      s.line(e.name + " [" + e.unit + "]  value +- u  [95 %]", value_text(e));
    s.line("reduced chi^2", fmt(cal.reduced_chi2, 3));
    s.line("iterations, simulations",
           std::to_string(cal.iterations) + ", " + std::to_string(cal.simulations));
    for (const ReferenceFit& r : cal.references)
      s.line("reference " + r.name,
             "f " + fmt(r.f, 7) + " Hz, relative residual " + fmt(r.relative_residual, 3) +
                 ", reduced chi^2 " + fmt(r.reduced_chi2, 3) +
                 (r.model_sampled ? "; sampled in step with the excitation: the "
                                    "model compared sampled at its times"
                                  : "") +
                 (r.z_negated ? "; z_M'' fitted negated" : "") +
                 (r.read_in_g ? "; fitted in g" : ""));
    if (!o.out.empty()) s.line("calibrated case", o.out);
    for (const std::string& w : cal.warnings) s.line("WARNING", w);
    std::cout << s.text();
  }
  std::cout.flush();
  return cal.converged ? kExitOk : kExitCaseFailed;
}

}  // namespace

void add_calibrate_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<CalibrateCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "calibrate",
      "The roller from reference records of known soil: fit chosen parameters of the case "
      "(--fit: roller.M0, roller.P0, roller.kd, roller.cd, ...) so that the model's harmonics of "
      "x_M'' and z_M'' match every reference record at once (each whole record one window, with "
      "its own f and time shift), with standard uncertainties, 95 % profile intervals and "
      "warnings when the references cannot tell the parameters apart; writes the calibrated case "
      "file (--out) that `oscidrum identify --case` then uses (docs/identify.md).");
  sub->footer(
      "Each REFERENCE is a record file with the soil under it after '@': its G in MN/m^2 on the "
      "--soil-scale (formulas: Appendix B (42)-(45) with the case's nu and rho; table2: the "
      "paper's Table 2, interpolated); a record without '@G' is on the case's soil. mu, MMd and "
      "everything not fitted come from --case, the flags and --set (defaults: the paper's "
      "roller); roller.M0 is scaled by (f / roller.f)^2 to each record's f (5).\n"
      "Examples:\n"
      "  oscidrum calibrate strip_a.csv@15 strip_b.csv@60 --fit roller.M0,roller.P0 --out "
      "my_roller.toml\n"
      "  oscidrum identify pass.csv --case my_roller.toml\n"
      "Exit codes: 0 calibrated, 1 the fit did not converge, 2 bad input, 130 interrupted.");
  sub->add_option("references", o->references,
                  "reference records: RECORD@G (G [MN/m^2] of the soil under it) or RECORD "
                  "(the case's soil)")
      ->required()
      ->type_name("REFERENCE");
  add_record_options(*sub, o->input, false, false);
  const char* meas = "Measurement";
  sub->add_option("--f", o->windows.f,
                  "excitation frequency [Hz]; default: estimated from each record")
      ->check(positive_number())
      ->group(meas);
  o->windows.n_max = 0;
  sub->add_option("--harmonics", o->windows.n_max,
                  "harmonics of each record's quality gates n = 1 ... N; 0 (the default): as "
                  "many as the sampling resolves, at most 10")
      ->check(CLI::Range(0, 200))
      ->group(meas);
  add_record_case_flags(*sub, o->config, o->c, "case file (TOML) of the roller to calibrate");
  const char* fit = "Calibration";
  sub->add_option("--fit", o->fit,
                  "the case fields fitted, comma-separated (default roller.M0): real roller, "
                  "contact or trough parameters > 0, each on a log scale")
      ->delimiter(',')
      ->type_name("KEY[,KEY...]")
      ->group(fit);
  sub->add_option("--soil-scale", o->soil_scale,
                  "the scale of the references' G: formulas (Appendix B (42)-(45), the default) "
                  "or table2 (the paper's Table 2, interpolated between its rows)")
      ->check(CLI::IsMember({"formulas", "table2"}))
      ->group(fit);
  sub->add_option("--compare", o->compare,
                  "harmonics n = 1 ... N of x_M'' and z_M'' compared (default 4)")
      ->check(CLI::Range(1, kMaxComparedHarmonics))
      ->group(fit);
  sub->add_option("--range", o->range,
                  "each estimate stays within [start / RANGE, start * RANGE] (default 10)")
      ->group(fit);
  sub->add_flag("--no-profile", o->no_profile, "skip the profile intervals (faster)")->group(fit);
  const char* out = "Output";
  sub->add_option("--out", o->out, "write the calibrated case file (TOML) to FILE")
      ->type_name("FILE")
      ->group(out);
  sub->add_option("--json", o->json, "write the calibration as JSON to FILE")
      ->type_name("FILE")
      ->group(out);
  sub->add_option("--format", o->format, "stdout: table or json")
      ->check(CLI::IsMember({"table", "json"}))
      ->group(out);
  sub->callback([o, &action] { action = [o] { return run(*o); }; });
}

}  // namespace oscidrum::cli
