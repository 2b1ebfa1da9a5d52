// metrics.cpp: the quantities the paper reads off a steady state (docs/model.md section 8): peak
// accelerations (Fig. 9), spectra (Figs. 14, 15, 19, 20), the lag between the excitation and phi
// (Fig. 10), the lag between x_M'' and z_M'' (Fig. 12), the enclosed area (Figs. 16, 22) and the
// time shares of the contact phases.
#include "oscidrum/metrics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "indicators.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/output_table.hpp"

namespace oscidrum {

namespace {

void require_size(const std::vector<double>& v, std::size_t n, const char* name) {
  if (v.size() != n) {
    throw Error(std::string("compute_metrics: samples.") + name + " has " +
                std::to_string(v.size()) + " entries; expected " + std::to_string(n) +
                " (as samples.t)");
  }
}

}  // namespace

AbsentSignals absent_signals(const Spectrum& ddx_harmonics, const Spectrum& ddz_harmonics) {
  const double absent = detail::absent_level(ddx_harmonics, ddz_harmonics);
  auto all_below = [absent](const Spectrum& h) {
    return std::all_of(h.begin(), h.end(),
                       [absent](const Harmonic& c) { return c.amplitude <= absent; });
  };
  return {all_below(ddx_harmonics), all_below(ddz_harmonics)};
}

AbsentSignals absent_signals(const Metrics& m) {
  // The peaks count beside the harmonics computed (with --harmonics 0 or 1 the spectra alone
  // would call a signal of even harmonics round-off).
  const double peaks = std::max(
      {std::abs(m.ddx_max), std::abs(m.ddx_min), std::abs(m.ddz_max), std::abs(m.ddz_min)});
  const double level = std::max(detail::absent_level(m.ddx_harmonics, m.ddz_harmonics),
                                detail::kAbsentFundamental * peaks);
  const auto below = [level](const Spectrum& h, double hi, double lo) {
    return std::abs(hi) <= level && std::abs(lo) <= level &&
           std::all_of(h.begin(), h.end(),
                       [level](const Harmonic& c) { return c.amplitude <= level; });
  };
  return {below(m.ddx_harmonics, m.ddx_max, m.ddx_min),
          below(m.ddz_harmonics, m.ddz_max, m.ddz_min)};
}

Metrics Metrics::unavailable() { return detail::all_unavailable<Metrics>(metric_outputs()); }

Metrics compute_metrics(const Result& result, int n_max) {
  const Samples& s = result.samples;
  const std::size_t n = s.size();
  if (n == 0) throw Error("compute_metrics: the result holds no samples");
  // Only a steady state has steady-state metrics: the samples of another status (the last
  // periods of a run that did not settle) are for inspection, and numbers read off them would
  // look like a steady state's.
  if (!ok(result.status))
    throw Error(std::string("compute_metrics: the result has status ") + to_string(result.status) +
                ", not a steady state: no metrics");
  if (n_max < 0) {
    throw Error("compute_metrics: n_max must be >= 0; got " + std::to_string(n_max));
  }
  if (result.sample_periods < 1 || result.samples_per_period < 1) {
    throw Error("compute_metrics: sample_periods and samples_per_period must be >= 1; got " +
                std::to_string(result.sample_periods) + " and " +
                std::to_string(result.samples_per_period));
  }
  const std::size_t per_period = static_cast<std::size_t>(result.samples_per_period);
  if (n != static_cast<std::size_t>(result.sample_periods) * per_period) {
    throw Error("compute_metrics: samples.t has " + std::to_string(n) +
                " entries; expected sample_periods * samples_per_period = " +
                std::to_string(result.sample_periods) + " * " +
                std::to_string(result.samples_per_period));
  }
  require_size(s.phi, n, "phi");
  require_size(s.dphi, n, "dphi");
  require_size(s.ddx_M, n, "ddx_M");
  require_size(s.ddz_M, n, "ddz_M");
  if (!s.delta.empty()) require_size(s.delta, n, "delta");

  Metrics m;
  const auto [x_min, x_max] = std::minmax_element(s.ddx_M.begin(), s.ddx_M.end());
  const auto [z_min, z_max] = std::minmax_element(s.ddz_M.begin(), s.ddz_M.end());
  m.ddx_min = *x_min;
  m.ddx_max = *x_max;
  m.ddz_min = *z_min;
  m.ddz_max = *z_max;
  // delta is optional (a record of accelerations alone has none): NaN when absent.
  m.delta_min = m.delta_max = std::numeric_limits<double>::quiet_NaN();
  if (!s.delta.empty()) {
    const auto [d_min, d_max] = std::minmax_element(s.delta.begin(), s.delta.end());
    m.delta_min = *d_min;
    m.delta_max = *d_max;
  }

  // psi needs theta_1(x_M'') and theta_2(z_M''), the harmonic ratios A_3/A_1: compute at least
  // up to n = 3.
  const int cycles = result.sample_periods;
  const double f = result.frequency;
  const double t0 = s.t.front();  // the absolute time of the first sample, not assumed n / f
  const int n_compute = std::max(n_max, 3);
  std::vector<Harmonic> hx = harmonics(s.ddx_M, cycles, f, t0, n_compute);
  std::vector<Harmonic> hz = harmonics(s.ddz_M, cycles, f, t0, n_compute);
  // THD: everything in x_M'' but its mean and fundamental is distortion. By Parseval the mean
  // square of the residual r = x_M'' - A_0 sin(theta_0) - A_1 sin(nu t + theta_1) over whole
  // periods is sum_{k>=2} A_k^2 / 2 (with any subharmonic content of a p-periodic state). The
  // residual is summed directly: no cancellation when the distortion is small.
  {
    const double nu = 2.0 * std::numbers::pi * f;
    double sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double r = s.ddx_M[j] - hx[0].amplitude * std::sin(hx[0].phase) -
                       hx[1].amplitude * std::sin(nu * s.t[j] + hx[1].phase);
      sum += r * r;
    }
    // z_M'''s subharmonics: none in a state of odd period p (frequencies k f / p); for an even p
    // a DFT at (2j + 1) f / 2 over the samples, which span whole steady periods (NaN if not).
    detail::HalfHarmonics half;
    const int p = result.diagnostics.multiplicity >= 1 ? result.diagnostics.multiplicity : 1;
    if (p % 2 == 0) {
      if (cycles % 2 != 0) {
        half.a05 = half.a15 = half.a25 = std::numeric_limits<double>::quiet_NaN();
      } else {
        std::array<double, 3> a{}, b{};
        for (std::size_t j = 0; j < n; ++j)
          for (std::size_t k = 0; k < 3; ++k) {
            const double w = std::numbers::pi * f * static_cast<double>(2 * k + 1) * (s.t[j] - t0);
            a[k] += s.ddz_M[j] * std::cos(w);
            b[k] += s.ddz_M[j] * std::sin(w);
          }
        const double scale = 2.0 / static_cast<double>(n);
        half.a05 = std::hypot(a[0], b[0]) * scale;
        half.a15 = std::hypot(a[1], b[1]) * scale;
        half.a25 = std::hypot(a[2], b[2]) * scale;
      }
    }
    detail::set_spectral_metrics(m, std::move(hx), std::move(hz),
                                 2.0 * sum / static_cast<double>(n), n_max, half);
  }

