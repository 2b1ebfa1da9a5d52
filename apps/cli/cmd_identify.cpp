// oscidrum identify: the soil under the drum from a measured acceleration record (or from the
// metrics `analyze --format json` wrote): one estimate of G (or ksh, ksv), optionally mu and
// MMd, per window along a pass, with uncertainties, 95 % profile intervals and warnings
// (identify.hpp, docs/identify.md).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "case_options.hpp"
#include "commands.hpp"
#include "estimate_json.hpp"
#include "flags.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/identify.hpp"
#include "oscidrum/simulate.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/csv.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "record_input.hpp"
#include "terminal.hpp"

namespace oscidrum::cli {
namespace {

struct IdentifyCliOptions {
  RecordInput input;
  WindowOptions windows;
  std::string config, metrics_file;
  CaseOptions c;
  std::string estimate = "G";
  std::string soil_scale = "formulas";
  bool fit_mu = false, fit_MMd = false, use_peaks = false, use_area = false, no_profile = false;
  bool transient = false;
  int compare = 4;
  double gain_uncertainty = 0.0;
  std::string csv, json, geojson, plot_dir, format = "table";
  CLI::Option* format_flag = nullptr;
  int plot_window = -1;
  bool quiet = false;
};

std::string cell(double v) { return io::format_double_short(v); }

// A text with each number in it (digits, a decimal point, an exponent) replaced by '#': the
// texts of two windows that say the same with their own numbers have the same shape.
std::string number_shape(const std::string& text) {
  std::string shape;
  const auto digit = [&](std::size_t i) {
    return i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]));
  };
  for (std::size_t i = 0; i < text.size();) {
    if (!digit(i) && !(text[i] == '.' && digit(i + 1))) {
      shape += text[i++];
      continue;
    }
    while (digit(i) || text[i] == '.') ++i;
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
      std::size_t j = i + 1;
      if (j < text.size() && (text[j] == '+' || text[j] == '-')) ++j;
      if (digit(j)) {
        i = j;
        while (digit(i)) ++i;
      }
    }
    shape += '#';
  }
  return shape;
}

// The windows a note belongs to, ascending: "window 3", "windows 0-2, 5, 7-59".
std::string windows_text(const std::vector<int>& windows) {
  std::string text;
  for (std::size_t i = 0; i < windows.size();) {
    std::size_t j = i;
    while (j + 1 < windows.size() && windows[j + 1] == windows[j] + 1) ++j;
    text += (text.empty() ? "" : ", ") + std::to_string(windows[i]) +
            (j > i ? "-" + std::to_string(windows[j]) : "");
    i = j + 1;
  }
  return (windows.size() == 1 ? "window " : "windows ") + text;
}

// The case the record is compared with: the case file, the flags, --set.
Case base_case(const IdentifyCliOptions& o) {
  io::CaseSpec spec;
  // G on the formulas scale goes through Appendix B: the case's nu, rho and drum width b take
  // effect (--nu 0.35 was refused as having no effect under the default Table 2 soil).
  return resolve_case(o.config, o.c, spec,
                      o.estimate == "G" && o.soil_scale == "formulas"
                          ? std::optional<SoilInput>(SoilInput::modulus)
                          : std::nullopt);
}

