// The summary of one run, for people.
#include "run_summary.hpp"

#include <algorithm>
#include <cmath>

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

std::string percent(double fraction) { return fmt(100.0 * fraction, 4) + " %"; }

}  // namespace

std::string run_summary(const io::CaseSpec& spec, const Case& c, const Result& result,
                        const Metrics* metrics, const std::string& config) {
  Summary s;
  s.section(std::string("oscidrum ") + version +
            ": oscillation drum on soil (Paulmichl, Adam & Adam 2019)");
  s.line("config", config.empty() ? "none (the paper's roller, HAMM HD+ 90 VO)" : config);

  s.section("case");
  const SoilCoefficients k = soil_coefficients(c.soil, c.roller);
  s.line("soil", io::soil_source(spec));
  s.line("ksh, ksv", fmt(k.ksh / 1e6, 4) + ", " + fmt(k.ksv / 1e6, 4) + " MN/m");
  s.line("csh, csv", fmt(k.csh / 1e3, 4) + ", " + fmt(k.csv / 1e3, 4) + " kN s/m");
  s.line("contact", c.contact.pure_rolling ? "pure rolling (no friction limit)"
                                           : "Coulomb friction, mu = " + fmt(c.contact.mu));
  s.line("trough", c.trough.k == 0.0
                       ? "circle, R = " + fmt(c.trough.a) + " m"
                       : "log spiral, k = " + fmt(c.trough.k) + ", a = " + fmt(c.trough.a) + " m");
  const double M0 = oscillation_moment(c.roller);
  s.line("excitation", "f = " + fmt(c.roller.f) + " Hz, M0 = " + fmt(M0) + " N m" +
                           (c.roller.unbalance > 0.0 ? " (4 m_u e_u e_w nu^2 (5), m_u e_u e_w = " +
                                                           fmt(c.roller.unbalance) + " kg m^2)"
                                                     : std::string()));
  s.line("driving torque MMd",
         fmt(c.MMd) + " N m" + (M0 != 0.0 ? " (" + fmt(c.MMd / M0, 4) + " M0)" : std::string()));
  const Transmissibility tr =
      transmissibility(c.roller.kd, c.roller.cd, c.roller.m_f, 2.0 * M_PI * c.roller.f);
  s.line("frame transmissibility",
         "Tp = " + fmt(tr.Tp, 3) + " (Appendix A, m_f = " + fmt(c.roller.m_f) + " kg)");

  s.section("result");
  const Diagnostics& d = result.diagnostics;
  s.line("status", to_string(result.status));
  if (!result.message.empty()) s.line("message", result.message);
  s.line("steady after", d.periods_to_steady >= 0
                             ? std::to_string(d.periods_to_steady) + " periods (multiplicity " +
                                   std::to_string(d.multiplicity) + ")"
                             : "not reached (" + std::to_string(d.periods_simulated) + " periods)");
  s.line("final change",
         fmt(d.final_change, 3) + " (tolerance " + fmt(c.numerics.steady_tol, 3) + ")");
  s.line("integrator", std::to_string(d.steps) + " steps, " + std::to_string(d.rhs_evaluations) +
                           " RHS evaluations");
  s.line("events", std::to_string(d.events) + " (" + std::to_string(d.switches) + " switches, " +
                       std::to_string(d.reversals) + " reversals, " +
                       std::to_string(d.inconsistent_slip_ends) + " inconsistent slip ends)");
  s.line("switches per period", fmt(d.switches_per_period, 4));
  s.line("max slip residual (39)", fmt(d.max_slip_residual, 3) + " (relative to W)");
  s.line("min N", fmt(d.min_N / 1e3, 5) + " kN");

  if (metrics) {
    const Metrics& m = *metrics;
    s.section("steady state (" + std::to_string(result.sample_periods) + " periods, " +
              std::to_string(result.samples.size()) + " samples)");
    s.line("x_M'' max, min", fmt(m.ddx_max, 5) + ", " + fmt(m.ddx_min, 5) + " m/s^2");
    s.line("z_M'' max, min", fmt(m.ddz_max, 5) + ", " + fmt(m.ddz_min, 5) + " m/s^2");
    const std::size_t shown = std::min<std::size_t>(6, m.ddx_harmonics.size());
    bool zeroed = false;
    s.line("x_M'' A(f) ... A(" + std::to_string(shown ? shown - 1 : 0) + "f)",
           harmonics_text(m.ddx_harmonics, shown - 1, zeroed));
    s.line("z_M'' A(f) ... A(" + std::to_string(shown ? shown - 1 : 0) + "f)",
           harmonics_text(m.ddz_harmonics, shown - 1, zeroed));
    if (zeroed)
      s.line("",
             "(0: below 1e-6 of the signal's largest harmonic, e.g. zero by symmetry; exact "
             "values: --json)");
    s.line("lag torque -> phi",
           fmt(m.phi_lag, 4) + " pi rad (amplitude " + fmt(m.phi_amplitude, 4) + " rad)");
    s.line("lag psi_xz", fmt(m.psi_xz, 4) + " rad");
    s.line("area z_M''(x_M'')", fmt(m.area, 5) + " m^2/s^4");
    s.line("stick, slip+, slip-", percent(m.stick_fraction) + ", " +
                                      percent(m.slip_positive_fraction) + ", " +
                                      percent(m.slip_negative_fraction));
  }
  return s.text();
}

}  // namespace oscidrum::cli
