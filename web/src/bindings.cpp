// web/src/bindings.cpp: Embind bindings of the oscidrum core for the browser explorer (web/).
// Only the public API of include/oscidrum/ is used. A case travels as a plain JavaScript object
// {"soil.G": 25e6, "contact.mu": 0.5, ...} whose keys are those of the field table
// (oscidrum::fields(), the same keys as `oscidrum fields` and the TOML case files); every key,
// unit, default and rule the page shows comes from that table.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <cmath>
#include <exception>
#include <span>
#include <string>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/parameters.hpp"
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
// samples, metrics, ...}.
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
      out.set("metrics", metrics_of(oscidrum::compute_metrics(model, r, n_max)));
    } else {
      out.set("metrics", val::null());
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

std::string version() { return oscidrum::version; }

}  // namespace

EMSCRIPTEN_BINDINGS(oscidrum) {
  emscripten::function("fields", &fields);
  emscripten::function("checkField", &check_field);
  emscripten::function("keyInEffect", &key_in_effect);
  emscripten::function("simulate", &simulate);
  emscripten::function("soilCoefficients", &soil_coefficients);
  emscripten::function("table2", &table2);
  emscripten::function("table2Soil", &table2_soil);
  emscripten::function("version", &version);
}