// The measured response from `analyze --format json` (schema oscidrum-record/1), and the
// window's times, position and samples into `window` (NaN where the JSON has none), and how
// analyze read the record's axes into `io` (its "reading", where the JSON has it).
MeasuredResponse read_metrics(const std::string& path, RecordWindow& window, IdentifyOptions& io) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw Error(path + ": not JSON: " + e.what());
  }
  if (j.value("schema", "") != "oscidrum-record/1")
    throw Error(path +
                ": expected the JSON of `oscidrum analyze --format json` (schema "
                "oscidrum-record/1)");
  // An analysis that failed (a gap, clipping, a poor fit) has no metrics: its reason, not that
  // of a number missing from the file.
  if (j.contains("valid") && j["valid"].is_boolean() && !j["valid"].get<bool>())
    throw Error(path + ": the analysis in it is not valid (" +
                (j.contains("reason") && j["reason"].is_string() ? j["reason"].get<std::string>()
                                                                 : std::string("no reason given")) +
                "): it has no metrics to identify from; `oscidrum identify RECORD` identifies "
                "the record window by window");
  auto number = [&](const char* key) {
    if (!j.contains(key) || !j[key].is_number())
      throw Error(path + ": '" + std::string(key) + "' must be a number (is the fit valid?)");
    return j[key].get<double>();
  };
  if (j.contains("reading") && j["reading"].is_object()) {
    const nlohmann::json& r = j["reading"];
    io.x_read_backward = r.contains("x_positive") && r["x_positive"] == "backward";
    io.z_read_up = r.contains("z_positive") && r["z_positive"] == "up";
  }
  RecordMetrics m;
  for (const char* key : {"ddx_harmonics", "ddz_harmonics"}) {
    std::vector<Harmonic>& h = key[2] == 'x' ? m.ddx_harmonics : m.ddz_harmonics;
    for (const auto& e : j.at(key)) {
      if (!e["amplitude"].is_number() || !e["phase"].is_number())
        throw Error(path + ": " + key + " holds a value that is not a number");
      h.push_back({e["amplitude"].get<double>(), e["phase"].get<double>()});
    }
  }
  m.residual_x = number("residual_x");
  m.residual_z = number("residual_z");
  m.ddx_max = number("ddx_max");
  m.ddx_min = number("ddx_min");
  m.ddz_max = number("ddz_max");
  m.ddz_min = number("ddz_min");
  m.area = number("area");
  const double samples = j.contains("samples") ? number("samples") : 1000.0;
  const auto optional = [&](const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>()
                                                 : std::numeric_limits<double>::quiet_NaN();
  };
  window.t_start = optional("t_start");
  window.t_end = optional("t_end");
  window.t_mid = optional("t");
  window.position = optional("position");
  window.samples_per_period = optional("samples_per_period");
  window.count = static_cast<std::size_t>(std::max(0.0, samples));
  return measured_response(m, number("f"), static_cast<std::size_t>(std::max(1.0, samples)));
}

const Estimate* find_estimate(const Identification& id, const std::string& name) {
  for (const Estimate& e : id.estimates)
    if (e.name == name) return &e;
  return nullptr;
}

std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : "; ") + s;
  return out;
}

// What Identification::model_sampled means, for the summary, with the window's samples per
// period.
std::string model_sampled_text(double samples_per_period) {
  return "sampled at the record's times (the record is sampled in step with the excitation, " +
         fmt(samples_per_period, 4) +
         " samples per period: its harmonics above those fitted alias onto the compared ones, as "
         "the model's do so sampled; docs/identify.md)";
}

// One row per window (docs/identify.md, "Output columns").
std::string pass_csv(const std::vector<PassEstimate>& pass, const IdentifyOptions& io) {
  std::ostringstream out;
  out << "window[-],t_start[s],t_end[s],t[s],position[m],f[Hz],change[-],valid[-],reason[-]";
  for (const auto& [name, unit] : identified_unknowns(io))
    for (const char* suffix : {"", "_u", "_lo", "_hi"})
      out << "," << name << suffix << "[" << unit << "]";
  if (io.modulus) out << ",soil_scale[-]";
  out << ",tau[s],rms_residual[m/s^2],relative_residual[-],reduced_chi2[-],condition[-],"
         "iterations[-],simulations[-],warnings[-],model_sampled[-],z_negated[-],read_in_g[-]\n";
  for (const PassEstimate& p : pass) {
    const RecordWindow& w = p.window;
    const Identification& id = p.identification;
    out << w.index << "," << cell(w.t_start) << "," << cell(w.t_end) << "," << cell(w.t_mid) << ","
        << cell(w.position) << "," << cell(w.f) << "," << cell(w.change) << "," << (p.valid ? 1 : 0)
        << "," << io::csv_quote(p.reason);
    for (const auto& [name, unit] : identified_unknowns(io)) {
      const Estimate* e = p.valid ? find_estimate(id, name) : nullptr;
      for (double v : {e ? e->value : NAN, e ? e->standard_uncertainty : NAN, e ? e->lower : NAN,
                       e ? e->upper : NAN})
        out << "," << cell(v);
    }
    const double nan = NAN;
    if (io.modulus) out << "," << to_string(io.soil_scale);
    out << "," << cell(p.valid ? id.time_shift : nan) << ","
        << cell(p.valid ? id.rms_residual : nan) << ","
        << cell(p.valid ? id.relative_residual : nan) << ","
        << cell(p.valid ? id.reduced_chi2 : nan) << "," << cell(p.valid ? id.condition : nan) << ","
        << (p.valid ? id.iterations : 0) << "," << (p.valid ? id.simulations : 0) << ","
        << io::csv_quote(join(id.warnings)) << "," << (p.valid && id.model_sampled ? 1 : 0) << ","
        << (p.valid && id.z_negated ? 1 : 0) << "," << (p.valid && id.read_in_g ? 1 : 0) << "\n";
  }
  return out.str();
}