  // phi need not be periodic: a driving torque makes the drum slip on by a net angle per period
  // (docs/model.md section 7). The mean of phi' over whole periods is that drift rate; removing the
  // ramp leaves the periodic part, whose fundamental is compared with M0 sin(nu t) (phase 0).
  double rate = 0.0;
  for (double v : s.dphi) rate += v;
  rate /= static_cast<double>(n);
  std::vector<double> phi(n);
  for (std::size_t j = 0; j < n; ++j) phi[j] = s.phi[j] - rate * (s.t[j] - t0);
  const std::vector<Harmonic> hphi = harmonics(phi, cycles, f, t0, 1);
  // Without an oscillating torque (a sampled torque column that is constant) phi lags nothing.
  const bool torque_oscillates =
      s.torque.size() != n ||
      std::any_of(s.torque.begin(), s.torque.end(), [&](double v) { return v != s.torque[0]; });
  detail::set_rotation_metrics(m, hphi[1], torque_oscillates);

  // The area over one steady period: `multiplicity` excitation periods (one if none was found).
  const int p = result.diagnostics.multiplicity >= 1 ? result.diagnostics.multiplicity : 1;
  const std::size_t n_area = std::min(n, static_cast<std::size_t>(p) * per_period);
  m.area = enclosed_area(std::span<const double>(s.ddx_M).first(n_area),
                         std::span<const double>(s.ddz_M).first(n_area));

