// oscidrum analyze: the paper's metrics for a measured (or any) acceleration record, to compare
// field measurements with simulations (paper Fig. 23): the excitation frequency estimated (or
// given), the record cut into windows, each fitted and checked by quality gates (record.hpp).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>

#include "case_options.hpp"
#include "commands.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/record.hpp"
#include "oscidrum/version.hpp"
#include "oscidrum_io/csv.hpp"
#include "output.hpp"
#include "record_input.hpp"

namespace oscidrum::cli {
namespace {

struct AnalyzeOptions {
  RecordInput input;
  std::string case_file;  // the vibratory drum's case, for kb (optional)
  WindowOptions windows;
  std::string format = "table";
};

nlohmann::ordered_json spectrum(const std::vector<Harmonic>& h) {
  nlohmann::ordered_json a = nlohmann::json::array();
  // {n, amplitude, phase} as the docs and `run --json` have them (n was missing).
  for (std::size_t n = 0; n < h.size(); ++n)
    a.push_back({{"n", n}, {"amplitude", h[n].amplitude}, {"phase", h[n].phase}});
  return a;
}

nlohmann::ordered_json window_json(const RecordWindow& w) {
  const RecordMetrics& m = w.metrics;
  nlohmann::ordered_json j = {{"window", w.index},
                              {"t_start", w.t_start},
                              {"t_end", w.t_end},
                              {"t", w.t_mid},
                              {"position", w.position},
                              {"samples", w.count},
                              {"samples_per_period", w.samples_per_period},
                              {"f", w.f},
                              {"drift", w.drift},
                              {"change", w.change},
                              {"valid", w.valid},
                              {"reason", w.reason}};
  // Every output of a record, from the output table (peaks, lag, area, compaction indicators,
  // residuals); the spectra as lists.
  for (const RecordOutput& out : record_outputs()) {
    if (std::holds_alternative<double RecordMetrics::*>(out.member))
      j[out.name] = scalar_value(m, out);
  }
  j["ddx_harmonics"] = spectrum(m.ddx_harmonics);
  j["ddz_harmonics"] = spectrum(m.ddz_harmonics);
  return j;
}

std::string cell(double v) { return io::format_double_short(v); }

// Why a window's kb is NaN ("" when it is a number): the record's reason (record_kb's note), the
// window's failed checks, or a vertical response without its fundamental.
std::string kb_reason(const RecordWindow& w, const std::string& kb_note) {
  if (!kb_note.empty()) return kb_note;
  if (std::isfinite(w.metrics.kb)) return "";
  if (!w.valid) return "the window failed its quality checks";
  return "z_M'' has no component at f (A_1 = 0): the drum's vertical balance gives no stiffness";
}

// One CSV row per window (docs/cli.md, `oscidrum analyze`): the window's own columns, then every
// scalar output of a record in the order of the output table, then the spectra's amplitudes.
std::string windows_csv(const std::vector<RecordWindow>& ws, int n_max) {
  std::string out =
      "window[-],t_start[s],t_end[s],t[s],position[m],samples[-],samples_per_period[-],f[Hz],"
      "drift[-],change[-],valid[-],reason[-]";
  for (const RecordOutput& o : record_outputs())
    if (std::holds_alternative<double RecordMetrics::*>(o.member))
      out.append(",").append(o.name).append("[").append(o.unit).append("]");
  for (const char* s : {"ddx", "ddz"})
    for (int n = 1; n <= n_max; ++n)
      out.append(",").append(s).append("_A").append(std::to_string(n)).append("[m/s^2]");
  out += "\n";
  for (const RecordWindow& w : ws) {
    const RecordMetrics& m = w.metrics;
    out += std::to_string(w.index) + "," + cell(w.t_start) + "," + cell(w.t_end) + "," +
           cell(w.t_mid) + "," + cell(w.position) + "," + std::to_string(w.count) + "," +
           cell(w.samples_per_period) + "," + cell(w.f) + "," + cell(w.drift) + "," +
           cell(w.change) + "," + (w.valid ? "1" : "0") + "," + io::csv_quote(w.reason);
    for (const RecordOutput& o : record_outputs())
      if (std::holds_alternative<double RecordMetrics::*>(o.member))
        out.append(",").append(cell(scalar_value(m, o)));
    for (const std::vector<Harmonic>* h : {&m.ddx_harmonics, &m.ddz_harmonics})
      for (int n = 1; n <= n_max; ++n)
        out.append(",").append(cell(n < static_cast<int>(h->size()) ? (*h)[n].amplitude : NAN));
    out += "\n";
  }
  return out;
}

int run(AnalyzeOptions o) {
  const RecordColumns rec = read_record(o.input);
  // How the record was read is said once nothing can fail any more: a refusal (exit code 2) is one
  // line on stderr.
  // --harmonics not given (0): 10, or as many as the record's sampling resolves when fewer.
  std::vector<RecordWindow> ws =
      analyze_windows(rec.t, rec.ddx_M, rec.ddz_M, rec.position, o.windows);
  // kb from the drum's vertical balance: the case's roller and the record's unbalance angle.
  std::optional<Case> roller;
  if (!o.case_file.empty()) {
    io::CaseSpec spec;
    roller = resolve_case(o.case_file, CaseOptions{}, spec);
  }
  const std::string kb_note =
      record_kb(ws, rec.t, rec.unbalance_angle, roller ? &*roller : nullptr);
  // analyze_windows refuses a record shorter than one window, so there is always a first window;
  // should that ever fail, say so instead of reading an empty list.
  if (ws.empty()) throw oscidrum::Error("analyze: no window fits in the record " + o.input.file);
  report_reading(rec);
  if (o.windows.window_periods > 0) {
    std::vector<const RecordWindow*> all;
    for (const RecordWindow& w : ws) all.push_back(&w);
    warn_unchecked_change(all, "analyze");
  }
  std::size_t valid = 0;
  for (const RecordWindow& w : ws) valid += w.valid ? 1 : 0;
  // An estimated f at which x_M'' is larger at 2f than half its component at f: an oscillation or
  // vibratory drum's x_M'' is largest at the excitation's frequency, so f may be half of it (a
  // period-2 response whose subharmonic outweighs its response at f, read as period 1 at f/2:
  // valid, its CMV-type value and rmv those of another frequency). Said once, from the first
  // valid window.
  if (o.windows.f == 0.0)
    for (const RecordWindow& w : ws) {
      if (!w.valid) continue;
      if (w.metrics.ddx_A2_A1 > 0.5)
        std::cerr << "oscidrum: analyze: x_M'' at 2f is " << fmt(w.metrics.ddx_A2_A1, 3)
                  << " of its component at the estimated f = " << fmt(w.f, 6)
                  << " Hz (a drum's x_M'' is largest at the excitation's frequency): if the "
                     "roller runs at "
                  << fmt(2.0 * w.f, 6)
                  << " Hz, this is a period-2 response read at half its frequency; give --f "
                  << fmt(2.0 * w.f, 6) << "\n";
      break;
    }
  // A record sampled in step with the excitation: what it reports of the harmonics above those it
  // resolves is aliased (said once, from the first valid window).
  for (const RecordWindow& w : ws) {
    if (!w.valid) continue;
    if (sampled_in_step(std::span<const double>(rec.t).subspan(w.first, w.count), w.f))
      std::cerr << "oscidrum: analyze: the record is sampled in step with the excitation ("
                << fmt(w.samples_per_period, 4)
                << " samples per period): its harmonics above those the fit resolves alias onto "
                   "the ones reported, the same way in every period (raw samples; a logger's "
                   "anti-aliasing filter would have removed them; identify compares the model "
                   "sampled alike: docs/identify.md)\n";
    break;
  }
  // Residuals that are the harmonics above those fitted, not noise (a clean or simulated record
  // of a stick-slip motion, whose accelerations jump at its switches): the peaks and the area of
  // the fitted signal then miss them. Said once, from the first valid window, with what a fit of
  // four times the harmonics (as many as the sampling resolves, at most 200) gives.
  for (const RecordWindow& w : ws) {
    if (!w.valid) continue;
    const int used = static_cast<int>(w.metrics.ddx_harmonics.size()) - 1;
    const int resolved =
        std::min(static_cast<int>((w.samples_per_period - 1.0) / 2.0), kMaxRecordHarmonics);
    const int more = std::min(4 * used, resolved);
    const double before = std::max(w.metrics.residual_x, w.metrics.residual_z);
    if (more < 2 * used || !(before > 2e-3)) break;
    const auto part = [&](const std::vector<double>& v) {
      return std::span<const double>(v).subspan(w.first, w.count);
    };
    RecordMetrics m;
    try {
      m = analyze_record(part(rec.t), part(rec.ddx_M), part(rec.ddz_M), w.f, more);
    } catch (const oscidrum::Error&) {
      break;  // the window's refined f resolving a harmonic fewer: nothing to say
    }
    const double after = std::max(m.residual_x, m.residual_z);
    if (after < before / 3.0)
      std::cerr << "oscidrum: analyze: the fit's residuals (x_M'' " << fmt(w.metrics.residual_x, 3)
                << ", z_M'' " << fmt(w.metrics.residual_z, 3) << ") are mostly harmonics above the "
                << used << " fitted, not noise: with " << more << " they are "
                << fmt(m.residual_x, 3) << ", " << fmt(m.residual_z, 3)
                << ", and the fitted signal's x_M'' max " << fmt(w.metrics.ddx_max, 5) << " -> "
                << fmt(m.ddx_max, 5) << " m/s^2, z_M'' max " << fmt(w.metrics.ddz_max, 5) << " -> "
                << fmt(m.ddz_max, 5) << " m/s^2, area " << fmt(w.metrics.area, 5) << " -> "
                << fmt(m.area, 5) << " m^2/s^4 (give --harmonics " << more
                << " for those; a stick-slip motion's accelerations jump at its switches, "
                   "which harmonics approach slowly)\n";
    break;
  }
  const bool single = o.windows.window_periods == 0;
  const std::string name = o.input.file == "-" ? "<stdin>" : o.input.file;
  // The harmonics fitted (every window holds n_max + 1, measured or NaN).
  const int n_max = static_cast<int>(ws.front().metrics.ddx_harmonics.size()) - 1;

  if (o.format == "json") {
    nlohmann::ordered_json j;
    if (single) {
      j = {{"schema", "oscidrum-record/1"}, {"oscidrum_version", version}, {"file", name}};
      j.update(window_json(ws.front()));
      j.erase("window");
      j["reading"] = reading_json(o.input, rec);
      j["kb_note"] = kb_reason(ws.front(), kb_note);  // empty where kb was computed
    } else {
      nlohmann::ordered_json rows = nlohmann::json::array();
      for (const RecordWindow& w : ws) rows.push_back(window_json(w));
      j = {{"schema", "oscidrum-record-windows/1"},
           {"oscidrum_version", version},
           {"file", name},
           {"window_periods", o.windows.window_periods},
           {"hop_periods",
            o.windows.hop_periods > 0 ? o.windows.hop_periods : o.windows.window_periods},
           {"reading", reading_json(o.input, rec)},
           {"valid_windows", valid},
           {"windows", rows}};
      j["kb_note"] = kb_note;
    }
    std::cout << j.dump(2) << "\n";
  } else if (!single || o.format == "csv") {
    if (o.format == "csv" && !single) {
      std::cout << windows_csv(ws, n_max);
    } else if (o.format == "csv") {
      // The spectrum of the whole record, as before windows existed.
      const RecordMetrics& m = ws.front().metrics;
      std::cout << "n,f[Hz],ddx_A[m/s^2],ddz_A[m/s^2],ddx_theta[rad],ddz_theta[rad]\n";
      for (int n = 0; n <= n_max; ++n)
        std::cout << n << "," << cell(n * ws.front().f) << "," << cell(m.ddx_harmonics[n].amplitude)
                  << "," << cell(m.ddz_harmonics[n].amplitude) << ","
                  << cell(m.ddx_harmonics[n].phase) << "," << cell(m.ddz_harmonics[n].phase)
                  << "\n";
    } else {
      TextTable t;
      t.header = {"window",    "t [s]", "position [m]", "f [Hz]", "x_M'' max",
                  "z_M'' max", "area",  "res x",        "res z",  "status"};
      t.right = {true, true, true, true, true, true, true, true, true, false};
      for (const RecordWindow& w : ws)
        t.rows.push_back({std::to_string(w.index), time_text(w.t_mid),
                          std::isfinite(w.position) ? fmt(w.position, 5) : "", fmt(w.f, 6),
                          fmt(w.metrics.ddx_max, 4), fmt(w.metrics.ddz_max, 4),
                          fmt(w.metrics.area, 4), fmt(w.metrics.residual_x, 3),
                          fmt(w.metrics.residual_z, 3), w.valid ? "ok" : w.reason});
      std::cout << name << ": " << ws.size() << " windows of " << fmt(o.windows.window_periods, 4)
                << " periods, " << valid << " valid (accelerations in m/s^2, area in m^2/s^4)\n"
                << t.text();
    }
  } else {
    const RecordWindow& w = ws.front();
    const RecordMetrics& m = w.metrics;
    Summary s;
    s.section("Record");
    s.line("file", name);
    s.line("excitation frequency f [Hz]",
           fmt(o.windows.f > 0 ? o.windows.f : w.f, 8) +
               (o.windows.f > 0 ? " (given)" : " (estimated from the record)"));
    s.line("excitation periods spanned", fmt(m.cycles, 4));
    s.line("frequency drift (between parts)", fmt(w.drift, 3));
    s.line("change of the response (parts)", fmt(w.change, 3) + " (relative RMS)");
    s.line("fit residual x_M'', z_M''",
           fmt(m.residual_x, 3) + ", " + fmt(m.residual_z, 3) + " (RMS relative to the signal)");
    if (m.fitted_periods == 2.0)
      s.line("period of the fitted signal",
             "2 excitation periods (a period-2 response: the subharmonics f/2, 3f/2, ... fitted)");
    else if (m.fitted_periods > 2.0) {
      const std::string p = fmt(m.fitted_periods, 1);
      s.line("period of the fitted signal", p + " excitation periods (a period-" + p +
                                                " response: the subharmonics f/" + p + ", 2f/" + p +
                                                ", ... fitted)");
    }
    s.line("quality", w.valid ? "ok" : "FAILED: " + w.reason);
    s.section("Metrics of the fitted periodic signal");
    s.line("x_M'' max / min [m/s^2]", fmt(m.ddx_max, 5) + " / " + fmt(m.ddx_min, 5));
    s.line("z_M'' max / min [m/s^2]", fmt(m.ddz_max, 5) + " / " + fmt(m.ddz_min, 5));
    s.line("psi (x_M'' -> z_M'') [rad]", fmt(m.psi_xz, 5));
    s.line("area z_M''(x_M'') [m^2/s^4]", fmt(m.area, 5));
    const std::string kb_why = kb_reason(w, kb_note);
    s.line("Kb-type stiffness kb [N/m]", kb_why.empty() ? fmt(m.kb, 6) : "n/a (" + kb_why + ")");
    TextTable t;
    t.header = {"n", "f [Hz]", "A(x_M'') [m/s^2]", "A(z_M'') [m/s^2]", "x / max", "z / max"};
    t.right = {true, true, true, true, true, true};
    double xmax = 0, zmax = 0;
    for (int n = 1; n <= n_max; ++n) {
      xmax = std::max(xmax, m.ddx_harmonics[n].amplitude);
      zmax = std::max(zmax, m.ddz_harmonics[n].amplitude);
    }
    for (int n = 0; n <= n_max; ++n)
      t.rows.push_back({std::to_string(n), fmt(n * w.f, 4), fmt(m.ddx_harmonics[n].amplitude, 5),
                        fmt(m.ddz_harmonics[n].amplitude, 5),
                        n ? fmt(m.ddx_harmonics[n].amplitude / xmax, 3) : "",
                        n ? fmt(m.ddz_harmonics[n].amplitude / zmax, 3) : ""});
    std::cout << s.text() << "\nHarmonics (normalised as in the paper's spectra):\n" << t.text();
  }
  if (valid == 0) {
    std::cerr << "oscidrum: error: " << name << ": no valid fit: " << failure_reasons(ws) << "\n";
    // Too few samples per period for the harmonics asked, in every window, is the input's
    // sampling against the flags (exit 2, docs/cli.md), not the measurement's quality (exit 1).
    const bool undersampled = std::all_of(ws.begin(), ws.end(), [&](const RecordWindow& w) {
      return w.samples_per_period < 2.0 * n_max + 1.0;
    });
    return undersampled ? kExitUsage : kExitCaseFailed;
  }
  return kExitOk;
}

}  // namespace

void add_analyze_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* sub = app.add_subcommand(
      "analyze",
      "The paper's metrics for a measured acceleration record. Reads a CSV with time [s] and the "
      "drum-centre accelerations x_M'', z_M'' (z down), estimates the excitation frequency "
      "(unless --f), fits the harmonics n f by least squares, over the whole record or in "
      "windows along a pass, checks each fit by quality gates (residual, frequency drift, "
      "clipping, samples per period, gaps) and reports peaks, spectrum, the lag psi [rad] and "
      "the area of the z_M''(x_M'') figure [m^2/s^4] of the fitted periodic signal. A window "
      "that fails a gate reports NaN and why; a record with no valid fit exits 1.");
  sub->footer(
      "Columns are found by name, with or without a [unit] suffix (defaults: t, ddx_M, ddz_M, as "
      "in `oscidrum run --csv`), or by 1-based index. Output columns: docs/cli.md.\nExamples:\n"
      "  oscidrum analyze field.csv --z-positive up   (columns and units from the header)\n"
      "  oscidrum analyze field.csv --t-col 1 --x-col 3 --z-col 4 --units g\n"
      "  oscidrum analyze pass.csv --window 40 --speed-col v --format csv > windows.csv\n"
      "  oscidrum run --csv steady.csv && oscidrum analyze steady.csv --f 39\n"
      "  oscidrum run vibratory.toml --csv v.csv   (its column alpha: the unbalance's angle)\n"
      "  oscidrum analyze v.csv --f 30 --case vibratory.toml --unbalance-col alpha   (kb)\n"
      "  cat record.txt | oscidrum analyze - --t-col 1 --x-col 2 --z-col 3");
  add_record_options(*sub, o->input);
  sub->add_option("--case", o->case_file,
                  "the vibratory drum's case file (roller.type = vibratory: roller.m, roller.kd, "
                  "roller.static_moment), for the Kb-type stiffness kb (with --unbalance-col)");
  sub->add_option("--unbalance-col", o->input.unbalance_col,
                  "column of the unbalance's angle alpha [rad] (the unbalance force's downward "
                  "component F0 sin(alpha); `oscidrum run --csv` writes it as the column alpha): "
                  "name or index; with --case gives kb, without it kb is NaN with the reason");
  add_window_options(*sub, o->windows, 0.0);
  o->windows.n_max = 0;  // not given: from the sampling (run)
  sub->add_option("--format", o->format,
                  "table, csv (the spectrum; with --window one row per window) or json")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  sub->callback([o, &action] { action = [o] { return run(*o); }; });
}

}  // namespace oscidrum::cli