nlohmann::ordered_json identification_json(const Identification& id) {
  nlohmann::ordered_json est = nlohmann::json::array();
  for (const Estimate& e : id.estimates) est.push_back(estimate_json(e));
  return {{"estimates", est},
          {"f", id.f},
          {"tau", id.time_shift},
          {"rms_residual", id.rms_residual},
          {"relative_residual", id.relative_residual},
          {"reduced_chi2", id.reduced_chi2},
          {"condition", id.condition},
          {"converged", id.converged},
          {"message", id.message},
          {"iterations", id.iterations},
          {"simulations", id.simulations},
          {"harmonics_fitted", id.measured.ddx.size()},
          {"noise_x", id.measured.noise_x},
          {"noise_z", id.measured.noise_z},
          {"warnings", id.warnings},
          {"model_sampled", id.model_sampled},
          {"z_negated", id.z_negated},
          {"read_in_g", id.read_in_g}};
}

// An unknown's soil field ("G" -> soil.G), whose display unit it is shown in (the field table's
// MN/m^2 for G, MN/m for ksh and ksv), else the unknown's own unit.
std::string shown_unit(const std::string& name, const std::string& unit) {
  const Field* f = find_field("soil." + name);
  return f && f->display_unit ? f->display_unit : unit;
}
double shown_scale(const std::string& name) {
  const Field* f = find_field("soil." + name);
  return f ? f->display_scale : 1.0;
}

std::string value_text(const Estimate& e) {
  const double k = 1.0 / shown_scale(e.name);
  auto f = [&](double v, int d) { return std::isfinite(v) ? fmt(v * k, d) : std::string("?"); };
  return f(e.value, 5) + " +- " + f(e.standard_uncertainty, 2) + "  [" + (e.lower_open ? "<" : "") +
         f(e.lower, 4) + ", " + f(e.upper, 4) + (e.upper_open ? ">" : "") + "]";
}

std::string unit_text(const Estimate& e) { return shown_unit(e.name, e.unit); }

std::string scale_text(SoilScale scale) {
  return scale == SoilScale::table2
             ? "paper Table 2 (--soil-scale table2; interpolated between its rows)"
             : "Appendix B (42)-(45) with the case's nu and rho (--soil-scale formulas)";
}

// The pass as GeoJSON (RFC 7946): a FeatureCollection with one Feature per window, its geometry
// the Point [lon, lat] at the window's centre (null without GNSS columns), its properties the
// window's place and time, valid, the reason or the warnings, and each estimate with its
// interval (in its display unit: G in MN/m^2).
nlohmann::ordered_json pass_geojson(const std::vector<PassEstimate>& pass, const RecordColumns& rec,
                                    const std::string& name) {
  nlohmann::ordered_json features = nlohmann::json::array();
  for (const PassEstimate& p : pass) {
    const RecordWindow& w = p.window;
    const auto [lat, lon] = lat_lon_at(rec, w.t_mid);
    nlohmann::ordered_json geometry = nullptr;
    if (std::isfinite(lat) && std::isfinite(lon))
      geometry = {{"type", "Point"}, {"coordinates", {lon, lat}}};
    nlohmann::ordered_json props = {
        {"window", w.index},      {"t", w.t_mid}, {"t_start", w.t_start}, {"t_end", w.t_end},
        {"position", w.position}, {"f", w.f},     {"valid", p.valid},     {"reason", p.reason}};
    if (const auto [east, north] = east_north_at(rec, w.t_mid); std::isfinite(east)) {
      props["easting"] = east;  // projected coordinates [m]: properties (GeoJSON is WGS 84)
      props["northing"] = north;
    }
    nlohmann::ordered_json warnings = nlohmann::json::array();
    if (p.valid) {
      for (const Estimate& e : p.identification.estimates) {
        const double k = 1.0 / shown_scale(e.name);
        props[e.name] = e.value * k;
        props[e.name + "_lower"] = e.lower * k;
        props[e.name + "_upper"] = e.upper * k;
        props[e.name + "_unit"] = unit_text(e);
      }
      for (const std::string& text : p.identification.warnings) warnings.push_back(text);
    }
    props["warnings"] = warnings;
    props["model_sampled"] = p.valid && p.identification.model_sampled;
    props["z_negated"] = p.valid && p.identification.z_negated;
    props["read_in_g"] = p.valid && p.identification.read_in_g;
    features.push_back({{"type", "Feature"}, {"geometry", geometry}, {"properties", props}});
  }
  return {{"type", "FeatureCollection"}, {"name", name}, {"features", features}};
}

