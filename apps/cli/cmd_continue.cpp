// oscidrum continue: a branch of periodic orbits followed through a parameter (pseudo-arclength
// continuation), with the Floquet multipliers and CCC metrics of every orbit and the bifurcations
// on the branch (docs/bifurcations.md).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "case_options.hpp"
#include "commands.hpp"
#include "flags.hpp"
#include "oscidrum/branch.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/text.hpp"
#include "oscidrum_io/branch_hdf5.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/csv.hpp"
#include "oscidrum_io/files.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "terminal.hpp"

namespace oscidrum::cli {
namespace {

struct ContinueOptions {
  std::string config;
  CaseOptions c;
  std::string key, csv, json, hdf5, bifurcations, plot, plot_metric = "area", format = "table";
  CLI::Option *plot_metric_flag = nullptr, *format_flag = nullptr;
  std::vector<CLI::Option*> output_flags;  // --csv, --bifurcations, --json, --hdf5, --plot
  std::string from_text, to_text;
  BranchOptions branch;
  bool quiet = false;
};

std::string cell(double v) { return io::format_double_short(v); }

// The branch and the period-2p branches switched onto at its period doublings, depth first:
// (branch, index of its parent or -1). Index 0 is the branch followed from --from.
std::vector<std::pair<const Branch*, int>> all_branches(const Branch& b) {
  std::vector<std::pair<const Branch*, int>> out = {{&b, -1}};
  for (std::size_t i = 0; i < out.size(); ++i)
    for (const Branch& c : out[i].first->children) out.push_back({&c, static_cast<int>(i)});
  return out;
}

// One CSV row per point: the parameter, the orbit's stability and multipliers, every metric.
std::string points_csv(const Branch& root) {
  const auto branches = all_branches(root);
  std::size_t n_mu = 0;
  for (const auto& [b, parent] : branches)
    for (const BranchPoint& p : b->points) n_mu = std::max(n_mu, p.floquet.multipliers.size());
  std::string out = "branch[-],point[-]," + root.key + "[" + root.unit +
                    "],arclength[-],multiplicity[-],stable[-],unstable[-],max_modulus[-],dq_ds[-],"
                    "min_N[N],corrector_iterations[-],sequence[-]";
  for (std::size_t i = 1; i <= n_mu; ++i)
    out += ",mu" + std::to_string(i) + "_re[-],mu" + std::to_string(i) + "_im[-]";
  // The harmonics' amplitudes A_1 ... A_H of each spectrum (H = --harmonics), as in a sweep's CSV.
  std::size_t n_harmonics = 0;
  for (const auto& [b, parent] : branches)
    n_harmonics =
        std::max(n_harmonics, harmonics_held(b->points, [](const BranchPoint& p) -> const Metrics& {
                   return p.metrics;
                 }));
  for (const MetricOutput& o : metric_outputs())
    if (std::holds_alternative<double Metrics::*>(o.member))
      out += std::string(",") + o.name + "[" + o.unit + "]";
  for (const MetricOutput& o : metric_outputs())
    if (!std::holds_alternative<double Metrics::*>(o.member))
      for (std::size_t n = 1; n <= n_harmonics; ++n)
        out += "," + spectrum_prefix(o.name) + "_A" + std::to_string(n) + "[" + o.unit + "]";
  out += "\n";
  for (std::size_t index = 0; index < branches.size(); ++index) {
    const Branch& b = *branches[index].first;
    for (std::size_t k = 0; k < b.points.size(); ++k) {
      const BranchPoint& p = b.points[k];
      out += std::to_string(index) + "," + std::to_string(k) + "," + cell(p.parameter) + "," +
             cell(p.arclength) + "," + std::to_string(p.multiplicity) + "," +
             (p.stable() ? "1" : "0") + "," + std::to_string(p.unstable) + "," +
             cell(p.floquet.max_modulus) + "," + cell(p.dq_ds) + "," + cell(p.min_N) + "," +
             std::to_string(p.corrector_iterations) + "," + io::csv_quote(p.sequence);
      for (std::size_t i = 0; i < n_mu; ++i) {
        const std::complex<double> m =
            i < p.floquet.multipliers.size() ? p.floquet.multipliers[i] : NAN;
        out.append(",").append(cell(m.real())).append(",").append(cell(m.imag()));
      }
      for (const MetricOutput& o : metric_outputs())
        if (std::holds_alternative<double Metrics::*>(o.member))
          out.append(",").append(cell(scalar_value(p.metrics, o)));
      for (const MetricOutput& o : metric_outputs())
        if (!std::holds_alternative<double Metrics::*>(o.member))
          for (std::size_t n = 1; n <= n_harmonics; ++n)
            out.append(",").append(cell(harmonic_amplitude(p.metrics, o, n)));
      out += "\n";
    }
  }
  return out;
}

// --plot-metric before the branch is followed: a numeric column of points_csv (a metric, or one
// of the orbit's own columns), never found missing after the whole run.
void check_plot_metric(const std::string& name, int harmonics) {
  static const char* const kOwn[] = {"arclength", "multiplicity",        "stable",
                                     "unstable",  "max_modulus",         "dq_ds",
                                     "min_N",     "corrector_iterations"};
  for (const char* own : kOwn)
    if (name == own) return;
  std::string metrics;
  for (const MetricOutput& m : metric_outputs())
    if (std::holds_alternative<double Metrics::*>(m.member)) {
      if (name == m.name) return;
      metrics += (metrics.empty() ? "" : ", ") + std::string(m.name);
    }
  // A harmonic's amplitude of a spectrum with --harmonics H: ddx_A1 ... ddx_AH (they were refused
  // though the CSV holds them).
  std::string amplitudes;
  for (const MetricOutput& m : metric_outputs())
    if (!std::holds_alternative<double Metrics::*>(m.member)) {
      const std::string prefix = spectrum_prefix(m.name) + "_A";
      amplitudes += (amplitudes.empty() ? "" : ", ") + prefix + "1 ... " + prefix + "H";
      if (name.starts_with(prefix) && name.size() > prefix.size() &&
          name.find_first_not_of("0123456789", prefix.size()) == std::string::npos &&
          name.size() - prefix.size() <= 6) {
        const int n = std::stoi(name.substr(prefix.size()));
        if (n >= 1 && n <= harmonics) return;
        throw Error("--plot-metric " + name + ": the branch CSV holds the amplitudes " + prefix +
                    "1 ... " + prefix + std::to_string(std::max(harmonics, 0)) + " (--harmonics " +
                    std::to_string(harmonics) + ")");
      }
    }
  // A multiplier's part: mu1_re, mu2_im, ...
  const std::size_t us = name.rfind('_');
  if (name.starts_with("mu") && us != std::string::npos && us > 2 &&
      (name.substr(us) == "_re" || name.substr(us) == "_im") &&
      name.find_first_not_of("0123456789", 2) == us)
    return;
  throw Error("--plot-metric " + name +
              ": not a numeric column of the branch CSV (docs/bifurcations.md): a metric (" +
              metrics +
              "), max_modulus, min_N, dq_ds, ..., a harmonic's amplitude with --harmonics H (" +
              amplitudes + ") or a multiplier's part, mu1_re, mu1_im");
}

std::string bifurcations_csv(const Branch& root) {
  const auto branches = all_branches(root);
  std::string out = "branch[-],kind[-]," + root.key + "[" + root.unit + "],tolerance[" + root.unit +
                    "],after_point[-],multiplier_re[-],multiplier_im[-],child_branch[-],"
                    "description[-]\n";
  for (std::size_t index = 0; index < branches.size(); ++index) {
    const auto& [b, parent] = branches[index];
    // The children of branch `index` are numbered after it in all_branches' order.
    std::size_t first_child = 0;
    for (std::size_t j = 0; j < branches.size(); ++j)
      if (branches[j].second == static_cast<int>(index)) {
        first_child = j;
        break;
      }
    for (const Bifurcation& f : b->bifurcations)
      out += std::to_string(index) + "," + to_string(f.kind) + "," + cell(f.parameter) + "," +
             cell(f.tolerance) + "," + std::to_string(f.after_point) + "," +
             cell(f.multiplier.real()) + "," + cell(f.multiplier.imag()) + "," +
             (f.child >= 0 ? std::to_string(first_child + static_cast<std::size_t>(f.child))
                           : std::string("-1")) +
             "," + io::csv_quote(f.description) + "\n";
  }
  return out;
}

nlohmann::ordered_json branch_json(const Branch& b) {
  nlohmann::ordered_json j = {{"schema", "oscidrum-branch/1"},
                              {"key", b.key},
                              {"unit", b.unit},
                              {"multiplicity", b.multiplicity},
                              {"end", to_string(b.end)},
                              {"message", b.message},
                              {"period_maps", b.period_maps},
                              {"seconds", b.seconds}};
  nlohmann::ordered_json bifs = nlohmann::json::array();
  for (const Bifurcation& f : b.bifurcations)
    bifs.push_back({{"kind", to_string(f.kind)},
                    {"parameter", f.parameter},
                    {"tolerance", f.tolerance},
                    {"after_point", f.after_point},
                    {"multiplier", {f.multiplier.real(), f.multiplier.imag()}},
                    {"child", f.child},
                    {"description", f.description}});
  j["bifurcations"] = bifs;
  nlohmann::ordered_json points = nlohmann::json::array();
  for (const BranchPoint& p : b.points) {
    nlohmann::ordered_json mu = nlohmann::json::array();
    for (const auto& m : p.floquet.multipliers) mu.push_back({m.real(), m.imag()});
    nlohmann::ordered_json metrics;
    for (const MetricOutput& o : metric_outputs()) {
      if (std::holds_alternative<double Metrics::*>(o.member)) {
        metrics[o.name] = scalar_value(p.metrics, o);
      } else {  // a spectrum: {n, amplitude, phase} for n = 0 ... H, as `run --json` has it
        nlohmann::ordered_json a = nlohmann::json::array();
        const Spectrum& h = p.metrics.*std::get<Spectrum Metrics::*>(o.member);
        for (std::size_t n = 0; n < h.size(); ++n)
          a.push_back({{"n", n}, {"amplitude", h[n].amplitude}, {"phase", h[n].phase}});
        metrics[o.name] = a;
      }
    }
    points.push_back({{"parameter", p.parameter},
                      {"arclength", p.arclength},
                      {"multiplicity", p.multiplicity},
                      {"stable", p.stable()},
                      {"unstable", p.unstable},
                      {"multipliers", mu},
                      {"dq_ds", p.dq_ds},
                      {"min_N", p.min_N},
                      {"sequence", p.sequence},
                      {"metrics", metrics}});
  }
  j["points"] = points;
  nlohmann::ordered_json children = nlohmann::json::array();
  for (const Branch& c : b.children) children.push_back(branch_json(c));
  j["children"] = children;
  return j;
}

std::string table(const Branch& root, const Field& f) {
  const double scale = f.display_unit ? f.display_scale : 1.0;
  const std::string unit = f.display_unit ? f.display_unit : f.unit;
  std::string out;
  const auto branches = all_branches(root);
  for (std::size_t index = 0; index < branches.size(); ++index) {
    const auto& [b, parent] = branches[index];
    if (index > 0)
      out += "\nbranch " + std::to_string(index) + ": period " + std::to_string(b->multiplicity) +
             (b->multiplicity < branches[static_cast<std::size_t>(parent)].first->multiplicity
                  ? " T, the orbit branch " + std::to_string(parent) +
                        " shrank onto at a period doubling ("
                  : " T, born at a period doubling of branch " + std::to_string(parent) + " (") +
             to_string(b->end) + ": " + b->message + ")\n";
    TextTable t;
    t.header = {"point",          root.key + " [" + unit + "]", "stable",  "max |mu|",
                "area [m^2/s^4]", "z_M'' max [m/s^2]",          "sequence"};
    t.right = {true, true, false, true, true, true, false};
    for (std::size_t k = 0; k < b->points.size(); ++k) {
      const BranchPoint& p = b->points[k];
      t.rows.push_back({std::to_string(k), fmt(p.parameter / scale, 6), p.stable() ? "yes" : "no",
                        fmt(p.floquet.max_modulus, 5), fmt(p.metrics.area, 5),
                        fmt(p.metrics.ddz_max, 5), p.sequence});
    }
    out += t.text();
    for (const Bifurcation& x : b->bifurcations)
      out += std::string(to_string(x.kind)) + " at " + root.key + " = " +
             fmt(x.parameter / scale, 8) + " +- " + fmt(x.tolerance / scale, 2) + " " + unit +
             ": " + x.description + "\n";
  }
  return out;
}

int run(ContinueOptions o) {
  const Field* field = find_field(o.key);
  if (!field) throw Error("--param: unknown key '" + o.key + "' (oscidrum fields lists them)");
  o.branch.key = o.key;
  o.branch.from = key_flag_value(*field, "--from", o.from_text);
  o.branch.to = key_flag_value(*field, "--to", o.to_text);
  // A file name given empty (--csv "") is refused, as run and sweep refuse it: it wrote nothing.
  for (const CLI::Option* flag : o.output_flags)
    if (given(flag) && flag->as<std::string>().empty()) check_output_file(flag->get_name(), "");
  if (!o.csv.empty()) check_output_file("--csv", o.csv);
  if (!o.json.empty()) check_output_file("--json", o.json);
  if (!o.bifurcations.empty()) check_output_file("--bifurcations", o.bifurcations);
  if (!o.hdf5.empty()) check_output_file("--hdf5", o.hdf5, false, true);
  check_distinct_files({{"the case file", o.config, true},
                        {"--csv", o.csv},
                        {"--json", o.json},
                        {"--bifurcations", o.bifurcations},
                        {"--hdf5", o.hdf5},
                        {"--plot", o.plot}});
  // Standard output carries one thing (the table printed after a --csv - made it unreadable).
  const bool stdout_taken =
      file_takes_stdout({{"--csv", o.csv}, {"--json", o.json}, {"--bifurcations", o.bifurcations}},
                        given(o.format_flag) ? o.format : "");
  if (!o.plot.empty()) {
    check_plot_file("--plot", o.plot);
    if (o.csv.empty() || o.csv == "-")
      throw Error("--plot " + o.plot + " needs --csv FILE (the plot is drawn from it)");
    check_plot_metric(o.plot_metric, o.branch.harmonics);
  } else if (given(o.plot_metric_flag)) {
    throw Error("--plot-metric " + o.plot_metric +
                " needs --plot FILE (the figure it is drawn in)");
  }
  io::CaseSpec spec;
  const Case c = resolve_case(o.config, o.c, spec);
  warn_if_replaced_by_param(spec, o.key);
  // A case file's MMd_fraction (or --MMd-fraction) holds at every value, as in a study: MMd
  // follows the M0 in effect there (roller.M0, or roller.f with roller.unbalance).
  if (spec.MMd_fraction) o.branch.MMd_fraction = *spec.MMd_fraction;
  check_harmonics(o.branch.harmonics, c.numerics.samples_per_period);
  install_interrupt_handlers();
  ProgressLine line(stderr_is_terminal() && !o.quiet);
  o.branch.cancelled = [] { return interrupted(); };
  const double scale = field->display_unit ? field->display_scale : 1.0;
  const std::string unit = field->display_unit ? field->display_unit : field->unit;
  o.branch.on_point = [&](int n, double q) {
    line.update("oscidrum continue: " + std::to_string(n) + " points, " + o.key + " = " +
                    fmt(q / scale, 6) + " " + unit,
                false);
  };
  const Branch b = continue_branch(c, o.branch);
  line.clear();
  if (b.end == BranchEnd::cancelled) {
    std::cerr << "oscidrum: interrupted after " << b.points.size() << " points; nothing written\n";
    return interrupted_exit_code();
  }
  if (!o.csv.empty()) write_output(o.csv, points_csv(b));
  if (!o.json.empty()) write_output(o.json, branch_json(b).dump(2) + "\n");
  if (!o.bifurcations.empty()) write_output(o.bifurcations, bifurcations_csv(b));
  if (!o.hdf5.empty()) io::write_branch_hdf5(o.hdf5, b);
  if (stdout_taken)
    ;  // the file named - was written there
  else if (o.format == "table")
    std::cout << table(b, *field);
  else if (o.format == "csv")
    std::cout << points_csv(b);
  else if (o.format == "json")
    std::cout << branch_json(b).dump(2) << "\n";
  std::cout.flush();
  if (!o.quiet)
    std::cerr << "oscidrum: " << b.points.size() << " points, " << b.bifurcations.size()
              << " bifurcations, " << b.period_maps << " period maps in " << fmt(b.seconds, 3)
              << " s; " << to_string(b.end) << ": " << b.message
              << (b.children.empty() ? std::string()
                                     : "; " + std::to_string(all_branches(b).size() - 1) +
                                           " more branches switched onto at period "
                                           "doublings")
              << "\n";
  if (!o.plot.empty()) {
    std::vector<std::string> args = {"oscidrum.plot", "branch",      "--csv", o.csv,
                                     "--metric",      o.plot_metric, "--out", o.plot};
    if (!o.bifurcations.empty()) args.insert(args.end(), {"--bifurcations", o.bifurcations});
    if (run_python(args, "the branch is in " + o.csv, {}, o.quiet) != 0)
      return interrupted() ? plot_interrupted("the branch is in " + o.csv) : kExitCaseFailed;
  }
  const bool ok = b.end == BranchEnd::reached_end || b.end == BranchEnd::left_range ||
                  b.end == BranchEnd::gross_slip || b.end == BranchEnd::lift_off ||
                  b.end == BranchEnd::period_halved;
  return ok ? kExitOk : kExitCaseFailed;
}

}  // namespace

void add_continue_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<ContinueOptions>();
  CLI::App* sub = app.add_subcommand(
      "continue",
      "Follow a branch of periodic orbits through a parameter (pseudo-arclength continuation of "
      "the shooting problem), stable and unstable alike, through folds; every orbit with its "
      "Floquet multipliers and CCC metrics; the bifurcations on the branch (fold, period "
      "doubling, Neimark-Sacker, branch point, lift-off, and grazing: a stick, slip or flight "
      "phase "
      "appearing or vanishing) detected and located. docs/bifurcations.md.");
  sub->footer(
      "Examples:\n"
      "  oscidrum continue --param soil.G --from 10 --to 80 --set soil.input=modulus\n"
      "  oscidrum continue case.toml --param MMd --from 0 --to 9000 --csv b.csv "
      "--bifurcations bif.csv --plot b.png\n"
      "--from/--to are in the unit the key is typed in (MN/m^2 for soil.G, else SI).\n"
      "Exit codes: 0 the branch reached --to (or turned back out of the range, or ended in gross "
      "slip), 1 it ended otherwise (the message says why), 2 bad input, 130 interrupted.");
  sub->add_option("case", o->config, "case file (TOML, see docs/config.md); default: none")
      ->type_name("CASE.toml");
  add_roller_flags(*sub, o->c);
  add_soil_flags(*sub, o->c);
  add_model_flags(*sub, o->c);
  add_set_flag(*sub, o->c);
  sub->add_option("--param", o->key, "the parameter to follow: a real key (oscidrum fields)")
      ->required()
      ->type_name("KEY");
  sub->add_option("--from", o->from_text, "start of the range (the first orbit is found here)")
      ->required();
  sub->add_option("--to", o->to_text, "end of the range")->required();
  sub->add_option("--step", o->branch.initial_step,
                  "first arclength step as a fraction of |to - from| (default 0.02)");
  sub->add_option("--max-step", o->branch.max_step,
                  "largest arclength step as a fraction of |to - from| (default 0.05)");
  sub->add_option("--tolerance", o->branch.tolerance,
                  "bifurcations are located to this fraction of |to - from| (default 1e-6)");
  sub->add_option("--max-points", o->branch.max_points, "points on the branch at most (2000)");
  sub->add_option("--switch-depth", o->branch.switch_depth,
                  "follow the period-2p branch born at each period doubling, and onward, to this "
                  "depth (default 1; 0: none)")
      ->check(CLI::Range(0, 5));
  sub->add_option("--harmonics", o->branch.harmonics,
                  "harmonics in the metrics, and the columns ddx_A1 ... ddx_AN, ddz_A1 ... ddz_AN "
                  "of --csv (default 10)")
      ->check(CLI::Range(2, 1000));
  o->output_flags.push_back(
      sub->add_option("--csv", o->csv, "write the points to FILE (one row per orbit)")
          ->type_name("FILE"));
  o->output_flags.push_back(
      sub->add_option("--bifurcations", o->bifurcations, "write the bifurcations to FILE (CSV)")
          ->type_name("FILE"));
  o->output_flags.push_back(
      sub->add_option("--json", o->json, "write the branch to FILE (schema oscidrum-branch/1)")
          ->type_name("FILE"));
  o->output_flags.push_back(
      sub->add_option("--hdf5", o->hdf5,
                      "write the branches and their bifurcations to FILE (HDF5, layout in "
                      "docs/bifurcations.md)")
          ->type_name("FILE"));
  o->output_flags.push_back(
      sub->add_option("--plot", o->plot,
                      "draw a metric against the parameter into FILE (.png or .svg; needs --csv): "
                      "stable solid, unstable dashed, bifurcations marked")
          ->type_name("FILE"));
  o->plot_metric_flag =
      sub->add_option("--plot-metric", o->plot_metric,
                      "the column --plot shows (default area; a metric such as ddx_max or "
                      "psi_xz, or max_modulus, min_N)")
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
