// oscidrum diagram: the brute-force bifurcation diagram. The motion at a row of values of one
// parameter, each started from the state the previous one ended in (up, down or both), its
// stroboscopic points and its verdict at each value (docs/bifurcations.md).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "case_options.hpp"
#include "commands.hpp"
#include "flags.hpp"
#include "oscidrum/diagram.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum_io/csv.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "terminal.hpp"

namespace oscidrum::cli {
namespace {

struct DiagramCommandOptions {
  std::string config;
  CaseOptions c;
  std::string key, from_text, to_text, sweep = "up", csv, json, plot, plot_quantity = "ddx_M";
  std::string format = "table";
  CLI::Option* format_flag = nullptr;
  std::vector<CLI::Option*> output_flags;  // --csv, --json, --plot
  DiagramOptions diagram;
  bool quiet = false;
};

std::string cell(double v) { return io::format_double_short(v); }

// A column of the stroboscopic points as numbers (the phase as 0, 1, -1).
double column_value(const Samples& s, const SampleOutput& o, std::size_t k) {
  return std::visit(
      [&](auto member) -> double {
        const auto& column = s.*member;
        if (k >= column.size()) return NAN;
        using T = typename std::remove_cvref_t<decltype(column)>::value_type;
        if constexpr (std::is_same_v<T, Phase>)
          return static_cast<double>(static_cast<int>(column[k]));
        else
          return column[k];
      },
      o.member);
}

const SampleOutput* find_column(const std::string& name) {
  for (const SampleOutput& o : sample_outputs())
    if (name == o.name) return &o;
  return nullptr;
}

const char* direction(const DiagramValue& v) { return v.direction > 0 ? "up" : "down"; }

// One row per stroboscopic point: where it was taken, the value's verdict, every output column.
std::string points_csv(const Diagram& d) {
  std::string out = "sweep[-],value[-]," + d.key + "[" + d.unit +
                    "],point[-],verdict[-],period[-],lyapunov[1/s],from_rest[-],shooting[-]";
  for (const SampleOutput& o : sample_outputs())
    out += std::string(",") + o.name + "[" + o.unit + "]";
  out += "\n";
  for (std::size_t i = 0; i < d.values.size(); ++i) {
    const DiagramValue& v = d.values[i];
    const std::string head =
        std::string(direction(v)) + "," + std::to_string(i) + "," + cell(v.parameter) + ",";
    const std::string verdict = "," + v.motion.kind + "," + std::to_string(v.period) + "," +
                                cell(v.motion.lyapunov) + "," + (v.from_rest ? "1" : "0") + "," +
                                (v.shooting ? "1" : "0");
    for (std::size_t k = 0; k < v.section.size(); ++k) {
      out += head + std::to_string(k + 1) + verdict;
      for (const SampleOutput& o : sample_outputs())
        out.append(",").append(cell(column_value(v.section, o, k)));
      out += "\n";
    }
  }
  return out;
}

nlohmann::ordered_json diagram_json(const Diagram& d, const DiagramCommandOptions& o) {
  nlohmann::ordered_json j = {{"schema", "oscidrum-diagram/1"},
                              {"key", d.key},
                              {"unit", d.unit},
                              {"from", o.diagram.from},
                              {"to", o.diagram.to},
                              {"steps", o.diagram.steps},
                              {"sweep", to_string(o.diagram.sweep)},
                              {"discard", o.diagram.discard},
                              {"periods", o.diagram.periods},
                              {"periods_integrated", d.periods_integrated},
                              {"seconds", d.seconds}};
  nlohmann::ordered_json values = nlohmann::json::array();
  for (const DiagramValue& v : d.values) {
    nlohmann::ordered_json section;
    for (const SampleOutput& c : sample_outputs()) {
      std::vector<double> column;
      for (std::size_t k = 0; k < v.section.size(); ++k)
        column.push_back(column_value(v.section, c, k));
      section[c.name] = column;
    }
    values.push_back({{"parameter", v.parameter},
                      {"direction", direction(v)},
                      {"from_rest", v.from_rest},
                      {"shooting", v.shooting},
                      {"verdict", v.motion.kind},
                      {"period", v.period},
                      {"lyapunov", v.motion.lyapunov},
                      {"lyapunov_halves", {v.motion.lyapunov_first, v.motion.lyapunov_second}},
                      {"recurrence", v.motion.recurrence},
                      {"converging_period", v.motion.converging_period},
                      {"evidence", v.motion.evidence},
                      {"section", section}});
  }
  j["values"] = values;
  return j;
}

// The points of one column at a value that differ by more than 1e-6 of the column's range over
// the diagram, or of its largest magnitude where that is larger: how many distinct stroboscopic
// points the value shows. (With the range alone a diagram of values whose points all lie within
// 1e-9 of each other counted the integration's round-off: one periodic orbit showed 1, 70 or 390
// points as the other values of the diagram were nearer to it.)
int distinct(const Samples& s, const SampleOutput& o, double range) {
  std::vector<double> v;
  for (std::size_t k = 0; k < s.size(); ++k) v.push_back(column_value(s, o, k));
  std::sort(v.begin(), v.end());
  int n = v.empty() ? 0 : 1;
  for (std::size_t k = 1; k < v.size(); ++k)
    if (v[k] - v[k - 1] > 1e-6 * range) ++n;
  return n;
}

std::string table(const Diagram& d, const Field& f, const SampleOutput& quantity) {
  const double scale = f.display_unit ? f.display_scale : 1.0;
  const std::string unit = f.display_unit ? f.display_unit : f.unit;
  double lo = INFINITY, hi = -INFINITY, size = 0.0;
  for (const DiagramValue& v : d.values)
    for (std::size_t k = 0; k < v.section.size(); ++k) {
      const double x = column_value(v.section, quantity, k);
      if (std::isfinite(x))
        lo = std::min(lo, x), hi = std::max(hi, x), size = std::max(size, std::abs(x));
    }
  const double range = std::max({hi > lo ? hi - lo : 0.0, size, 1e-300});
  TextTable t;
  const std::string q = std::string(quantity.name) + " [" + quantity.unit + "]";
  t.header = {"sweep",    d.key + " [" + unit + "]",
              "verdict",  "period",
              "lambda T", "distinct " + std::string(quantity.name),
              q + " min", q + " max"};
  t.right = {false, true, false, true, true, true, true, true};
  for (const DiagramValue& v : d.values) {
    double vlo = INFINITY, vhi = -INFINITY;
    for (std::size_t k = 0; k < v.section.size(); ++k) {
      const double x = column_value(v.section, quantity, k);
      if (std::isfinite(x)) vlo = std::min(vlo, x), vhi = std::max(vhi, x);
    }
    t.rows.push_back({direction(v), fmt(v.parameter / scale, 6), v.motion.kind,
                      v.period > 0 ? std::to_string(v.period) : "-",
                      std::isfinite(v.motion.lyapunov) && v.section.size() > 0
                          ? fmt(v.motion.lyapunov * v.excitation_period, 3)
                          : "-",
                      std::to_string(distinct(v.section, quantity, range)),
                      v.section.size() > 0 ? fmt(vlo, 6) : "-",
                      v.section.size() > 0 ? fmt(vhi, 6) : "-"});
  }
  return t.text();
}

int run(DiagramCommandOptions o) {
  const Field* field = find_field(o.key);
  if (!field) throw Error("--param: unknown key '" + o.key + "' (oscidrum fields lists them)");
  o.diagram.key = o.key;
  o.diagram.from = key_flag_value(*field, "--from", o.from_text);
  o.diagram.to = key_flag_value(*field, "--to", o.to_text);
  o.diagram.sweep = o.sweep == "down"   ? DiagramSweep::down
                    : o.sweep == "both" ? DiagramSweep::both
                                        : DiagramSweep::up;
  const SampleOutput* quantity = find_column(o.plot_quantity);
  if (!quantity || std::holds_alternative<SamplePhases Samples::*>(quantity->member)) {
    std::string names;
    for (const SampleOutput& c : sample_outputs())
      if (!std::holds_alternative<SamplePhases Samples::*>(c.member))
        names += (names.empty() ? "" : ", ") + std::string(c.name);
    throw Error("--plot-quantity: must be one of " + names + "; got '" + o.plot_quantity + "'");
  }
  // A file name given empty (--csv "") is refused, as run and sweep refuse it: it wrote nothing.
  for (const CLI::Option* flag : o.output_flags)
    if (given(flag) && flag->as<std::string>().empty()) check_output_file(flag->get_name(), "");
  if (!o.csv.empty()) check_output_file("--csv", o.csv);
  if (!o.json.empty()) check_output_file("--json", o.json);
  // Standard output carries one thing (the table printed after a --csv - made it unreadable).
  const bool stdout_taken = file_takes_stdout({{"--csv", o.csv}, {"--json", o.json}},
                                              given(o.format_flag) ? o.format : "");
  check_distinct_files({{"the case file", o.config, true},
                        {"--csv", o.csv},
                        {"--json", o.json},
                        {"--plot", o.plot}});
  if (!o.plot.empty()) {
    check_plot_file("--plot", o.plot);
    if (o.csv.empty() || o.csv == "-")
      throw Error("--plot " + o.plot + " needs --csv FILE (the plot is drawn from it)");
  }
  io::CaseSpec spec;
  const Case c = resolve_case(o.config, o.c, spec);
  warn_if_replaced_by_param(spec, o.key);
  // A case file's MMd_fraction (or --MMd-fraction) holds at every value, as in a study.
  if (spec.MMd_fraction) o.diagram.MMd_fraction = *spec.MMd_fraction;
  install_interrupt_handlers();
  ProgressLine line(stderr_is_terminal() && !o.quiet);
  o.diagram.cancelled = [] { return interrupted(); };
  const double scale = field->display_unit ? field->display_scale : 1.0;
  const std::string unit = field->display_unit ? field->display_unit : field->unit;
  const auto start = std::chrono::steady_clock::now();
  o.diagram.on_value = [&](int done, int total, double q) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
    line.update("oscidrum diagram: " + std::to_string(done) + "/" + std::to_string(total) +
                    " values, " + o.key + " = " + fmt(q / scale, 6) + " " + unit + ", ETA " +
                    duration(eta),
                done == total);
  };
  const Diagram d = bifurcation_diagram(c, o.diagram);
  line.clear();
  if (d.cancelled) {
    std::cerr << "oscidrum: interrupted after " << d.values.size() << " values; nothing written\n";
    return interrupted_exit_code();
  }
  if (!o.csv.empty()) write_output(o.csv, points_csv(d));
  if (!o.json.empty()) write_output(o.json, diagram_json(d, o).dump(2) + "\n");
  if (stdout_taken)
    ;  // the file named - was written there
  else if (o.format == "table")
    std::cout << table(d, *field, *quantity);
  else if (o.format == "csv")
    std::cout << points_csv(d);
  else if (o.format == "json")
    std::cout << diagram_json(d, o).dump(2) << "\n";
  std::cout.flush();
  if (!o.quiet) {
    std::map<std::string, int> verdicts;
    for (const DiagramValue& v : d.values) ++verdicts[v.motion.kind];
    std::string counts;
    for (const auto& [kind, n] : verdicts)
      counts += (counts.empty() ? "" : ", ") + std::to_string(n) + " " + kind;
    std::cerr << "oscidrum: " << d.values.size() << " values (" << counts << "), "
              << d.periods_integrated << " periods integrated in " << fmt(d.seconds, 3) << " s\n";
  }
  if (!o.plot.empty()) {
    const std::vector<std::string> args = {"oscidrum.plot", "diagram",       "--csv", o.csv,
                                           "--quantity",    o.plot_quantity, "--out", o.plot};
    if (run_python(args, "the diagram is in " + o.csv, {}, o.quiet) != 0)
      return interrupted() ? plot_interrupted("the diagram is in " + o.csv) : kExitCaseFailed;
  }
  return kExitOk;
}

}  // namespace