// Plot data of one window: measured and model over two periods, spectra, parameters. The model
// is drawn in the record's time (fit_curves: shifted by tau, with the window's offsets and
// drift), beside the samples and at them.
void write_fit_files(const std::string& dir, const RecordColumns& rec, const PassEstimate& p,
                     int n_max) {
  const Identification& id = p.identification;
  const double T = 1.0 / id.f;
  const RecordWindow& w = p.window;
  const double a = w.t_start, b = std::min(w.t_end, a + 2 * T);
  std::vector<double> ts;
  for (std::size_t i = w.first; i < w.first + w.count; ++i)
    if (rec.t[i] >= a && rec.t[i] <= b) ts.push_back(rec.t[i]);
  std::vector<double> grid;
  const int steps = 512;
  for (int j = 0; j <= steps; ++j) grid.push_back(a + (b - a) * j / steps);
  const FitCurves at_samples = fit_curves(id, ts), curve = fit_curves(id, grid);
  std::ostringstream model, measured, spectrum;
  model << "t[s],ddx_M[m/s^2],ddz_M[m/s^2]\n";
  for (std::size_t j = 0; j < grid.size(); ++j)
    model << cell(grid[j]) << "," << cell(curve.ddx_M[j]) << "," << cell(curve.ddz_M[j]) << "\n";
  measured << "t[s],ddx_M[m/s^2],ddz_M[m/s^2],ddx_M_fit[m/s^2],ddz_M_fit[m/s^2]\n";
  for (std::size_t i = w.first, k = 0; i < w.first + w.count; ++i)
    if (rec.t[i] >= a && rec.t[i] <= b) {
      measured << cell(rec.t[i]) << "," << cell(rec.ddx_M[i]) << "," << cell(rec.ddz_M[i]) << ","
               << cell(at_samples.ddx_M[k]) << "," << cell(at_samples.ddz_M[k]) << "\n";
      ++k;
    }
  const MeasuredResponse& d = id.measured;
  const int shown = std::min<int>(n_max, static_cast<int>(d.ddx.size()));
  Case c = id.fitted;
  c.numerics.output_periods = 1;
  const Model model_at_fit(c);
  const Result r = simulate(model_at_fit);
  if (!ok(r.status))
    throw Error("the best fit's model did not reach its steady state: " + r.message);
  const Metrics sim = compute_metrics(model_at_fit, r, shown);
  spectrum << "n[-],f[Hz],ddx_A_measured[m/s^2],ddx_A_model[m/s^2],ddz_A_measured[m/s^2],"
              "ddz_A_model[m/s^2]\n";
  for (int n = 1; n <= shown; ++n)
    spectrum << n << "," << cell(n * id.f) << "," << cell(std::abs(d.ddx[n - 1])) << ","
             << cell(sim.ddx_harmonics[n].amplitude) << "," << cell(std::abs(d.ddz[n - 1])) << ","
             << cell(sim.ddz_harmonics[n].amplitude) << "\n";
  nlohmann::ordered_json j = identification_json(id);
  j["window"] = w.index;
  j["t_start"] = w.t_start;
  j["t_end"] = w.t_end;
  j["position"] = w.position;
  j["pure_rolling"] = c.contact.pure_rolling;
  j["mu"] = c.contact.mu;
  j["MMd"] = c.MMd;
  write_output(dir + "/fit_model.csv", model.str());
  write_output(dir + "/fit_measured.csv", measured.str());
  write_output(dir + "/fit_spectrum.csv", spectrum.str());
  write_output(dir + "/fit.json", j.dump(2) + "\n");
}

