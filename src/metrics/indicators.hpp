// indicators.hpp (internal): the compaction indicators that simulated steady states (Metrics)
// and measured records (RecordMetrics) share, from their harmonics (docs/outputs.md): each is
// computed here once, whichever source (dense steady state, samples, record fit) feeds it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>
#include <variant>
#include <vector>

#include "oscidrum/metrics.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/soil.hpp"

namespace oscidrum::detail {

/// A fundamental below this fraction of the signal's largest harmonic counts as absent: it is
/// numerical noise (the integration tolerances leave ~1e-8), not a physical component.
inline constexpr double kAbsentFundamental = 1e-6;

/// Accelerations below this are round-off whatever the other signal [m/s^2]: 1e-12 g. The
/// integration resolves components down to about atol nu^2 (6e-7 m/s^2 at the default 1e-11 m
/// and 39 Hz) and a logger's noise lies far above it, so nothing measurable is below; a drum
/// without friction (mu = 0: the torque spins the drum alone) has x_M'' and z_M'' both at
/// 1e-16 m/s^2, which the relative level alone took for signals (CMV 299 of round-off).
inline constexpr double kRoundOffAcceleration = 1e-12 * 9.80665;

/// The level below which a component of x_M'' or z_M'' counts as absent: kAbsentFundamental
/// times the largest component (mean included) of the two signals, and at least
/// kRoundOffAcceleration. A signal that is all round-off (a directed vertical exciter's
/// x_M'' = 0, a record's constant channel) has its own harmonics all round-off, so that it can
/// only be judged against the other signal, or against the floor where both are round-off.
inline double absent_level(const Spectrum& hx, const Spectrum& hz) {
  double largest = 0.0;
  for (const Spectrum* h : {&hx, &hz})
    for (const Harmonic& c : *h) largest = std::max(largest, c.amplitude);
  return std::max(kAbsentFundamental * largest, kRoundOffAcceleration);
}

/// a / A_1 of the spectrum h; NaN when the fundamental is absent: below `absent` (absent_level)
/// or below kAbsentFundamental times h's own largest harmonic (a ratio to it is undefined: e.g.
/// z_M'' without driving torque has only even harmonics, paper Fig. 19b).
inline double ratio_to_fundamental(double a, const Spectrum& h, double absent) {
  double largest = 0.0;
  for (std::size_t n = 1; n < h.size(); ++n) largest = std::max(largest, h[n].amplitude);
  return h[1].amplitude > std::max(absent, kAbsentFundamental * largest)
             ? a / h[1].amplitude
             : std::numeric_limits<double>::quiet_NaN();
}

/// psi_xz = theta_2(z_M'') - 2 theta_1(x_M'') wrapped to (-pi, pi]; NaN when either component is
/// absent (below absent_level): its phase is then round-off's.
inline double phase_lag_psi(const Spectrum& hx, const Spectrum& hz) {
  const double absent = absent_level(hx, hz);
  if (!(hx[1].amplitude > absent && hz[2].amplitude > absent))
    return std::numeric_limits<double>::quiet_NaN();
  return wrap_pi(hz[2].phase - 2.0 * hx[1].phase);
}

/// The subharmonics A(f/2), A(3f/2), A(5f/2) of z_M'' [m/s^2] that the RMV- and CCV-type values
/// read: a p-periodic steady state has them only for an even p (its frequencies are k f / p); 0
/// for a period-1 state, NaN where they could not be measured.
struct HalfHarmonics {
  double a05 = 0.0, a15 = 0.0, a25 = 0.0;
  /// A(f), A(2f), A(3f) of z_M'' from the same fit as the subharmonics (a record's joint fit, so
  /// that the ratios do not mix two fits); NaN: those of the spectrum.
  double a1 = std::numeric_limits<double>::quiet_NaN();
  double a2 = std::numeric_limits<double>::quiet_NaN();
  double a3 = std::numeric_limits<double>::quiet_NaN();
};

/// Every metric that follows from the harmonics, set in one place for all three sources (the
/// dense steady state, its samples, a measured record's fit): psi_xz, the harmonic ratios A_2/A_1,
/// A_3/A_1 of x_M'' and z_M'', the CMV-type value 300 A_2/A_1 of z_M'', the THD of x_M'' from
/// `ddx_overtones` = sum_{k>=2} A_k^2 of x_M'' [(m/s^2)^2], and the spectra themselves, truncated
/// to n = n_max. hx, hz must reach n = 2 (psi needs the 2f harmonic); the A_3 ratios are NaN
/// without n = 3. `z_half`: the subharmonics of z_M'', for the RMV- and CCV-type values. M is
/// Metrics or RecordMetrics (OSCIDRUM_ACCELERATION_METRICS).
template <class M>
void set_spectral_metrics(M& m, Spectrum hx, Spectrum hz, double ddx_overtones, int n_max,
                          const HalfHarmonics& z_half = {}) {
  // psi = theta_2(z_M'') - 2 theta_1(x_M'') (docs/model.md section 8): the lag of the 2f
  // component of z_M'' against the square of the fundamental of x_M''; > 0: the 2f component
  // leads (paper Fig. 12); NaN when either component is absent (phase_lag_psi).
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  m.psi_xz = phase_lag_psi(hx, hz);
  // The ratios: NaN where the fundamental is absent, against the two signals (absent_level).
  const double absent = absent_level(hx, hz);
  m.ddx_A2_A1 = ratio_to_fundamental(hx[2].amplitude, hx, absent);
  m.ddx_A3_A1 = hx.size() > 3 ? ratio_to_fundamental(hx[3].amplitude, hx, absent) : nan;
  m.ddz_A2_A1 = ratio_to_fundamental(hz[2].amplitude, hz, absent);
  m.ddz_A3_A1 = hz.size() > 3 ? ratio_to_fundamental(hz[3].amplitude, hz, absent) : nan;
  // The compaction meter value CMV = C A(2f)/A(f) with C = 300 (Thurner and Sandstroem 1980),
  // here of the oscillation drum's vertical acceleration z_M''.
  m.cmv = 300.0 * m.ddz_A2_A1;
  // The resonance meter value RMV = A(Omega/2)/A(Omega) and the compaction control value
  // CCV = 100 [A(Omega/2) + A(3 Omega/2) + A(2 Omega) + A(5 Omega/2) + A(3 Omega)] /
  // [A(Omega/2) + A(Omega)] of vibratory rollers (docs/outputs.md, with their sources), of z_M''.
  // Undefined (NaN) where a denominator is absent against the signal's largest component or
  // against both signals (absent_level).
  {
    double largest = std::max({z_half.a05, z_half.a15, z_half.a25});
    for (std::size_t n = 1; n < hz.size(); ++n) largest = std::max(largest, hz[n].amplitude);
    const double a1 = std::isnan(z_half.a1) ? hz[1].amplitude : z_half.a1;
    const double a2 = std::isnan(z_half.a2) ? hz[2].amplitude : z_half.a2;
    const double a3 = std::isnan(z_half.a3) ? (hz.size() > 3 ? hz[3].amplitude : nan) : z_half.a3;
    const double floor = std::max(kAbsentFundamental * largest, absent);
    m.rmv = a1 > floor ? z_half.a05 / a1 : nan;
    const double below = z_half.a05 + a1;
    m.ccv = below > floor ? 100.0 * (z_half.a05 + z_half.a15 + a2 + z_half.a25 + a3) / below : nan;
  }
  m.ddx_thd = ratio_to_fundamental(std::sqrt(ddx_overtones), hx, absent);
  hx.resize(static_cast<std::size_t>(n_max) + 1);
  hz.resize(static_cast<std::size_t>(n_max) + 1);
  m.ddx_harmonics = std::move(hx);
  m.ddz_harmonics = std::move(hz);
}

/// The Kb-type soil stiffness [N/m] (docs/outputs.md): Re(F_v(f) / z_M(f)) from the fundamental
/// of F_v = N cos(delta) + T sin(delta), the soil's vertical force on the drum (25), and the
/// spectrum hz (n = 0 ... >= 2) of the drum centre's vertical displacement z_M. The soil is
/// massless, so F_v is its Kelvin-Voigt force ksv s_A + csv s_A' and, where z_M moves with s_A,
/// the stiffness is ksv. NaN when z_M's fundamental is absent (kAbsentFundamental against the
/// largest of z_M's mean and other harmonics in hz: the oscillation drum without driving torque,
/// whose z_M has even harmonics only; a test against the 2f component alone let through the
/// round-off fundamental where that component passes zero, as a number).
inline double soil_stiffness(const Harmonic& Fv, const Spectrum& hz) {
  const double z1 = hz[1].amplitude;
  double size = 0.0;
  for (const Harmonic& h : hz) size = std::max(size, h.amplitude);
  if (!(z1 > kAbsentFundamental * size)) return std::numeric_limits<double>::quiet_NaN();
  return Fv.amplitude / z1 * std::cos(Fv.phase - hz[1].phase);
}

/// The soil's Poisson's ratio the Evib-type modulus is evaluated with (docs/outputs.md): soil.nu
/// for soil.input = modulus, Table 2's nu = 0.3 for table2, NaN for a soil given by its
/// coefficients (it has no Poisson's ratio, so no Evib).
inline double evib_poisson_ratio(const Case& c) {
  switch (c.soil.input) {
    case SoilInput::modulus:
      return c.soil.nu;
    case SoilInput::table2:
      return kTable2Nu;
    case SoilInput::coefficients:
      break;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// soil_stiffness from the uniformly sampled steady state (`cycles` whole periods of f from t0);
/// NaN without the columns N, T, delta, z_M.
inline double soil_stiffness(const Samples& s, int cycles, double f, double t0) {
  const std::size_t n = s.t.size();
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (n == 0 || s.N.size() != n || s.T.size() != n || s.delta.size() != n || s.z_M.size() != n)
    return nan;
  std::vector<double> Fv(n);
  for (std::size_t j = 0; j < n; ++j)
    Fv[j] = s.N[j] * std::cos(s.delta[j]) + s.T[j] * std::sin(s.delta[j]);  // (25)
  return soil_stiffness(harmonics(Fv, cycles, f, t0, 1)[1], harmonics(s.z_M, cycles, f, t0, 2));
}

/// phi_amplitude and phi_lag from the fundamental of phi (its drift removed), against the
/// excitation M0 sin(nu t) (phase 0). The lag is in (-2, 0] in units of pi, as paper Fig. 10
/// plots it (-0.84 pi at G = 5, -> -pi without soil). `torque_oscillates`: false for a roller
/// without an oscillating torque (the vibratory drum, M0 = 0), where a lag behind it is undefined
/// (NaN; the phase of its phi can be round-off's: a vertical exciter's phi stays at 1e-26 rad).
inline void set_rotation_metrics(Metrics& m, const Harmonic& phi_1, bool torque_oscillates) {
  m.phi_amplitude = phi_1.amplitude;
  double lag = wrap_pi(phi_1.phase);
  if (lag > 0.0) lag -= 2.0 * std::numbers::pi;
  m.phi_lag = torque_oscillates ? lag / std::numbers::pi : std::numeric_limits<double>::quiet_NaN();
}

/// The phase fractions from the time spent in each phase [s] (any common unit): stick, slip with
/// v_rel > 0, slip with v_rel < 0, flight; slip_fraction is the two slips together.
inline void set_phase_fractions(Metrics& m, double stick, double slip_positive,
                                double slip_negative, double flight) {
  const double total = slip_negative + stick + slip_positive + flight;  // the period, to round-off
  m.stick_fraction = stick / total;
  m.slip_positive_fraction = slip_positive / total;
  m.slip_negative_fraction = slip_negative / total;
  m.flight_fraction = flight / total;
  m.slip_fraction = m.slip_positive_fraction + m.slip_negative_fraction;
}

/// mu_required = max |T| / N has no bound where the drum lifts off (N falls to 0 while T need not,
/// and the value found depends on how close a sample or a node comes to the lift-off): NaN when
/// the steady state has flight (after set_phase_fractions).
inline void no_required_mu_with_flight(Metrics& m) {
  if (m.flight_fraction > 0.0) m.mu_required = std::numeric_limits<double>::quiet_NaN();
}

/// Every number of an output table's struct NaN and its spectra empty: the metrics of what is not
/// a steady state or a window that failed (generated from the table, so a new metric cannot be
/// forgotten and read 0).
template <class Struct, class Table>
Struct all_unavailable(const Table& outputs) {
  Struct m;
  for (const auto& o : outputs)
    if (const auto* member = std::get_if<double Struct::*>(&o.member))
      m.*(*member) = std::numeric_limits<double>::quiet_NaN();
  return m;
}

}  // namespace oscidrum::detail
