// oscidrum run: one case from rest to its steady state.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "case_options.hpp"
#include "commands.hpp"
#include "flags.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/simulate.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/csv.hpp"
#include "oscidrum_io/files.hpp"
#include "oscidrum_io/json.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "run_summary.hpp"
#include "terminal.hpp"

namespace oscidrum::cli {
namespace {

struct RunOptions {
  std::string config;
  CaseOptions c;
  std::string csv, json, events, plot_dir, format = "table";
  // Given-but-empty names are errors (an empty --csv '' was silently ignored).
  CLI::Option *config_flag = nullptr, *csv_flag = nullptr, *json_flag = nullptr,
              *events_flag = nullptr, *plot_flag = nullptr, *format_flag = nullptr;
  int harmonics = 10;
  bool quiet = false, print_config = false;
};

// The steady state goes to its file or stdout as it is formatted, never whole in memory.
void write_steady_csv(const std::string& path, const Result& r) {
  if (path == "-") {
    io::write_steady_state_csv(std::cout, r);
    std::cout.flush();
  } else {
    io::write_file_atomic(path, [&r](std::ostream& out) { io::write_steady_state_csv(out, r); });
  }
}

int run(const RunOptions& o) {
  if (given(o.config_flag) && o.config.empty())
    throw Error("the case file name is empty; give a file, or none for the paper's defaults");
  if (given(o.csv_flag)) check_output_file("--csv", o.csv);
  if (given(o.json_flag)) check_output_file("--json", o.json);
  if (given(o.events_flag)) check_output_file("--events", o.events);
  check_distinct_files({{"the case file", o.config, true},
                        {"--csv", o.csv},
                        {"--json", o.json},
                        {"--events", o.events}});
  if (given(o.plot_flag) && o.plot_dir.empty())
    throw Error("--plot needs a directory name; got an empty one");
  // Standard output carries one thing: a file named - replaces the --format output; two of them
  // (or one and an explicit --format) would interleave into something no reader can parse.
  // (With --plot, --csv - names no file: see below.)
  const bool stdout_taken = file_takes_stdout({{"--csv", o.plot_dir.empty() ? o.csv : ""},
                                               {"--json", o.plot_dir.empty() ? o.json : ""},
                                               {"--events", o.plot_dir.empty() ? o.events : ""}},
                                              given(o.format_flag) ? o.format : "");
  io::CaseSpec spec;
  const Case c = resolve_case(o.config, o.c, spec);
  if (o.print_config) {
    std::cout << io::case_to_toml(c);
    return kExitOk;
  }
  check_harmonics(o.harmonics, c.numerics.samples_per_period);

  install_interrupt_handlers();
  ProgressLine line(stderr_is_terminal() && !o.quiet);
  const Model model(c);
  const Result result = simulate(
      model,
      [&](int period, double change) {
        line.update("oscidrum run: period " + std::to_string(period) + " of at most " +
                    std::to_string(c.numerics.max_periods) + ", change " + fmt(change, 3) +
                    " (steady below " + fmt(c.numerics.steady_tol, 3) + ")");
        return !interrupted();
      },
      [] { return interrupted(); });
  line.clear();
  if (interrupted()) {
    std::cerr << "oscidrum: interrupted after " << result.diagnostics.periods_simulated
              << " periods; nothing written\n";
    return interrupted_exit_code();
  }

  std::unique_ptr<Metrics> metrics;
  if (ok(result.status) && result.samples.size() > 0) {  // only a steady state has metrics
    try {
      metrics = std::make_unique<Metrics>(compute_metrics(model, result, o.harmonics));
    } catch (const Error& e) {
      warn(std::string("no metrics: ") + e.what());
    }
  }
  if (interrupted()) {  // while the metrics were computed: nothing is written
    std::cerr << "oscidrum: interrupted; nothing written\n";
    return interrupted_exit_code();
  }
  std::string csv_path = o.csv, json_path = o.json;
  if (!o.plot_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.plot_dir, ec);
    if (ec) throw Error("cannot create --plot directory " + o.plot_dir + ": " + ec.message());
    if (csv_path.empty() || csv_path == "-") csv_path = o.plot_dir + "/steady_state.csv";
    if (json_path.empty() || json_path == "-") json_path = o.plot_dir + "/summary.json";
  }
  const std::string json_text = io::case_json(spec, c, result, metrics.get(), o.config);
  if (!csv_path.empty()) write_steady_csv(csv_path, result);
  if (!json_path.empty()) write_output(json_path, json_text);
  if (!o.events.empty()) {
    std::ostringstream ev;
    io::write_events_csv(ev, result);
    write_output(o.events, ev.str());
  }
  if (stdout_taken)
    ;  // the file named - was written there
  else if (o.format == "table")
    std::cout << run_summary(spec, c, result, metrics.get(), o.config);
  else if (o.format == "json")
    std::cout << json_text;
  else
    write_steady_csv("-", result);
  std::cout.flush();