int run(const IdentifyCliOptions& o) {
  double window_periods = o.windows.window_periods;  // the window in effect (0: the record)
  if (o.input.file.empty() == o.metrics_file.empty())
    throw Error("identify: give either a record or --metrics FILE (the JSON of analyze)");
  check_distinct_files({{"the record", o.input.file, true},
                        {"--metrics", o.metrics_file, true},
                        {"the case file", o.config, true},
                        {"--csv", o.csv},
                        {"--json", o.json},
                        {"--geojson", o.geojson}});
  // Standard output carries one thing: the table after a --csv - made the CSV unreadable.
  const bool stdout_taken =
      file_takes_stdout({{"--csv", o.csv}, {"--json", o.json}, {"--geojson", o.geojson}},
                        given(o.format_flag) ? o.format : "");
  const Case base = base_case(o);
  IdentifyOptions io;
  io.modulus = o.estimate == "G";
  io.soil_scale = soil_scale_from(o.soil_scale, "--soil-scale");
  io.fit_mu = o.fit_mu;
  io.fit_MMd = o.fit_MMd;
  io.harmonics = o.compare;
  io.use_peaks = o.use_peaks;
  io.use_area = o.use_area;
  io.gain_uncertainty = o.gain_uncertainty;
  io.profile = !o.no_profile;
  io.shooting = !o.transient;
  io.measure.harmonics = o.windows.n_max;
  if (o.windows.n_max > 0 && o.compare > o.windows.n_max)
    throw Error("--compare must be <= --harmonics = " + std::to_string(o.windows.n_max) + "; got " +
                std::to_string(o.compare));

  std::vector<PassEstimate> pass;
  RecordColumns rec;
  std::string name = o.metrics_file;
  install_interrupt_handlers();
  if (!o.metrics_file.empty()) {
    PassEstimate p;
    const MeasuredResponse d = read_metrics(o.metrics_file, p.window, io);  // and its times
    p.window.f = d.f;
    p.window.change = NAN;  // measured by analyze (its JSON), not here
    p.identification = identify(base, d, io);
    // The record is read already: the advice on how to read it goes to analyze, which measured
    // these metrics (identify --metrics refuses the reading flags).
    for (std::string& w : p.identification.warnings)
      for (std::size_t at = w.find("read it with"); at != std::string::npos;
           at = w.find("read it with", at))
        w.replace(at, 12, "analyze the record again with");
    p.valid = true;
    pass.push_back(p);
  } else {
    name = o.input.file == "-" ? "<stdin>" : o.input.file;
    rec = read_record(o.input);
    io.z_open = rec.z_open;
    io.units_open = rec.units_open;
    io.x_read_backward = o.input.x_positive == "backward";
    io.z_read_up = rec.z_positive == "up";
    ProgressLine line(stderr_is_terminal() && !o.quiet);
    pass = identify_pass(base, rec.t, rec.ddx_M, rec.ddz_M, rec.position, o.windows, io,
                         [&](std::size_t k, std::size_t n) {
                           line.update("oscidrum identify: window " + std::to_string(k + 1) +
                                       " of " + std::to_string(n));
                           return !interrupted();
                         });
    line.clear();
    // How the record was read, once the pass has run: a refusal (exit code 2) is one line.
    report_reading(rec);
    {
      // The windows identify reports as valid: one the record's gates passed but too short for
      // the identification's fit (a sliver after a pause) is not counted among them.
      std::vector<const RecordWindow*> all;
      for (const PassEstimate& p : pass)
        if (p.valid) all.push_back(&p.window);
      warn_unchecked_change(all, "identify");
    }
    if (interrupted()) {
      std::cerr << "oscidrum: interrupted after " << pass.size() << " windows; nothing written\n";
      return interrupted_exit_code();
    }
    // WindowOptions::whole_if_shorter: the default window was longer than the record.
    if (pass.size() == 1 && pass.front().window.whole) {
      const RecordWindow& w = pass.front().window;
      // n samples cover n steps: the last sample's step counts.
      const double periods = (w.t_end - w.t_start) * w.f +
                             (w.samples_per_period > 0 ? 1.0 / w.samples_per_period : 0.0);
      window_periods = 0.0;
      if (!o.quiet)
        std::cerr << "oscidrum: identify: the record spans "
                  << (std::isfinite(periods)
                          ? "about " + fmt(periods, 3) + " periods, fewer than"
                          : fmt(w.t_end - w.t_start, 3) + " s (its frequency unknown), less than")
                  << " the default window of " << fmt(o.windows.window_periods, 3)
                  << ": identified whole, as one window (as --window 0)\n";
    }
  }
  std::size_t valid = 0, model_sampled = 0;
  const RecordWindow* sampled_window = nullptr;
  for (const PassEstimate& p : pass) {
    valid += p.valid ? 1 : 0;
    if (p.valid && p.identification.model_sampled) {
      ++model_sampled;
      if (!sampled_window) sampled_window = &p.window;
    }
  }
  // Said once for a pass (a single window's summary says it too): windows whose samples alias.
  if (sampled_window && pass.size() > 1 && !o.quiet)
    std::cerr << "oscidrum: identify: " << model_sampled << " of " << valid
              << " windows compared the model "
              << model_sampled_text(sampled_window->samples_per_period)
              << " (column model_sampled)\n";

  const std::string csv_text = pass_csv(pass, io);
  nlohmann::ordered_json rows = nlohmann::json::array();
  for (const PassEstimate& p : pass) {
    nlohmann::ordered_json r = {{"window", p.window.index},
                                {"t_start", p.window.t_start},
                                {"t_end", p.window.t_end},
                                {"t", p.window.t_mid},
                                {"position", p.window.position},
                                {"f", p.window.f},
                                {"change", p.window.change},
                                {"valid", p.valid},
                                {"reason", p.reason}};
    if (p.valid) r.update(identification_json(p.identification));
    rows.push_back(r);
  }
  const nlohmann::ordered_json j = {
      {"schema", "oscidrum-identify/1"},
      {"file", name},
      {"estimate", o.estimate},
      {"soil_scale", o.estimate == "G" ? o.soil_scale : ""},
      {"fit_mu", o.fit_mu},
      {"fit_MMd", o.fit_MMd},
      {"compare_harmonics", o.compare},
      {"gain_uncertainty", o.gain_uncertainty},
      {"model_method", o.transient ? "transient" : "shooting"},
      {"window_periods", window_periods},
      {"reading",
       o.metrics_file.empty() ? reading_json(o.input, rec) : nlohmann::ordered_json(nullptr)},
      {"valid_windows", valid},
      {"windows", rows}};
  std::string csv_path = o.csv;
  if (!o.plot_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.plot_dir, ec);
    if (ec) throw Error("cannot create --plot directory " + o.plot_dir + ": " + ec.message());
    write_output(o.plot_dir + "/identify.csv", csv_text);  // what the plots read
  }
  if (!csv_path.empty()) write_output(csv_path, csv_text);
  if (!o.json.empty()) write_output(o.json, j.dump(2) + "\n");
  if (!o.geojson.empty()) write_output(o.geojson, pass_geojson(pass, rec, name).dump(2) + "\n");

  if (stdout_taken) {
    // the file named - was written there
  } else if (o.format == "csv") {
    std::cout << csv_text;
  } else if (o.format == "json") {
    std::cout << j.dump(2) << "\n";
  } else if (pass.size() == 1 && pass.front().valid) {
    const Identification& id = pass.front().identification;
    Summary s;
    s.section("Identification");
    s.line("data", name);
    s.line("excitation frequency f [Hz]", fmt(id.f, 8));
    for (const Estimate& e : id.estimates)
      s.line(e.name + " [" + unit_text(e) + "]  value +- u  [95 %]", value_text(e));
    if (io.modulus) s.line("scale of G", scale_text(io.soil_scale));
    s.line("relative residual", fmt(id.relative_residual, 3) + " (harmonics n = 1 ... " +
                                    std::to_string(o.compare) + ")");
    s.line("reduced chi^2", fmt(id.reduced_chi2, 3));
    s.line("time shift tau [s]", fmt(id.time_shift, 6));
    s.line("iterations, simulations",
           std::to_string(id.iterations) + ", " + std::to_string(id.simulations));
    if (id.model_sampled)
      s.line("model compared", model_sampled_text(pass.front().window.samples_per_period));
    if (id.z_negated)
      s.line("z_M''", "fitted negated: the record's z axis points up (see the warning)");
    if (id.read_in_g)
      s.line("accelerations", "fitted in g: the record's columns have no unit (see the warning)");
    for (const std::string& w : id.warnings) s.line("WARNING", w);
    std::cout << s.text();
  } else {
    TextTable t;
    t.header = {"window", "t [s]", "position [m]", "f [Hz]"};
    for (const auto& [n, u] : identified_unknowns(io)) {
      const std::string unit = shown_unit(n, u);
      t.header.push_back(n + " [" + unit + "]  +- u  [95 %]");
    }
    t.header.push_back("rel. res.");
    t.header.push_back("status");
    t.right.assign(t.header.size(), true);
    t.right.back() = false;
    // A window's warnings (a poor fit's diagnosis runs to several hundred characters) and a long
    // reason for no estimate are notes below the table: in the status column they made every
    // row as wide as the longest. Windows whose texts differ only in their numbers share one
    // note, with the first one's numbers (a cause that every window of a pass has, each with its
    // own reduced chi^2: 60 windows, one note; the table gives each window's residual).
    constexpr std::size_t kInlineStatus = 60;
    struct Note {
      std::string text, shape;
      std::vector<int> windows;
    };
    std::vector<Note> notes;
    const auto status = [&](const PassEstimate& p) -> std::string {
      if (p.valid && p.identification.warnings.empty()) return "ok";
      const std::string text =
          p.valid ? "WARNING: " + join(p.identification.warnings) : std::string(p.reason);
      if (text.size() <= kInlineStatus) return text;
      const std::string shape = number_shape(text);
      auto it = std::find_if(notes.begin(), notes.end(),
                             [&](const Note& note) { return note.shape == shape; });
      if (it == notes.end()) it = notes.insert(notes.end(), Note{text, shape, {}});
      it->windows.push_back(p.window.index);
      return std::string(p.valid ? "WARNING" : "no estimate") + ", note [" +
             std::to_string(it - notes.begin() + 1) + "]";
    };
    for (const PassEstimate& p : pass) {
      std::vector<std::string> row = {
          std::to_string(p.window.index), time_text(p.window.t_mid),
          std::isfinite(p.window.position) ? fmt(p.window.position, 5) : "", fmt(p.window.f, 6)};
      for (const auto& [n, u] : identified_unknowns(io)) {
        const Estimate* e = p.valid ? find_estimate(p.identification, n) : nullptr;
        row.push_back(e ? value_text(*e) : "");
      }
      row.push_back(p.valid ? fmt(p.identification.relative_residual, 3) : "");
      row.push_back(status(p));
      t.rows.push_back(row);
    }
    std::cout << name << ": " << pass.size() << " windows, " << valid << " identified"
              << (io.modulus ? "; G on the scale of " + scale_text(io.soil_scale) : std::string())
              << "\n"
              << t.text();
    if (!notes.empty()) {
      std::cout << "\nnotes:\n";
      for (std::size_t k = 0; k < notes.size(); ++k)
        std::cout << "[" << k + 1 << "] " << windows_text(notes[k].windows)
                  << (notes[k].windows.size() > 1
                          ? " (the numbers of window " + std::to_string(notes[k].windows[0]) + ")"
                          : std::string())
                  << ": " << notes[k].text << "\n";
    }
  }
  std::cout.flush();

  if (!o.plot_dir.empty() && valid > 0) {
    // The window to compare in time: --plot-window, else the first valid one.
    const PassEstimate* chosen = nullptr;
    for (const PassEstimate& p : pass)
      if (p.valid && (o.plot_window < 0 || p.window.index == o.plot_window)) {
        chosen = &p;
        break;
      }
    if (!chosen)
      throw Error("--plot-window " + std::to_string(o.plot_window) +
                  " is not a window with an estimate");
    if (o.metrics_file.empty()) write_fit_files(o.plot_dir, rec, *chosen, 10);
    if (run_python({"oscidrum.identify", "plot", "--dir", o.plot_dir},
                   "the data are in " + o.plot_dir) != 0)
      return interrupted() ? plot_interrupted("the data are in " + o.plot_dir) : kExitCaseFailed;
  }
  if (valid == 0) {
    std::string reasons;
    for (const PassEstimate& p : pass)
      if (!p.valid && reasons.size() < 600)
        reasons += (reasons.empty() ? "" : "; ") + std::string("window ") +
                   std::to_string(p.window.index) + ": " + p.reason;
    std::cerr << "oscidrum: error: " << name << ": no window could be identified: " << reasons
              << "\n";
    return kExitCaseFailed;
  }
  return kExitOk;
}

}  // namespace

