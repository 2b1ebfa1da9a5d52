// JSON summaries of a case and of a sweep (docs/outputs.md).
#include "oscidrum_io/json.hpp"

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <span>

#include "oscidrum/fields.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/output_table.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/transmissibility.hpp"
#include "oscidrum/version.hpp"
#include "oscidrum_io/csv.hpp"

namespace oscidrum::io {
namespace {

using json = nlohmann::ordered_json;  // keys in the documented order

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json field_value(const Case& c, const Field& f) {
  switch (f.type) {
    case FieldType::boolean:
      return f.get(c) != 0.0;
    case FieldType::choice:
      return format_field(c, f);
    case FieldType::integer:
      return static_cast<long long>(f.get(c));
    case FieldType::real:
      break;
  }
  return number(f.get(c));
}

json harmonics_json(const std::vector<Harmonic>& h) {
  json a = json::array();
  for (std::size_t n = 0; n < h.size(); ++n)
    a.push_back({{"n", n}, {"amplitude", number(h[n].amplitude)}, {"phase", number(h[n].phase)}});
  return a;
}

// {name: value} of a metrics struct, in table order; spectra as arrays of harmonics.
template <class Struct, class... Types>
json outputs_json(const Struct& m, std::span<const Output<Struct, Types...>> table) {
  json out = json::object();
  for (const auto& o : table) {
    if (is_scalar(o))
      out[o.name] = number(scalar_value(m, o));
    else
      out[o.name] = harmonics_json(m.*std::get<Spectrum Struct::*>(o.member));
  }
  return out;
}

json soil_json(const Case& c) {
  json s;
  s["source"] = soil_source_id(c.soil);
  s["description"] = soil_summary(c.soil);
  // The coefficients the model uses (its one conversion of the soil input); G, nu, rho where the
  // input has them (Table 2: its nu = 0.3 and rho = 1900 kg/m^3).
  const SoilCoefficients k = soil_coefficients(c.soil, c.roller);
  const bool has_modulus = c.soil.input != SoilInput::coefficients;
  s["G"] = has_modulus ? number(c.soil.G) : json(nullptr);
  const bool table2 = c.soil.input == SoilInput::table2;
  s["nu"] = has_modulus ? number(table2 ? kTable2Nu : c.soil.nu) : json(nullptr);
  s["rho"] = has_modulus ? number(table2 ? kTable2Rho : c.soil.rho) : json(nullptr);
  s["a0"] = has_modulus ? number(k.a0) : json(nullptr);
  s["ksh"] = number(k.ksh);
  s["ksv"] = number(k.ksv);
  s["csh"] = number(k.csh);
  s["csv"] = number(k.csv);
  return s;
}

}  // namespace

std::string case_json(const CaseSpec& spec, const Case& c, const Result& result,
                      const Metrics* metrics, const std::string& config) {
  json j;
  j["schema"] = "oscidrum-case/1";
  j["oscidrum_version"] = version;
  j["config"] = config.empty() ? json(nullptr) : json(config);
  j["status"] = to_string(result.status);
  j["ok"] = ok(result.status);
  j["message"] = result.message;

  json params = json::object();
  // Every field's value (the case as given: it runs again from these), and the keys the case
  // does not read (key_not_in_effect: soil.ksh under Table 2, roller.M0 beside roller.unbalance)
  // named in unused_parameters: their values are defaults the run did not use (the values used
  // are under "soil" and "derived").
  json unused = json::array();
  for (const Field& f : fields()) {
    params[f.key] = field_value(c, f);
    if (!key_in_effect(c, f.key)) unused.push_back(f.key);
  }
  j["parameters"] = params;
  j["unused_parameters"] = unused;
  json origins = json::object();
  for (const auto& [key, where] : spec.origin) origins[key] = where;
  j["origins"] = origins;
  j["soil"] = soil_json(c);

  const Roller& R = c.roller;
  // The vibratory drum has no oscillation moment; its excitation is F0 = m_u e_u nu^2.
  const bool vibratory = R.type == RollerType::vibratory;
  const double nu = 2.0 * M_PI * R.f, M0 = vibratory ? 0.0 : oscillation_moment(R);
  j["derived"] = {{"Fz", number(R.P0 - R.m * R.g)},
                  {"W", number(R.P0)},
                  {"nu", number(nu)},
                  {"period", number(1.0 / R.f)},
                  {"M0", number(M0)},
                  {"MMd_fraction", number(M0 != 0.0 ? c.MMd / M0 : NAN)},
                  {"F0", number(vibratory ? R.static_moment * nu * nu : 0.0)}};
  // The trough as its shape describes itself: its name and its parameters (given and derived).
  json trough = {{"shape", trough_name(c.trough.shape)}};
  for (const TroughParameter& p : parameters(c.trough.shape)) trough[p.symbol] = number(p.value);
  trough["curvature_radius"] = number(curvature_radius_at_bottom(c.trough.shape));
  j["derived"]["trough"] = trough;
  // Appendix A: how much of the drum's oscillation reaches the frame (40); null without a
  // suspension spring (roller.kd = 0, a valid case: the frame has no natural frequency).
  if (R.kd > 0.0) {
    const Transmissibility tr = transmissibility(R.kd, R.cd, R.m_f, 2.0 * M_PI * R.f);
    j["derived"]["transmissibility"] = {{"m_f", number(R.m_f)},
                                        {"omega", number(tr.omega)},
                                        {"zeta", number(tr.zeta)},
                                        {"ratio", number(tr.ratio)},
                                        {"Tp", number(tr.Tp)}};
  } else {
    j["derived"]["transmissibility"] = nullptr;
  }

  json diagnostics = json::object();
  for (const DiagnosticOutput& d : diagnostic_outputs()) {
    if (is_text(d)) {
      diagnostics[d.name] = text_value(result.diagnostics, d);
      continue;
    }
    const double v = scalar_value(result.diagnostics, d);
    diagnostics[d.name] = is_integer(d) ? json(static_cast<long long>(v)) : number(v);
  }
  j["diagnostics"] = diagnostics;
  {
    const auto floquet_json = [](const Floquet& f) {
      json multipliers = json::array();
      for (const auto& z : f.multipliers)
        multipliers.push_back(json::array({number(z.real()), number(z.imag())}));
      return json{
          {"stability", to_string(f.stability)},
          {"max_modulus", f.stability == Stability::unknown ? json() : number(f.max_modulus)},
          {"multipliers", multipliers}};
    };
    j["floquet"] = floquet_json(result.floquet);
    // The unstable period-1 orbit a subharmonic steady state replaced (null otherwise).
    j["floquet"]["period1"] = result.period1_floquet.stability == Stability::unknown
                                  ? json()
                                  : floquet_json(result.period1_floquet);
  }
  j["sampling"] = {{"frequency", number(result.frequency)},
                   {"sample_periods", result.sample_periods},
                   {"samples_per_period", result.samples_per_period},
                   {"samples", result.samples.size()},
                   {"t0", result.samples.size() ? number(result.samples.t.front()) : json()}};
  // null, as documented, when nothing was sampled (it was an object of four nulls).
  if (result.samples.size() == 0 && std::isnan(result.stick_time))
    j["phase_times"] = nullptr;
  else
    j["phase_times"] = {{"stick", number(result.stick_time)},
                        {"slip_positive", number(result.slip_positive_time)},
                        {"slip_negative", number(result.slip_negative_time)},
                        {"flight", number(result.flight_time)}};
  j["metrics"] = metrics ? outputs_json(*metrics, metric_outputs()) : json(nullptr);
  return j.dump(2) + "\n";
}

std::string study_json(const std::string& header, const std::vector<std::string>& rows) {
  const std::vector<std::string> columns = csv_split(header);
  json j;
  j["schema"] = "oscidrum-sweep/1";
  j["oscidrum_version"] = version;
  j["columns"] = columns;
  json out = json::array();
  for (const std::string& line : rows) {
    const std::vector<std::string> cells = csv_split(line);
    json row = json::object();
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const std::string cell = i < cells.size() ? cells[i] : std::string();
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (cell.empty())
        row[columns[i]] = nullptr;
      else if (cell == "true" || cell == "false")
        row[columns[i]] = (cell == "true");
      else if (end == cell.c_str() + cell.size() && columns[i] != "message[-]")
        row[columns[i]] = cell.find_first_not_of("-0123456789") == std::string::npos
                              ? json(std::strtoll(cell.c_str(), nullptr, 10))
                              : number(v);
      else
        row[columns[i]] = cell;
    }
    out.push_back(row);
  }
  j["rows"] = out;
  return j.dump(2) + "\n";
}

}  // namespace oscidrum::io
