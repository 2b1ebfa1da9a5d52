// oscidrum fields: every config key with unit, default, rule and description, from the one
// field table (fields()) and the two shorthand keys of the config reader. docs/config.md holds
// the Markdown output; a test keeps them equal.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/version.hpp"
#include "oscidrum_io/case_spec.hpp"
#include "output.hpp"

namespace oscidrum::cli {
namespace {

int run(const std::string& format) {
  const Case defaults;
  TextTable fields_table, extra_table;
  fields_table.header = {"key", "unit", "default", "rule", "description"};
  for (const Field& f : fields())
    fields_table.rows.push_back(
        {f.key, f.unit, format_field(defaults, f), field_rule(f), f.description});
  extra_table.header = {"key", "unit", "default", "rule", "description"};
  for (const io::ExtraKey& e : io::extra_keys())
    extra_table.rows.push_back({e.key, e.unit, "(not set)", e.rule, e.description});

  if (format == "json") {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const Field& f : fields()) {
      nlohmann::ordered_json e = {{"key", f.key},
                                  {"unit", f.unit},
                                  {"rule", field_rule(f)},
                                  {"description", f.description},
                                  {"shorthand", false}};
      switch (f.type) {
        case FieldType::boolean:
          e["type"] = "boolean", e["default"] = f.get(defaults) != 0.0;
          break;
        case FieldType::choice:
          e["type"] = "choice", e["default"] = format_field(defaults, f);
          break;
        case FieldType::integer:
          e["type"] = "integer", e["default"] = static_cast<long long>(f.get(defaults));
          break;
        case FieldType::real:
          e["type"] = "real", e["default"] = f.get(defaults);
          break;
      }
      list.push_back(e);
    }
    for (const io::ExtraKey& x : io::extra_keys())
      list.push_back({{"key", x.key},
                      {"unit", x.unit},
                      {"rule", x.rule},
                      {"description", x.description},
                      {"shorthand", true},
                      {"type", "real"},
                      {"default", nullptr}});
    const nlohmann::ordered_json j = {{"schema", "oscidrum-fields/1"},
                                      {"oscidrum_version", version},
                                      {"fields", std::move(list)}};
    std::cout << j.dump(2) << "\n";
  } else if (format == "csv") {
    TextTable all = fields_table;
    all.rows.insert(all.rows.end(), extra_table.rows.begin(), extra_table.rows.end());
    std::cout << all.csv();
  } else if (format == "markdown") {
    std::cout << fields_table.markdown()
              << "\nShorthand keys (resolved when the case is built; "
                 "see below):\n\n"
              << extra_table.markdown();
  } else {
    std::cout << fields_table.text() << "\nShorthand keys:\n"
              << extra_table.text()
              << "\nUnits are SI. In a case file, key \"soil.G\" is G = ... in section [soil].\n";
  }
  return kExitOk;
}

}  // namespace

void add_fields_command(CLI::App& app, Action& action) {
  auto format = std::make_shared<std::string>("table");
  CLI::App* sub = app.add_subcommand(
      "fields",
      "List every config key with unit, default and rule. Every parameter a case file, a sweep or "
      "--set accepts: key, SI unit, default (the "
      "paper's roller), allowed values and meaning. The same table is in docs/config.md.");
  sub->alias("params");
  sub->footer(
      "Examples:\n"
      "  oscidrum fields\n"
      "  oscidrum fields --format markdown     (the table of docs/config.md)");
  sub->add_option("--format", *format, "table, markdown, csv or json")
      ->check(CLI::IsMember({"table", "markdown", "csv", "json"}));
  sub->callback([format, &action] { action = [format] { return run(*format); }; });
}

}  // namespace oscidrum::cli
