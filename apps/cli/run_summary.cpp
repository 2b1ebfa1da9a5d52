// The summary of one run, for people.
#include "run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "oscidrum/fields.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/transmissibility.hpp"
#include "oscidrum/version.hpp"
#include "output.hpp"

namespace oscidrum::cli {
namespace {

// Harmonics below this fraction of the signal's largest one are printed as 0: with MMd = 0 the
// even harmonics of x_M'' and the odd ones of z_M'' vanish by symmetry and only rounding
// remains (1e-9 ... 1e-8 of the largest at the default tolerances).
constexpr double kHarmonicZeroFraction = 1e-6;  // stated in the summary

std::string harmonics_text(const std::vector<Harmonic>& h, std::size_t n_max, bool& zeroed) {
  double largest = 0.0;
  for (std::size_t n = 1; n < h.size(); ++n) largest = std::max(largest, h[n].amplitude);
  std::string s;
  for (std::size_t n = 1; n < h.size() && n <= n_max; ++n) {
    const bool zero = h[n].amplitude < kHarmonicZeroFraction * largest;
    zeroed = zeroed || (zero && h[n].amplitude != 0.0);
    s += (n > 1 ? ", " : "") + (zero ? std::string("0") : fmt(h[n].amplitude, 4));
  }
  return s + " m/s^2";
}

// A harmonic ratio (A(nf)/A(f) of x_M'' or z_M'', the CMV-type value) in words where a number
// would mislead: "n/a" with the reason when the fundamental is absent (the ratio is NaN), "0" when
// the numerator is below the threshold at which the harmonics line prints 0 (e.g. A(2f) of x_M''
// without a driving torque: zero by symmetry, 1e-10 of rounding).
std::optional<std::string> ratio_note(const Metrics& m, std::string_view name, bool vibratory,
                                      int multiplicity) {
  struct Ratio {
    std::string_view name;
    double Metrics::*value;
    const Spectrum Metrics::*spectrum;
    std::size_t n;
    const char* signal;
  };
  static constexpr Ratio kRatios[] = {
      {"ddx_A2_A1", &Metrics::ddx_A2_A1, &Metrics::ddx_harmonics, 2, "x_M''"},
      {"ddx_A3_A1", &Metrics::ddx_A3_A1, &Metrics::ddx_harmonics, 3, "x_M''"},
      {"ddz_A2_A1", &Metrics::ddz_A2_A1, &Metrics::ddz_harmonics, 2, "z_M''"},
      {"ddz_A3_A1", &Metrics::ddz_A3_A1, &Metrics::ddz_harmonics, 3, "z_M''"},
      {"cmv", &Metrics::cmv, &Metrics::ddz_harmonics, 2, "z_M''"},
      {"ddx_thd", &Metrics::ddx_thd, &Metrics::ddx_harmonics, 2, "x_M''"},
  };
  // Where a signal is round-off as a whole (a directed vertical exciter's x_M''; both signals of
  // a drum without friction), its fundamental is absent against the two signals together or
  // against the round-off floor (docs/outputs.md).
  constexpr const char* kAbsentBoth =
      " is absent: below 1e-6 of the largest component of x_M'' "
      "and z_M'', or round-off below 1e-12 g)";
  if (name == "psi_xz" && std::isnan(m.psi_xz))
    return std::string("n/a (A(f) of x_M'' or A(2f) of z_M''") + kAbsentBoth;
  if (name == "phi_lag" && std::isnan(m.phi_lag))
    return std::string("n/a (no oscillating torque: M0 = 0, or the vibratory drum)");
  if (name == "mu_required" && std::isnan(m.mu_required))
    return std::string("n/a (the drum lifts off: N reaches 0, where |T|/N has no bound)");
  // The Kb-type stiffness: a ratio to the fundamental of z_M, where a vertical force excites the
  // drum (docs/outputs.md).
  if (name == "kb" && std::isnan(m.kb))
    return std::string(vibratory ? "n/a (z_M has no fundamental)"
                                 : "n/a (the oscillation drum has no vertical excitation force: "
                                   "its drum balance (20) gives m nu^2 - kd whatever the soil)");
  // The Evib-type modulus: Lundberg's cylinder needs the soil's Poisson's ratio.
  if (name == "evib" && std::isnan(m.evib))
    return std::string(
        "n/a (computed for the vibratory drum, roller.type = vibratory, on a soil with a "
        "Poisson's ratio, soil.input = modulus or table2)");
  // The RMV- and CCV-type values: ratios to A(f) (and A(f/2)) of z_M''.
  if (name == "rmv" || name == "ccv") {
    const double v = name == "rmv" ? m.rmv : m.ccv;
    if (std::isnan(v)) return std::string("n/a (A(f) of z_M'' is 0, e.g. by symmetry without MMd)");
    // A state of period p has the frequencies k f / p: f/2 only where p is even.
    if (name == "rmv" && v == 0.0)
      return multiplicity > 1
                 ? "0 (no f/2 component: the steady state repeats every " +
                       std::to_string(multiplicity) + " periods, an odd number)"
                 : std::string("0 (no f/2 component: the steady state repeats every period)");
    return std::nullopt;
  }
  for (const Ratio& r : kRatios) {
    if (r.name != name) continue;
    const Spectrum& h = m.*r.spectrum;
    if (h.size() <= r.n) {
      // The spectrum is kept only to --harmonics (0 or 2 here); the ratio itself, computed from
      // the harmonics up to 3 whatever --harmonics says, decides alone, as the harmonics would.
      const double ratio = m.*r.value / (r.name == "cmv" ? 300.0 : 1.0);
      if (std::isnan(ratio)) return std::string("n/a (A(f) of ") + r.signal + kAbsentBoth;
      if (r.name != "ddx_thd" && ratio < kHarmonicZeroFraction)
        return std::string("0 (A(") + std::to_string(r.n) + "f) of " + r.signal +
               " is below 1e-6 of A(f))";
      return std::nullopt;
    }
    double largest = 0.0;
    for (std::size_t k = 1; k < h.size(); ++k) largest = std::max(largest, h[k].amplitude);
    if (h[1].amplitude < kHarmonicZeroFraction * largest)
      return std::string("n/a (A(f) of ") + r.signal + " is 0, e.g. by symmetry without MMd)";
    if (std::isnan(m.*r.value)) return std::string("n/a (A(f) of ") + r.signal + kAbsentBoth;
    if (r.name == "ddx_thd") return std::nullopt;
    if (h[r.n].amplitude < kHarmonicZeroFraction * largest)
      return std::string("0 (A(") + std::to_string(r.n) + "f) of " + r.signal + " is 0)";
  }
  return std::nullopt;
}

// Two values of fields in the unit people read them in (the field table's display unit).
std::string pair_text(const char* key1, double v1, const char* key2, double v2) {
  const Field& f1 = *find_field(key1);
  const Field& f2 = *find_field(key2);
  return fmt(v1 / f1.display_scale, 4) + ", " + fmt(v2 / f2.display_scale, 4) + " " +
         display_unit(f2);
}

}  // namespace

std::string run_summary(const io::CaseSpec& /*spec*/, const Case& c, const Result& result,
                        const Metrics* metrics, const std::string& config) {
  Summary s;
  const bool vibratory = c.roller.type == RollerType::vibratory;
  s.section(std::string("oscidrum ") + version +
            (vibratory ? ": vibratory drum on soil (docs/model.md section 14)"
                       : ": oscillation drum on soil (Paulmichl, Adam & Adam 2019)"));
  s.line("config", config.empty() ? "none (the paper's roller, HAMM HD+ 90 VO)" : config);

  s.section("case");
  const SoilCoefficients k = soil_coefficients(c.soil, c.roller);
  s.line("soil", soil_summary(c.soil));
  s.line("ksh, ksv", pair_text("soil.ksh", k.ksh, "soil.ksv", k.ksv));
  s.line("csh, csv", pair_text("soil.csh", k.csh, "soil.csv", k.csv));
  // The law the numbers below come from (a regularised law read "Coulomb friction"; the static
  // coefficient and a contact that can open were not said).
  std::string contact =
      c.contact.pure_rolling ? std::string("pure rolling (no friction limit)")
      : c.contact.law == FrictionChoice::regularised
          ? "regularised friction, mu tanh(v_rel / v_eps), mu = " + fmt(c.contact.mu) +
                ", v_eps = " + fmt(c.contact.v_eps) + " m/s"
          : "Coulomb friction, mu = " + fmt(c.contact.mu) +
                (c.contact.mu_static >= 0.0 ? ", static mu_static = " + fmt(c.contact.mu_static)
                                            : std::string());
  if (c.contact.unilateral) contact += "; unilateral (the drum may lift off)";
  s.line("contact", contact);
  s.line("trough", summary(c.trough.shape));
  const double M0 = vibratory ? 0.0 : oscillation_moment(c.roller);
  const double nu = 2.0 * M_PI * c.roller.f;
  if (vibratory)
    s.line("excitation", "f = " + fmt(c.roller.f) + " Hz, unbalance force F0 = m_u e_u nu^2 = " +
                             fmt(c.roller.static_moment * nu * nu) +
                             " N (m_u e_u = " + fmt(c.roller.static_moment) + " kg m), exciter " +
                             format_field(c, *find_field("roller.exciter")));
  else
    s.line(
        "excitation",
        "f = " + fmt(c.roller.f) + " Hz, M0 = " + fmt(M0) + " N m" +
            (c.roller.unbalance > 0.0
                 ? " (4 m_u e_u e_w nu^2 (5), m_u e_u e_w = " + fmt(c.roller.unbalance) + " kg m^2)"
                 : std::string()));
  s.line("driving torque MMd",
         fmt(c.MMd) + " N m" + (M0 != 0.0 ? " (" + fmt(c.MMd / M0, 4) + " M0)" : std::string()));
  if (c.roller.kd > 0.0) {
    const Transmissibility tr =
        transmissibility(c.roller.kd, c.roller.cd, c.roller.m_f, 2.0 * M_PI * c.roller.f);
    s.line("frame transmissibility",
           "Tp = " + fmt(tr.Tp, 3) + " (Appendix A, m_f = " + fmt(c.roller.m_f) + " kg)");
  } else {
    s.line("frame transmissibility", "n/a (roller.kd = 0: no suspension spring, Appendix A)");
  }

  s.section("result");
  s.line("status", to_string(result.status));
  if (!result.message.empty()) s.line("message", result.message);
  if (result.floquet.stability != Stability::unknown)
    s.line("Floquet", std::string(to_string(result.floquet.stability)) + ", largest |multiplier| " +
                          fmt(result.floquet.max_modulus, 6));
  if (result.period1_floquet.stability != Stability::unknown)
    s.line("period-1 orbit (replaced)", std::string(to_string(result.period1_floquet.stability)) +
                                            ", largest |multiplier| " +
                                            fmt(result.period1_floquet.max_modulus, 6));

  if (metrics) {
    const Metrics& m = *metrics;
    s.section("steady state (" + std::to_string(result.sample_periods) + " periods, " +
              std::to_string(result.samples.size()) + " samples)");
    bool zeroed = false;
    // A signal of round-off as a whole (the vertical exciter's x_M'', both signals of a drum
    // without friction): its peaks, harmonics and the area are printed as computed, said so.
    const AbsentSignals absent = absent_signals(m);
    const auto round_off = [&](std::string_view name) -> std::string {
      const bool x = absent.ddx && (name.starts_with("ddx_") || name == "area");
      const bool z = absent.ddz && (name.starts_with("ddz_") || name == "area");
      if (!x && !z) return "";
      return std::string(" (round-off: ") +
             (x && z ? "x_M'' and z_M'' are"
              : x    ? "x_M'' is"
                     : "z_M'' is") +
             " absent)";
    };
    const auto& outputs = metric_outputs();
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const MetricOutput& out = outputs[i];
      if (is_scalar(out)) {
        const auto note = ratio_note(m, out.name, vibratory, result.diagnostics.multiplicity);
        s.line(out.label, note ? *note : output_text(m, out) + round_off(out.name));
        continue;
      }
      const Spectrum& h = m.*std::get<Spectrum Metrics::*>(out.member);
      if (h.size() < 2) {  // --harmonics 0: the mean only
        s.line(out.label, "none asked (--harmonics 0)");
        continue;
      }
      const std::size_t shown = std::min<std::size_t>(6, h.size());
      s.line(
          std::string(out.label) + (shown == 2 ? std::string(" A(f)")
                                               : " A(f) ... A(" + std::to_string(shown - 1) + "f)"),
          harmonics_text(h, shown - 1, zeroed) + round_off(out.name));
      // After the last of consecutive spectra: what a printed 0 means.
      if (zeroed && (i + 1 == outputs.size() || is_scalar(outputs[i + 1]))) {
        s.line("",
               "(0: below 1e-6 of the signal's largest harmonic, e.g. zero by symmetry; "
               "exact values: --json)");
        zeroed = false;
      }
    }
  }
  // How it was computed: after the results (people read the metrics first).
  s.section("how it was computed");
  for (const DiagnosticOutput& out : diagnostic_outputs()) {
    std::string value = output_text(result.diagnostics, out);
    if (std::string_view(out.name) == "warm_start") {  // a code in CSV and JSON; words here
      const int w = result.diagnostics.warm_start;
      value = w > 0   ? "yes: from the neighbouring case's steady state"
              : w < 0 ? "failed: started again from rest"
                      : "no: started from rest";
    }
    // The codes for "none" (-1 steady after, multiplicity 0) in words: a run that found no
    // steady state must not show numbers that look like one.
    if (std::string_view(out.name) == "periods_to_steady" &&
        result.diagnostics.periods_to_steady < 0)
      value = "never (no steady state)";
    if (std::string_view(out.name) == "multiplicity" && result.diagnostics.multiplicity <= 0)
      value = "none (no steady state)";
    // A diagnostic that does not apply to this run (NaN; empty in CSV, null in JSON): in words,
    // not "nan" (a run that ended in gross slip printed "switches per period nan").
    if (!is_text(out) && !is_integer(out) && std::isnan(scalar_value(result.diagnostics, out)))
      value = std::string_view(out.name) == "switches_per_period" ? "n/a (no sampled window)"
              : std::string_view(out.name) == "phi_drift"         ? "n/a (no steady state)"
                                                                  : "n/a";
    // The examination of a motion without a steady state: its exponent only when it ran.
    if (std::string_view(out.name) == "lyapunov_exponent" && result.diagnostics.motion.empty())
      value.clear();
    if (!value.empty()) s.line(out.label, value);  // the fallback reason only when there is one
  }
  return s.text();
}

}  // namespace oscidrum::cli