void add_diagram_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<DiagramCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "diagram",
      "The brute-force bifurcation diagram: the motion at steps + 1 values of a parameter, each "
      "started from the state the previous value ended in (a quasi-static sweep up, down or "
      "both, so that coexisting motions and hysteresis show); at each value the transient is "
      "discarded and the stroboscopic points (every output column once per excitation period) "
      "are kept with the motion's verdict (periodic with its period, converging, "
      "quasi_periodic, chaotic, undecided, gross_slip) and its largest Lyapunov exponent. Where "
      "shooting from the previous state finds no stable orbit, the transient from that state "
      "decides (never a start from rest, which could jump to another attractor). A start from "
      "rest (the first value) is run's: under numerics.start_ramp_periods, or retried with a "
      "20-period ramp when it loses contact; a value continued from the previous state runs "
      "without the ramp. docs/bifurcations.md.");
  sub->footer(
      "Examples:\n"
      "  oscidrum diagram --param soil.G --from 110 --to 140 --steps 30 --set soil.input=modulus "
      "--set trough.k=0.002 --set trough.a=0.601 --mu 0.7 --set roller.unbalance=0.22877 --f 25\n"
      "  oscidrum diagram case.toml --param roller.f --from 20 --to 40 --sweep both --csv d.csv "
      "--plot d.png --plot-quantity ddz_M\n"
      "--from/--to are in the unit the key is typed in (MN/m^2 for soil.G, else SI).\n"
      "Exit codes: 0 done (whatever the verdicts), 1 the plot failed, 2 bad input, 130 "
      "interrupted.");
  sub->add_option("case", o->config, "case file (TOML, see docs/config.md); default: none")
      ->type_name("CASE.toml");
  add_roller_flags(*sub, o->c);
  add_soil_flags(*sub, o->c);
  add_model_flags(*sub, o->c);
  add_set_flag(*sub, o->c);
  sub->add_option("--param", o->key, "the parameter to vary: a real key (oscidrum fields)")
      ->required()
      ->type_name("KEY");
  sub->add_option("--from", o->from_text, "smallest value")->required();
  sub->add_option("--to", o->to_text, "largest value (> --from)")->required();
  sub->add_option("--steps", o->diagram.steps,
                  "intervals between --from and --to: steps + 1 values per sweep (default 50)")
      ->check(CLI::Range(1, 100000));
  sub->add_option("--sweep", o->sweep,
                  "up (from --from to --to, default), down (from --to to --from) or both (up, "
                  "then down from where it ended)")
      ->check(CLI::IsMember({"up", "down", "both"}));
  sub->add_option("--discard", o->diagram.discard,
                  "excitation periods integrated and dropped at each value (default 200)")
      ->check(CLI::Range(0, 1000000));
  sub->add_option("--periods", o->diagram.periods,
                  "stroboscopic points kept at each value, and the periods its verdict examines "
                  "(default 400, the window simulate examines)")
      ->check(CLI::Range(20, 100000));
  o->output_flags.push_back(
      sub->add_option("--csv", o->csv, "write the stroboscopic points to FILE (one row per point)")
          ->type_name("FILE"));
  o->output_flags.push_back(
      sub->add_option("--json", o->json, "write the diagram to FILE (schema oscidrum-diagram/1)")
          ->type_name("FILE"));
  o->output_flags.push_back(
      sub->add_option("--plot", o->plot,
                      "draw the stroboscopic points of --plot-quantity against the parameter into "
                      "FILE (.png or .svg; needs --csv)")
          ->type_name("FILE"));
  sub->add_option("--plot-quantity", o->plot_quantity,
                  "the numeric output column --plot shows and the table summarises (default "
                  "ddx_M; oscidrum outputs lists them; not phase, which is a category)")
      ->type_name("COLUMN");
  o->format_flag = sub->add_option("--format", o->format,
                                   "stdout: table (default), csv, json or none; not with a file "
                                   "named - (stdout carries one "
                                   "output)")
                       ->check(CLI::IsMember({"table", "csv", "json", "none"}));
  sub->add_flag("--quiet,-q", o->quiet, "no progress line and no summary on stderr");
  sub->callback([o, &action] { action = [o] { return run(*o); }; });
}

}  // namespace oscidrum::cli
