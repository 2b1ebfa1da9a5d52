// oscidrum analyze: the paper's metrics for a measured (or any) acceleration record, to compare
// field measurements with simulations (paper Fig. 23). Uses analyze_record (record.hpp).
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/record.hpp"
#include "oscidrum_io/csv.hpp"
#include "oscidrum_io/json.hpp"
#include "output.hpp"

namespace oscidrum::cli {
namespace {

struct AnalyzeOptions {
  std::string file;
  double f = 39.0;
  std::string t_col = "t", x_col = "ddx_M", z_col = "ddz_M";
  int harmonics = 10;
  std::string format = "table";
};

int run(const AnalyzeOptions& o) {
  const io::NumericTable table = io::read_numeric_csv(o.file);
  auto column = [&](const std::string& name, const char* flag) -> const std::vector<double>& {
    const int c = table.find(name);
    if (c < 0) {
      std::string names;
      for (const std::string& h : table.header) names += (names.empty() ? "" : ", ") + h;
      throw Error(o.file + ": no column '" + name + "' (choose one with " + flag +
                  "); the header has: " + names);
    }
    return table.columns[static_cast<std::size_t>(c)];
  };
  const RecordMetrics m = analyze_record(column(o.t_col, "--t-col"), column(o.x_col, "--x-col"),
                                         column(o.z_col, "--z-col"), o.f, o.harmonics);
  if (o.format == "json") {
    std::cout << io::record_json(o.file, o.f, m);
    return kExitOk;
  }
  Summary s;
  s.section("Record");
  s.line("file", o.file);
  bool metrics_section = false;
  for (const RecordOutput& out : record_outputs()) {
    if (!is_scalar(out)) continue;  // the spectra are the table below
    if (is_acceleration_metric(out.name) && !metrics_section) {
      s.section("Metrics of the fitted periodic signal");
      metrics_section = true;
    }
    s.line(out.label, output_text(m, out));
  }
  TextTable t;
  t.header = {"n", "f [Hz]", "A(x_M'') [m/s^2]", "A(z_M'') [m/s^2]", "x / max", "z / max"};
  t.right = {true, true, true, true, true, true};
  double xmax = 0, zmax = 0;
  for (int n = 1; n <= o.harmonics; ++n) {
    xmax = std::max(xmax, m.ddx_harmonics[n].amplitude);
    zmax = std::max(zmax, m.ddz_harmonics[n].amplitude);
  }
  for (int n = 0; n <= o.harmonics; ++n)
    t.rows.push_back({std::to_string(n), fmt(n * o.f, 4), fmt(m.ddx_harmonics[n].amplitude, 5),
                      fmt(m.ddz_harmonics[n].amplitude, 5),
                      n ? fmt(m.ddx_harmonics[n].amplitude / xmax, 3) : "",
                      n ? fmt(m.ddz_harmonics[n].amplitude / zmax, 3) : ""});
  if (o.format == "csv") {
    std::cout << t.csv();
  } else {
    std::cout << s.text() << "\nHarmonics (normalised as in the paper's spectra):\n" << t.text();
  }
  return kExitOk;
}

}  // namespace

void add_analyze_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* sub = app.add_subcommand(
      "analyze",
      "The paper's metrics for a measured acceleration record. Reads a CSV with time [s] and the "
      "drum-centre accelerations x_M'', z_M'' [m/s^2] (z down), any sampling and length (at "
      "least one period), fits the harmonics n f by least squares and reports peaks, spectrum, "
      "the lag psi [rad] and the area of the z_M''(x_M'') figure [m^2/s^4] of the fitted "
      "periodic signal, to compare field data with `oscidrum run`.");
  sub->footer(
      "Columns are found by name, with or without a [unit] suffix (defaults: t, ddx_M, ddz_M, as "
      "in `oscidrum run --csv`).\nExamples:\n"
      "  oscidrum analyze field.csv --f 39 --t-col time --x-col ax --z-col az\n"
      "  oscidrum run --csv steady.csv && oscidrum analyze steady.csv");
  sub->add_option("record", o->file, "CSV file with a header line")->required();
  sub->add_option("--f", o->f, "excitation frequency [Hz] (default 39)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--t-col", o->t_col, "time column [s] (default t)");
  sub->add_option("--x-col", o->x_col, "horizontal acceleration column [m/s^2] (default ddx_M)");
  sub->add_option("--z-col", o->z_col,
                  "vertical acceleration column, down positive [m/s^2] (default ddz_M)");
  sub->add_option("--harmonics", o->harmonics, "harmonics n = 0 ... N fitted (default 10)")
      ->check(CLI::Range(2, 200));
  sub->add_option("--format", o->format, "table, csv (the spectrum) or json")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  sub->callback([o, &action] { action = [o] { return run(*o); }; });
}

}  // namespace oscidrum::cli
