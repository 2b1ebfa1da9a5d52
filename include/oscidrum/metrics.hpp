// oscidrum/metrics.hpp: what continuous compaction control reads off the drum accelerations.
// The signal-level functions work on any uniformly sampled record (simulated or measured).
#pragma once

#include <span>
#include <vector>

#include "oscidrum/result.hpp"

namespace oscidrum {

/// One harmonic n f of a signal written as  y(t) = sum_n A_n sin(n nu t + theta_n)  with t the
/// absolute time (t = 0 at the start of the excitation M0 sin(nu t)). n = 0: A_0 = |mean| and
/// theta_0 = +-pi/2, so that A_0 sin(theta_0) is the mean.
struct Harmonic {
  double amplitude = 0.0;  ///< A_n >= 0 [unit of the signal]
  double phase = 0.0;      ///< theta_n in (-pi, pi] [rad]
};

/// Harmonics n = 0 ... n_max of y sampled uniformly over exactly `cycles` periods of f:
/// y[j] = y(t0 + j / (f * samples_per_cycle)), j = 0 ... cycles*samples_per_cycle - 1. A DFT over
/// whole periods: no window, no leakage. Only multiples of f (bin n * cycles) are returned.
/// Throws oscidrum::Error if y.size() is not a positive multiple of `cycles` or n_max is too
/// large for the sampling (n_max < samples_per_cycle / 2).
std::vector<Harmonic> harmonics(std::span<const double> y, int cycles, double f, double t0,
                                int n_max);

/// Area of the region enclosed by the closed polygon (x[j], y[j]) (last point joins the first):
/// the set of points with non-zero winding number. For a figure-eight this is the sum of both
/// lobes (the signed shoelace sum would cancel them). [unit x * unit y]
double enclosed_area(std::span<const double> x, std::span<const double> y);

/// Wrap an angle to (-pi, pi].
double wrap_pi(double angle);

/// Metrics of a simulated steady state (docs/model.md section 8).
struct Metrics {
  double ddx_max = 0.0, ddx_min = 0.0;      ///< extremes of x_M'' [m/s^2]
  double ddz_max = 0.0, ddz_min = 0.0;      ///< extremes of z_M'' [m/s^2]
  double delta_max = 0.0, delta_min = 0.0;  ///< extremes of delta [rad] (NaN without samples)
  std::vector<Harmonic> ddx_harmonics;      ///< harmonics n = 0 ... n_max of x_M'' [m/s^2]
  std::vector<Harmonic> ddz_harmonics;      ///< harmonics n = 0 ... n_max of z_M'' [m/s^2]
  /// Phase lag between the excitation M0 sin(nu t) and phi: theta_1 of phi (linear drift
  /// removed), wrapped to (-2, 0] and given in units of pi, as in paper Fig. 10 [pi rad].
  double phi_lag = 0.0;
  double phi_amplitude = 0.0;  ///< A_1 of phi [rad]
  /// Lag between x_M'' and z_M'': psi = theta_2(z_M'') - 2 theta_1(x_M'') wrapped to (-pi, pi]
  /// (docs/model.md section 8; psi > 0: the 2f component of z_M'' leads) [rad].
  double psi_xz = 0.0;
  double area = 0.0;            ///< area enclosed by z_M'' over x_M'' (non-zero winding) [m^2/s^4]
  double stick_fraction = 0.0;  ///< of the sampled time [-]
  double slip_positive_fraction = 0.0;  ///< [-]
  double slip_negative_fraction = 0.0;  ///< [-]

  /// Every number NaN and no harmonics: what a result that is not a steady state has.
  static Metrics unavailable();
};

/// Compute the metrics from a Result's samples (harmonics up to n_max). Throws oscidrum::Error if
/// the result holds no samples or its status is not Status::steady_state.
Metrics compute_metrics(const Result& result, int n_max = 10);

}  // namespace oscidrum