  // Friction: mu_required = max |T|/N (24-26); the friction work dissipated per excitation
  // period, the mean of |T v_rel| (the power of sliding friction, zero in stick) times 1/f.
  m.mu_required = m.friction_work = std::numeric_limits<double>::quiet_NaN();
  if (s.T.size() == n && s.N.size() == n) {
    m.mu_required = 0.0;
    for (std::size_t j = 0; j < n; ++j)
      m.mu_required = std::max(m.mu_required, std::abs(s.T[j]) / s.N[j]);
  }
  if (s.T.size() == n && s.v_rel.size() == n) {
    double power = 0.0;
    for (std::size_t j = 0; j < n; ++j) power += std::abs(s.T[j] * s.v_rel[j]);
    m.friction_work = power / static_cast<double>(n) / f;
  }

  const double total = result.stick_time + result.slip_positive_time + result.slip_negative_time +
                       result.flight_time;
  if (total > 0.0) {
    detail::set_phase_fractions(m, result.stick_time, result.slip_positive_time,
                                result.slip_negative_time, result.flight_time);
  } else {
    // No phase times recorded: count the samples (uniform in time, so counts are time shares).
    if (s.phase.size() != n) {
      throw Error("compute_metrics: no phase times recorded and samples.phase has " +
                  std::to_string(s.phase.size()) + " entries; expected " + std::to_string(n));
    }
    const auto count = [&s](Phase ph) {
      return static_cast<double>(std::count(s.phase.begin(), s.phase.end(), ph));
    };
    detail::set_phase_fractions(m, count(Phase::stick), count(Phase::slip_positive),
                                count(Phase::slip_negative), count(Phase::flight));
  }
  detail::no_required_mu_with_flight(m);
  // Flight (contact.unilateral): lift-offs and landings are events of the sampled window; the
  // largest gap is the samples' (the dense output's is compute_metrics(model, result)'s).
  long lift_offs = 0;
  m.landing_velocity = 0.0;
  for (const Event& e : result.events) {
    if (e.kind == EventKind::lift_off) ++lift_offs;
    if (e.kind == EventKind::landing) m.landing_velocity = std::max(m.landing_velocity, e.speed);
  }
  m.liftoffs_per_period = static_cast<double>(lift_offs) / result.sample_periods;
  m.gap_max = 0.0;
  if (s.gap.size() == n)
    for (double g : s.gap) m.gap_max = std::max(m.gap_max, g);
  // The Kb-type stiffness only where a vertical force excites the drum (see steady_metrics.cpp:
  // without one it is m nu^2 - kd whatever the soil). The samples do not hold that force; an
  // oscillating torque column is the oscillation drum's excitation, which has none.
  const bool torque_column_oscillates =
      s.torque.size() == n &&
      std::any_of(s.torque.begin(), s.torque.end(), [&](double v) { return v != s.torque[0]; });
  m.kb = torque_column_oscillates ? std::numeric_limits<double>::quiet_NaN()
                                  : detail::soil_stiffness(s, cycles, f, t0);
  // The Evib-type modulus needs the drum's radius and length and the soil's Poisson's ratio,
  // which a Result does not hold: compute_metrics(model, result) computes it.
  m.evib = std::numeric_limits<double>::quiet_NaN();
  return m;
}

}  // namespace oscidrum
