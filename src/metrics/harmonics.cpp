// harmonics.cpp: the Fourier coefficients at the multiples of the excitation frequency, read off a
// record that covers whole periods (docs/model.md section 8: spectra of paper Figs. 14, 15, 19, 20
// and the phase lags of Figs. 10, 12).
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/metrics.hpp"

namespace oscidrum {

double wrap_pi(double angle) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  // std::remainder is exact and lands in [-pi, pi]; -pi itself is moved to +pi so that the
  // interval is half-open as documented.
  double r = std::remainder(angle, two_pi);
  if (r <= -std::numbers::pi) r += two_pi;
  return r;
}

namespace {

/// The fractional part of u in [-0.5, 0.5]: the phase shift n nu t0 is reduced in "cycles" before
/// it is multiplied by 2 pi, so that a late record start t0 (hundreds of periods into the run)
/// does not cost more accuracy than the representation of f t0 itself.
double fractional_cycles(double u) { return u - std::nearbyint(u); }

}  // namespace

std::vector<Harmonic> harmonics(std::span<const double> y, int cycles, double f, double t0,
                                int n_max) {
  const std::size_t n_samples = y.size();
  if (n_samples == 0) throw Error("harmonics: the signal y is empty");
  if (cycles < 1) {
    throw Error("harmonics: cycles must be >= 1; got " + std::to_string(cycles));
  }
  if (n_samples % static_cast<std::size_t>(cycles) != 0) {
    throw Error("harmonics: y.size() must be a multiple of cycles; got y.size() = " +
                std::to_string(n_samples) + ", cycles = " + std::to_string(cycles));
  }
  if (!std::isfinite(f) || f <= 0.0) {
    throw Error("harmonics: the frequency f must be finite and > 0 [Hz]; got " + std::to_string(f));
  }
  if (!std::isfinite(t0)) throw Error("harmonics: the start time t0 must be finite [s]");
  const std::size_t per_cycle = n_samples / static_cast<std::size_t>(cycles);
  if (n_max < 0) throw Error("harmonics: n_max must be >= 0; got " + std::to_string(n_max));
  // Bin k = n cycles must stay below the Nyquist bin N/2, where the sine part is not resolved and
  // the negative frequency folds onto the positive one.
  if (2 * static_cast<std::size_t>(n_max) >= per_cycle) {
    throw Error("harmonics: n_max must be < samples_per_cycle / 2 (Nyquist); got n_max = " +
                std::to_string(n_max) + " with " + std::to_string(per_cycle) +
                " samples per cycle");
  }

  // cos and sin of the exact angles 2 pi m / N, m = 0 ... N-1: bin k at sample j uses
  // m = (k j) mod N, reduced in integers, so no angle error accumulates along the record.
  const double n_d = static_cast<double>(n_samples);
  std::vector<double> cos_table(n_samples), sin_table(n_samples);
  for (std::size_t m = 0; m < n_samples; ++m) {
    const double angle = 2.0 * std::numbers::pi * static_cast<double>(m) / n_d;
    cos_table[m] = std::cos(angle);
    sin_table[m] = std::sin(angle);
  }

  const double cycles_at_t0 = fractional_cycles(f * t0);
  std::vector<Harmonic> out(static_cast<std::size_t>(n_max) + 1);

  // n = 0: the mean. A_n >= 0 holds for every n, so the sign of the mean goes into the phase:
  // A_0 = |mean| and theta_0 = +pi/2 (mean >= 0) or -pi/2 (mean < 0), so A_0 sin(theta_0) = mean.
  double sum = 0.0;
  for (double v : y) sum += v;
  const double mean = sum / n_d;
  out[0].amplitude = std::abs(mean);
  out[0].phase = mean >= 0.0 ? std::numbers::pi / 2.0 : -std::numbers::pi / 2.0;

  for (int n = 1; n <= n_max; ++n) {
    const std::size_t k = static_cast<std::size_t>(n) * static_cast<std::size_t>(cycles);
    // a = sum y_j cos(2 pi k j / N), b = sum y_j sin(2 pi k j / N). For
    // y_j = A sin(2 pi k j / N + p): a = (N/2) A sin p and b = (N/2) A cos p (0 < k < N/2).
    double a = 0.0, b = 0.0;
    std::size_t m = 0;
    for (std::size_t j = 0; j < n_samples; ++j) {
      a += y[j] * cos_table[m];
      b += y[j] * sin_table[m];
      m += k;
      if (m >= n_samples) m -= n_samples;  // k < N/2, so one subtraction suffices
    }
    out[static_cast<std::size_t>(n)].amplitude = 2.0 * std::hypot(a, b) / n_d;
    // p is the phase at the record start: n nu t = n nu t0 + 2 pi k j / N. The absolute-time
    // phase is theta_n = p - n nu t0.
    const double shift = 2.0 * std::numbers::pi * fractional_cycles(n * cycles_at_t0);
    out[static_cast<std::size_t>(n)].phase = wrap_pi(std::atan2(a, b) - shift);
  }
  return out;
}

}  // namespace oscidrum
