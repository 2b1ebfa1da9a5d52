// oscidrum transmissibility: Appendix A, how much of the drum's motion reaches the frame.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "case_options.hpp"
#include "commands.hpp"
#include "oscidrum/transmissibility.hpp"
#include "oscidrum_io/csv.hpp"
#include "output.hpp"

namespace oscidrum::cli {
namespace {

struct TransmissibilityOptions {
  CaseOptions c;
  std::string format = "table";
};

int run(const TransmissibilityOptions& o) {
  io::CaseSpec spec;
  apply(o.c, spec);
  const Roller r = io::finalize(spec).roller;
  const double nu = 2.0 * M_PI * r.f;
  const double mf = r.m_f;
  const Transmissibility t = transmissibility(r.kd, r.cd, mf, nu);
  // The paper's Appendix A values, shown when the inputs are the paper's.
  const Roller paper;
  const bool is_paper = r.kd == paper.kd && r.cd == paper.cd && r.f == paper.f && mf == paper.m_f;
  struct Row {
    const char* name;
    const char* unit;
    const char* meaning;
    double value;
    const char* paper;
  };
  const Row rows[] = {
      {"omega", "rad/s", "natural circular frequency sqrt(kd/m_f)", t.omega, "38.1"},
      {"f_n", "Hz", "natural frequency omega/(2 pi)", t.omega / (2.0 * M_PI), ""},
      {"zeta", "-", "damping ratio cd/(2 m_f omega)", t.zeta, "0.014"},
      {"nu/omega", "-", "excitation over natural frequency", t.ratio, "6.4"},
      {"Tp", "-", "displacement transmissibility (40)", t.Tp, "0.025"},
  };
  if (o.format == "json") {
    nlohmann::ordered_json j = {
        {"schema", "oscidrum-transmissibility/1"},
        {"inputs", {{"kd", r.kd}, {"cd", r.cd}, {"m_f", mf}, {"f", r.f}, {"nu", nu}}},
        {"omega", t.omega},
        {"f_n", t.omega / (2.0 * M_PI)},
        {"zeta", t.zeta},
        {"ratio", t.ratio},
        {"Tp", t.Tp}};
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }
  TextTable table;
  table.header = {"quantity", "value", "unit", "meaning"};
  table.right = {false, true, false, false};
  if (is_paper) table.header.push_back("paper");
  for (const Row& row : rows) {
    std::vector<std::string> cells = {
        row.name, o.format == "csv" ? io::format_double(row.value) : fmt(row.value, 5), row.unit,
        row.meaning};
    if (is_paper) cells.emplace_back(row.paper);
    table.rows.push_back(cells);
  }
  if (o.format == "csv") {
    std::cout << table.csv();
  } else {
    std::cout << "Appendix A: frame of mass m_f = " << fmt(mf)
              << " kg on the suspension kd = " << fmt(r.kd) << " N/m, cd = " << fmt(r.cd)
              << " N s/m, base excitation at f = " << fmt(r.f) << " Hz (nu = " << fmt(nu, 5)
              << " rad/s)\n\n"
              << table.text()
              << "\nTp << 1: the frame hardly follows the drum's oscillation, which is why the "
                 "model leaves the frame out.\n";
  }
  return kExitOk;
}

}  // namespace

void add_transmissibility_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<TransmissibilityOptions>();
  CLI::App* sub = app.add_subcommand(
      "transmissibility",
      "Appendix A: how much of the drum's oscillation reaches the frame. The frame (mass m_f) on "
      "the drum suspension (kd, cd) excited at the drum's "
      "frequency f: natural circular frequency omega [rad/s], damping ratio zeta [-], frequency "
      "ratio nu/omega [-] and the absolute displacement transmissibility Tp (40) [-].");
  sub->footer(
      "Examples:\n"
      "  oscidrum transmissibility                 the paper's values (Tp = 0.025)\n"
      "  oscidrum transmissibility --mf 3000 --kd 5e6 --format json");
  add_roller_flags(*sub, o->c, {"roller.m_f", "roller.kd", "roller.cd", "roller.f"});
  add_set_flag(*sub, o->c, {"roller.m_f", "roller.kd", "roller.cd", "roller.f"});
  sub->add_option("--format", o->format, "table, csv or json")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  sub->callback([o, &action] { action = [o] { return run(*o); }; });
}

}  // namespace oscidrum::cli