void add_identify_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<IdentifyCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "identify",
      "The soil under the drum from its measured accelerations: for each window of a record "
      "(analyze's windows and quality gates), the shear modulus G [MN/m^2] through Appendix B "
      "(42)-(45) (or the springs ksh, ksv), optionally mu and the driving torque MMd, such that "
      "the model's complex harmonics of x_M'' and z_M'' at f, 2f, ... match the measured ones "
      "(Levenberg-Marquardt; the record's time origin is fitted too). Each estimate comes with "
      "a standard uncertainty, a 95 % interval from the profile of the objective, the fit "
      "quality and warnings when parameters cannot be told apart. The G identified is the one "
      "of this lumped model (docs/identify.md).");
  sub->footer(
      "The roller and everything not estimated come from --case, the flags and --set (defaults: "
      "the paper's roller); roller.M0 is scaled by (f / roller.f)^2 to the record's f (5).\n"
      "Output columns: docs/identify.md.\nExamples:\n"
      "  oscidrum identify pass.csv --speed-col v --csv G.csv --plot plots/\n"
      "  oscidrum identify record.csv --window 0 --fit-mu\n"
      "  oscidrum identify --metrics record.json --pure-rolling\n"
      "Exit codes: 0 at least one window identified, 1 none, 2 bad input, 130 interrupted.");
  const std::size_t before_reading = sub->get_options().size();
  add_record_options(*sub, o->input, false);
  add_window_options(*sub, o->windows, 40.0, true);
  // The record's reading and window flags: metrics measured already (--metrics) cannot use them.
  const std::vector<CLI::Option*> added = sub->get_options();
  std::vector<const CLI::Option*> reading;
  for (std::size_t i = before_reading; i < added.size(); ++i)
    if (added[i]->nonpositional()) reading.push_back(added[i]);
  sub->add_option("--metrics", o->metrics_file,
                  "identify from these metrics (the JSON of `oscidrum analyze --format json`) "
                  "instead of a record")
      ->type_name("FILE");
  add_record_case_flags(*sub, o->config, o->c,
                        "case file (TOML) of the roller and the known parameters");
  const char* fit = "Identification";
  sub->add_option("--estimate", o->estimate,
                  "G (shear modulus through Appendix B with the case's nu and rho) or ks (ksh and "
                  "ksv, with the case's csh and csv) (default G)")
      ->check(CLI::IsMember({"G", "ks"}))
      ->group(fit);
  sub->add_option("--soil-scale", o->soil_scale,
                  "the scale of G: formulas (Appendix B (42)-(45) with the case's nu and rho, "
                  "the default) or table2 (the paper's Table 2, interpolated between its rows: "
                  "the soil `oscidrum run --G` simulates)")
      ->check(CLI::IsMember({"formulas", "table2"}))
      ->group(fit);
  sub->add_flag("--fit-mu", o->fit_mu, "estimate the friction coefficient mu too")->group(fit);
  sub->add_flag("--fit-MMd", o->fit_MMd, "estimate the driving torque MMd too")->group(fit);
  sub->add_option("--compare", o->compare,
                  "harmonics n = 1 ... N of x_M'' and z_M'' compared (default 4)")
      ->check(CLI::Range(1, kMaxComparedHarmonics))
      ->group(fit);
  sub->add_option("--gain-uncertainty", o->gain_uncertainty,
                  "relative standard uncertainty of each accelerometer channel's gain (its "
                  "calibration, e.g. 0.02), 0 ... 0.5; its effect on each estimate (refits with "
                  "each gain that far off) is added to the uncertainty and the 95 % interval "
                  "(default 0: not counted; a gain error biases G, which the fit cannot see)");
  sub->add_flag("--use-peaks", o->use_peaks, "compare the peaks of x_M'' and z_M'' too")
      ->group(fit);
  sub->add_flag("--use-area", o->use_area, "compare the area of the z_M''(x_M'') figure too")
      ->group(fit);
  sub->add_flag("--no-profile", o->no_profile,
                "skip the profile intervals (faster; the columns _lo, _hi are NaN)")
      ->group(fit);
  sub->add_flag("--transient", o->transient,
                "find the model's steady states by the transient from rest (the paper's method) "
                "instead of shooting (slower, the same estimates)")
      ->group(fit);
  const char* out = "Output";
  sub->add_option("--csv", o->csv, "write one row per window to FILE ('-': stdout)")
      ->type_name("FILE")
      ->group(out);
  sub->add_option("--json", o->json, "write the JSON of the identification to FILE")
      ->type_name("FILE")
      ->group(out);
  sub->add_option("--geojson", o->geojson,
                  "write the pass as a map to FILE (GeoJSON): one feature per window, a point at "
                  "its centre from the latitude and longitude (--lat-col/--lon-col, or the "
                  "header's lat/lon columns found by name; no geometry without them), with the "
                  "estimates, their 95 % intervals, valid and the warnings, and the window's "
                  "easting and northing where --east-col/--north-col (or the header's) give them")
      ->type_name("FILE")
      ->group(out);
  o->format_flag =
      sub->add_option(
             "--format", o->format,
             "stdout: table, csv or json; not with a file named - (stdout carries one output)")
          ->check(CLI::IsMember({"table", "csv", "json"}))
          ->group(out);
  sub->add_option("--plot", o->plot_dir,
                  "plot into DIR: G with its band against time or position, and measured against "
                  "simulated accelerations, spectra and z_M''(x_M'') of one window")
      ->type_name("DIR")
      ->group(out);
  sub->add_option("--plot-window", o->plot_window,
                  "the window compared in --plot (default: the first identified)")
      ->group(out);
  sub->add_flag("--quiet,-q", o->quiet, "no progress line on stderr")->group(out);
  sub->callback([o, sub, reading, &action] {
    // The default window (40 periods) of a record shorter than it: the whole record, said.
    o->windows.whole_if_shorter = sub->count("--window") == 0;
    // --metrics with a record's flags: they were accepted without effect, and a warning's advice
    // to read the record "with --z-positive up" changed nothing.
    if (!o->metrics_file.empty()) {
      std::string given;
      for (const CLI::Option* opt : reading)
        if (opt->count() > 0) given += (given.empty() ? "" : ", ") + opt->get_name();
      if (!given.empty())
        throw CLI::ValidationError(
            "--metrics", "the metrics were measured already: " + given +
                             " (reading a record, its windows and gates) cannot change them; "
                             "give them to `oscidrum analyze RECORD --format json` and identify "
                             "from its output, or identify from the record itself");
    }
    action = [o] { return run(*o); };
  });
}

}  // namespace oscidrum::cli