  if (!ok(result.status) && !o.quiet)
    std::cerr << "oscidrum: case ended with status " << to_string(result.status) << ": "
              << result.message << "\n";
  // A run that ended before its sampling (gross slip, contact lost) has nothing to draw: said so,
  // with the files that were written (the plotting module failed on the empty CSV, and the
  // message asked whether the Python package was installed).
  if (!o.plot_dir.empty() && result.samples.size() == 0) {
    std::cerr << "oscidrum: no plots: the run ended (" << to_string(result.status)
              << ") before any sampled period; " << csv_path << " and " << json_path
              << " are written\n";
  } else if (!o.plot_dir.empty() && !run_plot(csv_path, json_path, o.plot_dir, o.quiet)) {
    return interrupted() ? plot_interrupted("the data are in " + csv_path + " and " + json_path)
                         : kExitCaseFailed;
  }
  if (interrupted()) return interrupted_exit_code();  // during the writing: the files are whole
  return ok(result.status) ? kExitOk : kExitCaseFailed;
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand(
      "run",
      "Simulate one case to its steady state and print its metrics. Starting from rest at the "
      "bottom of the trough, it finds the periodic steady state (by default by shooting: Newton's "
      "method on the period map after a short transient, falling back to the paper's method when "
      "that fails; --set numerics.method=transient integrates until the response repeats from one "
      "excitation period to the next, as the paper does), then samples it and computes its "
      "metrics: "
      "peaks of the drum-centre accelerations x_M'', z_M'' [m/s^2], their harmonics n f, the lag "
      "between torque and drum rotation [pi rad], the x_M''-z_M'' lag psi [rad], the area of the "
      "z_M''(x_M'') figure [m^2/s^4] and the stick/slip fractions. Defaults: the paper's roller "
      "(HAMM HD+ 90 VO) on Table 2 soil at G = 25 MN/m^2, circular trough R = 0.606 m, mu = 0.5, "
      "no driving torque.");
  sub->footer(
      "Examples:\n"
      "  oscidrum run\n"
      "  oscidrum run --G 40 --pure-rolling --MMd-fraction 0.05\n"
      "  oscidrum run examples/case.toml --mu 0.4 --csv steady.csv --json summary.json\n"
      "  oscidrum run --G 27 --soil-formula --set numerics.samples_per_period=512\n"
      "Settings apply in this order: the case file, the flags, then each --set.\n"
      "Exit codes: 0 steady state, 1 another status (see the output), 2 bad input, 130 "
      "interrupted.");
  o->config_flag =
      sub->add_option("case", o->config, "case file (TOML, see docs/config.md); default: none")
          ->type_name("CASE.toml");
  add_roller_flags(*sub, o->c);
  add_soil_flags(*sub, o->c);
  add_model_flags(*sub, o->c);
  add_set_flag(*sub, o->c);
  const char* out = "Output";
  o->csv_flag = sub->add_option("--csv", o->csv,
                                "write the sampled steady state to FILE ('-': stdout), columns of "
                                "docs/csv-columns.md")
                    ->type_name("FILE")
                    ->group(out);
  o->json_flag =
      sub->add_option("--json", o->json, "write a JSON summary to FILE (docs/outputs.md)")
          ->type_name("FILE")
          ->group(out);
  o->events_flag =
      sub->add_option("--events", o->events, "write the event list (t[s],kind,from,to) to FILE")
          ->type_name("FILE")
          ->group(out);
  o->format_flag = sub->add_option("--format", o->format,
                                   "what to print on stdout: table (a summary), csv (the "
                                   "steady state) or json (the summary); nothing when --csv, "
                                   "--json or --events is - (standard output)")
                       ->check(CLI::IsMember({"table", "csv", "json"}))
                       ->group(out);
  sub->add_option("--harmonics", o->harmonics, "harmonics n = 0 ... N in the metrics (default 10)")
      ->check(CLI::Range(0, 100000))
      ->group(out);
  o->plot_flag =
      sub->add_option(
             "--plot", o->plot_dir,
             "plot into DIR with the Python package (oscidrum.plot, run by the interpreter "
             "it is installed for: docs/python.md); writes the CSV and JSON there unless "
             "--csv/--json name files")
          ->type_name("DIR")
          ->group(out);
  sub->add_flag("--print-config", o->print_config,
                "print the resolved case as a TOML case file (every key) and exit")
      ->group(out);
  sub->add_flag("--quiet,-q", o->quiet, "no progress line and no status note on stderr")
      ->group(out);
  sub->callback([o, &action] { action = [o] { return run(*o); }; });
}

}  // namespace oscidrum::cli
