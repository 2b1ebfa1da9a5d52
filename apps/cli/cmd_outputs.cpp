// oscidrum outputs: every output (statuses, steady-state columns, diagnostics, metrics) with its
// unit and description, from the output table (oscidrum/output_table.hpp). docs/outputs.md,
// docs/csv-columns.md and the README hold the Markdown output between markers; a test keeps them
// equal.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "oscidrum/output_table.hpp"
#include "output.hpp"

namespace oscidrum::cli {
namespace {

struct OutputsOptions {
  std::string group = "all";
  std::string format = "table";
};

std::string code(const std::string& s) { return "`" + s + "`"; }

TextTable statuses_table(bool markdown) {
  TextTable t;
  t.header = {"status", "meaning"};
  for (const StatusInfo& s : statuses())
    t.rows.push_back({markdown ? code(s.name) : s.name, s.description});
  return t;
}

TextTable samples_table(bool markdown) {
  TextTable t;
  t.header = {"column", "unit", "meaning"};
  for (const SampleOutput& c : sample_outputs()) {
    const std::string header = std::string(c.name) + "[" + c.unit + "]";
    t.rows.push_back({markdown ? code(header) : header, c.unit, c.description});
  }
  return t;
}

TextTable diagnostics_table(bool markdown) {
  TextTable t;
  t.header = {"key", "unit", "type", "meaning"};
  for (const DiagnosticOutput& d : diagnostic_outputs())
    t.rows.push_back({markdown ? code(d.name) : d.name, d.unit,
                      is_integer(d) ? "integer"
                      : is_text(d)  ? "text"
                                    : "real",
                      d.description});
  return t;
}

// Simulation metrics and record metrics in one table: which command computes each.
TextTable metrics_table(bool markdown) {
  TextTable t;
  t.header = {"key", "unit", "run", "analyze", "meaning"};
  auto name = [markdown](const char* n, bool scalar) {
    const std::string s = markdown ? code(n) : n;
    if (scalar) return s;
    const std::string columns = spectrum_prefix(n) + "_A1";
    return s + " (CSV " + (markdown ? code(columns) : columns) + " ...)";
  };
  for (const MetricOutput& m : metric_outputs())
    t.rows.push_back({name(m.name, is_scalar(m)), m.unit, "yes",
                      is_acceleration_metric(m.name) ? "yes" : "", m.description});
  for (const RecordOutput& m : record_outputs())
    if (!is_acceleration_metric(m.name))
      t.rows.push_back({name(m.name, is_scalar(m)), m.unit, "", "yes", m.description});
  return t;
}

std::string text(const TextTable& t, const std::string& format) {
  if (format == "markdown") return t.markdown();
  if (format == "csv") return t.csv();
  return t.text();
}

template <class Table>
nlohmann::ordered_json json_rows(const Table& table) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const auto& o : table)
    a.push_back({{"name", o.name},
                 {"unit", o.unit},
                 {"type", is_integer(o)  ? "integer"
                          : is_scalar(o) ? "real"
                          : is_text(o)   ? "text"
                                         : "array"},
                 {"label", o.label},
                 {"description", o.description}});
  return a;
}

int run(const OutputsOptions& o) {
  const bool markdown = o.format == "markdown";
  if (o.format == "json") {
    nlohmann::ordered_json j;
    j["schema"] = "oscidrum-outputs/1";
    nlohmann::ordered_json st = nlohmann::ordered_json::array();
    for (const StatusInfo& s : statuses())
      st.push_back({{"name", s.name}, {"description", s.description}});
    j["statuses"] = st;
    j["samples"] = json_rows(sample_outputs());
    j["diagnostics"] = json_rows(diagnostic_outputs());
    j["metrics"] = json_rows(metric_outputs());
    j["record_metrics"] = json_rows(record_outputs());
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }
  const std::pair<const char*, TextTable> groups[] = {
      {"statuses", statuses_table(markdown)},
      {"samples", samples_table(markdown)},
      {"diagnostics", diagnostics_table(markdown)},
      {"metrics", metrics_table(markdown)},
  };
  bool first = true;
  for (const auto& [name, table] : groups) {
    if (o.group != "all" && o.group != name) continue;
    if (o.group == "all") std::cout << (first ? "" : "\n") << name << ":\n\n";
    std::cout << text(table, o.format);
    first = false;
  }
  return kExitOk;
}

}  // namespace

void add_outputs_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<OutputsOptions>();
  CLI::App* sub = app.add_subcommand(
      "outputs",
      "List every output with unit and meaning: the statuses a run ends with, the columns of the "
      "steady-state CSV, the diagnostics and the metrics (of `run` and of `analyze`). The same "
      "tables are in docs/outputs.md.");
  sub->footer(
      "Examples:\n"
      "  oscidrum outputs\n"
      "  oscidrum outputs --group metrics --format markdown   (a table of docs/outputs.md)");
  sub->add_option("--group", o->group, "all, statuses, samples, diagnostics or metrics")
      ->check(CLI::IsMember({"all", "statuses", "samples", "diagnostics", "metrics"}));
  sub->add_option("--format", o->format, "table, markdown, csv or json (json: every group)")
      ->check(CLI::IsMember({"table", "markdown", "csv", "json"}));
  sub->callback([o, &action] { action = [o] { return run(*o); }; });
}

}  // namespace oscidrum::cli
