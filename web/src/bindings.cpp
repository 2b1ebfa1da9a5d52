// web/src/bindings.cpp: Embind bindings of the oscidrum core for the browser explorer (web/).
// Only the public API of include/oscidrum/ is used. A case travels as a plain JavaScript object
// {"soil.G": 25e6, "contact.mu": 0.5, ...} whose keys are those of the field table
// (oscidrum::fields(), the same keys as `oscidrum fields` and the TOML case files); every key,
// unit, default and rule the page shows comes from that table.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/identify.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/record.hpp"
#include "oscidrum/record_reader.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/simulate.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/version.hpp"

namespace {

using emscripten::val;

const char* type_name(oscidrum::FieldType type) {
  switch (type) {
    case oscidrum::FieldType::real:
      return "real";
    case oscidrum::FieldType::integer:
      return "integer";
    case oscidrum::FieldType::boolean:
      return "boolean";
    case oscidrum::FieldType::choice:
      return "choice";
  }
  return "real";
}

// The choice names of a field ("coefficients|modulus" -> ["coefficients", "modulus"]).
val choice_names(const oscidrum::Field& field) {
  val names = val::array();
  if (field.choices == nullptr) return names;
  const std::string all = field.choices;
  std::size_t begin = 0;
  while (begin <= all.size()) {
    const std::size_t end = all.find('|', begin);
    const std::size_t stop = end == std::string::npos ? all.size() : end;
    names.call<void>("push", all.substr(begin, stop - begin));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return names;
}

// Every field of the table with its key, type, unit, description, rule and default value.
val fields() {
  const oscidrum::Case defaults;
  val out = val::array();
  for (const oscidrum::Field& field : oscidrum::fields()) {
    val f = val::object();
    f.set("key", std::string(field.key));
    f.set("type", std::string(type_name(field.type)));
    f.set("unit", std::string(field.unit));
    f.set("description", std::string(field.description));
    f.set("min", field.min);
    f.set("max", field.max);
    f.set("min_open", field.min_open);
    f.set("max_open", field.max_open);
    f.set("choices", choice_names(field));
    f.set("rule", oscidrum::field_rule(field));
    f.set("default", field.get(defaults));
    // The unit the page shows and reads the value in (MN/m^2 for soil.G): value / display_scale.
    f.set("display_unit", std::string(oscidrum::display_unit(field)));
    f.set("display_scale", field.display_scale);
    out.call<void>("push", f);
  }
  return out;
}

// Empty if `value` satisfies the rule of field `key`, else the library's message.
std::string check_field(const std::string& key, double value) {
  const oscidrum::Field* field = oscidrum::find_field(key);
  if (field == nullptr) {
    try {
      oscidrum::Case c;
      oscidrum::set_field(c, key, value);  // throws the "did you mean" message
    } catch (const std::exception& e) {
      return e.what();
    }
    return "unknown parameter '" + key + "'";
  }
  return oscidrum::check_field(*field, value);
}

// A Case from the defaults and the keys set in `values` (numbers; unknown keys and values that
// break a rule throw oscidrum::Error).
oscidrum::Case case_from(const val& values) {
  oscidrum::Case c;
  if (values.isUndefined() || values.isNull()) return c;
  const val keys = val::global("Object").call<val>("keys", values);
  const auto n = keys["length"].as<unsigned>();
  for (unsigned i = 0; i < n; ++i) {
    const auto key = keys[i].as<std::string>();
    const val v = values[key];
    if (v.typeOf().as<std::string>() == "boolean") {
      oscidrum::set_field(c, key, v.as<bool>() ? 1.0 : 0.0);
    } else if (v.typeOf().as<std::string>() == "string") {
      oscidrum::set_field_text(c, key, v.as<std::string>());
    } else {
      oscidrum::set_field(c, key, v.as<double>());
    }
  }
  return c;
}

// The value of every field of a case, keyed as in the field table.
val case_values(const oscidrum::Case& c) {
  val out = val::object();
  for (const oscidrum::Field& field : oscidrum::fields()) out.set(field.key, field.get(c));
  return out;
}

// The rules of several fields (trough.a > roller.r, ...) on the case of `values` (the defaults
// for the keys not given): {error, key} of the first one broken, or null. Only the Model is built
// (it validates the case); nothing is integrated.
val check_case(const val& values) {
  try {
    const oscidrum::Model model(case_from(values));
  } catch (const oscidrum::Error& e) {
    val out = val::object();
    out.set("error", std::string(e.what()));
    out.set("key", e.key());
    return out;
  } catch (const std::exception& e) {
    val out = val::object();
    out.set("error", std::string(e.what()));
    out.set("key", std::string());
    return out;
  }
  return val::null();
}

// Whether each field takes effect in the case (oscidrum::key_in_effect), keyed as above.
val keys_in_effect(const oscidrum::Case& c) {
  val out = val::object();
  for (const oscidrum::Field& field : oscidrum::fields())
    out.set(field.key, oscidrum::key_in_effect(c, field.key));
  return out;
}

// Whether `key` takes effect in the case `values` (oscidrum::key_in_effect): the page asks which
// soil keys each soil.input reads.
bool key_in_effect(const val& values, const std::string& key) {
  try {
    return oscidrum::key_in_effect(case_from(values), key);
  } catch (const std::exception&) {
    return false;
  }
}

// The soil the model uses: how it is given, in words, and the coefficients of the model's one
// conversion of the soil input (oscidrum::soil_coefficients).
val soil_of(const oscidrum::Case& c) {
  const oscidrum::SoilCoefficients k = oscidrum::soil_coefficients(c.soil, c.roller);
  val out = val::object();
  out.set("source", std::string(oscidrum::soil_source_id(c.soil)));
  out.set("summary", oscidrum::soil_summary(c.soil));
  out.set("a0", k.a0);  // [m], 0 when the coefficients are given directly
  out.set("ksh", k.ksh);
  out.set("ksv", k.ksv);
  out.set("csh", k.csh);
  out.set("csv", k.csv);
  return out;
}

// A copy of a vector as a Float64Array (not a view into the WebAssembly memory, which may move).
val float64_array(const std::vector<double>& v) {
  const val view(emscripten::typed_memory_view(v.size(), v.data()));
  return val::global("Float64Array").new_(view);
}

val harmonics_of(const std::vector<oscidrum::Harmonic>& h) {
  std::vector<double> amplitude, phase;
  for (const auto& x : h) {
    amplitude.push_back(x.amplitude);
    phase.push_back(x.phase);
  }
  val out = val::object();
  out.set("amplitude", float64_array(amplitude));  // A_n [unit of the signal]
  out.set("phase", float64_array(phase));          // theta_n [rad]
  return out;
}

// Which signal is round-off as a whole (the vertical exciter's x_M'', a record's dead channel),
// {ddx_M, ddz_M}: the page draws it flat on zero with a note instead of scaling it up
// (oscidrum::absent_signals).
val absent_of(const oscidrum::Spectrum& hx, const oscidrum::Spectrum& hz) {
  const oscidrum::AbsentSignals absent = oscidrum::absent_signals(hx, hz);
  val flags = val::object();
  flags.set("ddx_M", absent.ddx);
  flags.set("ddz_M", absent.ddz);
  return flags;
}

// Every metric of the output table (oscidrum/outputs.hpp): numbers, and the spectra as
// {amplitude, phase} arrays.
val metrics_of(const oscidrum::Metrics& m) {
  val out = val::object();
  for (const oscidrum::MetricOutput& o : oscidrum::metric_outputs()) {
    if (const auto* h = std::get_if<oscidrum::Spectrum oscidrum::Metrics::*>(&o.member))
      out.set(o.name, harmonics_of(m.**h));
    else
      out.set(o.name, oscidrum::scalar_value(m, o));
  }
  return out;
}

// Every diagnostic of the output table (oscidrum/output_table.hpp): numbers, or text for the
// method and the fallback reason.
val diagnostics_of(const oscidrum::Diagnostics& d) {
  val out = val::object();
  for (const oscidrum::DiagnosticOutput& o : oscidrum::diagnostic_outputs()) {
    if (oscidrum::is_text(o))
      out.set(o.name, oscidrum::text_value(d, o));
    else
      out.set(o.name, oscidrum::scalar_value(d, o));
  }
  return out;
}

// Every column of the output table (oscidrum/outputs.hpp), and `columns`: [name, unit] pairs in
// file order, from which the page writes the CSV of `oscidrum run --csv`.
val samples_of(const oscidrum::Samples& s) {
  val out = val::object();
  val columns = val::array();
  for (const oscidrum::SampleOutput& o : oscidrum::sample_outputs()) {
    val column = val::array();
    column.call<void>("push", std::string(o.name));
    column.call<void>("push", std::string(o.unit));
    columns.call<void>("push", column);
    if (const auto* m = std::get_if<oscidrum::SampleValues oscidrum::Samples::*>(&o.member)) {
      out.set(o.name, float64_array(s.**m));
    } else {  // the phase: 0 stick, 1 slip+, -1 slip-, 2 flight
      std::vector<double> phase;
      phase.reserve(s.phase.size());
      for (const oscidrum::Phase p : s.phase)
        phase.push_back(static_cast<double>(static_cast<int>(p)));
      out.set(o.name, float64_array(phase));
    }
  }
  out.set("columns", columns);
  return out;
}

// The trough as its shape describes itself: its name, a summary, and its surface (the contact
// points C = M + r (sin delta, cos delta) of (15)-(16) for |delta| <= 1.2 rad) relative to the drum
// centre at rest, x to the right and z down [m], for drawing any shape.
val trough_of(const oscidrum::TroughGeometry& g) {
  val out = val::object();
  out.set("shape", std::string(oscidrum::trough_name(g.shape)));
  out.set("summary", oscidrum::summary(g.shape));
  std::vector<double> x, z;
  for (int i = -60; i <= 60; ++i) {
    const double delta = 0.02 * i;
    const oscidrum::Kinematics k = oscidrum::kinematics(g, delta);
    x.push_back(k.x_roll + g.r * k.sin_delta);
    z.push_back(k.z_roll + g.r * k.cos_delta);
  }
  val outline = val::object();
  outline.set("x", float64_array(x));
  outline.set("z", float64_array(z));
  out.set("outline", outline);
  return out;
}

val error_object(const std::string& message, const std::string& key = {}) {
  val out = val::object();
  out.set("ok", false);
  out.set("error", message);
  if (!key.empty()) out.set("key", key);  // the parameter the error is about (oscidrum::Error)
  return out;
}

// Simulate the case `values` from rest to its steady state (oscidrum::simulate) and compute its
// metrics (oscidrum::compute_metrics from the dense output, as the CLI, harmonics n = 0 ... n_max).
// Returns {ok: false, error} for bad input, else {ok: true, status, message, diagnostics, case,
// samples, metrics, absent: {ddx_M, ddz_M} (absent_of; null with the metrics), ...}.
val simulate(const val& values, int n_max) {
  try {
    const oscidrum::Case c = case_from(values);
    // The Model validates the case (throws oscidrum::Error) here, in code built with exception
    // support; the integrator itself is built without it (scripts/build-web.sh) and never throws.
    const oscidrum::Model model(c);
    const oscidrum::Result r = oscidrum::simulate(model);
    val out = val::object();
    out.set("ok", true);
    out.set("status", std::string(oscidrum::to_string(r.status)));
    out.set("message", r.message);
    out.set("case", case_values(c));
    out.set("in_effect", keys_in_effect(c));
    out.set("soil", soil_of(c));
    out.set("trough", trough_of(model.geometry()));
    out.set("diagnostics", diagnostics_of(r.diagnostics));
    out.set("frequency", r.frequency);
    out.set("sample_periods", r.sample_periods);
    out.set("samples_per_period", r.samples_per_period);
    out.set("stick_time", r.stick_time);
    out.set("slip_positive_time", r.slip_positive_time);
    out.set("slip_negative_time", r.slip_negative_time);
    out.set("flight_time", r.flight_time);
    out.set("samples", samples_of(r.samples));
    // Metrics only for a steady state; another status keeps its last periods' samples to draw
    // (as the CLI does), with no numbers that look like a steady state's.
    if (r.samples.size() > 0 && oscidrum::ok(r.status)) {
      const oscidrum::Metrics m = oscidrum::compute_metrics(model, r, n_max);
      out.set("metrics", metrics_of(m));
      out.set("absent", absent_of(m.ddx_harmonics, m.ddz_harmonics));
    } else {
      out.set("metrics", val::null());
      out.set("absent", val::null());
    }
    return out;
  } catch (const oscidrum::Error& e) {
    return error_object(e.what(), e.key());
  } catch (const std::exception& e) {
    return error_object(e.what());
  }
}

val coefficients_of(const oscidrum::SoilCoefficients& s) {
  val out = val::object();
  out.set("a0", s.a0);    // [m]
  out.set("ksh", s.ksh);  // [N/m]
  out.set("ksv", s.ksv);
  out.set("csh", s.csh);  // [N s/m]
  out.set("csv", s.csv);
  return out;
}

// Appendix B (42)-(45): the soil coefficients from G [Pa], nu [-], rho [kg/m^3] and the roller of
// the case `values` (r, b, P0). Returns {ok: false, error} on non-physical input.
val soil_coefficients(double G, double nu, double rho, const val& values) {
  try {
    const oscidrum::Case c = case_from(values);
    val out = coefficients_of(oscidrum::soil_coefficients(G, nu, rho, c.roller));
    out.set("ok", true);
    return out;
  } catch (const std::exception& e) {
    return error_object(e.what());
  }
}

// Paper Table 2 (SI units), one object per row.
val table2() {
  val out = val::array();
  for (const oscidrum::Table2Row& row : oscidrum::table2()) {
    val r = val::object();
    r.set("G", row.G);
    r.set("a0", row.a0);
    r.set("ksh", row.ksh);
    r.set("ksv", row.ksv);
    r.set("csh", row.csh);
    r.set("csv", row.csv);
    out.call<void>("push", r);
  }
  return out;
}

// The Table 2 soil at G [Pa] as field values ({"soil.input": 2, "soil.G": ..., "soil.ksh": ...}).
val table2_soil(double G) {
  try {
    oscidrum::Case c;
    c.soil = oscidrum::table2_soil(G);
    val out = case_values(c);
    out.set("ok", true);
    return out;
  } catch (const std::exception& e) {
    return error_object(e.what());
  }
}

// ---- measured records: read, analysed and identified as `oscidrum analyze` and `identify` do

// A text option of `options` (a JavaScript object) or its default; throws oscidrum::Error when
// the value is not one of `allowed` ("a|b|c"), naming the option and the choices.
std::string text_option(const val& options, const char* key, const std::string& fallback,
                        const std::string& allowed) {
  if (options.isUndefined() || options.isNull()) return fallback;
  const val v = options[key];
  if (v.isUndefined() || v.isNull()) return fallback;
  const auto text = v.as<std::string>();
  if (allowed.empty()) return text;
  std::size_t begin = 0;
  while (begin <= allowed.size()) {
    const std::size_t end = std::min(allowed.find('|', begin), allowed.size());
    if (allowed.substr(begin, end - begin) == text) return text;
    begin = end + 1;
  }
  std::string choices;
  for (char ch : allowed) choices += ch == '|' ? std::string(", ") : std::string(1, ch);
  throw oscidrum::Error(std::string("record option ") + key + " must be one of " + choices +
                        "; got '" + text + "'");
}

// How the record's text is read (oscidrum::RecordReading, the options of `oscidrum analyze`):
// {units: "auto"|"m/s2"|"g"|"mg", t_units: "auto"|"s"|"ms"|"us"|"ns", x_positive:
// "forward"|"backward", z_positive: "auto"|"down"|"up", t_col, x_col, z_col: a name or 1-based
// index, empty: recognised}.
oscidrum::RecordReading reading_from(const val& options) {
  oscidrum::RecordReading o;
  o.units = text_option(options, "units", "auto", "auto|m/s2|g|mg");
  o.t_units = text_option(options, "t_units", "auto", "auto|s|ms|us|ns");
  o.x_positive = text_option(options, "x_positive", "forward", "forward|backward");
  o.z_positive = text_option(options, "z_positive", "auto", "auto|down|up");
  o.t_col = text_option(options, "t_col", "", "");
  o.x_col = text_option(options, "x_col", "", "");
  o.z_col = text_option(options, "z_col", "", "");
  return o;
}

oscidrum::RecordColumns record_of(const std::string& text, const std::string& name,
                                  const val& options) {
  std::istringstream in(text);
  return oscidrum::read_record(in, name, reading_from(options));
}

// How the record was read: the columns taken, their factors and the notes (as the CLI reports
// them), the delimiter and the number of samples.
val reading_of(const oscidrum::RecordColumns& rec) {
  val out = val::object();
  out.set("delimiter", rec.delimiter);
  out.set("t_column", rec.t_column);
  out.set("x_column", rec.x_column);
  out.set("z_column", rec.z_column);
  out.set("t_factor", rec.t_factor);
  out.set("x_factor", rec.x_factor);
  out.set("z_factor", rec.z_factor);
  out.set("z_positive", rec.z_positive);
  out.set("z_open", rec.z_open);
  out.set("units_open", rec.units_open);
  val notes = val::array();
  for (const std::string& n : rec.notes) notes.call<void>("push", n);
  out.set("notes", notes);
  out.set("samples", static_cast<double>(rec.t.size()));
  out.set("duration", rec.t.empty() ? 0.0 : rec.t.back() - rec.t.front());
  return out;
}

// One period of the fitted periodic signal y(t) = sum_n A_n sin(n 2 pi f t + theta_n) (the
// harmonics' own definition, oscidrum/outputs.hpp), `points` samples from t = 0, for drawing the
// measured z_M''(x_M'') figure.
val periodic_of(const std::vector<oscidrum::Harmonic>& h, int points) {
  std::vector<double> y(static_cast<std::size_t>(points), 0.0);
  for (int j = 0; j < points; ++j) {
    const double phase = 2.0 * std::numbers::pi * j / points;
    for (std::size_t n = 0; n < h.size(); ++n)
      y[static_cast<std::size_t>(j)] +=
          h[n].amplitude * std::sin(static_cast<double>(n) * phase + h[n].phase);
  }
  return float64_array(y);
}

// Every metric of a record (the output table's record outputs, as `oscidrum analyze` writes
// them): numbers, and the spectra as {amplitude, phase}.
val record_metrics_of(const oscidrum::RecordMetrics& m) {
  val out = val::object();
  for (const oscidrum::RecordOutput& o : oscidrum::record_outputs()) {
    if (const auto* h = std::get_if<oscidrum::Spectrum oscidrum::RecordMetrics::*>(&o.member))
      out.set(o.name, harmonics_of(m.**h));
    else
      out.set(o.name, oscidrum::scalar_value(m, o));
  }
  return out;
}

// Read the record `text` and analyse it as one window (oscidrum::analyze_windows with the
// defaults of `oscidrum analyze`: the whole record, f estimated, harmonics n = 0 ... 10 or as
// many as the sampling resolves when fewer, the quality gates). Returns {ok: false, error} for a
// record that cannot be read, else {ok: true, reading, valid, reason, f, metrics, periodic: {ddx_M,
// ddz_M} (one period of the fit)}.
val analyze_record(const std::string& text, const std::string& name, const val& options) {
  try {
    const oscidrum::RecordColumns rec = record_of(text, name, options);
    const std::vector<oscidrum::RecordWindow> ws =
        oscidrum::analyze_windows(rec.t, rec.ddx_M, rec.ddz_M, rec.position, {});
    if (ws.empty()) throw oscidrum::Error(name + ": no window fits in the record");
    const oscidrum::RecordWindow& w = ws.front();
    val out = val::object();
    out.set("ok", true);
    out.set("reading", reading_of(rec));
    out.set("valid", w.valid);
    out.set("reason", w.reason);
    out.set("f", w.f);
    out.set("samples_per_period", w.samples_per_period);
    out.set("metrics", record_metrics_of(w.metrics));
    out.set("absent", absent_of(w.metrics.ddx_harmonics, w.metrics.ddz_harmonics));
    val periodic = val::object();
    periodic.set("ddx_M", periodic_of(w.metrics.ddx_harmonics, 512));
    periodic.set("ddz_M", periodic_of(w.metrics.ddz_harmonics, 512));
    out.set("periodic", periodic);
    return out;
  } catch (const oscidrum::Error& e) {
    return error_object(e.what(), e.key());
  } catch (const std::exception& e) {
    return error_object(e.what());
  }
}

val estimate_of(const oscidrum::Estimate& e) {
  val out = val::object();
  out.set("name", e.name);
  out.set("unit", e.unit);
  out.set("value", e.value);
  out.set("u", e.standard_uncertainty);
  out.set("lower", e.lower);  // 95 % interval from the profile (NaN: none)
  out.set("upper", e.upper);
  out.set("lower_open", e.lower_open);
  out.set("upper_open", e.upper_open);
  return out;
}

// Identify the soil under the drum from the record `text` as `oscidrum identify RECORD --window
// 0` does (oscidrum::identify_pass over one window of the whole record, its harmonics from the
// sampling, n = 1 ... 4 compared, 95 % intervals from the profile), the roller and everything
// not estimated from the case `values`; G on the scale `soil_scale` ("formulas": Appendix B
// (42)-(45), "table2": the paper's Table 2 interpolated). Returns {ok: false, error} for bad
// input, else {ok: true, valid, reason, f, estimates: [{name, unit, value, u, lower, upper}],
// relative_residual, reduced_chi2, time_shift, warnings, iterations, simulations, message,
// model_sampled, z_negated, read_in_g}.
val identify_record(const std::string& text, const std::string& name, const val& options,
                    const val& values, const std::string& soil_scale) {
  try {
    const oscidrum::RecordColumns rec = record_of(text, name, options);
    const oscidrum::Case base = case_from(values);
    oscidrum::WindowOptions windows;
    windows.window_periods = 0.0;  // the whole record
    windows.n_max = 0;             // harmonics from the sampling (identify's default)
    oscidrum::IdentifyOptions io;
    io.soil_scale = oscidrum::soil_scale_from(soil_scale, "soil_scale");
    io.measure.harmonics = windows.n_max;
    io.z_open = rec.z_open;
    io.units_open = rec.units_open;
    const std::vector<oscidrum::PassEstimate> pass =
        oscidrum::identify_pass(base, rec.t, rec.ddx_M, rec.ddz_M, rec.position, windows, io);
    if (pass.empty()) throw oscidrum::Error(name + ": no window fits in the record");
    const oscidrum::PassEstimate& p = pass.front();
    const oscidrum::Identification& id = p.identification;
    val out = val::object();
    out.set("ok", true);
    out.set("valid", p.valid);
    out.set("reason", p.reason);
    out.set("soil_scale", std::string(oscidrum::to_string(io.soil_scale)));
    out.set("f", p.window.f);
    val estimates = val::array();
    if (p.valid)
      for (const oscidrum::Estimate& e : id.estimates) estimates.call<void>("push", estimate_of(e));
    out.set("estimates", estimates);
    out.set("converged", id.converged);
    out.set("message", id.message);
    out.set("relative_residual", id.relative_residual);
    out.set("reduced_chi2", id.reduced_chi2);
    out.set("time_shift", id.time_shift);
    out.set("iterations", id.iterations);
    out.set("simulations", id.simulations);
    out.set("model_sampled", p.valid && id.model_sampled);
    out.set("z_negated", p.valid && id.z_negated);
    out.set("read_in_g", p.valid && id.read_in_g);
    val warnings = val::array();
    for (const std::string& w : id.warnings) warnings.call<void>("push", w);
    out.set("warnings", warnings);
    return out;
  } catch (const oscidrum::Error& e) {
    return error_object(e.what(), e.key());
  } catch (const std::exception& e) {
    return error_object(e.what());
  }
}

// A synthetic record of the case `values` made by the engine (oscidrum::synthetic_record), for
// tests: {duration [s], sample_rate [1/s], noise [-], seed} -> {t, ddx_M, ddz_M} in the model's
// conventions.
val synthetic_record(const val& values, const val& options) {
  try {
    oscidrum::SyntheticRecord o;
    o.duration = options["duration"].as<double>();
    o.sample_rate = options["sample_rate"].as<double>();
    o.noise = options["noise"].as<double>();
    o.seed = options["seed"].as<unsigned>();
    const oscidrum::RecordSamples r = oscidrum::synthetic_record({case_from(values)}, o);
    val out = val::object();
    out.set("ok", true);
    out.set("t", float64_array(r.t));
    out.set("ddx_M", float64_array(r.ddx_M));
    out.set("ddz_M", float64_array(r.ddz_M));
    return out;
  } catch (const std::exception& e) {
    return error_object(e.what());
  }
}

std::string version() { return oscidrum::version; }

}  // namespace

EMSCRIPTEN_BINDINGS(oscidrum) {
  emscripten::function("fields", &fields);
  emscripten::function("checkField", &check_field);
  emscripten::function("checkCase", &check_case);
  emscripten::function("keyInEffect", &key_in_effect);
  emscripten::function("simulate", &simulate);
  emscripten::function("soilCoefficients", &soil_coefficients);
  emscripten::function("table2", &table2);
  emscripten::function("table2Soil", &table2_soil);
  emscripten::function("analyzeRecord", &analyze_record);
  emscripten::function("identifyRecord", &identify_record);
  emscripten::function("syntheticRecord", &synthetic_record);
  emscripten::function("version", &version);
}
